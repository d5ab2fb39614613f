// Dependencies point down only: the module table in docs/ARCHITECTURE.md is
// the rule, every #include "..." of the product code and every link of its
// CMake targets must follow it, and the check must catch an upward include
// and an upward link in a fixture tree.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "tests/arch/include_check.h"

namespace {

namespace fs = std::filesystem;
using asgard::arch::FindUpwardIncludes;
using asgard::arch::Layers;
using asgard::arch::ParseLayers;

const fs::path kSource = ASGARD_SOURCE_DIR;

Layers DocumentedLayers() {
  std::ifstream in(kSource / "docs/ARCHITECTURE.md");
  std::ostringstream s;
  s << in.rdbuf();
  std::string error;
  Layers layers = ParseLayers(s.str(), &error);
  EXPECT_EQ(error, "");
  return layers;
}

std::string Describe(const std::vector<asgard::arch::Violation>& vs) {
  std::string s;
  for (const auto& v : vs) s += v.Describe() + "\n";
  return s;
}

TEST(IncludeDirection, TheDocumentedTableNamesEveryModuleFolder) {
  const Layers layers = DocumentedLayers();
  ASSERT_FALSE(layers.empty());
  for (const auto& [module, deps] : layers)
    EXPECT_TRUE(fs::is_directory(kSource / module)) << module << " is in the table, not the tree";
  for (const char* parent : {"core", "formats"})
    for (const auto& e : fs::directory_iterator(kSource / parent))
      if (e.is_directory()) {
        const std::string m = std::string(parent) + "/" + e.path().filename().string();
        EXPECT_TRUE(layers.count(m)) << m << " is missing from the table in docs/ARCHITECTURE.md";
      }
}

// True if .gitignore names `name` (a top-level entry): a line that is the
// name, or ends in '*' and is a prefix of it, with its slashes dropped.
bool Ignored(const std::string& name) {
  std::ifstream in(kSource / ".gitignore");
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '/' || line.back() == '\r')) line.pop_back();
    if (line.starts_with("/")) line.erase(0, 1);
    if (line.empty()) continue;
    if (line == name || (line.back() == '*' && name.starts_with(line.substr(0, line.size() - 1))))
      return true;
  }
  return false;
}

// The customer fixed the top level: these names, and the four folders they
// allowed to be added.  Hidden entries (.ci, .clang-format, .git) and what
// .gitignore names (build trees) are not part of the layout.
TEST(IncludeDirection, TheTopLevelHoldsOnlyTheAgreedNames) {
  const std::set<std::string> agreed = {"CMakeLists.txt", "core",  "medium-plugin", "host-shim",
                                        "formats",        "tests", "samples",       "README.md",
                                        "bench",          "docs",  "web",           "scripts"};
  for (const auto& e : fs::directory_iterator(kSource)) {
    const std::string name = e.path().filename().string();
    if (name.starts_with(".") || Ignored(name)) continue;
    EXPECT_TRUE(agreed.count(name)) << name << " is not one of the agreed top-level names";
  }
}

TEST(IncludeDirection, EveryIncludeOfTheTreePointsDown) {
  const auto violations = FindUpwardIncludes(kSource, DocumentedLayers());
  EXPECT_TRUE(violations.empty()) << Describe(violations);
}

TEST(IncludeDirection, TheExecutablesAreIncludedByNoLibrary) {
  const Layers layers = DocumentedLayers();
  for (const auto& [module, deps] : layers) EXPECT_FALSE(deps.count("core/app")) << module;
}

// What the check must report on the fixture tree, in order.
struct Expected {
  std::string file;
  int line;
  std::string to;         // the module reached (the target's folder for links)
  std::string described;  // a part of Describe()
};

void ExpectReported(const std::vector<asgard::arch::Violation>& violations,
                    const std::vector<Expected>& expected) {
  ASSERT_EQ(violations.size(), expected.size()) << Describe(violations);
  for (size_t k = 0; k < expected.size(); ++k) {
    const auto& v = violations[k];
    EXPECT_EQ(v.file, expected[k].file);
    EXPECT_EQ(v.line, expected[k].line) << v.file;
    EXPECT_EQ(v.to, expected[k].to) << v.file;
    EXPECT_NE(v.Describe().find(expected[k].described), std::string::npos) << v.Describe();
  }
}

const fs::path kFixture = kSource / "tests/arch/fixtures/upward";

TEST(IncludeDirection, AnUpwardIncludeInAFixtureIsReported) {
  // core/geometry includes core/render, and medium-plugin reaches past the
  // pipe protocol into core/session.
  ExpectReported(
      FindUpwardIncludes(kFixture, DocumentedLayers()),
      {{"core/geometry/hull.h", 4, "core/render", "core/geometry may not include core/render"},
       {"medium-plugin/plugin.cc", 4, "core/session",
        "medium-plugin may not include core/session"}});
}

TEST(IncludeDirection, EveryTargetLinksDownAndOnlyItsOwnFolderAddsToIt) {
  const auto violations = asgard::arch::FindUpwardLinks(kSource, DocumentedLayers());
  EXPECT_TRUE(violations.empty()) << Describe(violations);
}

TEST(IncludeDirection, AnUpwardLinkAndAForeignTargetInAFixtureAreReported) {
  // Geometry links render; render's CMakeLists.txt adds to session's target.
  ExpectReported(asgard::arch::FindUpwardLinks(kFixture, DocumentedLayers()),
                 {{"core/geometry/CMakeLists.txt", 3, "core/render",
                   "asgard_geometry links asgard_render: core/geometry may not depend on "
                   "core/render"},
                  {"core/render/CMakeLists.txt", 4, "core/session",
                   "target_link_libraries(asgard_session ...) adds to a target core/render "
                   "does not define"}});
}

TEST(IncludeDirection, TheTableMustBeACycleFreeListOfDeclaredModules) {
  std::string error;
  ParseLayers("| module | depends on |\n|---|---|\n| `a` | `b` |\n| `b` | `a` |\n", &error);
  EXPECT_NE(error.find("cycle"), std::string::npos) << error;
  ParseLayers("| module | depends on |\n|---|---|\n| `a` | `c` |\n", &error);
  EXPECT_NE(error.find("does not declare"), std::string::npos) << error;
  ParseLayers("no table here", &error);
  EXPECT_NE(error.find("no '| module | depends on |' table"), std::string::npos) << error;
}

}  // namespace
