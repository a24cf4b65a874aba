// Fuzzing the files flaplag reads, beyond the command line (cli_fuzz_test): case files (TOML and
// JSON) given to `flaplag run FILE`, and result files given to `flaplag run`, `flaplag plot` and
// `flaplag merge`, each a mutation of a REAL result that the built flaplag writes once per test
// run (a small sweep, a study, a map in two --shard parts, a response, a simulation).  Every run
// is checked against the contract of README "Using flaplag" and against what a received file may
// do:
//   - no signal, no hang; exit code 0, 2 or 3 (3: `flaplag plot` and gnuplot failed);
//   - exit 2 (or 3): exactly one stderr line "flaplag: error: ...", nothing on stdout;
//     exit 0: nothing on stderr but at most one "flaplag: warning: ..." line;
//   - no file created or changed but the paths the test typed (-o, --plot, or the output keys
//     of a TOML case file the test wrote), and those only on exit 0; every run is in a fresh
//     directory, and a watched directory next to it (with a victim file) must stay as it was:
//     no marker file of a payload's `touch` (no command ran) and no file written outside;
//   - gnuplot, when flaplag spawns it, is a fake first in PATH that keeps the script it was
//     given and draws a tiny SVG; in that script a payload may appear only inside a gnuplot
//     single-quoted string (with ' doubled) or not at all (script_problems below);
//   - the address space of every run is capped (RLIMIT_AS, 1 GiB) and so is the size of a file
//     it writes (RLIMIT_FSIZE, 256 MiB): unbounded memory or output is an exit 1 or a signal,
//     both violations;
//   - merge: a part that is not what the case computes is refused; an exit 0 must write exactly
//     the bytes of the unsharded run;
//   - a case file that is not a valid case (a key twice, in one table or in two, nesting, an
//     array, a directory) is refused, naming the file.
//
// Deterministic: a fixed seed (FLAPLAG_FUZZ_SEED overrides it) and a bounded budget per input
// kind: FLAPLAG_FILE_FUZZ_VECTORS vectors (default 200..400, at the TESTs below),
// FLAPLAG_FUZZ_JOBS at a time (default 2), each killed after FLAPLAG_FUZZ_TIMEOUT seconds
// (default 60: a hang).
// The enumeration of every string field (EveryStringFieldToPlot) is not a budget: it runs every
// field, with FLAPLAG_FILE_FUZZ_FIELD_PAYLOADS (1..3, default 3) payloads each.
// FLAPLAG_FUZZ_KEEP=1 keeps the directories of the runs that failed (their paths are printed).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "process.h"

#ifndef FLAPLAG_EXE
#error "FLAPLAG_EXE must name the flaplag binary"
#endif

extern char** environ;

namespace file_fuzz_test {

namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

constexpr rlim_t kMemoryCap = rlim_t{2} << 30;      // bytes of address space per run
constexpr rlim_t kFileSizeCap = rlim_t{256} << 20;  // bytes per file written by a run

using flaplag::testing::env_long;
using flaplag::testing::slurp;

void spit(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

// Text for a failure message: control and non-ASCII bytes escaped, long text abbreviated.
std::string shown(const std::string& s, std::size_t max = 400) {
  std::string o;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (o.size() > max) {
      o += "... (" + std::to_string(s.size()) + " bytes)";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '\n') {
      o += "\\n";
    } else if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      o += buf;
    } else {
      o += static_cast<char>(c);
    }
  }
  return o;
}

std::string shell_quoted(const std::vector<std::string>& args) {
  std::string s = "flaplag";
  for (const std::string& a : args) {
    bool plain = !a.empty();
    for (char c : a)
      plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_.:/=+,", c));
    if (plain) {
      s += " " + a;
    } else {
      std::string q = " '";
      for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
      s += q + "'";
    }
  }
  return shown(s, 600);
}

// ---- hostile strings ---------------------------------------------------------------------------

// Every payload starts and ends with "PWN": the gnuplot check below looks for that word outside
// single-quoted strings.  Its commands touch files in ../watch (the watched directory next to
// the run's working directory).
const std::vector<std::string>& payloads() {
  static const std::vector<std::string> p = {
      "PWN`touch ../watch/mark-backquote`PWN",
      "PWN'PWN",
      "PWN\"PWN",
      "PWN\\PWN",
      "PWN\\",
      "PWN\n!touch ../watch/mark-newline\nPWN",
      "PWN\" . system(\"touch ../watch/mark-system\") . \"PWN",
      "PWN' . system('touch ../watch/mark-system1') . 'PWN",
      "PWN@macro PWN",
      "PWN" + std::string(100000, 'x') + "PWN",
      "PWN\r\nset output '../watch/victim'\r\nPWN",
      std::string("PWN\0PWN", 7),
      "PWN\nEOD\n!touch ../watch/mark-eod\nPWN",
      "PWN'\nsystem('touch ../watch/mark-quote')\n'PWN",
  };
  return p;
}

// A payload that is not valid UTF-8 (inserted as raw bytes where a JSON string would be).
const char* const kNonUtf8 = "\"PWN\xff\xfe\x80 \xc3PWN\"";

// ---- the gnuplot script check ------------------------------------------------------------------

// "EOD" of a line "$name << EOD" (an inline data block follows, up to a line "EOD"), or "".
std::string heredoc_terminator(const std::string& line) {
  const auto word = [&](std::size_t& i) {
    const std::size_t start = i;
    while (i < line.size() && (std::isalnum(static_cast<unsigned char>(line[i])) || line[i] == '_'))
      ++i;
    return line.substr(start, i - start);
  };
  const auto blanks = [&](std::size_t& i) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  };
  std::size_t i = 0;
  blanks(i);
  if (i >= line.size() || line[i] != '$') return "";
  ++i;
  if (word(i).empty()) return "";
  blanks(i);
  if (line.compare(i, 2, "<<") != 0) return "";
  i += 2;
  blanks(i);
  const std::string end = word(i);
  blanks(i);
  return i == line.size() ? end : "";
}

// What in a gnuplot script a payload may never reach: outside a single-quoted string (code,
// comments, double-quoted strings — gnuplot runs backquotes in those — and inline data blocks)
// the word PWN, a backquote, "system" or '@' (a macro), and a line starting with '!' (a shell
// command).  A single-quoted string ends at its line's end (gnuplot has no multi-line strings);
// a line ending in a backslash continues on the next one (done first, as gnuplot reads lines).
std::vector<std::string> script_problems(const std::string& raw) {
  std::vector<std::string> p;
  const std::string script = replace_all(raw, "\\\n", "");
  std::istringstream in(script);
  std::string line, heredoc_end;
  int number = 0;
  auto unsafe = [&](const std::string& text, const std::string& where) {
    for (const char* bad : {"PWN", "`", "system", "@"}) {
      if (text.find(bad) != std::string::npos) {
        p.push_back(std::string("\"") + bad + "\" " + where + " (gnuplot script line " +
                    std::to_string(number) + "): " + shown(line, 200));
        return;
      }
    }
  };
  while (std::getline(in, line)) {
    ++number;
    if (!heredoc_end.empty()) {
      if (line == heredoc_end) {
        heredoc_end.clear();
      } else {
        unsafe(line, "in an inline data block");
      }
      continue;
    }
    if (const std::string end = heredoc_terminator(line); !end.empty()) {
      heredoc_end = end;
      continue;
    }
    std::string code, dquoted;
    const std::size_t first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line[first] == '!')
      p.push_back("a shell command (gnuplot script line " + std::to_string(number) +
                  "): " + shown(line, 200));
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (c == '\'') {
        std::size_t j = i + 1;
        for (; j < line.size(); ++j) {
          if (line[j] != '\'') continue;
          if (j + 1 < line.size() && line[j + 1] == '\'') {
            ++j;
            continue;
          }
          break;
        }
        if (j >= line.size()) {
          p.push_back("an unterminated single-quoted string (gnuplot script line " +
                      std::to_string(number) + "): " + shown(line, 200));
        }
        i = j;
      } else if (c == '"') {
        std::size_t j = i + 1;
        for (; j < line.size() && line[j] != '"'; ++j) {
          if (line[j] == '\\') ++j;
          if (j < line.size()) dquoted += line[j];
        }
        if (j >= line.size()) {
          p.push_back("an unterminated double-quoted string (gnuplot script line " +
                      std::to_string(number) + "): " + shown(line, 200));
        }
        i = j;
      } else {
        code += c;
      }
    }
    unsafe(code, "in gnuplot code");
    unsafe(dquoted, "in a double-quoted string");
  }
  return p;
}

// ---- the fake gnuplot and the real results -----------------------------------------------------

// The fake gnuplot appends what it was given (its argument files, other arguments as lines, and
// standard input) to $FLAPLAG_FUZZ_GNUPLOT_LOG.N and writes a tiny SVG on standard output.
const char* const kFakeGnuplot = R"(#!/bin/sh
log="${FLAPLAG_FUZZ_GNUPLOT_LOG:-/dev/null}"
n=0
while [ -e "$log.$n" ]; do n=$((n+1)); done
out="$log.$n"
: > "$out"
for a in "$@"; do
  if [ -f "$a" ]; then cat -- "$a" >> "$out"; else printf '%s\n' "$a" >> "$out"; fi
done
if [ ! -t 0 ]; then cat >> "$out"; fi
printf '<svg xmlns="http://www.w3.org/2000/svg" width="1" height="1"></svg>\n'
)";

struct Outcome {
  int exit_code = -1, signal = 0;
  bool timed_out = false;
  double seconds = 0.0;
  std::string out, err;
};

// One run of flaplag: `args` in `cwd`, standard input /dev/null, PATH with the fake gnuplot
// first, the address space capped (not under ASan), killed after `limit`.
Outcome run_flaplag(const std::vector<std::string>& args, const std::string& cwd,
                    const std::string& io_dir, const std::string& bin_dir,
                    const std::string& gnuplot_log, std::chrono::seconds limit) {
  Outcome r;
  const std::string out = io_dir + "/stdout", err = io_dir + "/stderr";
  std::string exe = FLAPLAG_EXE;
  std::vector<std::string> copy = args;
  std::vector<char*> argv{exe.data()};
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string s = *e;
    if (s.rfind("PATH=", 0) != 0 && s.rfind("FLAPLAG_FUZZ_GNUPLOT_LOG=", 0) != 0) env.push_back(s);
  }
  env.push_back("PATH=" + bin_dir + ":/usr/local/bin:/usr/bin:/bin");
  env.push_back("FLAPLAG_FUZZ_GNUPLOT_LOG=" + gnuplot_log);
  std::vector<char*> envp;
  for (std::string& s : env) envp.push_back(s.data());
  envp.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec (the parent has threads).
    const int in = ::open("/dev/null", O_RDONLY);
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (in < 0 || fo < 0 || fe < 0 || ::dup2(in, 0) < 0 || ::dup2(fo, 1) < 0 || ::dup2(fe, 2) < 0 ||
        ::chdir(cwd.c_str()) != 0)
      ::_exit(125);
    if (!FLAPLAG_TEST_ASAN) {
      struct rlimit lim {};
      lim.rlim_cur = lim.rlim_max = kMemoryCap;
      ::setrlimit(RLIMIT_AS, &lim);
    }
    // A file larger than this is a signal (SIGXFSZ), reported, instead of a full disk.
    struct rlimit size {};
    size.rlim_cur = size.rlim_max = kFileSizeCap;
    ::setrlimit(RLIMIT_FSIZE, &size);
    ::execve(exe.c_str(), argv.data(), envp.data());
    ::_exit(126);
  }
  if (pid < 0) {
    r.err = "fork failed";
    return r;
  }
  const flaplag::testing::ChildEnd end = flaplag::testing::wait_for_child(pid, start, limit);
  r.exit_code = end.exit_code;
  r.signal = end.signal;
  r.timed_out = end.timed_out;
  r.seconds = end.seconds;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// The scratch space of one test process: the fake gnuplot and the real results.
class Workspace {
 public:
  static Workspace& get() {
    static Workspace w;
    return w;
  }
  const std::string& base() const { return base_; }
  const std::string& bin() const { return bin_; }
  // The --json output of a real run (stdout), by name; failures are test failures.
  const std::string& seed(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = seeds_.find(name);
    if (it != seeds_.end()) return it->second;
    return seeds_[name] = make_seed(name);
  }
  ~Workspace() {
    if (env_long("FLAPLAG_FUZZ_KEEP", 0) > 0) return;  // the failed runs are kept in it
    std::error_code ec;
    fs::remove_all(base_, ec);
  }

 private:
  Workspace() {
    char tmpl[] = "/tmp/flaplag_file_fuzz.XXXXXX";
    const char* d = ::mkdtemp(tmpl);
    if (d == nullptr) throw std::runtime_error("mkdtemp failed");
    base_ = d;
    bin_ = base_ + "/bin";
    fs::create_directories(bin_);
    spit(bin_ + "/gnuplot", kFakeGnuplot);
    fs::permissions(bin_ + "/gnuplot", fs::perms::owner_all);
  }

  // Small and cheap: a few points each.
  std::string make_seed(const std::string& name) {
    static const std::map<std::string, std::vector<std::string>> kSeeds = {
        {"sweep", {"sweep", "--mu", "0:0.2:0.1", "--json"}},
        {"sweep-trimmed", {"--trim", "thrust", "sweep", "--mu", "0:0.1:0.1", "--json"}},
        {"sweep-plot", {"sweep", "--mu", "0:0.2:0.1", "--json", "--plot", "sweep.svg"}},
        {"study",
         {"study", "--vary", "omega-lag=0.6,1.4", "--mu-max", "0.3", "--scan-step", "0.1",
          "--json"}},
        {"study-1",
         {"study", "--vary", "omega-lag=0.6,1.4", "--mu-max", "0.3", "--scan-step", "0.1", "--json",
          "--shard", "1/2"}},
        {"study-2",
         {"study", "--vary", "omega-lag=0.6,1.4", "--mu-max", "0.3", "--scan-step", "0.1", "--json",
          "--shard", "2/2"}},
        {"map", {"map", "--x", "mu=0:0.2:0.1", "--y", "omega-lag=0.6:1.4:0.4", "--json"}},
        {"map-1",
         {"map", "--x", "mu=0:0.2:0.1", "--y", "omega-lag=0.6:1.4:0.4", "--json", "--shard",
          "1/2"}},
        {"map-2",
         {"map", "--x", "mu=0:0.2:0.1", "--y", "omega-lag=0.6:1.4:0.4", "--json", "--shard",
          "2/2"}},
        {"map-mu", {"map", "--x", "omega-lag=0.6,1.4", "--y", "mu=0:0.2:0.1", "--json"}},
        {"map-mu-1",
         {"map", "--x", "omega-lag=0.6,1.4", "--y", "mu=0:0.2:0.1", "--json", "--shard", "1/2"}},
        {"map-mu-2",
         {"map", "--x", "omega-lag=0.6,1.4", "--y", "mu=0:0.2:0.1", "--json", "--shard", "2/2"}},
        {"response", {"response", "--mu", "0.3", "--json"}},
        {"simulate", {"simulate", "--mu", "0.3", "--revs", "1", "--samples", "12", "--json"}},
        {"point", {"point", "--mu", "0.3", "--json"}},
        {"critical", {"critical", "--mu-max", "0.3", "--scan-step", "0.1", "--json"}},
        {"modes", {"modes", "--flap-modes", "2", "--points", "5", "--json"}},
        {"campbell", {"campbell", "--speeds", "3", "--harmonics", "2", "--json"}},
    };
    const auto it = kSeeds.find(name);
    if (it == kSeeds.end()) throw std::runtime_error("no seed " + name);
    const std::string dir = base_ + "/seed-" + name;
    fs::create_directories(dir);
    const Outcome o =
        run_flaplag(it->second, dir, dir, bin_, dir + "/gnuplot", std::chrono::seconds(300));
    if (o.exit_code != 0 || o.out.empty() || o.out[0] != '{') {
      ADD_FAILURE() << "the real result " << name
                    << " could not be made: " << shell_quoted(it->second) << " gave exit "
                    << o.exit_code << ": " << o.err;
    }
    return o.out;
  }

  std::string base_, bin_;
  std::mutex mutex_;
  std::map<std::string, std::string> seeds_;
};

// ---- vectors -----------------------------------------------------------------------------------

struct Input {
  std::string name;  // in the working directory
  std::string content;
  bool directory = false;
};

struct Vector {
  std::string kind;  // input kind and mutation, for the totals and the report
  std::string what;  // the mutation in words (the reproducer's description)
  std::vector<Input> inputs;
  std::vector<std::string> args;
  std::vector<std::string> outputs;  // paths typed (in the working directory): may be written
  std::string must_refuse;           // non-empty: exit 2 expected, for this reason
  bool must_succeed = false;         // an unmutated control: exit 0 expected
  std::string expected_output;       // non-empty: an exit 0 writes exactly this (merge)
  std::string error_must_name;       // non-empty: an exit-2 line holds this (a file, an option)
  bool plot_command = false;         // `flaplag plot`: exit 3 is allowed (gnuplot failed)
  std::string page;                  // `flaplag report`: the page written, checked for markup
};

struct Verdict {
  Outcome outcome;
  std::vector<std::string> problems;
  std::string kept;  // the run's directory, when kept
};

std::string listing_entry(const fs::directory_entry& e) {
  if (e.is_symlink()) return "symlink";
  if (e.is_directory()) return "directory";
  return slurp(e.path().string());
}

std::map<std::string, std::string> listing(const std::string& dir) {
  std::map<std::string, std::string> m;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    m[e.path().filename().string()] = listing_entry(e);
  return m;
}

// Exactly one line (ending in its newline) that starts with `prefix`.
bool one_line(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0 && text.size() > prefix.size() &&
         text.find('\n') == text.size() - 1;
}
const char* const kVictim = "a file nobody asked flaplag to touch\n";

Verdict run_vector(const Vector& v, std::size_t index, std::chrono::seconds limit) {
  Verdict verdict;
  std::vector<std::string>& p = verdict.problems;
  const std::string dir = Workspace::get().base() + "/run-" + std::to_string(index);
  const std::string work = dir + "/work", watch = dir + "/watch", logs = dir + "/gnuplot";
  fs::create_directories(work);
  fs::create_directories(watch);
  fs::create_directories(logs);
  spit(watch + "/victim", kVictim);
  for (const Input& in : v.inputs) {
    if (in.directory) {
      fs::create_directories(work + "/" + in.name);
    } else {
      spit(work + "/" + in.name, in.content);
    }
  }
  const std::map<std::string, std::string> before = listing(work);
  const Outcome o = run_flaplag(v.args, work, dir, Workspace::get().bin(), logs + "/script", limit);
  verdict.outcome = o;
  if (o.timed_out) p.push_back("hang: killed after " + std::to_string(o.seconds) + " s");
  if (o.signal != 0) p.push_back("killed by signal " + std::to_string(o.signal));
  const int code = o.exit_code;
  if (!o.timed_out && o.signal == 0) {
    if (code != 0 && code != 2 && !(code == 3 && v.plot_command)) {
      p.push_back("exit code " + std::to_string(code) + ", stderr: " + shown(o.err));
    } else if (code != 0) {
      if (!one_line(o.err, "flaplag: error: "))
        p.push_back("exit " + std::to_string(code) + " without one error line: [" + shown(o.err) +
                    "]");
      if (!o.out.empty()) p.push_back("stdout on exit " + std::to_string(code));
      if (!v.error_must_name.empty() && o.err.find(v.error_must_name) == std::string::npos)
        p.push_back("the error does not name " + v.error_must_name + ": " + shown(o.err));
    } else if (!o.err.empty() && !one_line(o.err, "flaplag: warning: ")) {
      p.push_back("exit 0 with stderr: " + shown(o.err));
    }
    if (!v.must_refuse.empty() && code == 0) p.push_back("accepted " + v.must_refuse);
    if (v.must_succeed && code != 0) p.push_back("an unmutated control failed: " + shown(o.err));
  }
  // Files: only the typed outputs may appear or change, and only on success.
  const std::map<std::string, std::string> after = listing(work);
  for (const auto& [name, content] : after) {
    const bool typed = std::find(v.outputs.begin(), v.outputs.end(), name) != v.outputs.end();
    const auto was = before.find(name);
    if (was == before.end()) {
      if (!typed || code != 0) p.push_back("wrote " + shown(name, 80) + " (not typed)");
      if (typed && code != 0)
        p.back() = "wrote " + shown(name, 80) + " on exit " + std::to_string(code);
    } else if (was->second != content && !(typed && code == 0)) {
      p.push_back("changed " + shown(name, 80));
    }
  }
  for (const auto& [name, content] : before)
    if (after.count(name) == 0) p.push_back("removed " + shown(name, 80));
  // What the command line asked for is there after an exit 0 (a picture may be missing with
  // its warning line).
  for (std::size_t i = 0; code == 0 && i + 1 < v.args.size(); ++i) {
    const bool picture = v.args[i] == "--plot";
    if ((v.args[i] == "-o" || picture) && after.count(v.args[i + 1]) == 0 &&
        !(picture && !o.err.empty()))
      p.push_back("exit 0 without the file asked for: " + v.args[i] + " " + v.args[i + 1]);
  }
  const std::map<std::string, std::string> watched = listing(watch);
  for (const auto& [name, content] : watched) {
    if (name == "victim") {
      if (content != kVictim) p.push_back("wrote outside its directory: ../watch/victim");
    } else {
      p.push_back("a command ran or a file was written outside: ../watch/" + shown(name, 80));
    }
  }
  if (watched.count("victim") == 0) p.push_back("removed ../watch/victim");
  // Merge: exactly the unsharded run.
  if (code == 0 && !v.expected_output.empty()) {
    std::string written = o.out;
    for (const std::string& name : v.outputs)
      if (after.count(name)) written = after.at(name);
    if (written != v.expected_output)
      p.push_back("exit 0 with an output other than the run's own (a tampered part accepted)");
  }
  // A report's page: the result's texts are text, nothing in it runs or loads.
  if (code == 0 && !v.page.empty() && after.count(v.page)) {
    const std::string& html = after.at(v.page);
    for (const char* tag : {"<script", "<img", "<iframe", "<object", "<embed", "<link", "<base",
                            "javascript:", "<a href=\"http"})
      if (html.find(tag) != std::string::npos)
        p.push_back(std::string("the page holds ") + tag + " (a text of the result as markup)");
    if (html.find("Content-Security-Policy\" content=\"default-src 'none'") == std::string::npos)
      p.push_back("the page lacks its Content-Security-Policy");
  }
  // JSON on stdout parses.
  if (code == 0 && !o.out.empty() && o.out[0] == '{' && !nlohmann::json::accept(o.out))
    p.push_back("exit 0 with malformed JSON on stdout");
  // The gnuplot scripts.
  for (const auto& [name, script] : listing(logs)) {
    for (const std::string& s : script_problems(script)) {
      if (p.size() < 12) p.push_back(s);
    }
  }
  if (!p.empty() && env_long("FLAPLAG_FUZZ_KEEP", 0) > 0) {
    verdict.kept = dir;
  } else {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  return verdict;
}

// ---- the generators ----------------------------------------------------------------------------

class Random {
 public:
  explicit Random(std::uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  std::size_t index(std::size_t n) {
    return static_cast<std::size_t>(integer(0, static_cast<int>(n) - 1));
  }
  bool chance(double p) { return uniform(0, 1) < p; }
  template <typename T>
  const T& pick(const std::vector<T>& v) {
    return v[index(v.size())];
  }
  std::string garbage(std::size_t n) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i) s += static_cast<char>(integer(0, 255));
    return s;
  }

 private:
  std::mt19937_64 rng_;
};

const std::vector<int> kDepths = {64, 1000, 20000, 50000, 100000};

std::string deep_json(int depth, bool objects) {
  std::string s;
  s.reserve(static_cast<std::size_t>(depth) * 6 + 8);
  for (int i = 0; i < depth; ++i) s += objects ? "{\"a\":" : "[";
  s += "1";
  for (int i = 0; i < depth; ++i) s += objects ? "}" : "]";
  return s;
}

std::string huge_json_array(std::size_t n) {
  std::string s = "[";
  for (std::size_t i = 0; i < n; ++i) s += i == 0 ? "0.5" : ",0.5";
  return s + "]";
}

// A unique string: a node replaced by it is later replaced, in the dumped text, by raw text
// (deep nesting, a huge array, a NaN token, bytes that are not UTF-8, a duplicated key).
const char* const kSlot = "FUZZ_SLOT_4711";

// Every node of a JSON document, as pointers.
void walk(const Json& j, const Json::json_pointer& at, std::vector<Json::json_pointer>& all) {
  all.push_back(at);
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) walk(it.value(), at / it.key(), all);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) walk(j[i], at / i, all);
  }
}

std::vector<Json::json_pointer> nodes(const Json& j, const std::function<bool(const Json&)>& keep,
                                      const std::string& under = "") {
  std::vector<Json::json_pointer> all, kept;
  walk(j, Json::json_pointer(), all);
  for (const auto& ptr : all)
    if (keep(j.at(ptr)) && ptr.to_string().rfind(under, 0) == 0 && !ptr.empty())
      kept.push_back(ptr);
  return kept;
}

// The reference tokens of a JSON pointer text ("/a/0/b" -> a, 0, b; ~1 and ~0 decoded).
std::vector<std::string> split_pointer(const std::string& text) {
  std::vector<std::string> tokens;
  std::size_t at = 0;
  while (at < text.size() && text[at] == '/') {
    const std::size_t end = text.find('/', at + 1);
    std::string t =
        text.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
    tokens.push_back(replace_all(replace_all(t, "~1", "/"), "~0", "~"));
    at = end == std::string::npos ? text.size() : end;
  }
  return tokens;
}

std::string dump(const Json& j) { return j.dump(2) + "\n"; }

// Which string fields the one-field mutations take next: a round robin over every string field
// of every result, so that each is covered.
struct Coverage {
  std::map<std::string, std::size_t> next;
  std::size_t take(const std::string& key, std::size_t n) { return n == 0 ? 0 : next[key]++ % n; }
};

// Mutations of a JSON document (a result or a case): one text, described in `what`.
// `under` restricts the node mutations to a subtree ("/case" for run).  `protect`: keys whose
// removal would make the run expensive (run reruns the case).
std::string mutate_json(Random& rnd, Coverage& cov, const std::string& seed_name, Json j,
                        const std::string& under, const std::set<std::string>& protect,
                        std::string& what, std::string& kind) {
  auto is_string = [](const Json& n) { return n.is_string(); };
  auto is_number = [](const Json& n) { return n.is_number(); };
  auto any = [](const Json&) { return true; };
  auto is_object = [](const Json& n) { return n.is_object(); };
  auto is_array = [](const Json& n) { return n.is_array(); };
  auto protected_key = [&](const Json::json_pointer& ptr) {
    return protect.count(ptr.back()) == 1;
  };
  const int choice = rnd.integer(0, 15);
  switch (choice) {
    case 0:
    case 1:
    case 2: {  // a payload in one string field (round robin over all of them)
      const auto strings = nodes(j, is_string, under);
      if (strings.empty()) break;
      const Json::json_pointer ptr = strings[cov.take(seed_name + under, strings.size())];
      const std::size_t k = rnd.index(payloads().size());
      j[ptr] = payloads()[k];
      kind = "hostile string (one field)";
      what = ptr.to_string() + " = payload " + std::to_string(k) + " " + shown(payloads()[k], 60);
      return dump(j);
    }
    case 3: {  // payloads in every string field
      const auto strings = nodes(j, is_string, under);
      if (strings.empty()) break;
      const std::size_t k = rnd.index(payloads().size());
      for (const auto& ptr : strings)
        j[ptr] = payloads()[(k + ptr.to_string().size()) % payloads().size()];
      kind = "hostile string (every field)";
      what = "every string field a payload (from payload " + std::to_string(k) + ")";
      return dump(j);
    }
    case 4: {  // a payload as a key
      const auto objects = nodes(j, is_object, under);
      if (objects.empty()) break;
      const auto& ptr = rnd.pick(objects);
      const std::size_t k = rnd.index(payloads().size());
      j[ptr][payloads()[k]] = 1;
      kind = "hostile key";
      what = ptr.to_string() + " gets key payload " + std::to_string(k);
      return dump(j);
    }
    case 5:
    case 6: {  // a wrong type anywhere
      auto all = nodes(j, any, under);
      if (all.empty()) break;
      const auto ptr = rnd.pick(all);
      static const std::vector<Json> kWrong = {nullptr,
                                               true,
                                               false,
                                               0,
                                               -1,
                                               1e308,
                                               -1e308,
                                               "",
                                               "word",
                                               "0.3",
                                               Json::array(),
                                               Json::object(),
                                               Json::array({1, "a", nullptr}),
                                               99999999999999999,
                                               Json::object({{"a", 1}}),
                                               -0.0,
                                               4294967297LL};
      const Json w = kWrong[rnd.index(kWrong.size())];
      if (protected_key(ptr) && (w.is_null() || w.is_boolean())) break;
      j[ptr] = w;
      kind = "wrong type";
      what = ptr.to_string() + " = " + w.dump();
      return dump(j);
    }
    case 7: {  // a number as a string, or a NaN-like token
      const auto numbers = nodes(j, is_number, under);
      if (numbers.empty()) break;
      const auto ptr = rnd.pick(numbers);
      if (rnd.chance(0.4)) {
        const std::string s = j[ptr].dump();
        j[ptr] = s;
        kind = "number as string";
        what = ptr.to_string() + " = \"" + s + "\"";
        return dump(j);
      }
      static const std::vector<std::string> kTokens = {
          "NaN", "nan", "Infinity", "-Infinity", "inf",     "1e999",   "-1e999",   "0x10",     "1.",
          ".5",  "+1",  "01",       "1e",        "\"NaN\"", "\"inf\"", "\"-nan\"", "\"1e999\""};
      const std::string t = rnd.pick(kTokens);
      j[ptr] = kSlot;
      kind = "NaN-like token";
      what = ptr.to_string() + " = " + t;
      return replace_all(dump(j), std::string("\"") + kSlot + "\"", t);
    }
    case 8: {  // a key deleted
      auto all = nodes(j, any, under);
      std::vector<Json::json_pointer> keys;
      for (const auto& ptr : all)
        if (j[ptr.parent_pointer()].is_object() && !protected_key(ptr)) keys.push_back(ptr);
      if (keys.empty()) break;
      const auto ptr = rnd.pick(keys);
      j[ptr.parent_pointer()].erase(ptr.back());
      kind = "key deleted";
      what = ptr.to_string() + " deleted";
      return dump(j);
    }
    case 9: {  // a key duplicated (in the text: the JSON reader keeps one of them)
      auto all = nodes(j, any, under);
      std::vector<Json::json_pointer> keys;
      for (const auto& ptr : all)
        if (j[ptr.parent_pointer()].is_object()) keys.push_back(ptr);
      if (keys.empty()) break;
      const auto ptr = rnd.pick(keys);
      Json& parent = j[ptr.parent_pointer()];
      const Json value = rnd.chance(0.5) ? parent[ptr.back()] : Json("PWN-duplicate");
      parent[kSlot] = value;
      kind = "key duplicated";
      what = ptr.to_string() + " twice (the second " + value.dump().substr(0, 60) + ")";
      return replace_all(dump(j), std::string("\"") + kSlot + "\"", Json(ptr.back()).dump());
    }
    case 10:
    case 11: {  // deep nesting in place of a node
      auto all = nodes(j, any, under);
      if (all.empty()) break;
      const auto ptr = rnd.pick(all);
      const int depth = rnd.pick(kDepths);
      const bool objects = rnd.chance(0.5);
      j[ptr] = kSlot;
      kind = "deep nesting";
      what = ptr.to_string() + " = " + std::to_string(depth) + " nested " +
             (objects ? "objects" : "arrays");
      return replace_all(dump(j), std::string("\"") + kSlot + "\"", deep_json(depth, objects));
    }
    case 12: {  // a huge array in place of an array (or any node)
      auto arrays = nodes(j, is_array, under);
      if (arrays.empty()) arrays = nodes(j, any, under);
      if (arrays.empty()) break;
      const auto ptr = rnd.pick(arrays);
      const std::size_t n = rnd.pick(std::vector<std::size_t>{10000, 100000, 1000000});
      j[ptr] = kSlot;
      kind = "huge array";
      what = ptr.to_string() + " = an array of " + std::to_string(n) + " numbers";
      return replace_all(dump(j), std::string("\"") + kSlot + "\"", huge_json_array(n));
    }
    case 13: {  // bytes that are not UTF-8 in a string field
      const auto strings = nodes(j, is_string, under);
      if (strings.empty()) break;
      const auto ptr = rnd.pick(strings);
      j[ptr] = kSlot;
      kind = "non-UTF-8 string";
      what = ptr.to_string() + " = " + shown(kNonUtf8);
      return replace_all(dump(j), std::string("\"") + kSlot + "\"", kNonUtf8);
    }
    case 14: {  // a very long string in a string field
      const auto strings = nodes(j, is_string, under);
      if (strings.empty()) break;
      const auto ptr = rnd.pick(strings);
      const std::size_t n = rnd.pick(std::vector<std::size_t>{4096, 1000000, 4000000});
      j[ptr] = "PWN" + std::string(n, 'y') + "PWN";
      kind = "long string";
      what = ptr.to_string() + " = a string of " + std::to_string(n) + " bytes";
      return dump(j);
    }
    default:
      break;
  }
  // The whole file: empty, truncated, garbage, not an object.
  const std::string text = dump(j);
  switch (rnd.integer(0, 3)) {
    case 0:
      kind = "empty file";
      what = "an empty file";
      return "";
    case 1: {
      const std::size_t n = rnd.index(text.size());
      kind = "truncated";
      what = "the first " + std::to_string(n) + " bytes";
      return text.substr(0, n);
    }
    case 2:
      kind = "binary garbage";
      what = "random bytes";
      return rnd.garbage(static_cast<std::size_t>(rnd.integer(1, 4096)));
    default:
      kind = "not an object";
      what = "a JSON array of the result";
      return "[" + text + "]";
  }
}

std::string seed_text(const std::string& name) { return Workspace::get().seed(name); }

Json seed_json(const std::string& name) {
  const std::string& t = seed_text(name);
  try {
    return Json::parse(t);
  } catch (const std::exception&) {
    return Json::object();
  }
}

// `flaplag plot` of a mutated result (sometimes two sweeps, with --label, --mode, --max-zeta).
Vector plot_vector(Random& rnd, Coverage& cov) {
  static const std::vector<std::string> kSeeds = {
      "sweep", "sweep-plot", "sweep-trimmed", "study", "map",     "map-mu",
      "map-1", "response",   "simulate",      "modes", "campbell"};
  Vector v;
  v.plot_command = true;
  const std::string seed = rnd.pick(kSeeds);
  std::string what, kind;
  Input in{"result.json", "", false};
  if (rnd.chance(0.03)) {
    in.directory = true;
    kind = "directory";
    what = "a directory";
  } else if (rnd.chance(0.1)) {
    in.content = seed_text(seed);  // the honest file, with hostile options below
    kind = "honest file";
    what = "unmutated";
  } else {
    in.content = mutate_json(rnd, cov, seed, seed_json(seed), "", {}, what, kind);
  }
  v.inputs.push_back(in);
  v.args = {"plot", "result.json"};
  const bool sweep = seed.rfind("sweep", 0) == 0;
  if (sweep && rnd.chance(0.3)) {
    v.inputs.push_back({"other.json", seed_text(rnd.chance(0.5) ? "sweep" : "sweep-trimmed")});
    v.args.push_back("other.json");
  }
  std::string options;
  if (rnd.chance(0.25)) {
    const std::size_t labels = v.inputs.size();
    for (std::size_t i = 0; i < labels; ++i) {
      const std::size_t k = rnd.index(payloads().size());
      v.args.insert(v.args.end(), {"--label", payloads()[k]});
      options += " --label payload " + std::to_string(k);
    }
  }
  if (rnd.chance(0.15)) {
    const std::size_t k = rnd.index(payloads().size());
    const std::string mode = rnd.chance(0.5) ? payloads()[k] : rnd.chance(0.5) ? "lag" : "flap";
    v.args.insert(v.args.end(), {"--mode", mode});
    options += " --mode " + shown(mode, 40);
  }
  if (rnd.chance(0.1)) v.args.push_back("--max-zeta");
  const std::string picture = rnd.chance(0.8) ? "o.svg" : "o.png";
  if (kind == "honest file" && options.empty() && rnd.chance(0.3)) {
    // A picture path in a directory that does not exist: refused naming --plot, nothing written.
    v.args.insert(v.args.end(), {"--plot", "missing/" + picture});
    v.must_refuse = "--plot in a missing directory";
    v.error_must_name = "--plot";
    options += " --plot missing/" + picture;
  } else {
    v.args.insert(v.args.end(), {"--plot", picture});
    v.outputs = {picture};
  }
  v.kind =
      "plot: " + kind + (options.find("payload") != std::string::npos ? " + hostile option" : "");
  v.what = seed + ".json: " + what + options;
  return v;
}

// `flaplag report RESULT.json -o o.html` of a mutated result: refused in one line, or a page on
// which every text of the result is text.
Vector report_vector(Random& rnd, Coverage& cov) {
  static const std::vector<std::string> kSeeds = {"sweep",    "sweep-trimmed", "study", "map",
                                                  "response", "simulate",      "modes", "campbell",
                                                  "point",    "critical"};
  Vector v;
  const std::string seed = rnd.pick(kSeeds);
  std::string what, kind;
  Input in{"result.json", "", false};
  if (rnd.chance(0.1)) {
    in.content = seed_text(seed);
    kind = "honest file";
    what = "unmutated";
    v.must_succeed = true;
  } else {
    in.content = mutate_json(rnd, cov, seed, seed_json(seed), "", {}, what, kind);
  }
  v.inputs.push_back(in);
  v.args = {"report", "result.json", "-o", "o.html"};
  v.outputs = {"o.html"};
  v.page = "o.html";
  v.kind = "report: " + kind;
  v.what = seed + ".json: " + what;
  return v;
}

// `flaplag run RESULT.json`: reruns the case; the case's output paths must not be followed.
Vector run_result_vector(Random& rnd, Coverage& cov) {
  static const std::vector<std::string> kSeeds = {
      "sweep", "sweep-plot", "study", "map", "map-1", "response", "simulate", "point", "critical"};
  // Keys whose removal (or null) turns a cheap case into a long one.
  static const std::set<std::string> kProtect = {"mu",     "mu-max", "scan-step", "x",
                                                 "y",      "vary",   "revs",      "samples",
                                                 "points", "shard",  "command"};
  Vector v;
  const std::string seed = rnd.pick(kSeeds);
  std::string what, kind;
  Json j = seed_json(seed);
  Input in{"received.json", "", false};
  const double r = rnd.uniform(0, 1);
  if (r < 0.25) {
    // The case names an output or a plot: a received file must not write anywhere.
    static const std::vector<std::string> kPaths = {"../watch/victim", "stolen.txt", "stolen.svg",
                                                    "../watch/new.svg", "received.json"};
    const std::string key = rnd.chance(0.5) ? "output" : "plot";
    const std::string path = rnd.pick(kPaths);
    if (j.contains("case") && j["case"].is_object()) j["case"][key] = path;
    in.content = dump(j);
    kind = "case names an output";
    what = "case." + key + " = \"" + path + "\"";
  } else if (r < 0.3) {
    in.content = seed_text(seed);
    kind = "honest file";
    what = "unmutated";
    v.must_succeed = true;
  } else {
    in.content =
        mutate_json(rnd, cov, seed, j, rnd.chance(0.7) ? "/case" : "", kProtect, what, kind);
  }
  v.inputs.push_back(in);
  v.args = {"run", "received.json"};
  if (rnd.chance(0.2)) {
    v.args.insert(v.args.end(), {"-o", "typed.json"});
    v.outputs.push_back("typed.json");
  }
  // A picture the user asks for draws the received file's strings.
  static const std::set<std::string> kPlottable = {"sweep", "sweep-plot", "study",   "map",
                                                   "map-1", "response",   "simulate"};
  if (kPlottable.count(seed) == 1 && rnd.chance(0.3)) {
    if (kind == "honest file" && rnd.chance(0.5)) {
      // Checked before the run: refused naming --plot, nothing written (not even -o).
      v.args.insert(v.args.end(), {"--plot", "missing/typed.svg"});
      v.must_refuse = "--plot in a missing directory";
      v.must_succeed = false;
      v.error_must_name = "--plot";
      what += ", --plot missing/typed.svg";
    } else {
      v.args.insert(v.args.end(), {"--plot", "typed.svg"});
      v.outputs.push_back("typed.svg");
    }
  }
  v.kind = "run result: " + kind;
  v.what = seed + ".json: " + what;
  return v;
}

// `flaplag merge` of two real parts, one (or both) mutated; exit 0 must give the unsharded run.
Vector merge_vector(Random& rnd, Coverage& cov) {
  static const std::vector<std::string> kJobs = {"map", "map-mu", "study"};
  const std::string job = rnd.pick(kJobs);
  Vector v;
  v.expected_output = seed_text(job);
  std::string what, kind;
  std::vector<Input> parts = {{"part-1.json", seed_text(job + "-1"), false},
                              {"part-2.json", seed_text(job + "-2"), false}};
  const std::size_t target = rnd.index(2);
  const double r = rnd.uniform(0, 1);
  if (r < 0.06) {
    kind = "honest parts";
    what = "unmutated";
    v.must_succeed = true;
  } else if (r < 0.4) {
    // Tampering a human would do: a cell, a label, an axis value, a row, a status.
    Json j = seed_json(job + "-" + std::to_string(target + 1));
    auto numbers = nodes(j, [](const Json& n) { return n.is_number(); });
    auto strings = nodes(j, [](const Json& n) { return n.is_string(); });
    const int t = rnd.integer(0, 4);
    kind = "tampered part";
    if (t <= 1 && !numbers.empty()) {
      const auto ptr = rnd.pick(numbers);
      const double x = j[ptr].get<double>();
      const double y = t == 0 ? x + 1e-3 : x * (1 + 1e-12) + 1e-300;
      j[ptr] = y;
      what = ptr.to_string() + " edited (" + j[ptr].dump() + ")";
    } else if (t == 2 && !strings.empty()) {
      const auto ptr = rnd.pick(strings);
      j[ptr] = rnd.pick(std::vector<std::string>{"lag", "flap", "ok", "failed", "warning",
                                                 "flutter", "periodic", "lag2", ""});
      what = ptr.to_string() + " = " + j[ptr].dump();
    } else if (t == 3) {
      j["status"] = rnd.pick(std::vector<Json>{5, "failed", "warning", nullptr, "ok"});
      what = "/status = " + j["status"].dump();
    } else {
      const std::string key = j.contains("rows") ? "rows" : "max_zeta";
      if (j.contains(key) && j[key].is_array() && !j[key].empty()) {
        j[key].push_back(j[key].back());
        j[key].erase(j[key].begin());
      }
      what = "/" + key + " rotated";
    }
    parts[target].content = dump(j);
  } else {
    parts[target].content =
        mutate_json(rnd, cov, job + "-" + std::to_string(target + 1),
                    seed_json(job + "-" + std::to_string(target + 1)), "", {}, what, kind);
  }
  if (rnd.chance(0.5)) std::swap(parts[0], parts[1]);
  v.inputs = parts;
  v.args = {"merge", parts[0].name, parts[1].name};
  if (rnd.chance(0.5)) {
    v.args.insert(v.args.end(), {"-o", "merged.json"});
    v.outputs = {"merged.json"};
  }
  v.kind = "merge: " + kind;
  v.what = job + " part-" + std::to_string(target + 1) + ": " + what;
  return v;
}

// Every string field of every plottable result (array elements as one field: all of them at
// once), each with the backquote payload, the quote-and-system() payload and one more in turn
// (FLAPLAG_FILE_FUZZ_FIELD_PAYLOADS below), and every mode label renamed everywhere:
// to `flaplag plot`, and the case's fields also to `flaplag run FILE --plot` (a picture the user
// asks for).  An enumeration, the same in every run.
std::vector<Vector> every_string_field_vectors() {
  // (sweep-plot and map-1 have the fields of sweep and map.)
  static const std::vector<std::string> kSeeds = {"sweep",    "sweep-trimmed", "study",
                                                  "map",      "map-mu",        "response",
                                                  "simulate", "modes",         "campbell"};
  // FLAPLAG_FILE_FUZZ_FIELD_PAYLOADS: 1 (one payload per field, in turn), 2 (and the backquote),
  // 3 (and the quote with system(); the default).
  const long payloads_per_field = std::min(env_long("FLAPLAG_FILE_FUZZ_FIELD_PAYLOADS", 3), 3L);
  std::vector<Vector> all;
  std::size_t turn = 0;
  for (const std::string& seed : kSeeds) {
    const Json j = seed_json(seed);
    std::map<std::string, std::vector<Json::json_pointer>> groups;
    for (const auto& ptr : nodes(j, [](const Json& n) { return n.is_string(); })) {
      std::string pattern;
      for (const std::string& token : split_pointer(ptr.to_string()))
        pattern += "/" + (token.find_first_not_of("0123456789") == std::string::npos ? "*" : token);
      groups[pattern].push_back(ptr);
    }
    // A mode label renamed consistently (the labels, the rows' keys, the exponents' labels).
    std::vector<std::pair<std::string, Json>> mutated;
    if (j.contains("labels") && j["labels"].is_array()) {
      for (const Json& label : j["labels"]) {
        const std::string l = label.get<std::string>();
        const std::size_t k = ++turn % payloads().size();
        const std::string& pay = payloads()[k];
        Json m = j;
        for (Json& e : m["labels"])
          if (e == l) e = pay;
        for (Json& row : m["rows"]) {
          if (row.contains(l)) {
            row[pay] = row[l];
            row.erase(l);
          }
          if (row.contains("exponents"))
            for (Json& e : row["exponents"])
              if (e.value("label", "") == l) e["label"] = pay;
        }
        mutated.push_back({"mode label " + l + " renamed everywhere = payload " +
                               std::to_string(k) + " " + shown(pay, 60),
                           m});
      }
    }
    for (const auto& [pattern, members] : groups) {
      const std::size_t rotating = ++turn % payloads().size();
      std::set<std::size_t> ks = {rotating};
      if (payloads_per_field > 1) ks.insert(0);
      if (payloads_per_field > 2) ks.insert(7);
      for (std::size_t k : ks) {
        Json m = j;
        for (const auto& ptr : members) m[ptr] = payloads()[k];
        mutated.push_back(
            {pattern + " = payload " + std::to_string(k) + " " + shown(payloads()[k], 60), m});
      }
    }
    const bool sweep = seed.rfind("sweep", 0) == 0;
    for (const auto& [what, m] : mutated) {
      // plot FILE; plot FILE OTHER (curves named from each file's case); run FILE --plot.
      for (int command = 0; command < 3; ++command) {
        if (command == 1 && !sweep) continue;
        if (command == 2 && what.rfind("/case/", 0) != 0) continue;
        Vector v;
        v.inputs.push_back({"result.json", dump(m), false});
        if (command == 0) {
          v.args = {"plot", "result.json", "--plot", "o.svg"};
          v.kind = "plot: every string field";
        } else if (command == 1) {
          v.inputs.push_back({"other.json", seed_text("sweep"), false});
          v.args = {"plot", "result.json", "other.json", "--plot", "o.svg"};
          v.kind = "plot two sweeps: every string field";
        } else {
          v.args = {"run", "result.json", "--plot", "o.svg"};
          v.kind = "run --plot: every string field of the case";
        }
        v.plot_command = command < 2;
        v.outputs = {"o.svg"};
        v.what = seed + ".json: " + what;
        all.push_back(v);
      }
    }
  }
  return all;
}

// ---- case files
// ----------------------------------------------------------------------------------

// Cheap valid cases: (TOML text, the output files it names).
struct CaseBase {
  std::string toml;
  std::vector<std::string> outputs;
};

const std::vector<CaseBase>& case_bases() {
  static const std::vector<CaseBase> b = {
      {"command = \"point\"\nmu = 0.3\n[parameters]\ntheta = 0.15\ngamma = 5.0\n", {}},
      {"command = \"sweep\"\n[parameters]\ntheta = 0.15\n[sweep]\nmu = \"0:0.2:0.1\"\n", {}},
      {"command = \"sweep\"\njson = true\n[sweep]\nmu = \"0:0.2:0.1\"\n[output]\noutput = "
       "\"out.json\"\nplot = \"out.svg\"\n",
       {"out.json", "out.svg"}},
      {"command = \"response\"\nmu = 0.3\n[plot]\nplot = \"tip.svg\"\n", {"tip.svg"}},
      {"command = \"critical\"\n[critical]\nmu-max = 0.3\nscan-step = 0.1\n[method]\nmethod = "
       "\"hsu\"\n",
       {}},
      {"command = \"system\"\nmu = 0.3\npsi = 1.0\nmodel = \"paper\"\n", {}},
      {"command = \"models\"\n", {}},
      {"command = \"study\"\n[study]\nvary = \"omega-lag=0.6,1.4\"\nmu-max = 0.3\nscan-step = "
       "0.1\n",
       {}},
      {"command = \"map\"\n[map]\nx = \"mu=0:0.2:0.1\"\ny = \"omega-lag=0.6,1.4\"\n[output]\n"
       "json = true\n",
       {}},
      {"command = \"simulate\"\nmu = 0.3\nrevs = 1\nsamples = 12\n", {}},
      {"command = \"trim\"\nmu = 0.2\nthrust-coefficient = 0.005\n", {}},
  };
  return b;
}

// A TOML basic string of any text (escaped as TOML requires).
std::string toml_string(const std::string& s) {
  std::string q = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      q += '\\';
      q += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      q += buf;
    } else {
      q += static_cast<char>(c);
    }
  }
  return q + "\"";
}

// `key = value` in place of the key's line when the case has one (a second line for the key
// would be a duplicate, another error), or as the first line.
std::string set_key(const std::string& toml, const std::string& key, const std::string& value) {
  std::istringstream in(toml);
  std::string out, line;
  bool done = false;
  while (std::getline(in, line)) {
    if (!done && line.rfind(key + " = ", 0) == 0) {
      line = key + " = " + value;
      done = true;
    }
    out += line + "\n";
  }
  return done ? out : key + " = " + value + "\n" + toml;
}

Vector case_vector(Random& rnd, Coverage& cov) {
  Vector v;
  bool names_file = true;
  const CaseBase& base = rnd.pick(case_bases());
  std::string toml = base.toml;
  std::string what, kind;
  v.outputs = base.outputs;
  std::string name = "case.toml";
  // Options taking a string, with values that are hostile (they may be refused or draw).
  static const std::vector<std::string> kStringKeys = {"model", "mode", "vary",   "x",
                                                       "y",     "trim", "method", "format",
                                                       "label", "spec", "mu",     "command"};
  static const std::vector<std::string> kNumberKeys = {"gamma", "theta", "mu",    "omega-lag",
                                                       "sigma", "steps", "mu-max"};
  // Now and then sizes that are legal one by one but too large together (a 10^4 x 10^4 map,
  // 10^9 simulation samples): refused before the run, or run within the caps (memory, time,
  // output size).  Not under AddressSanitizer: without the memory cap they would take the
  // machine's memory (pass 1 of the CI runs them).
  const bool huge = rnd.chance(0.01) && !FLAPLAG_TEST_ASAN;
  const int choice = huge ? -1 : rnd.integer(0, 19);
  switch (choice) {
    case -1:
      kind = "huge legal size";
      toml = rnd.chance(0.5) ? "command = \"map\"\n[map]\nx = \"mu=0:1.9998:0.0002\"\ny = "
                               "\"omega-lag=0.2:2.4997:0.00023\"\n"
                             : "command = \"simulate\"\nmu = 0.3\nrevs = 100000\nsamples = 10000\n";
      what = "a huge computation of legal sizes";
      v.outputs.clear();
      break;
    case 0:
      kind = "unknown key";
      toml += rnd.pick(std::vector<std::string>{
          "bogus = 1\n", "\"a`b\" = 1\n", "[parameters]\nnot-a-parameter = 2\n",
          "[bogus]\ngamma = 5\n", "[[parameters]]\n", "\"\" = 1\n", "-- = 1\n"});
      what = "an unknown key or table";
      v.must_refuse = "an unknown key";
      break;
    case 1:
    case 2: {
      kind = "wrong type";
      const std::string key = rnd.pick(rnd.chance(0.5) ? kStringKeys : kNumberKeys);
      const std::string value = rnd.pick(std::vector<std::string>{
          "[1, 2]", "{ a = 1 }", "1979-05-27T07:32:00Z", "07:32:00", "true", "false", "[]", "{}",
          "[[1], [\"a\"]]", "-0", "0x10", "1e308", "\"\""});
      toml = set_key(toml, key, value);
      what = key + " = " + value;
      if (value[0] == '[' || value[0] == '{' || value.find(':') != std::string::npos)
        v.must_refuse = "an array, table or date as a value";
      break;
    }
    case 3: {  // the same key twice in one table
      kind = "duplicate key (one table)";
      toml += "[parameters]\ngamma = 5.0\ngamma = 6.0\n";
      what = "[parameters] gamma twice";
      v.must_refuse = "a key twice in one table";
      break;
    }
    case 4:
    case 5: {  // the same key in two tables (file order would not decide)
      kind = "duplicate key (two tables)";
      // A key and tables the base does not have (a table defined twice is another error).
      std::vector<std::string> keys;
      for (const char* k : {"gamma", "theta", "omega-lag", "sigma", "damping-lag"})
        if (toml.find(std::string(k) + " =") == std::string::npos) keys.push_back(k);
      const std::string key = rnd.pick(keys);
      std::vector<std::string> tables = {""};
      for (const char* t :
           {"[parameters]\n", "[blade]\n", "[method]\n", "[analysis]\n", "[output]\n", "[plot]\n"})
        if (toml.find(t) == std::string::npos) tables.push_back(t);
      const std::size_t a = rnd.index(tables.size());
      std::size_t b = rnd.index(tables.size());
      if (tables.size() > 1 && a == b) b = (a + 1) % tables.size();
      const auto place = [&](const std::string& table, const char* value) {
        if (table.empty()) {
          toml = key + " = " + value + "\n" + toml;  // before the first table
        } else {
          toml += table + key + " = " + value + "\n";
        }
      };
      place(tables[a], "5.0");
      place(tables[b], "6.0");
      what = key + " in " +
             (tables[a].empty() ? "the top table" : tables[a].substr(0, tables[a].size() - 1)) +
             " and " +
             (tables[b].empty() ? "the top table" : tables[b].substr(0, tables[b].size() - 1));
      v.must_refuse = "the same key in two tables";
      break;
    }
    case 6:
    case 7: {  // deep nesting
      kind = "deep nesting";
      const int depth = rnd.pick(kDepths);
      const int form = rnd.integer(0, 2);
      std::string s;
      if (form == 0) {
        s = "a";
        for (int i = 0; i < depth; ++i) s += ".a";
        s += " = 1\n";
        what = std::to_string(depth) + " dotted keys";
      } else {
        s = "gamma = ";
        for (int i = 0; i < depth; ++i) s += form == 1 ? "{ a = " : "[";
        s += "1";
        for (int i = 0; i < depth; ++i) s += form == 1 ? " }" : "]";
        s += "\n";
        what = std::to_string(depth) + (form == 1 ? " nested inline tables" : " nested arrays");
      }
      toml = s + toml;
      v.must_refuse = "nesting";
      break;
    }
    case 8: {  // a huge array
      kind = "huge array";
      const std::size_t n = rnd.pick(std::vector<std::size_t>{10000, 100000, 1000000});
      std::string s = "theta = [";
      for (std::size_t i = 0; i < n; ++i) s += i == 0 ? "0.1" : ", 0.1";
      toml = s + "]\n" + toml;
      what = "theta = an array of " + std::to_string(n);
      v.must_refuse = "an array as a value";
      break;
    }
    case 9:
    case 10:
    case 11: {  // a hostile string as a value
      kind = "hostile string";
      const std::string key = kStringKeys[cov.take("case-keys", kStringKeys.size())];
      const std::size_t k = rnd.index(payloads().size());
      toml = set_key(toml, key, toml_string(payloads()[k]));
      what = key + " = payload " + std::to_string(k) + " " + shown(payloads()[k], 60);
      break;
    }
    case 12: {
      kind = "NaN-like value";
      const std::string key = rnd.pick(kNumberKeys);
      const std::string value =
          rnd.pick(std::vector<std::string>{"nan", "+inf", "-inf", "-nan", "\"nan\"", "\"inf\"",
                                            "1e999", "99999999999999999999", "\"1e999\""});
      toml = set_key(toml, key, value);
      what = key + " = " + value;
      v.must_refuse = "a value that is not a finite number";
      break;
    }
    case 13:
      kind = "empty command";
      toml = "command = \"\"\n" + replace_all(toml, "command = ", "# command = ");
      what = "command = \"\"";
      break;
    case 14:
      kind = "empty file";
      toml = "";
      what = "an empty file";
      v.outputs.clear();
      break;
    case 15:
      kind = "directory";
      what = "a directory";
      v.must_refuse = "a directory as a case file";
      break;
    case 16:
      kind = "binary garbage";
      toml = rnd.garbage(static_cast<std::size_t>(rnd.integer(1, 4096)));
      what = "random bytes";
      v.outputs.clear();
      break;
    case 17: {
      kind = "truncated";
      const std::size_t n = rnd.index(toml.size());
      toml = toml.substr(0, n);
      what = "the first " + std::to_string(n) + " bytes";
      names_file = false;  // a valid case that lacks an option: the option is named
      break;
    }
    case 18: {
      kind = "long string";
      const std::size_t n = rnd.pick(std::vector<std::size_t>{4096, 1000000, 4000000});
      toml = set_key(toml, "model", "\"" + std::string(n, 'm') + "\"");
      what = "model = a string of " + std::to_string(n);
      v.must_refuse = "an unknown model";
      break;
    }
    default: {
      // A JSON case: {"case": {...}} of a real result, mutated (no output keys are typed).
      name = "case.json";
      const std::string seed =
          rnd.pick(std::vector<std::string>{"sweep", "point", "response", "critical", "simulate"});
      Json j = seed_json(seed);
      Json c = j.contains("case") ? j["case"] : Json::object();
      static const std::set<std::string> kProtect = {"mu",   "mu-max",  "scan-step",
                                                     "revs", "samples", "command"};
      toml =
          mutate_json(rnd, cov, "case-" + seed, Json{{"case", c}}, "/case", kProtect, what, kind);
      kind = "JSON case: " + kind;
      what = seed + " case: " + what;
      v.outputs.clear();
      break;
    }
  }
  if (names_file) v.error_must_name = name;
  Input in{name, toml, kind == "directory"};
  v.inputs.push_back(in);
  v.args = {"run", name};
  if (rnd.chance(0.1)) {
    v.args.insert(v.args.end(), {"-o", "typed.txt"});
    v.outputs.push_back("typed.txt");
  }
  v.kind = (name == "case.json" ? "" : "TOML case: ") + kind;
  v.what = name + ": " + what;
  return v;
}

// ---- the driver
// ----------------------------------------------------------------------------------

std::string reproducer(const Vector& v) {
  std::string s = "  " + v.what + "\n  cd DIR && " + shell_quoted(v.args) + "\n";
  for (const Input& in : v.inputs) {
    s += "  " + in.name + ": " + (in.directory ? "(a directory)" : shown(in.content, 300)) + "\n";
  }
  return s;
}

// A violation class for the totals: the problem without its specifics.
std::string problem_class(const std::string& problem) {
  std::string c = problem.substr(0, std::min<std::size_t>(problem.find(':'), 80));
  static const std::regex kNumbers("[0-9]+");
  c = std::regex_replace(c, kNumbers, "N");
  return c.substr(0, 80);
}

struct Summary {
  std::string kind, reproducer, args;
  Verdict verdict;
};

// `fixed`: exactly default_vectors (an enumeration, not a budget).
void fuzz(const char* name, long default_vectors,
          const std::function<Vector(Random&, Coverage&)>& make, bool fixed = false) {
  const long vectors =
      fixed ? default_vectors : env_long("FLAPLAG_FILE_FUZZ_VECTORS", default_vectors);
  const long jobs = env_long("FLAPLAG_FUZZ_JOBS", 2);
  const std::uint64_t seed = static_cast<std::uint64_t>(env_long("FLAPLAG_FUZZ_SEED", 19740601));
  const std::chrono::seconds limit(env_long("FLAPLAG_FUZZ_TIMEOUT", 60));
  Random rnd(seed ^ std::hash<std::string>{}(name));
  Coverage cov;
  // Vectors are made one at a time, in order, under a lock (the same vectors for a seed
  // whatever the jobs), and dropped after their run (some inputs are tens of megabytes).
  std::mutex generator;
  long made = 0;
  std::vector<Summary> results(static_cast<std::size_t>(vectors));
  static std::atomic<std::size_t> run_number{0};
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> workers;
  for (long w = 0; w < jobs; ++w) {
    workers.emplace_back([&] {
      for (;;) {
        Vector v;
        std::size_t i = 0;
        {
          std::lock_guard<std::mutex> lock(generator);
          if (made >= vectors) return;
          i = static_cast<std::size_t>(made++);
          v = make(rnd, cov);
        }
        Summary& s = results[i];
        s.kind = v.kind;
        s.args = shell_quoted(v.args);
        s.verdict = run_vector(v, run_number++, limit);
        if (!s.verdict.problems.empty()) s.reproducer = reproducer(v);
        s.verdict.outcome.out = s.verdict.outcome.out.substr(0, 200);
        s.verdict.outcome.err = s.verdict.outcome.err.substr(0, 400);
      }
    });
  }
  for (std::thread& t : workers) t.join();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::map<std::string, int> kinds, exits, classes;
  std::map<std::string, std::string> first_of_class;
  int violations = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Summary& s = results[i];
    const Verdict& r = s.verdict;
    ++kinds[s.kind];
    const int code = r.outcome.timed_out ? -2 : r.outcome.signal != 0 ? -1 : r.outcome.exit_code;
    ++exits["exit " + std::to_string(code)];
    if (r.problems.empty()) continue;
    ++violations;
    std::string text;
    for (const std::string& p : r.problems) {
      text += "\n    " + p;
      const std::string c = s.kind + " | " + problem_class(p);
      if (classes[c]++ == 0) first_of_class[c] = s.reproducer;
    }
    ADD_FAILURE() << name << " vector " << i << " (" << s.kind << ")" << text << "\n"
                  << s.reproducer << (r.kept.empty() ? "" : "  kept in " + r.kept + "\n");
  }
  std::vector<std::size_t> order(results.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return results[a].verdict.outcome.seconds > results[b].verdict.outcome.seconds;
  });
  std::printf(
      "file fuzz %s: seed %llu, %ld vectors, %ld jobs, %.1f s wall, memory cap %s; %d "
      "violations\n",
      name, static_cast<unsigned long long>(seed), vectors, jobs, wall,
      FLAPLAG_TEST_ASAN ? "off (AddressSanitizer)" : "1 GiB", violations);
  for (const auto& [k, n] : exits) std::printf("  %s: %d\n", k.c_str(), n);
  for (const auto& [k, n] : kinds) std::printf("  %s: %d\n", k.c_str(), n);
  for (const auto& [c, n] : classes)
    std::printf("  violation class (%d): %s\n%s", n, c.c_str(), first_of_class[c].c_str());
  for (std::size_t i = 0; i < std::min<std::size_t>(3, order.size()); ++i)
    std::printf("  slow: %.2f s  %s\n", results[order[i]].verdict.outcome.seconds,
                results[order[i]].args.c_str());
  std::fflush(stdout);
}

// The checker itself: what it must accept and refuse.
TEST(FileFuzz, GnuplotScriptCheckFindsUnquotedPayloads) {
  EXPECT_TRUE(script_problems("set title 'a PWN`x`PWN b'\nplot $d title 'it''s PWN'\n").empty());
  EXPECT_TRUE(script_problems("$d << EOD\n1 2\nEOD\nplot $d using 1:2 title 'x'\n").empty());
  // What a correct quoting makes of the quote-and-system() payload: one string.
  EXPECT_TRUE(script_problems("set title 'PWN'' . system(''touch x'') . ''PWN: flap'\n").empty());
  EXPECT_FALSE(script_problems("set title \"a PWN`touch x`PWN\"\n").empty());
  EXPECT_FALSE(script_problems("set title 'PWN' . system('touch x') . 'PWN'\n").empty());
  EXPECT_FALSE(script_problems("set title 'PWN\n!touch x\nPWN'\n").empty());
  EXPECT_TRUE(script_problems("set title 'a\\\nb'\n").empty());  // a continued line
  EXPECT_FALSE(script_problems("set title 'x'\\\n@macro\n").empty());
  EXPECT_FALSE(script_problems("$d << EOD\nPWN\nEOD\n").empty());
  EXPECT_FALSE(script_problems("set title 'unterminated\n").empty());
}

TEST(FileFuzz, CaseFiles) { fuzz("case files", 300, case_vector); }

TEST(FileFuzz, ResultFilesToPlot) { fuzz("results to plot", 400, plot_vector); }

TEST(FileFuzz, EveryStringFieldToPlot) {
  const std::vector<Vector> all = every_string_field_vectors();
  std::size_t next = 0;
  fuzz(
      "every string field", static_cast<long>(all.size()),
      [&](Random&, Coverage&) { return all[next++]; }, true);
}

TEST(FileFuzz, ResultFilesToReport) { fuzz("results to report", 150, report_vector); }

TEST(FileFuzz, ResultFilesToRun) { fuzz("results to run", 200, run_result_vector); }

TEST(FileFuzz, ResultFilesToMerge) { fuzz("results to merge", 300, merge_vector); }

}  // namespace

}  // namespace file_fuzz_test
