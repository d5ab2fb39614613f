// The include-direction check: every #include "..." in the product folders
// must name a module the including module may depend on.
//
//   docs/ARCHITECTURE.md ── ParseLayers ──▶ Layers (module → direct dependencies)
//   a source tree ─────── FindUpwardIncludes(root, layers) ──▶ violations
//
// A module is a folder named in the table (core/render, host-shim/include,
// medium-plugin, ...); a file belongs to the longest module that holds it.  A
// module may include itself and everything its dependencies may include (the
// transitive closure), nothing else.  Includes resolve as the build does:
// from the source root, "asgard/..." from host-shim/include, or beside the
// including file.
#pragma once

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace asgard::arch {

// module → the modules it depends on directly.
using Layers = std::map<std::string, std::set<std::string>>;

// Reads the table whose header row is "| module | depends on |": one row per
// module, names in backquotes, "—" for none.  Sets `error` (and returns what
// it read) when the table is missing, names an undeclared module, or has a
// cycle.
Layers ParseLayers(const std::string& markdown, std::string* error);

struct Violation {
  std::string file;  // relative to the root
  int line = 0;
  std::string include;
  std::string from, to;  // modules; `to` empty when the include resolves to no module
  std::string message;   // links: what is wrong (includes are described from the above)
  std::string Describe() const;
};

// The folders of the product code that the check reads.
inline const std::vector<std::string> kProductFolders = {"core", "formats", "host-shim",
                                                         "medium-plugin", "web/server"};

// Scans every .h/.cc/.c file under root/<folder> for each product folder that
// exists.  A file outside every module is a violation too (the table must
// name every folder).
std::vector<Violation> FindUpwardIncludes(const std::filesystem::path& root, const Layers& layers);

// The same rule for the build: in every module folder's CMakeLists.txt, each
// target_link_libraries names a target that folder defines (no folder adds to
// another's target), and each Asgard target it links belongs to a module the
// folder may depend on.  Targets no module folder defines (asgard_warnings,
// third-party ones) are not checked.  `include` holds the target named.
std::vector<Violation> FindUpwardLinks(const std::filesystem::path& root, const Layers& layers);

}  // namespace asgard::arch
