#include "web/server/launch.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>

#include "formats/document/document.h"
#include "formats/document/file.h"
#include "web/server/server.h"

extern char** environ;

namespace asgard::serve {
namespace fs = std::filesystem;

const char* const kServeUsage =
    "  dochost serve DOC.ens [--port P] [--open] [--core PATH]\n"
    "  asgard studio SCENE.al [--port P] [--open] [--core PATH]\n"
    "Serves the live document view and the Asgard editor on http://127.0.0.1:P/ (a free\n"
    "port when P is 0 or absent; only this machine can connect).\n";

bool ParseLaunchArgs(const std::vector<std::string>& args, std::string* file, LaunchOptions* o,
                     std::string* error) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--port" || a == "--core") {
      if (i + 1 >= args.size()) {
        *error = a + " needs a value";
        return false;
      }
      const std::string& v = args[++i];
      if (a == "--core") {
        o->core = v;
        continue;
      }
      char* end = nullptr;
      const long p = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || p < 0 || p > 65535) {
        *error = "--port needs a number from 0 to 65535";
        return false;
      }
      o->port = static_cast<int>(p);
    } else if (a == "--open") {
      o->open = true;
    } else if (!a.empty() && a[0] == '-') {
      *error = "unknown option '" + a + "'";
      return false;
    } else if (file->empty()) {
      *file = a;
    } else {
      *error = "unexpected argument '" + a + "'";
      return false;
    }
  }
  if (file->empty()) {
    *error = "a file is required";
    return false;
  }
  return true;
}

namespace {

fs::path ExeDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::current_path() : exe.parent_path();
}

// The first candidate (relative to the executable's folder) that exists.
std::string Find(const std::vector<std::string>& candidates, const std::string& leaf) {
  for (const auto& c : candidates) {
    const fs::path p = ExeDir() / c;
    std::error_code ec;
    if (fs::exists(p / leaf, ec)) return fs::weakly_canonical(p, ec).string();
  }
  return (ExeDir() / candidates.front()).string();
}

}  // namespace

std::string WebRoot(const std::string& given) {
  const char* env = std::getenv("ASGARD_WEB_ROOT");
  return !given.empty() ? given
         : env && *env  ? std::string(env)
                        : Find({"../web", "../../web"}, "index.html");
}

namespace {

Options MakeOptions(const LaunchOptions& lo) {
  Options o;
  o.port = lo.port;
  o.core_program =
      !lo.core.empty()
          ? lo.core
          : (fs::path(Find({".", "../core/app"}, "asgard-core")) / "asgard-core").string();
  o.render_program = (fs::path(Find({".", "../core/app"}, "asgard")) / "asgard").string();
  o.web_root = WebRoot(lo.web_root);
  const bool open = lo.open;
  o.on_listening = [open](int port) {
    const std::string url = "http://127.0.0.1:" + std::to_string(port) + "/";
    std::cout << "serving on " << url << std::endl;
    if (!open) return;
    std::string a0 = "xdg-open", a1 = url;
    char* argv[] = {a0.data(), a1.data(), nullptr};
    pid_t pid = -1;
    if (::posix_spawnp(&pid, "xdg-open", nullptr, nullptr, argv, environ) != 0)
      std::cerr << "cannot run xdg-open; open " << url << " in a browser\n";
  };
  return o;
}

// The document's animations (<ASGARD> texts) in order, their places, and
// a page of its text with each animation as a live rendition with the
// host's toolbar (or, without a rendition, an editor frame).
struct Walk {
  std::vector<document::Node*> animations;
  std::vector<std::vector<size_t>> paths;
  const std::vector<Animation>* made = nullptr;  // the second walk writes the page
  std::string html;
};

// One animation in the document view: a rendition (WebGL from the pose
// stream, or the picture its slave draws, GET /frame) and the toolbar of
// seed 6.2.4 — play, pause, loop, the time slider, recompute, handles, the
// editor, another rendition.  The page's WebSocket to the animation is one
// more view of it: a `scene` event (an edit's new motion, from any editor)
// reaches every rendition, and all renditions of it follow one clock.
// A length in whole CSS pixels, for a style or an attribute.
std::string Px(double v) { return std::to_string(static_cast<long>(std::lround(v))); }
// A length to a hundredth of a CSS pixel (a font's size, a text line's box).
std::string Px2(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", std::isfinite(v) ? v : 0.0);
  return b;
}

// On a host page (`region`) the figure lies over the animation's region,
// its picture the region's size and its toolbar over the picture's foot.
std::string RenditionHtml(size_t i, const Animation& a, const PageRegion* region = nullptr) {
  const std::string n = std::to_string(i);
  const std::string place =
      region ? " placed\" style=\"left:" + Px(region->x) + "px;top:" + Px(region->y) + "px" : "";
  const std::string size = region ? "\" width=\"" + Px(region->w) + "\" height=\"" + Px(region->h)
                                  : "\" width=\"360\" height=\"240";
  return "<figure class=\"rendition" + place + "\" data-a=\"" + n + "\"><img alt=\"" +
         HtmlEscape(a.title) + size +
         "\"><figcaption>"
         "<button class=\"play\">Play</button> <label><input type=\"checkbox\" class=\"loop\">"
         "Loop</label> <input type=\"range\" class=\"time\" min=\"0\" max=\"1000\" "
         "value=\"0\"> <span class=\"t\"></span> <button class=\"recompute\">Recompute</button> "
         "<label><input type=\"checkbox\" class=\"handles\">Handles</label> <a href=\"/edit?a=" +
         n +
         "\" target=\"_blank\">Edit</a> <button class=\"another\" title=\"Another rendition of "
         "this animation, in step with this one\">Another view</button> <span "
         "class=\"status\"></span></figcaption></figure>\n";
}

// The page's script: web/src/document.js, bundled (WebGL renditions from
// the animation's pose stream on one clock; the slave's picture as the
// fallback).
const char* const kDocumentScript = "<script type=\"module\" src=\"/document.js\"></script>\n";

void Collect(std::vector<document::Node>& nodes, Walk& w, std::vector<size_t>& path) {
  for (size_t k = 0; k < nodes.size(); ++k) {
    document::Node& n = nodes[k];
    path.push_back(k);
    if (n.IsElement("ASGARD")) {
      const size_t i = w.animations.size();
      w.animations.push_back(&n);
      w.paths.push_back(path);
      if (w.made && (*w.made)[i].rendition)
        w.html += RenditionHtml(i, (*w.made)[i]);
      else if (w.made)
        w.html += "<iframe class=\"animation\" src=\"/edit?a=" + std::to_string(i) +
                  "\" style=\"width:100%;height:520px;border:1px solid #999\"></iframe>\n";
    } else {
      if (n.kind == document::NodeKind::kText) {
        const std::string t = n.Text();
        if (t.find_first_not_of(" \t\r\n") != std::string::npos)
          w.html += "<p>" + HtmlEscape(t) + "</p>\n";
      }
      if (n.kind == document::NodeKind::kElement) Collect(n.children, w, path);
    }
    path.pop_back();
  }
}

// The document view on the host's pages: each page's picture with its text
// laid over it (transparent, each line where the host set it and stretched
// to its width by document.js, so that it can be selected, copied, found and
// read aloud), a rendition over each animation's region, and a place for
// the renditions added with "Another view" after the pages.
const char* const kPageStyle =
    "<style>body{background:#d8d8d8;margin:0;font:13px sans-serif}"
    "h1{font-size:15px;margin:8px 16px}"
    ".page{position:relative;margin:12px auto;background:#fff;box-shadow:0 1px 4px #888}"
    ".page-picture{display:block;width:100%;height:100%}"
    ".page-text{position:absolute;left:0;top:0;right:0;bottom:0;overflow:hidden;line-height:1}"
    ".page-text span{position:absolute;white-space:pre;color:transparent;transform-origin:0 0;"
    "cursor:text}"
    ".page-text ::selection{color:transparent;background:rgba(40,110,255,.32)}"
    "figure.rendition.placed{position:absolute;margin:0}"
    "figure.rendition.placed figcaption{position:absolute;left:0;right:0;bottom:0;"
    "background:rgba(255,255,255,.82);font-size:11px;padding:2px 4px;opacity:.5;"
    "transition:opacity .15s}"
    "figure.rendition.placed:hover figcaption,figure.rendition.placed:focus-within figcaption"
    "{opacity:1}"
    "#more-renditions{width:794px;margin:12px auto}h2,ul{margin-left:16px}</style>\n";

// The page's lines of text: one span each, at its box, in its font.
// Pieces of one line (a field's label and its text: the same top) are
// apart by a space, lines by a break, so that a copy reads as the page.
std::string LinesHtml(const std::vector<PageLine>& lines) {
  std::string html;
  for (size_t k = 0; k < lines.size(); ++k) {
    const PageLine& l = lines[k];
    if (k > 0 && l.y == lines[k - 1].y)  // a space of its own: between spans it would collapse
      html += "<span style=\"left:" + Px2(l.x) + "px;top:" + Px2(l.y) + "px\"> </span>";
    else if (k > 0)
      html += "<br>";
    std::string family;  // a CSS string: the family's name without quotes or escapes
    for (char c : l.family)
      if (std::isalnum(static_cast<unsigned char>(c)) || c == ' ' || c == '-') family += c;
    const bool serif = family.find("Serif") != std::string::npos;
    html += "<span style=\"left:" + Px2(l.x) + "px;top:" + Px2(l.y) + "px;height:" + Px2(l.h) +
            "px;font:" + (l.bold ? "bold " : "") + Px2(l.font_px) + "px '" + family + "'," +
            (serif ? "serif" : "sans-serif") + ";line-height:" + Px2(l.h) + "px\" data-w=\"" +
            Px2(l.w) + "\">" + HtmlEscape(l.text) + "</span>";
  }
  return html;
}

std::string PagesHtml(const std::vector<HostPage>& pages, const Walk& w,
                      const std::vector<Animation>& animations) {
  std::string html = kPageStyle;
  for (size_t k = 0; k < pages.size(); ++k) {
    const HostPage& p = pages[k];
    const std::string of = "Page " + std::to_string(k + 1) + " of " + std::to_string(pages.size());
    html += "<div class=\"page\" data-page=\"" + std::to_string(k) +
            "\" style=\"width:" + Px(p.width) + "px;height:" + Px(p.height) +
            "px\"><img class=\"page-picture\" src=\"/page?n=" + std::to_string(k) + "\" alt=\"" +
            of + "\" loading=\"lazy\"><div class=\"page-text\">" + LinesHtml(p.lines) + "</div>\n";
    for (const PageRegion& r : p.regions)
      for (size_t i = 0; i < w.paths.size(); ++i)
        if (w.paths[i] == r.element_path && animations[i].rendition)
          html += RenditionHtml(i, animations[i], &r);
    html += "</div>\n";
  }
  return html + "<div id=\"more-renditions\"></div>\n";
}

}  // namespace

int ServeDocument(const std::string& path, const LaunchOptions& lo, const AttachHost& attach,
                  const HostPages& pages) {
  auto loaded = document::LoadDocument(path);
  if (!loaded.document) {
    std::cerr << loaded.error << "\n";
    return 1;
  }
  auto doc = std::make_shared<document::Document>(std::move(*loaded.document));
  auto lock = std::make_shared<std::mutex>();  // animations save from their own threads
  Walk w;
  std::vector<size_t> at;
  Collect(doc->nodes, w, at);
  std::vector<Animation> animations;
  for (size_t i = 0; i < w.animations.size(); ++i) {
    document::Node* node = w.animations[i];
    Animation a;
    a.title = fs::path(path).filename().string() + ", animation " + std::to_string(i + 1);
    for (const auto& c : node->children)
      if (c.kind == document::NodeKind::kText) a.text += c.Text();
    // Saving replaces this animation's text and writes the document
    // atomically; every other byte stays as read.
    a.save = [doc, node, path, lock](const std::string& text, std::string* error) {
      std::lock_guard guard(*lock);
      std::vector<document::Node> children;
      children.push_back(document::Node::TextNode(text));
      node->children = std::move(children);
      return document::SaveDocument(*doc, path, error);
    };
    if (attach) attach(w.paths[i], a);
    animations.push_back(std::move(a));
  }
  Walk page;
  page.made = &animations;
  at.clear();
  Collect(doc->nodes, page, at);
  Options o = MakeOptions(lo);
  o.document_title = fs::path(path).filename().string();
  o.document_html = "<h1>" + HtmlEscape(o.document_title) + "</h1>\n" +
                    (pages.pages.empty() ? page.html : PagesHtml(pages.pages, page, animations));
  o.page_count = pages.pages.size();
  o.page_picture = pages.picture;
  // The script plays the renditions and fits the pages' text to its lines.
  bool script = !pages.pages.empty();
  for (const Animation& a : animations) script = script || a.rendition;
  if (script) o.document_html += kDocumentScript;
  return Serve(o, std::move(animations));
}

int ServeScene(const std::string& path, const LaunchOptions& lo) {
  Animation a;
  std::string error;
  if (!document::ReadFile(path, a.text, &error)) {
    std::cerr << error << "\n";
    return 1;
  }
  a.title = fs::path(path).filename().string();
  a.save = [path](const std::string& text, std::string* err) {
    return document::WriteFileAtomic(path, text, err);
  };
  std::vector<Animation> animations;
  animations.push_back(std::move(a));
  Options o = MakeOptions(lo);
  o.document_title = fs::path(path).filename().string();
  return Serve(o, std::move(animations));
}

}  // namespace asgard::serve
