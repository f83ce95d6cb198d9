#include "io/results/job_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace xpl::io {

namespace {

/// Attempts before giving up when the lock file keeps being replaced under us (an owner
/// removing it between our open and our flock).
constexpr int LOCK_ATTEMPTS = 20;

/// The first line of the lock file (the owner's pid), without trailing blanks.
std::string read_owner(int fd) {
  char buffer[64] = {};
  const ssize_t n = pread(fd, buffer, sizeof buffer - 1, 0);
  std::string text(buffer, n > 0 ? static_cast<std::size_t>(n) : 0);
  const std::size_t end = text.find_first_of("\r\n");
  if (end != std::string::npos) text.resize(end);
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

/// Whether `fd` is still the file at `path` (an owner that released the lock unlinks it,
/// so a lock on an unlinked file protects nothing).
bool same_file(int fd, const std::filesystem::path& path) {
  struct stat held {};
  struct stat named {};
  if (fstat(fd, &held) != 0 || stat(path.c_str(), &named) != 0) return false;
  return held.st_dev == named.st_dev && held.st_ino == named.st_ino;
}

}  // namespace

JobLock::JobLock(const std::filesystem::path& directory, const std::string& job_name)
    : m_path(directory / (job_name + ".lck")) {
  for (int attempt = 0; attempt < LOCK_ATTEMPTS; ++attempt) {
    const int fd = open(m_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw std::runtime_error("cannot create the lock file " + m_path.string() + ": " +
                               std::strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string owner = read_owner(fd);
      close(fd);
      if (error == EWOULDBLOCK)
        throw JobLocked("job " + job_name + " is already running in " +
                        (directory.empty() ? std::string(".") : directory.string()) + " (process " +
                        (owner.empty() ? std::string("unknown") : owner) + " holds " +
                        m_path.string() + "); nothing was written");
      throw std::runtime_error("cannot lock " + m_path.string() + ": " + std::strerror(error));
    }
    if (!same_file(fd, m_path)) {  // released and removed meanwhile: lock the new file
      close(fd);
      continue;
    }
    m_stale_owner = read_owner(fd);
    const std::string pid = std::to_string(getpid()) + "\n";
    if (ftruncate(fd, 0) != 0 ||
        pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
      const int error = errno;
      unlink(m_path.c_str());
      close(fd);
      throw std::runtime_error("cannot write the lock file " + m_path.string() + ": " +
                               std::strerror(error));
    }
    m_fd = fd;
    return;
  }
  throw std::runtime_error("cannot lock " + m_path.string() +
                           ": the lock file keeps being replaced");
}

JobLock::~JobLock() {
  if (m_fd < 0) return;
  // Unlink while still holding the lock, so that no other run can lock this file after it.
  unlink(m_path.c_str());
  close(m_fd);
}

}  // namespace xpl::io
