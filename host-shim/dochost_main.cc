// dochost: the document host on the command line.
//
//   dochost convert IN -o OUT.{pdf,png,html,xml,ens}
//   dochost verb IN VERB [ARGS] [-o OUT]       (host verbs of seed 6.2.4)
//
// Design: both commands load the document, find its embedded subdocuments and
// their media (host_document.h), and, when the output needs pictures, start
// one node per subdocument and simulate it.  A verb changes the view state
// (time, handles, playing) or the document (recompute: re-simulate and
// refresh the poster frame), then the same output step writes the result.
// Like the asgard CLI: usage problems print the help and exit 2; a document
// that cannot be read or an output that cannot be written exits 1.  An
// animation that fails is a warning on stderr, its poster and status are
// shown, and the exit status is 3 (kExitIncomplete): OUT was written but is
// not everything IN asks for.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "formats/cli/cli.h"
#include "formats/document/file.h"
#include "formats/document/xml.h"
#include "host-shim/host_document.h"
#include "host-shim/html.h"
#include "host-shim/layout.h"
#include "host-shim/serve_host.h"
#include "web/server/launch.h"

namespace asgard::host {
namespace {

using document::Extension;

// OUT was written, but something in it is not what IN asks for (an animation
// shown by its poster or a placeholder, a part of IN ignored); stderr says
// what.
constexpr int kExitIncomplete = 3;

const char* const kHelp = R"(Usage: dochost convert IN -o OUT [options]
       dochost verb IN VERB [ARGS] [options]
       dochost serve IN [--port P] [--open]   (the live document view and editor)
       dochost help

Compound documents with embedded Asgard animations (.ens: the SGML-like
format of the dissertation's Figure 6.2; .xml: its XML flavour).

convert writes IN as OUT; the extension of OUT chooses the output device:
  .pdf        pages (A4), text set with Pango, each animation as a frame
  .png        the same pages as pictures (OUT, OUT-2.png, ...)
  .html       one self-contained page; each animation plays with play/pause
              and a seek slider, starting from its poster frame: in WebGL
              from its embedded meshes and poses (rotatable: drag, wheel,
              double-click), or its pre-rendered frames where WebGL is
              missing (see --html)
  .ens .xml   the document itself, in either flavour (byte-exact)

verb runs a host verb (seed 6.2.4) headless on the first animation (or the
one given with --animation N), then writes the result to -o OUT (any of the
formats above; for recompute without -o, IN itself is rewritten):
  play [--from T] [--to T]   play the animation; with -o PATTERN.png write
                             every frame of the playback (OUT_0000.png ...)
  pause [T] | seek T         stop at time T; -o shows the document then
  recompute                  recompute the motion (re-simulate) and refresh
                             the animation's poster frame in the document
  handles on|off             show the position handles in its renditions
  viewer                     open a viewer: write a page (-o OUT.html) with
                             the scene text and the player
  restart                    restart the animation's slave process
  status                     print every animation's status

Options:
  -o OUT               output file
  --animation N        the animation a verb applies to (default 1)
  --time T             time of the frames on pages and of poster frames
                       (default: the start of each animation)
  --handles            show position handles in the pictures
  --html MODE          what an .html page embeds per animation: webgl (the
                       default: meshes, poses and the WebGL player, with the
                       poster and frames as the fallback), webgl-poster
                       (the same with only the poster as the fallback), or
                       frames (pre-rendered frames only)
  --dpi N              resolution of .png pages (default 96)
  --layout FILE        also write the page layout as JSON
  --plugin-path DIR    look for medium plugins in DIR first (repeatable;
                       also $ASGARD_MEDIUM_PATH, colon-separated)
  --core PATH          the asgard-core slave program (default: beside the
                       plugin, or $ASGARD_CORE)
  --timeout S          watchdog: longest silence from a slave (default 60)
  --slaves N           animations simulated at once (default 4): beyond them
                       the slave used longest ago is stopped, and started
                       again when its animation is drawn
  --slave-memory MIB   memory of each slave process (default 2048); one that
                       needs more ends, and its animation shows its poster
  --quiet              no progress bar, notes or messages on stdout; warnings
                       that change OUT are still printed
  -h, --help           this help

A slave that dies while loading its text, simulating or drawing is started
again once; if it dies again, its animation is shown by its poster frame.
Under serve, each animation's editor and its picture in the document view
share the animation's slave; one that dies starts again at the next action.

Exit status 0 on success; 1 when IN cannot be read, OUT cannot be written or
a verb fails; 2 on bad usage; 3 when OUT was written but is not all that IN
asks for: an animation shown by its poster or a placeholder, or a part of IN
ignored (each said on stderr).
)";

struct Options {
  std::string command, in, out, verb, layout;
  std::vector<std::string> verb_args, plugin_path;
  std::string core, html = "webgl";
  std::optional<double> time, from, to;
  double timeout = 0, dpi = 96, slave_memory = 0;
  int animation = 1, slaves = kDefaultMaxSlaves;
  bool handles = false, quiet = false;
};

int Usage(const std::string& message) { return cli::Usage("dochost", message, kHelp); }

// Returns an exit status when parsing ends the program (help, usage).
std::optional<int> Parse(const std::vector<std::string>& args, Options& o) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::optional<std::string> {
      if (i + 1 >= args.size()) return std::nullopt;
      return args[++i];
    };
    auto number = [&](double& out) {
      auto v = value();
      return v && cli::ParseNumber(*v, out);
    };
    double d = 0;
    if (a == "-h" || a == "--help") {
      std::cout << kHelp;
      return 0;
    } else if (a == "-o") {
      auto v = value();
      if (!v || v->empty()) return Usage("-o needs a file name");
      o.out = *v;
    } else if (a == "--time" || a == "--from" || a == "--to") {
      if (!number(d)) return Usage(a + " needs a number");
      (a == "--time" ? o.time : a == "--from" ? o.from : o.to) = d;
    } else if (a == "--timeout") {
      if (!number(d) || d <= 0) return Usage("--timeout needs a positive number of seconds");
      o.timeout = d;
    } else if (a == "--dpi") {
      if (!number(d) || d < 10 || d > 1200) return Usage("--dpi needs a number from 10 to 1200");
      o.dpi = d;
    } else if (a == "--slaves") {
      if (!number(d) || d < 1 || d > 64 || d != std::floor(d))
        return Usage("--slaves needs a whole number from 1 to 64");
      o.slaves = static_cast<int>(d);
    } else if (a == "--slave-memory") {
      if (!number(d) || d < 64 || d > 1 << 20)
        return Usage("--slave-memory needs a number of MiB from 64 to 1048576");
      o.slave_memory = d;
    } else if (a == "--animation") {
      if (!number(d) || d < 1 || d != std::floor(d)) return Usage("--animation needs N >= 1");
      o.animation = static_cast<int>(d);
    } else if (a == "--layout" || a == "--plugin-path" || a == "--core") {
      auto v = value();
      if (!v || v->empty()) return Usage(a + " needs a value");
      if (a == "--layout") o.layout = *v;
      if (a == "--plugin-path") o.plugin_path.push_back(*v);
      if (a == "--core") o.core = *v;
    } else if (a == "--html") {
      auto v = value();
      if (!v || (*v != "webgl" && *v != "webgl-poster" && *v != "frames"))
        return Usage("--html needs webgl, webgl-poster or frames");
      o.html = *v;
    } else if (a == "--handles") {
      o.handles = true;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a.size() > 1 && a[0] == '-' &&
               !(std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')) {
      return Usage("unknown option '" + a + "'");
    } else if (o.command.empty()) {
      o.command = a;
    } else if (o.in.empty()) {
      o.in = a;
    } else if (o.command == "verb" && o.verb.empty()) {
      o.verb = a;
    } else if (o.command == "verb") {
      o.verb_args.push_back(a);
    } else {
      return Usage("unexpected argument '" + a + "'");
    }
  }
  if (o.command == "help" || o.command.empty()) {
    std::cout << kHelp;
    return o.command.empty() ? 2 : 0;
  }
  if (o.command != "convert" && o.command != "verb")
    return Usage("unknown command '" + o.command + "'");
  if (o.in.empty()) return Usage(o.command + ": IN is required");
  if (o.command == "convert" && o.out.empty()) return Usage("convert: -o OUT is required");
  if (o.command == "verb" && o.verb.empty()) return Usage("verb: VERB is required");
  return std::nullopt;
}

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled) {}
  void operator()(const Embedded& item, double f) {
    if (!enabled_) return;
    const int filled = static_cast<int>(std::lround(std::clamp(f, 0.0, 1.0) * 30));
    std::fprintf(stderr, "\r[%s%s] simulating animation %d %3.0f%%",
                 std::string(filled, '#').c_str(), std::string(30 - filled, '.').c_str(),
                 item.index, f * 100);
    if (f >= 1) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  bool enabled_;
};

struct Host {
  Options o;
  std::unique_ptr<MediumRegistry> registry;
  std::unique_ptr<HostDocument> doc;

  bool incomplete = false;      // a warning changed OUT: exit kExitIncomplete
  std::set<int> reported;       // items whose failure is on stderr
  std::set<int> noted_restart;  // items whose restart is on stderr
  std::optional<std::string> player_script;

  // Something OUT shows otherwise than IN asks: always said, and the exit
  // status says so too.
  void Warn(const std::string& m) {
    incomplete = true;
    std::cerr << "dochost: " << m << "\n";
  }
  // Nothing is missing from OUT (a slave started again, say).
  void Note(const std::string& m) const {
    if (!o.quiet) std::cerr << "dochost: " << m << "\n";
  }
  std::string Where(const Embedded& item) const {
    return o.in + ": animation " + std::to_string(item.index) + ": ";
  }
  // Once per item: why it is shown by its poster or a placeholder.
  void Report(const Embedded& item) {
    if (reported.insert(item.index).second) Warn(Where(item) + item.message);
  }
  // Once per item: that its slave died and was started again.
  void NoteRestart(const Embedded& item) {
    if (item.restarted && noted_restart.insert(item.index).second)
      Note(Where(item) + item.restart_reason + "; it was restarted once");
  }
  // Simulated (again, when its slave was stopped to make room); false,
  // reported, when it cannot be.
  bool Ready(Embedded& item) {
    if (!item.medium) return false;
    const bool ok = item.simulated || doc->Simulate(item);
    NoteRestart(item);
    if (!ok) Report(item);
    return ok;
  }
  double TimeFor(const Embedded& item) const {
    return std::clamp(o.time.value_or(item.t0), item.t0, std::max(item.t0, item.t1));
  }
  std::string Caption(const Embedded& item, bool live, double t) const {
    char buf[200];
    if (live) {
      std::snprintf(buf, sizeof buf, "Animation %d · %s · frame at t = %.2f s", item.index,
                    item.message.c_str(), t);
      return buf;
    }
    std::string s = "Animation " + std::to_string(item.index) + " · " + item.message;
    if (!item.poster.empty()) s += " · showing the last poster frame";
    return s;
  }
  uint32_t Flags() const {
    return o.handles ? static_cast<uint32_t>(ASGARD_RENDITION_HANDLES) : 0u;
  }

  std::vector<RegionContent> Regions() {
    auto& items = doc->items();
    std::vector<RegionContent> regions(items.size());
    // Each animation is drawn right after it is simulated, in document
    // order, before its slave can be stopped to make room for a later one's:
    // with more animations than --slaves, each still simulates once.
    for (size_t k = 0; k < items.size(); ++k) {
      Embedded& item = items[k];
      RegionContent& r = regions[k];
      bool live = false;
      const double t = TimeFor(item);
      if (Ready(item)) {
        r.picture = doc->Frame(item, ASGARD_DEVICE_PAGE, item.width * 2, item.height * 2, t,
                               Flags(), &live);
        NoteRestart(item);
        if (!live) Report(item);
      }
      if (r.picture.empty()) r.picture = item.poster;
      r.caption = Caption(item, live, t);
    }
    return regions;
  }

  HtmlAnimation Html(Embedded& item) {
    HtmlAnimation a;
    a.width = item.width;
    a.height = item.height;
    a.scene = item.text;
    if (Ready(item)) {
      // A page holds every frame as a PNG: no more than the usual rate.
      const double rate = std::min(item.frame_rate, protocol::kDefaultFrameRate);
      int n = static_cast<int>(std::floor((item.t1 - item.t0) * rate + 1e-9)) + 1;
      n = std::clamp(n, 1, 300);
      const double step = n > 1 ? std::min(1.0 / rate, (item.t1 - item.t0) / (n - 1)) : 0;
      for (int k = 0; k < n; ++k) a.times.push_back(item.t0 + k * step);
      if (a.times.back() < item.t1 - 1e-9) a.times.push_back(item.t1);
      const double poster_t = TimeFor(item);
      bool all_live = true;
      for (size_t k = 0; k < a.times.size(); ++k) {
        bool live = false;
        const Picture p =
            doc->Frame(item, ASGARD_DEVICE_HTML, a.width, a.height, a.times[k], Flags(), &live);
        if (!live) {
          all_live = false;
          break;
        }
        a.frames.push_back(EncodePng(p));
        if (a.times[k] <= poster_t + 1e-9) a.poster = static_cast<int>(k);
      }
      a.live = all_live;
      NoteRestart(item);
      if (!all_live) Report(item);  // the page falls back to the poster: say why
    }
    if (!a.live) {
      a.frames.clear();
      a.times.clear();
      a.poster = 0;
      if (!item.poster.empty()) {
        a.frames.push_back(EncodePng(item.poster));
        a.times.push_back(item.poster.time);
      }
    }
    if (a.live && o.html != "frames" && !PlayerScript().empty()) {
      // The same slave's meshes and poses, at the frames' rate.
      std::string reply, error;
      const double rate = a.times.size() > 1 ? (a.times.size() - 1) / (a.times.back() - a.times[0])
                                             : protocol::kDefaultFrameRate;
      char line[64];
      std::snprintf(line, sizeof line, "player %.9g", rate);
      if (doc->Command(item, line, &reply))
        a.player = PlayerJson(reply, &error);
      else
        error = reply;
      if (a.player.empty()) {
        Warn(Where(item) + "no WebGL data (" + error + "); the page plays its frames");
      } else if (o.html == "webgl-poster") {
        const auto k = static_cast<size_t>(a.poster);
        a.frames = {a.frames[k]};
        a.times = {a.times[k]};
        a.poster = 0;
      }
    }
    a.caption = a.live ? "Animation " + std::to_string(item.index) + " · " + item.message
                       : Caption(item, false, 0);
    return a;
  }

  // The WebGL player of .html pages (web/src/player.js, bundled by the
  // build), read once; empty when it is not there (said once).
  const std::string& PlayerScript() {
    if (!player_script) {
      player_script.emplace();
      const std::string path = serve::WebRoot() + "/player.js";
      std::string error;
      if (!document::ReadFile(path, *player_script, &error) || player_script->empty())
        Note(path +
             " is missing (the build bundles it with node and npm); "
             "pages play pre-rendered frames");
    }
    return *player_script;
  }

  std::string Title() const {
    const auto blocks = Blocks(*doc);
    for (const Block& b : blocks)
      if (b.kind == Block::kTitle || (b.kind == Block::kField && b.label == "Subject"))
        return b.text;
    return o.in;
  }

  int Write(const std::string& out, bool viewer_only = false) {
    const std::string ext = Extension(out);
    std::string error;
    if (ext == "ens" || ext == "xml") {
      if (!document::SaveDocument(doc->document(), out, &error)) return Fail(error);
      if (!o.quiet) std::cout << o.in << ": wrote " << out << "\n";
      return 0;
    }
    if (ext == "html") {
      std::vector<HtmlAnimation> animations;
      for (Embedded& item : doc->items()) animations.push_back(Html(item));
      std::vector<Block> blocks = Blocks(*doc);
      if (viewer_only) {
        const int k = o.animation - 1;
        blocks = {{Block::kTitle, "", "Asgard viewer: animation " + std::to_string(k + 1)},
                  {Block::kEmbedded, "", "", k}};
      }
      const std::string html = WriteHtml(Title(), blocks, animations, viewer_only,
                                         o.html == "frames" ? "" : PlayerScript());
      if (!document::WriteFileAtomic(out, html, &error)) return Fail(error);
      if (!o.quiet) std::cout << o.in << ": wrote " << out << "\n";
      return 0;
    }
    if (ext != "pdf" && ext != "png")
      return Usage("OUT must end in .pdf, .png, .html, .xml or .ens");
    // The pictures first: drawing starts each node, which gives the
    // animation's size the pages need.
    const auto regions = Regions();
    const auto pages = Paginate(Blocks(*doc), *doc);
    std::vector<std::string> written;
    const bool ok = ext == "pdf" ? WritePdf(out, pages, regions, &error)
                                 : WritePngPages(out, pages, regions, o.dpi, &written, &error);
    if (!ok) return Fail(error);
    if (!o.layout.empty() && !document::WriteFileAtomic(o.layout, LayoutJson(pages), &error))
      return Fail(error);
    if (!o.quiet)
      std::cout << o.in << ": wrote " << pages.size() << (pages.size() == 1 ? " page" : " pages")
                << " to " << (written.size() > 1 ? written.front() + " …" : out) << "\n";
    return 0;
  }

  // A verb's or Write's status, kExitIncomplete when it succeeded with
  // warnings that changed OUT.
  int Status(int status) const { return status == 0 && incomplete ? kExitIncomplete : status; }

  int Fail(const std::string& message) const {
    std::cerr << "dochost: " << message << "\n";
    return 1;
  }
};

int RunVerb(Host& h) {
  Options& o = h.o;
  auto& items = h.doc->items();
  if (o.verb == "status") {  // a failing animation is an answer here, not a warning
    for (Embedded& item : items)
      if (item.medium && !item.simulated) h.doc->Simulate(item);
    for (Embedded& item : items)
      std::cout << "animation " << item.index << " <" << item.element << ">: " << item.message
                << "\n";
    return 0;
  }
  if (o.animation > static_cast<int>(items.size()))
    return h.Fail(o.in + " has " + std::to_string(items.size()) + " embedded animation(s), not " +
                  std::to_string(o.animation));
  Embedded& item = items[static_cast<size_t>(o.animation - 1)];
  if (!item.medium)
    return h.Fail(o.in + ": animation " + std::to_string(item.index) + ": " + item.message);
  auto need_simulated = [&]() { return h.Ready(item); };
  if (o.verb == "restart") {
    // Only the slave process: the document is written only to -o OUT.
    if (!h.doc->Restart(item))
      return h.Fail(o.in + ": animation " + std::to_string(item.index) + ": " + item.message);
    if (!o.quiet)
      std::cout << "animation " << item.index << ": restarted: " << item.message << "\n";
    return o.out.empty() ? 0 : h.Write(o.out);
  }
  if (o.verb == "recompute") {
    if (!h.doc->SetText(item, item.text))
      return h.Fail(o.in + ": animation " + std::to_string(item.index) + ": " + item.message);
    bool live = false;
    const Picture p = h.doc->Frame(item, ASGARD_DEVICE_PAGE, item.width * 2, item.height * 2,
                                   h.TimeFor(item), h.Flags(), &live);
    if (!live)  // the slave died or failed: the stored poster is not refreshed
      return h.Fail(o.in + ": animation " + std::to_string(item.index) +
                    ": not recomputed: " + item.message);
    h.doc->SetPoster(item, p);
    if (!o.quiet)
      std::cout << "animation " << item.index << ": recomputed: " << item.message << "\n";
    return h.Write(o.out.empty() ? o.in : o.out);
  }
  if (o.verb == "pause" || o.verb == "seek") {
    double t = 0;
    if (o.verb_args.size() > 1 || (o.verb == "seek" && o.verb_args.empty()) ||
        (!o.verb_args.empty() && !cli::ParseNumber(o.verb_args[0], t)))
      return Usage(o.verb + " takes one time in seconds");
    if (!o.verb_args.empty()) o.time = t;
    if (!need_simulated()) return 1;
    if (!o.quiet)
      std::cout << "animation " << item.index << ": " << (o.verb == "pause" ? "paused" : "sought")
                << " at t = " << h.TimeFor(item) << " s\n";
    return o.out.empty() ? 0 : h.Write(o.out);
  }
  if (o.verb == "handles") {
    if (o.verb_args.size() != 1 || (o.verb_args[0] != "on" && o.verb_args[0] != "off"))
      return Usage("handles takes on or off");
    o.handles = o.verb_args[0] == "on";
    if (!need_simulated()) return 1;
    std::string reply;
    if (!h.doc->Command(item, "handles " + o.verb_args[0], &reply)) return h.Fail(item.message);
    if (!o.quiet) std::cout << "animation " << item.index << ": " << reply << "\n";
    return o.out.empty() ? 0 : h.Write(o.out);
  }
  if (o.verb == "play") {
    if (!o.verb_args.empty()) return Usage("play takes no arguments (use --from, --to)");
    if (!need_simulated()) return 1;
    const double from = std::clamp(o.from.value_or(item.t0), item.t0, item.t1);
    const double to = std::clamp(o.to.value_or(item.t1), from, item.t1);
    const int n =
        std::max(1, static_cast<int>(std::floor((to - from) * item.frame_rate + 1e-9)) + 1);
    const bool frames = !o.out.empty() && Extension(o.out) == "png";
    int played = 0;
    for (int k = 0; k < n; ++k) {
      const double t = std::min(to, from + k / item.frame_rate);
      bool live = false;
      const Picture p =
          h.doc->Frame(item, ASGARD_DEVICE_SCREEN, item.width, item.height, t, h.Flags(), &live);
      if (!live)
        return h.Fail("animation " + std::to_string(item.index) +
                      ": playback stopped: " + item.message);
      ++played;
      if (frames) {
        char suffix[32];
        std::snprintf(suffix, sizeof suffix, "_%04d", k);
        const size_t dot = o.out.rfind('.');
        std::string error;
        if (!document::WriteFileAtomic(o.out.substr(0, dot) + suffix + o.out.substr(dot),
                                       EncodePng(p), &error))
          return h.Fail(error);
      }
    }
    if (!o.quiet)
      std::cout << "animation " << item.index << ": played " << played << " frames, t = " << from
                << " .. " << to << " s" << (frames ? " (frames written)" : "") << "\n";
    if (!o.out.empty() && !frames) return h.Write(o.out);
    return 0;
  }
  if (o.verb == "viewer") {
    if (o.out.empty()) {
      std::cout << "animation " << item.index << ": a viewer needs a display; write it with "
                << "-o viewer.html and open that page\n";
      return 0;
    }
    if (Extension(o.out) != "html") return Usage("viewer writes an .html page");
    return h.Write(o.out, true);
  }
  return Usage("unknown verb '" + o.verb + "'");
}

// The document view's pages: laid out as `convert` lays out the PDF, and
// each drawn as it draws the PDF's pages (each region with its poster; the
// live rendition lies over it), at twice the CSS pixel density, when the
// browser first asks for it (a long document opens at once; pictures are
// kept once drawn; a page that cannot be drawn is answered 500 and said on
// stderr).
serve::HostPages ServePages(HostDocument& doc) {
  constexpr double kCssPx = 96.0 / 72.0;  // CSS pixels per point
  struct Drawing {
    PageStyle style;
    std::vector<Page> pages;
    std::vector<RegionContent> regions;
    std::mutex mutex;  // the server's threads ask; Pango and Cairo draw one page at a time
    std::vector<std::string> drawn;
  };
  auto d = std::make_shared<Drawing>();
  d->regions.resize(doc.items().size());
  for (size_t k = 0; k < d->regions.size(); ++k) {
    const Embedded& item = doc.items()[k];
    d->regions[k].picture = item.poster;
    // A live rendition's toolbar says its status; one without says why.
    const bool live = item.medium && item.medium->node_rpc();
    d->regions[k].caption = "Animation " + std::to_string(item.index) +
                            (live || item.message.empty() ? "" : " · " + item.message);
  }
  d->pages = Paginate(Blocks(doc), doc, d->style);
  d->drawn.resize(d->pages.size());
  serve::HostPages out;
  for (const Page& page : d->pages) {
    serve::HostPage p;
    p.width = d->style.width * kCssPx;
    p.height = d->style.height * kCssPx;
    for (const TextLine& l : PageLines(page))
      p.lines.push_back({l.x * kCssPx, l.y * kCssPx, l.w * kCssPx, l.h * kCssPx, l.size * kCssPx,
                         l.family, l.bold, l.text});
    for (const Placed& b : page.items) {
      if (b.block.kind != Block::kEmbedded) continue;
      const Embedded& item = doc.items()[static_cast<size_t>(b.block.item)];
      p.regions.push_back({item.path, b.x * kCssPx, b.y * kCssPx, b.w * kCssPx, b.h * kCssPx});
    }
    out.pages.push_back(std::move(p));
  }
  out.picture = [d](size_t k) -> std::string {
    std::lock_guard lock(d->mutex);
    if (k >= d->pages.size()) return {};
    if (d->drawn[k].empty()) {
      std::string error;
      d->drawn[k] = PagePng(d->pages[k], d->regions, 2 * 96.0, &error, d->style);
      if (d->drawn[k].empty())
        std::cerr << "dochost serve: page " << k + 1 << ": " << error << "\n";
    }
    return d->drawn[k];
  };
  return out;
}

// dochost serve: the editor server (web/server/launch.h).
int ServeCommand(const std::vector<std::string>& args) {
  std::string file, error;
  serve::LaunchOptions lo;
  if (!serve::ParseLaunchArgs({args.begin() + 1, args.end()}, &file, &lo, &error)) {
    std::cerr << "dochost serve: " << error << "\nUsage:\n" << serve::kServeUsage;
    return 2;
  }
  // The editor and the document view's renditions share each animation's
  // slave: the medium's nodes, with room for one per animation (each Hub
  // calls only its own item, from its own thread).
  auto loaded = document::LoadDocument(file);
  if (!loaded.document) {
    std::cerr << "dochost serve: " << loaded.error << "\n";
    return 1;
  }
  MediumRegistry registry(MediumRegistry::DefaultSearchPath());
  HostOptions ho;
  ho.slave_path = lo.core;
  ho.max_slaves = std::numeric_limits<int>::max();
  ho.name = file;
  std::vector<std::string> warnings;
  HostDocument doc(std::move(*loaded.document), registry, ho, &warnings);
  for (const auto& w : warnings) std::cerr << "dochost serve: " << w << "\n";
  return serve::ServeDocument(file, lo, AttachTo(doc), ServePages(doc));
}

int Main(const std::vector<std::string>& args) {
  if (!args.empty() && args[0] == "serve") return ServeCommand(args);
  Host h;
  if (auto status = Parse(args, h.o)) return *status;
  Options& o = h.o;
  if (o.command == "convert" && Extension(o.out) != "pdf" && Extension(o.out) != "png" &&
      Extension(o.out) != "html" && Extension(o.out) != "xml" && Extension(o.out) != "ens")
    return Usage("convert: OUT must end in .pdf, .png, .html, .xml or .ens");
  auto loaded = document::LoadDocument(o.in);
  if (!loaded.document) return h.Fail(loaded.error);
  std::vector<std::string> path = o.plugin_path;
  for (const auto& d : MediumRegistry::DefaultSearchPath()) path.push_back(d);
  h.registry = std::make_unique<MediumRegistry>(path);
  HostOptions ho;
  ho.slave_path = o.core;
  ho.timeout_seconds = o.timeout;
  ho.max_slaves = o.slaves;
  ho.slave_memory_mb = o.slave_memory;
  ho.name = o.in;
  ProgressBar bar(!o.quiet && isatty(STDERR_FILENO));
  ho.progress = [&bar](const Embedded& item, double f) { bar(item, f); };
  std::vector<std::string> warnings;
  h.doc = std::make_unique<HostDocument>(std::move(*loaded.document), *h.registry, ho, &warnings);
  for (const auto& w : warnings) h.Warn(w);
  if (o.command == "convert") return h.Status(h.Write(o.out));
  return h.Status(RunVerb(h));
}

}  // namespace
}  // namespace asgard::host

int main(int argc, char** argv) {
  try {
    return asgard::host::Main(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& e) {
    std::cerr << "dochost: internal error: " << e.what() << "\n";
    return 1;
  }
}
