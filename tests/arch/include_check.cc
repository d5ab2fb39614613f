// The include-direction check (see include_check.h).
#include "tests/arch/include_check.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>

namespace asgard::arch {
namespace fs = std::filesystem;

namespace {

std::vector<std::string> Quoted(const std::string& cell) {
  std::vector<std::string> names;
  static const std::regex kName("`([^`]+)`");
  for (auto it = std::sregex_iterator(cell.begin(), cell.end(), kName);
       it != std::sregex_iterator(); ++it)
    names.push_back((*it)[1]);
  return names;
}

std::vector<std::string> Cells(const std::string& row) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(row);
  std::getline(in, cell, '|');  // before the first bar
  while (std::getline(in, cell, '|')) cells.push_back(cell);
  if (!cells.empty() && cells.back().find_first_not_of(" \t\r") == std::string::npos)
    cells.pop_back();
  return cells;
}

// The module holding `path` (relative, '/'-separated), or "".
std::string ModuleOf(const std::string& path, const Layers& layers) {
  std::string best;
  for (const auto& [m, deps] : layers)
    if (path.starts_with(m + "/") && m.size() > best.size()) best = m;
  return best;
}

// What each module may use: itself and the closure of its dependencies.
std::map<std::string, std::set<std::string>> Allowed(const Layers& layers) {
  std::map<std::string, std::set<std::string>> allowed;
  std::function<void(const std::string&, std::set<std::string>&)> close =
      [&](const std::string& m, std::set<std::string>& out) {
        if (!out.insert(m).second) return;
        const auto it = layers.find(m);
        if (it != layers.end())
          for (const auto& d : it->second) close(d, out);
      };
  for (const auto& [m, deps] : layers) close(m, allowed[m]);
  return allowed;
}

std::string Read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

Layers ParseLayers(const std::string& markdown, std::string* error) {
  Layers layers;
  std::istringstream in(markdown);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    const auto cells = Cells(line);
    if (!inside) {
      static const std::regex kHeader(R"(^\s*\|\s*module\s*\|\s*depends on\s*\|\s*$)");
      inside = std::regex_match(line, kHeader);
      continue;
    }
    if (line.find('|') == std::string::npos) break;
    if (line.find("---") != std::string::npos && Quoted(line).empty()) continue;
    const auto names = cells.empty() ? std::vector<std::string>{} : Quoted(cells[0]);
    if (cells.size() != 2 || names.size() != 1) {
      if (error) *error = "a row of the module table is not '| `module` | `dep` ... |': " + line;
      return layers;
    }
    const auto deps = Quoted(cells[1]);
    layers[names[0]].insert(deps.begin(), deps.end());
  }
  if (layers.empty()) {
    if (error) *error = "no '| module | depends on |' table";
    return layers;
  }
  for (const auto& [m, deps] : layers)
    for (const auto& d : deps)
      if (!layers.count(d)) {
        if (error) *error = m + " depends on " + d + ", which the table does not declare";
        return layers;
      }
  // Depth-first search for a cycle.
  std::map<std::string, int> state;  // 1 on the stack, 2 done
  std::function<bool(const std::string&)> cyclic = [&](const std::string& m) {
    if (state[m] == 1) return true;
    if (state[m] == 2) return false;
    state[m] = 1;
    for (const auto& d : layers[m])
      if (cyclic(d)) return true;
    state[m] = 2;
    return false;
  };
  for (const auto& [m, deps] : layers)
    if (cyclic(m)) {
      if (error) *error = "the module table has a cycle through " + m;
      return layers;
    }
  return layers;
}

std::string Violation::Describe() const {
  const std::string where = file + ":" + std::to_string(line) + ": ";
  if (!message.empty()) return where + message;
  if (from.empty()) return where + "the file is in no module of the table";
  if (to.empty()) return where + "#include \"" + include + "\" resolves to no module";
  return where + "#include \"" + include + "\" points up: " + from + " may not include " + to;
}

std::vector<Violation> FindUpwardIncludes(const fs::path& root, const Layers& layers) {
  auto allowed = Allowed(layers);

  std::vector<Violation> out;
  static const std::regex kInclude(R"(^\s*#\s*include\s*"([^"]+)\")");
  for (const auto& folder : kProductFolders) {
    if (!fs::is_directory(root / folder)) continue;
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(root / folder)) {
      const auto ext = e.path().extension();
      if (e.is_regular_file() && (ext == ".h" || ext == ".cc" || ext == ".c"))
        files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& path : files) {
      const std::string rel = fs::relative(path, root).generic_string();
      const std::string from = ModuleOf(rel, layers);
      if (from.empty()) {
        out.push_back({rel, 0, "", "", "", ""});
        continue;
      }
      std::istringstream text(Read(path));
      std::string line;
      for (int n = 1; std::getline(text, line); ++n) {
        std::smatch m;
        if (!std::regex_search(line, m, kInclude)) continue;
        const std::string inc = m[1];
        std::string target;
        for (const fs::path& base : {root, root / "host-shim/include", path.parent_path()}) {
          const fs::path p = (base / inc).lexically_normal();
          if (fs::exists(p)) {
            target = fs::relative(p, root).generic_string();
            break;
          }
        }
        const std::string to = target.empty() ? "" : ModuleOf(target, layers);
        if (to.empty() || !allowed[from].count(to)) out.push_back({rel, n, inc, from, to, ""});
      }
    }
  }
  return out;
}

std::vector<Violation> FindUpwardLinks(const fs::path& root, const Layers& layers) {
  const auto allowed = Allowed(layers);
  // Which module folder defines each target.
  static const std::regex kDefine(R"((?:add_library|add_executable)\(\s*([A-Za-z0-9_.-]+))");
  static const std::regex kLink(R"(target_link_libraries\(([^)]*)\))");
  static const std::regex kWord(R"([A-Za-z0-9_.:${}<>-]+)");
  std::map<std::string, std::string> owner;
  std::map<std::string, std::string> lists;  // module → its CMakeLists.txt text
  for (const auto& [module, deps] : layers) {
    const fs::path file = root / module / "CMakeLists.txt";
    if (!fs::exists(file)) continue;
    lists[module] = Read(file);
    const std::string& text = lists[module];
    for (auto it = std::sregex_iterator(text.begin(), text.end(), kDefine);
         it != std::sregex_iterator(); ++it)
      owner[(*it)[1]] = module;
  }
  std::vector<Violation> out;
  for (const auto& [module, text] : lists) {
    const std::string file = module + "/CMakeLists.txt";
    for (auto it = std::sregex_iterator(text.begin(), text.end(), kLink);
         it != std::sregex_iterator(); ++it) {
      const std::string args = (*it)[1];
      const int line =
          1 + static_cast<int>(std::count(text.begin(), text.begin() + it->position(), '\n'));
      std::vector<std::string> words;
      for (auto w = std::sregex_iterator(args.begin(), args.end(), kWord);
           w != std::sregex_iterator(); ++w)
        words.push_back(w->str());
      if (words.empty()) continue;
      const auto target = owner.find(words[0]);
      if (target == owner.end() || target->second != module) {
        out.push_back({file, line, words[0], module, target == owner.end() ? "" : target->second,
                       "target_link_libraries(" + words[0] + " ...) adds to a target " + module +
                           " does not define"});
        continue;
      }
      for (size_t k = 1; k < words.size(); ++k) {
        const auto linked = owner.find(words[k]);
        if (linked == owner.end() || allowed.at(module).count(linked->second)) continue;
        out.push_back({file, line, words[k], module, linked->second,
                       words[0] + " links " + words[k] + ": " + module + " may not depend on " +
                           linked->second});
      }
    }
  }
  return out;
}

}  // namespace asgard::arch
