// In-process deck fuzzer: `xpl check` of many decks in one process (fuzz_decks.py
// --in-process writes the mutated decks and hands them over in batches).
//
//   xpl_fuzz_check LIST OUT_DIR [--timeout SECONDS]
//
// LIST holds one deck path per line. Each deck is checked by xpl::apps::run_job, the code
// `xpl check DECK -o OUT_DIR --quiet` runs, and its outcome is printed on stdout, flushed, so
// that the script knows which deck was running if the process dies:
//
//   start K              before deck K (0-based line of LIST)
//   done K RC SECONDS    after it: RC is the exit code `xpl check` would have returned
//   done K RC SECONDS raw-control     ... and its messages or logs hold raw control bytes
//   done K RC SECONDS leak            ... and LeakSanitizer found memory it lost
//   hang K SECONDS       deck K ran past the time limit: the process ends with exit code 124
//
// Decks are isolated from each other: run_job catches every exception, the messages it
// writes to std::cerr are captured per deck (and written to DECK.stderr when the deck is a
// finding: RC not 0 or 1, raw control bytes or a leak), OUT_DIR is emptied after each deck, a
// watchdog thread ends the process when a deck takes longer than the limit, and under
// AddressSanitizer every deck ends with a leak check of its own. A sanitizer report ends the
// process (halt on error) after "start K": the script attributes it to deck K and goes on
// with the next deck in a new process.

#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apps/job.hpp"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define XPL_FUZZ_LEAK_CHECK 1
#endif

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Exit code of the process when a deck passed the time limit (as timeout(1)).
constexpr int EXIT_HANG = 124;

/// Writes a line to stdout at once (the script reads it even if the process dies next).
void say(const std::string& line) {
  std::fputs((line + "\n").c_str(), stdout);
  std::fflush(stdout);
}

/// Ends the process when one deck runs past the limit. arm() before a deck, disarm() after.
class Watchdog {
 public:
  explicit Watchdog(double limit_seconds) : m_limit(limit_seconds) {
    m_thread = std::thread([this] { watch(); });
  }
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_quit = true;
    }
    m_wake.notify_one();
    m_thread.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  void arm(long deck) {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_deck = deck;
      m_start = Clock::now();
    }
    m_wake.notify_one();
  }
  void disarm() {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_deck = -1;
  }

 private:
  void watch() {
    std::unique_lock<std::mutex> lock(m_mutex);
    while (!m_quit) {
      if (m_deck < 0) {
        m_wake.wait(lock);
        continue;
      }
      const long deck = m_deck;
      const auto deadline = m_start + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(m_limit));
      if (m_wake.wait_until(lock, deadline) == std::cv_status::timeout && m_deck == deck &&
          Clock::now() >= deadline) {
        const std::string line = "hang " + std::to_string(deck) + " " + std::to_string(m_limit);
        say(line);
        std::fprintf(stderr, "xpl_fuzz_check: deck %ld did not end within %g s\n", deck, m_limit);
        std::_Exit(EXIT_HANG);  // the checking thread is stuck: nothing else can end it
      }
    }
  }

  double m_limit;
  std::mutex m_mutex;
  std::condition_variable m_wake;
  long m_deck = -1;
  Clock::time_point m_start;
  bool m_quit = false;
  std::thread m_thread;
};

/// True when `text` holds a control byte escape_control would have escaped (below 0x20 other
/// than tab and newline, or DEL): deck text echoed raw.
bool has_raw_control(const std::string& text) {
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\t' && c != '\n') || c == 0x7f) return true;
  }
  return false;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The job's log files (.msg, .sta) with raw control bytes, if any ("" if none).
std::string logs_with_raw_control(const fs::path& out_dir) {
  std::string found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out_dir, ec)) {
    const fs::path& p = entry.path();
    if (p.extension() != ".msg" && p.extension() != ".sta") continue;
    if (has_raw_control(read_file(p))) found += (found.empty() ? "" : ", ") + p.filename().string();
  }
  return found;
}

/// Empties the output directory (the next deck starts from nothing).
void empty_directory(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) fs::remove_all(entry.path(), ec);
}

int usage() {
  std::fprintf(stderr, "usage: xpl_fuzz_check LIST OUT_DIR [--timeout SECONDS]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 5) return usage();
  double limit = 10.0;
  if (argc == 5) {
    if (std::string(argv[3]) != "--timeout") return usage();
    limit = std::atof(argv[4]);
    if (!(limit > 0.0)) return usage();
  }
  std::ifstream list(argv[1]);
  if (!list) {
    std::fprintf(stderr, "xpl_fuzz_check: cannot read %s\n", argv[1]);
    return 2;
  }
  std::vector<std::string> decks;
  for (std::string line; std::getline(list, line);)
    if (!line.empty()) decks.push_back(line);
  const fs::path out_dir = argv[2];
  std::error_code ec;
  fs::create_directories(out_dir, ec);

  Watchdog watchdog(limit);
  for (std::size_t k = 0; k < decks.size(); ++k) {
    say("start " + std::to_string(k));
    std::ostringstream captured;
    std::streambuf* const cerr_buffer = std::cerr.rdbuf(captured.rdbuf());
    std::streambuf* const cout_buffer = std::cout.rdbuf(captured.rdbuf());
    xpl::apps::JobArguments job;
    job.check = true;
    job.deck = decks[k];
    job.out_dir = out_dir;
    job.quiet = true;
    const auto start = Clock::now();
    watchdog.arm(static_cast<long>(k));
    const int rc = xpl::apps::run_job(job, nullptr);
    watchdog.disarm();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::cerr.rdbuf(cerr_buffer);
    std::cout.rdbuf(cout_buffer);

    std::string flags;
    std::string text = captured.str();
    const std::string raw_logs = logs_with_raw_control(out_dir);
    if (has_raw_control(text) || !raw_logs.empty()) {
      flags += " raw-control";
      if (!raw_logs.empty()) text += "\n[raw control bytes in " + raw_logs + "]\n";
    }
    empty_directory(out_dir);
#ifdef XPL_FUZZ_LEAK_CHECK
    if (__lsan_do_recoverable_leak_check() != 0) flags += " leak";
#endif
    if ((rc != 0 && rc != 1) || !flags.empty()) {
      std::ofstream(decks[k] + ".stderr", std::ios::binary) << text;
    }
    char line[128];
    std::snprintf(line, sizeof line, "done %zu %d %.4f", k, rc, seconds);
    say(line + flags);
  }
  return 0;
}
