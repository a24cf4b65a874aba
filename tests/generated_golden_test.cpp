// The checked-in generated/ sources and reports equal a fresh generation (SymForce pattern).
// On a difference the test prints the first differing lines and the refresh command.
#include <gtest/gtest.h>

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

INSTANTIATE_TEST_SUITE_P(Models, Golden, ::testing::ValuesIn(model_names()), [](const auto& tp) {
  std::string s = tp.param;
  for (char& ch : s) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return s;
});

}  // namespace
