// What a received file or a typed text can make flaplag do, run as a user would: a result file
// given to `flaplag plot` (every string in it hostile), --label, the gnuplot script that reaches
// gnuplot, symbolic links planted by another user in a sticky directory, output paths checked
// before computing, -o to an open descriptor (/dev/stdout into a pipe), a full standard output,
// and SIGTERM during a study.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "process.h"

namespace cli_security_test {

namespace {

using Json = nlohmann::json;

using flaplag::testing::Outcome;
using flaplag::testing::slurp;
using flaplag::testing::TempDir;

Outcome run(const std::vector<std::string>& args, const std::string& path_env = "") {
  return flaplag::testing::run_process(FLAPLAG_EXE, args, std::chrono::seconds(300), path_env);
}

bool gnuplot_available() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

std::string path_env() {
  const char* p = std::getenv("PATH");
  return p != nullptr ? p : "/usr/bin:/bin";
}

// ---- hostile strings ---------------------------------------------------------------------------

// Texts that would run `touch MARK` if any of them were pasted into gnuplot code: a backquote
// (shell command substitution), breaking out of a single- or double-quoted string, a line break
// that starts a new command (also gnuplot's "!" shell escape), system(), and a macro.
std::vector<std::string> payloads(const std::string& mark) {
  const std::string t = "touch " + mark;
  return {"a`" + t + "`b",
          "a'b`" + t + "`c'",
          "a' . system('" + t + "') . 'b",
          "a\" . system(\"" + t + "\") . \"b",
          "a\\' ; system('" + t + "') #\\",
          "a\nsystem('" + t + "')\nb",
          "a\r!" + t + "\rb",
          "a'\n!" + t + "\n'",
          "@x",
          "a @x ` @x",
          "x = system(\"" + t + "\")"};
}

// Every string value of j (keys as a path "a.b[2]") but "command", which says what the file is;
// of an array of objects or arrays (rows) only the first element's (the others have the same
// keys).
void string_paths(const Json& j, const std::string& at, std::vector<Json::json_pointer>& out,
                  const Json::json_pointer& ptr) {
  if (j.is_string()) {
    if (at != "command") out.push_back(ptr);
  } else if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it)
      string_paths(it.value(), at.empty() ? it.key() : at + "." + it.key(), out, ptr / it.key());
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) {
      if (i > 0 && (j[i].is_object() || j[i].is_array())) break;
      string_paths(j[i], at + "[" + std::to_string(i) + "]", out, ptr / i);
    }
  }
}

// A sweep result keys its rows by its mode labels: rows whose keys follow hostile labels
// (a key k becomes k + payload where the labels hold that).
Json rows_follow_labels(Json j, const std::string& payload) {
  if (j["command"] != "sweep") return j;
  for (Json& row : j["rows"]) {
    Json renamed = Json::object();
    for (auto it = row.begin(); it != row.end(); ++it) {
      bool relabelled = false;
      for (const Json& l : j["labels"]) relabelled = relabelled || l == it.key() + payload;
      renamed[relabelled ? it.key() + payload : it.key()] = it.value();
    }
    row = renamed;
  }
  return j;
}

// The results flaplag plot draws, written once for all tests.
class Results : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    const std::vector<std::pair<std::string, std::vector<std::string>>> commands = {
        {"sweep", {"sweep", "--mu", "0:0.2:0.1"}},
        {"study", {"study", "--vary", "omega-lag=1.0,1.3", "--mu-max", "0.6"}},
        {"map", {"map", "--x", "mu=0:0.4:0.2", "--y", "omega-lag=1,1.3"}},
        {"response", {"response", "--mu", "0.3"}},
        {"simulate", {"simulate", "--mu", "0.3", "--revs", "2"}},
        {"modes", {"modes", "--flap-modes", "2", "--points", "5"}},
        {"campbell", {"campbell", "--speeds", "3", "--harmonics", "2"}}};
    for (const auto& [name, args] : commands) {
      std::vector<std::string> a = args;
      const std::string file = dir_->file(name + ".json");
      a.insert(a.end(), {"--json", "-o", file});
      const Outcome r = run(a);
      ASSERT_EQ(0, r.exit_code) << name << ": " << r.err;
      files_.push_back(file);
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
    files_.clear();
  }
  static TempDir* dir_;
  static std::vector<std::string> files_;  // sweep ... simulate, modes, campbell
};
TempDir* Results::dir_ = nullptr;
std::vector<std::string> Results::files_;

// A fake gnuplot first on PATH that keeps the script it is given and answers with an image.
class FakeGnuplot {
 public:
  FakeGnuplot() {
    const std::string exe = dir_.file("gnuplot");
    std::ofstream(exe) << "#!/bin/sh\ncat >> '" << log() << "'\ncat /proc/$PPID/comm >> '"
                       << parents() << "'\nprintf '<svg></svg>'\n";
    ::chmod(exe.c_str(), 0755);
  }
  std::string path() const { return dir_.path() + ":" + path_env(); }
  std::string log() const { return dir_.file("scripts.gp"); }
  // The names of the processes that started it, one a line.
  std::string parents() const { return dir_.file("parents"); }
  // The scripts received so far, then forgotten.
  std::string take() {
    const std::string s = slurp(log());
    std::remove(log().c_str());
    return s;
  }

 private:
  TempDir dir_;
};

// A gnuplot script read as gnuplot reads it: outside datablocks, each line's code (outside
// strings) and its single-quoted strings ('' is one quote).  Fails the test on anything but
// plain code and single-quoted strings: a double-quoted string (backquotes are expanded there),
// an unterminated string, a control character, a backquote, "@" or "system" in code, a line
// starting with "!" (a shell command), or a datablock line that is not numbers.
struct ReadScript {
  std::vector<std::string> code, strings;
};

ReadScript read_script(const std::string& script) {
  ReadScript r;
  std::istringstream in(script);
  std::string line, block_end;
  const std::regex numbers("[-+0-9.eEaNn ]*");
  while (std::getline(in, line)) {
    if (!block_end.empty()) {
      if (line == block_end)
        block_end.clear();
      else
        EXPECT_TRUE(std::regex_match(line, numbers)) << "datablock line: " << line;
      continue;
    }
    const auto heredoc = line.find(" << ");
    if (!line.empty() && line[0] == '$' && heredoc != std::string::npos) {
      block_end = line.substr(heredoc + 4);
      continue;
    }
    EXPECT_FALSE(!line.empty() && line[0] == '!') << line;
    std::string code;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << "control character";
      if (c == '"') {
        ADD_FAILURE() << "double-quoted string in: " << line;
        break;
      }
      if (c != '\'') {
        code += c;
        continue;
      }
      std::string s;
      bool closed = false;
      for (++i; i < line.size(); ++i) {
        if (line[i] == '\'' && i + 1 < line.size() && line[i + 1] == '\'') {
          s += '\'';
          ++i;
        } else if (line[i] == '\'') {
          closed = true;
          break;
        } else {
          s += line[i];
        }
      }
      EXPECT_TRUE(closed) << "unterminated string in: " << line;
      r.strings.push_back(s);
      code += "''";
    }
    EXPECT_EQ(std::string::npos, code.find('`')) << line;
    EXPECT_EQ(std::string::npos, code.find('@')) << line;
    EXPECT_EQ(std::string::npos, code.find("system")) << line;
    EXPECT_EQ(std::string::npos, code.find("touch")) << line;
    r.code.push_back(code);
  }
  EXPECT_TRUE(block_end.empty()) << "unterminated datablock";
  return r;
}

// What quoting keeps of a text: control characters become blanks.
std::string as_quoted(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return s;
}

// ---- gnuplot cannot be made to run anything ----------------------------------------------------

// Every string of every kind of result, each payload in every string at once, and three of them
// (backquote, quote breakout, line break) in one string at a time: the real gnuplot draws
// (exit 0) or flaplag refuses the file naming it and the key (exit 2); nothing runs.
TEST_F(Results, HostileStringsInAResultRunNothing) {
  TempDir d;
  const std::string mark = d.file("MARK"), svg = d.file("o.svg");
  const bool real = gnuplot_available();
  FakeGnuplot fake;
  int drawn = 0, refused = 0;
  for (const std::string& file : files_) {
    const Json original = Json::parse(slurp(file));
    std::vector<Json::json_pointer> strings;
    string_paths(original, "", strings, Json::json_pointer());
    ASSERT_FALSE(strings.empty()) << file;
    const std::vector<std::string> all_payloads = payloads(mark);
    for (std::size_t k = 0; k < all_payloads.size(); ++k) {
      const std::string& payload = all_payloads[k];
      const bool one_at_a_time = k == 0 || k == 2 || k == 5;
      // All at once (real gnuplot, if installed), then one string at a time (the fake).
      std::vector<std::pair<Json, bool>> variants;
      Json all = original;
      for (const auto& p : strings) all[p] = all[p].get<std::string>() + payload;
      variants.emplace_back(rows_follow_labels(all, payload), real);
      for (const auto& p : strings) {
        if (!one_at_a_time) break;
        Json one = original;
        one[p] = one[p].get<std::string>() + payload;
        variants.emplace_back(rows_follow_labels(one, payload), false);
      }
      for (const auto& [j, use_real] : variants) {
        const std::string evil = d.file("evil.json");
        std::ofstream(evil) << j.dump();
        const Outcome r = run({"plot", evil, "--plot", svg}, use_real ? "" : fake.path());
        ASSERT_FALSE(flaplag::testing::exists(mark)) << payload << "\n" << j.dump();
        ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.exit_code << r.err;
        if (r.exit_code == 2) {
          ++refused;
          // One line naming the file and the key.
          EXPECT_TRUE(std::regex_match(
              r.err, std::regex("flaplag: error: argument = " + evil + ": key [^\n]*\n")))
              << r.err;
          EXPECT_FALSE(flaplag::testing::exists(svg));
        } else {
          ++drawn;
          EXPECT_TRUE(r.err.empty()) << r.err;
          std::remove(svg.c_str());
        }
        if (!use_real) read_script(fake.take());
      }
    }
  }
  // Both happen: fields that are not drawn are harmless, those that are get checked.
  EXPECT_GT(drawn, 0);
  EXPECT_GT(refused, 0);
}

// Each field flaplag draws is checked against what flaplag writes there, named in the refusal.
TEST_F(Results, DrawnNamesMustBeWhatFlaplagWrites) {
  TempDir d;
  const std::string svg = d.file("o.svg");
  FakeGnuplot fake;
  const struct {
    std::size_t file;
    const char* pointer;
    const char* key;
  } fields[] = {{0, "/model/name", "model.name"},
                {0, "/labels/0", "labels[0]"},
                {1, "/vary", "vary"},
                {2, "/x/name", "x.name"},
                {2, "/y/name", "y.name"},
                {6, "/labels/1", "labels[1]"}};
  for (const auto& f : fields) {
    Json j = Json::parse(slurp(files_[f.file]));
    const Json::json_pointer p(f.pointer);
    for (const std::string& bad : {std::string("paper cyclic"), std::string("flap'"),
                                   std::string("lag`id`"), std::string("")}) {
      j[p] = bad;
      const std::string evil = d.file("evil.json");
      std::ofstream(evil) << j.dump();
      const Outcome r = run({"plot", evil, "--plot", svg}, fake.path());
      EXPECT_EQ(2, r.exit_code) << f.key << " = " << bad;
      EXPECT_NE(std::string::npos, r.err.find("key " + std::string(f.key) + " = ")) << r.err;
      EXPECT_TRUE(fake.take().empty()) << "gnuplot ran for " << f.key;
    }
  }
  // case.trim labels the curves of several sweeps.
  Json j = Json::parse(slurp(files_[0]));
  j["case"]["trim"] = "moment`touch x`";
  const std::string evil = d.file("trim.json");
  std::ofstream(evil) << j.dump();
  const Outcome r = run({"plot", evil, files_[0], "--plot", svg}, fake.path());
  EXPECT_EQ(2, r.exit_code);
  EXPECT_NE(std::string::npos, r.err.find("key case.trim = ")) << r.err;
}

// --label: any text without control characters is drawn, single-quoted, exactly as typed; one
// with a control character is refused (exit 2); nothing runs either way.
TEST_F(Results, HostileLabelsRunNothing) {
  TempDir d;
  const std::string mark = d.file("MARK"), svg = d.file("o.svg");
  FakeGnuplot fake;
  for (const std::string& payload : payloads(mark)) {
    for (const bool real : {false, true}) {
      if (real && !gnuplot_available()) continue;
      const Outcome r =
          run({"plot", files_[0], "--label", payload, "--plot", svg}, real ? "" : fake.path());
      ASSERT_FALSE(flaplag::testing::exists(mark)) << payload;
      const bool control = as_quoted(payload) != payload;
      EXPECT_EQ(control ? 2 : 0, r.exit_code) << payload << r.err;
      if (control) {
        EXPECT_TRUE(std::regex_match(r.err, std::regex("flaplag: error: --label = [^\n]*\n")))
            << r.err;
        EXPECT_FALSE(flaplag::testing::exists(svg));
      }
      if (!real) {
        const ReadScript s = read_script(fake.take());
        bool found = false;
        for (const std::string& text : s.strings) found = found || text.find(payload) == 0;
        EXPECT_EQ(!control, found) << payload;
      }
      std::remove(svg.c_str());
    }
  }
  // --mode must name a mode of the sweep.
  const Outcome m =
      run({"plot", files_[0], "--mode", "flap`touch " + mark + "`", "--plot", svg}, fake.path());
  EXPECT_EQ(2, m.exit_code);
  EXPECT_FALSE(flaplag::testing::exists(mark));
}

// gnuplot is executed directly by flaplag (its parent process), not through a shell, and reads
// the whole script on its standard input.
TEST_F(Results, GnuplotRunsWithoutAShell) {
  TempDir d;
  FakeGnuplot fake;
  const std::string svg = d.file("o.svg");
  const Outcome r = run({"plot", files_[2], "--plot", svg}, fake.path());
  EXPECT_EQ(0, r.exit_code) << r.err;
  EXPECT_EQ("<svg></svg>", slurp(svg));
  EXPECT_EQ("flaplag\n", slurp(fake.parents()));
  const std::string script = fake.take();
  EXPECT_NE(std::string::npos, script.find("$map << EOD")) << script;
  EXPECT_NE(std::string::npos, script.find("unset table")) << script;
  read_script(script);
}

// ---- symbolic links in sticky directories ------------------------------------------------------

// Root, a sticky world-writable directory (as /tmp), a link planted there by nobody (uid 65534)
// pointing at root's file: -o and --plot refuse to follow it and the file is unchanged; root's
// own link in the same directory is followed.
TEST_F(Results, AnotherUsersLinkInAStickyDirectoryIsNotFollowed) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to create a link owned by another user";
  TempDir sticky, safe;
  ASSERT_EQ(0, ::chmod(sticky.path().c_str(), 01777));
  const std::string victim = safe.file("victim.txt"), picture = safe.file("victim.svg");
  std::ofstream(victim) << "root's file\n";
  std::ofstream(picture) << "root's picture\n";
  const std::string planted = sticky.file("out.txt"), planted_svg = sticky.file("out.svg");
  ASSERT_EQ(0, ::symlink(victim.c_str(), planted.c_str()));
  ASSERT_EQ(0, ::symlink(picture.c_str(), planted_svg.c_str()));
  ASSERT_EQ(0, ::lchown(planted.c_str(), 65534, 65534));
  ASSERT_EQ(0, ::lchown(planted_svg.c_str(), 65534, 65534));

  const Outcome o = run({"models", "-o", planted});
  EXPECT_EQ(2, o.exit_code);
  EXPECT_TRUE(std::regex_match(
      o.err, std::regex("flaplag: error: -o = " + planted + ": .*uid 65534.*not followed\n")))
      << o.err;
  EXPECT_EQ("root's file\n", slurp(victim));

  FakeGnuplot fake;
  const Outcome p = run({"plot", files_[0], "--plot", planted_svg}, fake.path());
  EXPECT_EQ(2, p.exit_code);
  EXPECT_TRUE(std::regex_match(
      p.err, std::regex("flaplag: error: --plot = " + planted_svg + ": .*not followed\n")))
      << p.err;
  EXPECT_EQ("root's picture\n", slurp(picture));
  const Outcome s = run({"sweep", "--mu", "0:0.1:0.1", "--plot", planted_svg}, fake.path());
  EXPECT_EQ(2, s.exit_code);
  EXPECT_NE(std::string::npos, s.err.find("--plot = ")) << s.err;
  EXPECT_EQ("root's picture\n", slurp(picture));

  // A planted link among the directories of the path, directly or behind root's own link.
  const std::string dir_link = sticky.file("d"), chain = sticky.file("chain");
  ASSERT_EQ(0, ::symlink(safe.path().c_str(), dir_link.c_str()));
  ASSERT_EQ(0, ::lchown(dir_link.c_str(), 65534, 65534));
  ASSERT_EQ(0, ::symlink("d", chain.c_str()));
  for (const std::string& through : {dir_link + "/victim.txt", dir_link + "/new.txt",
                                     chain + "/victim.txt", chain + "/./new.txt"}) {
    const Outcome t = run({"models", "-o", through});
    EXPECT_EQ(2, t.exit_code) << through;
    EXPECT_TRUE(
        std::regex_match(t.err, std::regex("flaplag: error: -o = " + through + ": symbolic link " +
                                           dir_link + " owned by uid 65534 .*not followed\n")))
        << t.err;
  }
  EXPECT_EQ("root's file\n", slurp(victim));
  EXPECT_FALSE(flaplag::testing::exists(safe.file("new.txt")));

  // Root's own link there is followed: the target is replaced, the link kept.
  const std::string own = sticky.file("own.txt");
  ASSERT_EQ(0, ::symlink(victim.c_str(), own.c_str()));
  const Outcome ok = run({"models", "-o", own});
  EXPECT_EQ(0, ok.exit_code) << ok.err;
  EXPECT_NE("root's file\n", slurp(victim));
  EXPECT_NE(std::string::npos, slurp(victim).find("paper"));
  struct stat st {};
  ASSERT_EQ(0, ::lstat(own.c_str(), &st));
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  // A link owned by the directory's owner is followed too (the kernel's rule).
  ASSERT_EQ(0, ::chown(sticky.path().c_str(), 65534, 65534));
  const Outcome dir_owner = run({"models", "-o", planted});
  EXPECT_EQ(0, dir_owner.exit_code) << dir_owner.err;
}

// ---- every output path is checked before computing ---------------------------------------------

TEST_F(Results, ABadPlotPathIsFoundBeforeTheRunAndNamed) {
  TempDir d;
  const std::string out = d.file("lost.json"), bad = "/no/such/dir/map.png";
  const std::vector<std::vector<std::string>> commands = {
      {"map", "--x", "mu=0:2:0.004", "--y", "omega-lag=0.2:2.5:0.01", "--json", "-o", out, "--plot",
       bad},
      {"study", "--vary", "omega-lag=0.2:2.5:0.001", "--json", "-o", out, "--plot", bad},
      {"sweep", "--mu", "0:2:0.0001", "-o", out, "--plot", bad},
      {"response", "--mu", "0.3", "-o", out, "--plot", bad},
      {"simulate", "--mu", "0.3", "--revs", "2", "-o", out, "--plot", bad},
      {"plot", files_[2], "--plot", bad}};
  for (const auto& args : commands) {
    const auto start = std::chrono::steady_clock::now();
    const Outcome r = run(args);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(2, r.exit_code) << args[0] << ": " << r.err;
    EXPECT_TRUE(std::regex_match(r.err, std::regex("flaplag: error: --plot = " + bad + ": .*\n")))
        << args[0] << ": " << r.err;
    EXPECT_FALSE(flaplag::testing::exists(out)) << args[0];
    EXPECT_LT(seconds, 20.0) << args[0] << ": the run went ahead";
  }
  // -o of merge and plot's --plot as typed too.
  const Outcome m = run({"merge", files_[2], "-o", "/no/such/dir/m.json"});
  EXPECT_EQ(2, m.exit_code);
  EXPECT_TRUE(std::regex_match(m.err, std::regex("flaplag: error: -o = /no/such/dir/m.json: .*\n")))
      << m.err;
}

// An output that cannot be written (-o /dev/full: the check passes, the write fails) ends the
// run with exit 2 naming -o, and the picture of that run is not written.
TEST_F(Results, NoPictureWhenTheOutputFails) {
  TempDir d;
  FakeGnuplot fake;
  const std::string svg = d.file("o.svg");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"sweep", "--mu", "0:0.2:0.1"},
        std::vector<std::string>{"study", "--vary", "omega-lag=1.0", "--mu-max", "0.6"}}) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"-o", "/dev/full", "--plot", svg});
    const Outcome r = run(a, fake.path());
    EXPECT_EQ(2, r.exit_code) << r.err;
    EXPECT_TRUE(std::regex_match(r.err, std::regex("flaplag: error: -o = /dev/full: .*\n")))
        << r.err;
    EXPECT_FALSE(flaplag::testing::exists(svg)) << args[0];
  }
}

// ---- standard output and open descriptors ------------------------------------------------------

// Runs flaplag with `out` as its standard output (stderr captured); what the child wrote to out
// is the caller's to read.
Outcome run_with_stdout(const std::vector<std::string>& args, int out,
                        const std::function<void()>& while_running = {}) {
  TempDir io;
  const std::string err = io.file("stderr");
  std::vector<std::string> copy = args;
  std::string exe = FLAPLAG_EXE;
  std::vector<char*> argv{exe.data()};
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fe < 0 || ::dup2(out, 1) < 0 || ::dup2(fe, 2) < 0) ::_exit(127);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  if (while_running) while_running();
  int status = 0;
  ::waitpid(pid, &status, 0);
  Outcome r;
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.err = slurp(err);
  return r;
}

std::string drain(int fd) {
  std::string s;
  char buf[4096];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;)
    s.append(buf, static_cast<std::size_t>(n));
  return s;
}

// -o /dev/stdout (or /dev/fd/1, /proc/self/fd/1) into a pipe or a socket writes through it, as
// `flaplag critical -o /dev/stdout | cat` needs.
TEST(CliDescriptors, DevStdoutIntoAPipeOrSocketIsWrittenThrough) {
  const Outcome reference = run({"models"});
  ASSERT_EQ(0, reference.exit_code);
  for (const char* name : {"/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"}) {
    for (const bool socket : {false, true}) {
      int fds[2];
      ASSERT_EQ(0, socket ? ::socketpair(AF_UNIX, SOCK_STREAM, 0, fds) : ::pipe(fds));
      std::string got;
      const Outcome r = run_with_stdout({"models", "-o", name}, fds[1], [&] {
        ::close(fds[1]);
        got = drain(fds[0]);
      });
      ::close(fds[0]);
      EXPECT_EQ(0, r.exit_code) << name << (socket ? " socket: " : " pipe: ") << r.err;
      EXPECT_EQ(reference.out, got) << name;
    }
  }
  // A file the shell opened for appending stays that file: written at its end, not replaced.
  TempDir d;
  const std::string log = d.file("log.txt");
  std::ofstream(log) << "before\n";
  const int fd = ::open(log.c_str(), O_WRONLY | O_APPEND);
  ASSERT_GE(fd, 0);
  const Outcome r = run_with_stdout({"models", "-o", "/dev/stdout"}, fd);
  ::close(fd);
  EXPECT_EQ(0, r.exit_code) << r.err;
  EXPECT_EQ("before\n" + reference.out, slurp(log));
  EXPECT_EQ(std::vector<std::string>{"log.txt"}, d.entries());
}

// A full standard output is an output error (exit 2, one line), not an internal error.
TEST(CliDescriptors, FullStandardOutputIsAnOutputError) {
  const int full = ::open("/dev/full", O_WRONLY);
  ASSERT_GE(full, 0);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"models"}, std::vector<std::string>{"--version"},
        std::vector<std::string>{"--help"},
        std::vector<std::string>{"models", "-o", "/dev/stdout"}}) {
    const Outcome r = run_with_stdout(args, full);
    EXPECT_EQ(2, r.exit_code) << args.back() << ": " << r.err;
    EXPECT_TRUE(
        std::regex_match(r.err, std::regex("flaplag: error: [^\n]*No space left on device\n")))
        << r.err;
  }
  ::close(full);
}

// ---- SIGTERM -----------------------------------------------------------------------------------

bool catches(pid_t pid, int signal) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(f, line);)
    if (line.rfind("SigCgt:", 0) == 0)
      return (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1u;
  return false;
}

// SIGTERM (a batch scheduler's time limit) during a study is handled as Ctrl-C: the values
// finished are written as a valid output with status "cancelled", one line on stderr, and the
// exit code is 143 (128 + SIGTERM).
TEST(CliSignals, SigtermDuringAStudyKeepsTheValuesFinished) {
  TempDir d;
  const std::string out = d.file("partial.json"), err = d.file("stderr");
  std::string exe = FLAPLAG_EXE;
  std::vector<std::string> args = {
      "study", "--vary", "omega-lag=0.5:2.5:0.001", "--json", "--threads", "2", "-o", out};
  std::vector<char*> argv{exe.data()};
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fe < 0 || ::dup2(fe, 2) < 0) ::_exit(127);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  // Sent once the study catches it (a SIGTERM before would end it: the old behaviour) and
  // has run for a second; at most a minute later it must have ended.
  const auto start = std::chrono::steady_clock::now();
  bool sent = false;
  int status = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    const auto now = std::chrono::steady_clock::now();
    if (!sent && now > start + std::chrono::seconds(1) &&
        (catches(pid, SIGTERM) || now > start + std::chrono::seconds(10))) {
      ::kill(pid, SIGTERM);
      sent = true;
    }
    if (w < 0 || now > start + std::chrono::seconds(120)) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      FAIL() << "the study did not end";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(143, WEXITSTATUS(status));
  EXPECT_TRUE(std::regex_match(
      slurp(err), std::regex("flaplag: interrupted: [0-9]+ of 2001 values \\(omega-lag\\) .*\n")))
      << slurp(err);
  const Json j = Json::parse(slurp(out));  // throws (fails) if not a whole JSON document
  EXPECT_EQ("cancelled", j["status"]);
  ASSERT_LT(j["rows"].size(), 2001u);
  for (std::size_t i = 0; i < j["rows"].size(); ++i)
    EXPECT_NEAR(0.5 + 0.001 * static_cast<double>(i), j["rows"][i]["value"].get<double>(), 1e-12);
}

}  // namespace

}  // namespace cli_security_test
