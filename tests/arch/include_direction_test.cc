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

TEST(IncludeDirection, AnUpwardIncludeInAFixtureIsReported) {
  // tests/arch/fixtures/upward: core/geometry includes core/render, and
  // medium-plugin reaches past the pipe protocol into core/session.
  const auto violations =
      FindUpwardIncludes(kSource / "tests/arch/fixtures/upward", DocumentedLayers());
  ASSERT_EQ(violations.size(), 2u) << Describe(violations);
  EXPECT_EQ(violations[0].file, "core/geometry/hull.h");
  EXPECT_EQ(violations[0].line, 4);
  EXPECT_EQ(violations[0].from, "core/geometry");
  EXPECT_EQ(violations[0].to, "core/render");
  EXPECT_EQ(violations[1].file, "medium-plugin/plugin.cc");
  EXPECT_EQ(violations[1].to, "core/session");
  EXPECT_NE(violations[0].Describe().find("core/geometry may not include core/render"),
            std::string::npos)
      << violations[0].Describe();
}

TEST(IncludeDirection, EveryTargetLinksDownAndOnlyItsOwnFolderAddsToIt) {
  const auto violations = asgard::arch::FindUpwardLinks(kSource, DocumentedLayers());
  EXPECT_TRUE(violations.empty()) << Describe(violations);
}

TEST(IncludeDirection, AnUpwardLinkAndAForeignTargetInAFixtureAreReported) {
  // fixtures/upward: geometry links render; render's CMakeLists.txt adds to
  // session's target.
  const auto violations =
      asgard::arch::FindUpwardLinks(kSource / "tests/arch/fixtures/upward", DocumentedLayers());
  ASSERT_EQ(violations.size(), 2u) << Describe(violations);
  EXPECT_EQ(violations[0].file, "core/geometry/CMakeLists.txt");
  EXPECT_EQ(violations[0].line, 3);
  EXPECT_EQ(violations[0].include, "asgard_render");
  EXPECT_EQ(violations[0].to, "core/render");
  EXPECT_EQ(violations[1].file, "core/render/CMakeLists.txt");
  EXPECT_EQ(violations[1].line, 4);
  EXPECT_EQ(violations[1].include, "asgard_session");
  EXPECT_NE(violations[1].Describe().find("adds to a target core/render does not define"),
            std::string::npos)
      << violations[1].Describe();
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
