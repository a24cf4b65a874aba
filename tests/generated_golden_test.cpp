// The checked-in generated/ sources and reports equal a fresh generation (SymForce pattern), and
// generated/ holds no output that no spec produces any more (an orphan, e.g. of a deleted or
// renamed spec).  On a difference the test prints the first differing lines and the refresh
// command; `refresh-generated` (generated/CMakeLists.txt, cmake/refresh_generated.cmake) copies
// the fresh files and removes the orphans, by the same rule as orphans() below.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> model_names() {
  std::vector<std::string> v;
  std::stringstream ss(FLAPLAG_MODEL_NAMES);
  std::string s;
  while (std::getline(ss, s, ',')) {
    if (!s.empty()) v.push_back(s);
  }
  return v;
}

std::vector<std::string> lines_of(const std::string& path, bool* ok) {
  std::ifstream in(path);
  *ok = static_cast<bool>(in);
  std::vector<std::string> v;
  std::string s;
  while (std::getline(in, s)) v.push_back(s);
  return v;
}

// Generator output in dir (*.cc, *.md) that none of the models produces, sorted.
std::vector<std::string> orphans(const std::filesystem::path& dir,
                                 const std::vector<std::string>& models) {
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const auto ext = entry.path().extension().string();
    if (ext != ".cc" && ext != ".md") continue;
    const std::string stem = entry.path().stem().string();
    if (std::find(models.begin(), models.end(), stem) == models.end()) {
      found.push_back(entry.path().filename().string());
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

// A scratch directory with the given (empty) files.
class ScratchDir {
 public:
  ScratchDir(const std::string& tag, const std::vector<std::string>& files)
      : dir_(std::filesystem::temp_directory_path() / ("flaplag_golden_" + tag)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    for (const auto& f : files) std::ofstream(dir_ / f) << f << "\n";
  }
  ~ScratchDir() { std::filesystem::remove_all(dir_); }
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

class Golden : public ::testing::TestWithParam<std::string> {};

TEST_P(Golden, CheckedInEqualsFreshGeneration) {
  for (const char* ext : {".cc", ".md"}) {
    const std::string name = GetParam() + ext;
    bool ok_golden = false, ok_fresh = false;
    const auto golden = lines_of(std::string(FLAPLAG_GOLDEN_DIR) + "/" + name, &ok_golden);
    const auto fresh = lines_of(std::string(FLAPLAG_FRESH_DIR) + "/" + name, &ok_fresh);
    ASSERT_TRUE(ok_fresh) << "no fresh generation of " << name;
    ASSERT_TRUE(ok_golden) << "generated/" << name << " is missing; refresh with: cmake --build "
                           << "build --target refresh-generated";
    if (golden == fresh) continue;
    std::ostringstream diff;
    int shown = 0;
    for (size_t j = 0; j < std::max(golden.size(), fresh.size()) && shown < 12; ++j) {
      const std::string a = j < golden.size() ? golden[j] : "<end of file>";
      const std::string b = j < fresh.size() ? fresh[j] : "<end of file>";
      if (a == b) continue;
      diff << "  line " << j + 1 << "\n    generated/: " << a << "\n    fresh:      " << b << "\n";
      ++shown;
    }
    ADD_FAILURE() << "generated/" << name << " differs from a fresh generation:\n"
                  << diff.str() << "refresh with: cmake --build build --target refresh-generated";
  }
}

TEST(GoldenFiles, NoOrphansInGenerated) {
  const auto extra = orphans(FLAPLAG_GOLDEN_DIR, model_names());
  std::string list;
  for (const auto& f : extra) list += " generated/" + f;
  EXPECT_TRUE(extra.empty()) << "no spec produces" << list
                             << "; remove with: cmake --build build --target refresh-generated";
}

// The rule itself, on a directory with a stale model and a file that is no generator output.
TEST(GoldenFiles, OrphanDetectionFlagsOnlyOutputNoSpecProduces) {
  const ScratchDir d("orphans", {"paper.cc", "paper.md", "CMakeLists.txt", "old-model.cc",
                                 "old-model.md", "notes.txt", "paper-2x2.md"});
  EXPECT_EQ(orphans(d.path(), {"paper", "paper-2x2"}),
            (std::vector<std::string>{"old-model.cc", "old-model.md"}));
  EXPECT_EQ(orphans(d.path(), {"paper"}),
            (std::vector<std::string>{"old-model.cc", "old-model.md", "paper-2x2.md"}));
}

// The refresh target's script removes the orphans and copies the fresh output.
TEST(GoldenFiles, RefreshScriptRemovesOrphansAndCopiesFreshOutput) {
  const ScratchDir golden("refresh_golden", {"paper.cc", "CMakeLists.txt", "old-model.cc",
                                             "old-model.md", "notes.txt"});
  const ScratchDir fresh("refresh_fresh", {"paper.cc", "paper.md"});
  std::ofstream(fresh.path() / "paper.cc") << "fresh\n";
  const std::string cmd = std::string("\"") + FLAPLAG_CMAKE_COMMAND +
                          "\" -DFRESH_DIR=" + fresh.path().string() +
                          " -DGENERATED_DIR=" + golden.path().string() + " -DMODELS=paper -P " +
                          FLAPLAG_REFRESH_SCRIPT + " > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_TRUE(orphans(golden.path(), {"paper"}).empty());
  EXPECT_TRUE(std::filesystem::exists(golden.path() / "CMakeLists.txt"));
  EXPECT_TRUE(std::filesystem::exists(golden.path() / "notes.txt"));
  EXPECT_TRUE(std::filesystem::exists(golden.path() / "paper.md"));
  std::ifstream in(golden.path() / "paper.cc");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "fresh");
}

INSTANTIATE_TEST_SUITE_P(Models, Golden, ::testing::ValuesIn(model_names()), [](const auto& tp) {
  std::string s = tp.param;
  for (char& ch : s) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return s;
});

}  // namespace
