// Dependencies point down only: the module table in docs/ARCHITECTURE.md is
// the rule, every #include "..." of the product code and every link of its
// CMake targets must follow it, and the check must catch an upward include
// and an upward link in a fixture tree.
#include <gtest/gtest.h>

#include <fstream>
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
