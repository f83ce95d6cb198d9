#pragma once
/// \file JOB.lck: one run of a job per directory at a time (Abaqus' convention).

#include <filesystem>
#include <stdexcept>
#include <string>

namespace xpl::io {

/// Another live process holds the job's lock: the run must not open any output file.
class JobLocked : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An exclusive flock on DIRECTORY/JOB.lck, which holds the owner's pid (for the message a
/// second run prints). Taken before any output file is opened; the file is removed when the
/// lock is released (destructor). A lock file whose process died (no flock is held on it) is
/// taken over, and stale_owner() names the process that left it.
class JobLock {
 public:
  /// Takes the lock; throws JobLocked if a live process holds it, std::runtime_error if the
  /// lock file cannot be created.
  JobLock(const std::filesystem::path& directory, const std::string& job_name);
  ~JobLock();
  JobLock(const JobLock&) = delete;
  JobLock& operator=(const JobLock&) = delete;

  /// Path of the lock file.
  const std::filesystem::path& path() const { return m_path; }
  /// The pid a stale lock file held when it was taken over, or an empty string.
  const std::string& stale_owner() const { return m_stale_owner; }

 private:
  std::filesystem::path m_path;
  int m_fd = -1;
  std::string m_stale_owner;
};

}  // namespace xpl::io
