// Shared test helper: run a program as a user would (fork + exec, no shell), capture its
// stdout and stderr, and temporary directories that clean up after themselves.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

// AddressSanitizer reserves terabytes of virtual address space (its shadow memory): a cap on
// the address space (RLIMIT_AS, ulimit -v) stops every instrumented run at startup, so tests
// that cap it run uncapped in sanitizer builds.  The binary under test is what counts: the
// command-line drivers are built uninstrumented, so CMake tells them (FLAPLAG_EXE_ASAN) when the
// build's flags instrument the binary (tests/cli.cmake).
#if defined(FLAPLAG_EXE_ASAN) || defined(__SANITIZE_ADDRESS__)
#define FLAPLAG_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FLAPLAG_TEST_ASAN 1
#endif
#endif
#ifndef FLAPLAG_TEST_ASAN
#define FLAPLAG_TEST_ASAN 0
#endif

namespace flaplag::testing {

struct Outcome {
  int exit_code = -1;  // -1: did not exit normally (signal, or killed after the time limit)
  std::string out, err;
  std::chrono::milliseconds interrupted_at{-1};  // when SIGINT was sent (from the start), or -1
};

inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// A positive whole number from the environment variable `name`, or `fallback` when it is not
// set or not such a number (the fuzzers' budgets).
inline long env_long(const char* name, long fallback) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return fallback;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  return end != v && *end == '\0' && n > 0 ? n : fallback;
}

inline bool exists(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0;
}

// A fresh directory per test, removed with its contents afterwards.
class TempDir {
 public:
  TempDir() {
    char tmpl[] = "/tmp/flaplag_test.XXXXXX";
    const char* d = ::mkdtemp(tmpl);
    if (d == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = d;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // Names in the directory (to see that no temporary files are left behind).
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_)) {
      names.push_back(e.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::string path_;
};

// How a child ended: waits for `pid` (started at `start`) and kills it (SIGKILL) once `limit`
// has passed, a hang then being `timed_out`.
struct ChildEnd {
  int exit_code = -1;  // when it exited
  int signal = 0;      // when a signal ended it
  bool timed_out = false;
  double seconds = 0.0;
};
inline ChildEnd wait_for_child(pid_t pid, std::chrono::steady_clock::time_point start,
                               std::chrono::seconds limit) {
  ChildEnd e;
  int status = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid || w < 0) break;
    if (std::chrono::steady_clock::now() - start > limit) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      e.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!e.timed_out) {
    if (WIFEXITED(status)) e.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
  }
  return e;
}

// True once the process catches SIGINT (the SigCgt mask of /proc/PID/status): a SIGINT sent
// before the child has installed its handler would end it instead of being handled, and a
// loaded or instrumented build can take seconds to get there.
inline bool catches_sigint(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(f, line);) {
    if (line.rfind("SigCgt:", 0) == 0)
      return (std::stoull(line.substr(7), nullptr, 16) >> (SIGINT - 1)) & 1u;
  }
  return false;
}

// fork + exec of `program` with stdout/stderr captured in files: no shell, so arguments arrive
// verbatim (empty strings, '*', quotes).  A run longer than `limit` is killed (exit_code -1): a
// test of an output that must not block (a FIFO nobody reads) fails instead of hanging.
// `interrupt_after` > 0: SIGINT is sent once, that long after the start (Ctrl-C in a terminal)
// and not before the child catches it (catches_sigint).
inline Outcome run_process(const std::string& program, const std::vector<std::string>& args,
                           std::chrono::seconds limit = std::chrono::seconds(120),
                           const std::string& path_env = "",
                           std::chrono::milliseconds interrupt_after = {}) {
  TempDir io;
  const std::string out = io.file("stdout"), err = io.file("stderr");
  std::vector<std::string> copy = args;
  std::string exe = program;
  std::vector<char*> argv{exe.data()};
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fo < 0 || fe < 0 || ::dup2(fo, 1) < 0 || ::dup2(fe, 2) < 0) ::_exit(127);
    if (!path_env.empty()) ::setenv("PATH", path_env.c_str(), 1);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  Outcome r;
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + limit;
  bool interrupted = false;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (interrupt_after.count() > 0 && !interrupted &&
        std::chrono::steady_clock::now() >= start + interrupt_after && catches_sigint(pid)) {
      ::kill(pid, SIGINT);
      interrupted = true;
    }
    if (w < 0 || std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      status = -1;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// As run_process, but with stderr on a pseudo-terminal (isatty(2) is true in the child, as in an
// interactive shell); Outcome::err is what the terminal received (the pty turns "\n" into
// "\r\n").  `interrupt_after` > 0: SIGINT once, that long after the start, not before the child
// catches it (catches_sigint) and not before the terminal has received `interrupt_when` (when
// given).
inline Outcome run_process_on_terminal(const std::string& program,
                                       const std::vector<std::string>& args,
                                       std::chrono::seconds limit,
                                       std::chrono::milliseconds interrupt_after = {},
                                       const std::string& interrupt_when = {}) {
  TempDir io;
  const std::string out = io.file("stdout");
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0)
    throw std::runtime_error("no pseudo-terminal");
  const std::string slave = ::ptsname(master);
  std::vector<std::string> copy = args;
  std::string exe = program;
  std::vector<char*> argv{exe.data()};
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setsid();
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int fe = ::open(slave.c_str(), O_RDWR);
    if (fo < 0 || fe < 0 || ::dup2(fo, 1) < 0 || ::dup2(fe, 2) < 0) ::_exit(127);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
  Outcome r;
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  bool interrupted = false;
  auto drain = [&] {
    char buf[4096];
    for (ssize_t n; (n = ::read(master, buf, sizeof buf)) > 0;)
      r.err.append(buf, static_cast<std::size_t>(n));
  };
  for (;;) {
    drain();
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    const auto now = std::chrono::steady_clock::now();
    if (interrupt_after.count() > 0 && !interrupted && now >= start + interrupt_after &&
        (interrupt_when.empty() || r.err.find(interrupt_when) != std::string::npos) &&
        catches_sigint(pid)) {
      ::kill(pid, SIGINT);
      interrupted = true;
      r.interrupted_at = std::chrono::duration_cast<std::chrono::milliseconds>(now - start);
    }
    if (w < 0 || now > start + limit) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      status = -1;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  drain();
  ::close(master);
  if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.out = slurp(out);
  return r;
}

}  // namespace flaplag::testing
