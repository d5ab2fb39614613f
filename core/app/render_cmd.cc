// asgard render / asgard export: pictures, movies and scene files.
//
//   asgard render FILE [-t T | --frames START:END:COUNT] [--size WxH]
//                      [--style wire|shaded] [view options] [--overlay LIST] -o OUT
//   asgard export FILE --format rayshade|povray|gltf [-t T] [view options] -o OUT
//
// Design: both commands simulate the whole scene first (the default view
// frames the animation: render::SceneSampler::SceneBound), then sample poses
// at the requested times through render::SceneSampler; a view element's
// -follow or -trajectory (or --follow) moves the view centre per frame.  The output file's
// extension chooses the writer.  Conventions follow `asgard simulate` (main.cc): usage problems
// print the message and the help and exit 2; scene errors, solver failures and write errors exit 1;
// a progress bar is shown on stderr for multi-frame jobs when it is a terminal.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/app/cli.h"
#include "core/app/commands.h"
#include "core/lang/lang.h"
#include "core/physics/trajectory.h"
#include "core/pipeline/pipeline.h"
#include "core/protocol/protocol.h"
#include "core/render/sampler.h"
#include "core/render/shaded.h"
#include "core/render/wire.h"
#include "formats/document/file.h"
#include "formats/export/export.h"

namespace asgard::app {

const char* const kRenderHelp = R"(Usage: asgard render FILE [options] -o OUT

Simulates the scene script FILE and draws it.  The extension of OUT chooses
the output:
  .png .ppm        pictures (one per frame: OUT_0000.png ..., or give a
                   pattern such as frame%04d.png)
  .svg             line drawing (one file per frame)
  .pdf .ps         line drawings, one page per frame
  .mp4 .webm .gif  movies (H.264, VP9, animated GIF) through ffmpeg

Times (default: the start time for pictures, every frame of the animation at
the scene's frame rate for movies):
  -t T                     one frame at time T
  --frames START:END:COUNT COUNT frames evenly spaced from START to END
  --until T                simulate to T instead of the simulator's -finish

Picture:
  --size WxH        size in pixels (default 640x480)
  --style S         shaded (OpenGL shading; default for pictures and movies)
                    or wire (line drawing; always used for .svg .pdf .ps)
  --aa N            shaded antialiasing: N×N supersampling, 1..4 (default 2)
  --overlay LIST    comma-separated: handles, links, forces, paths, or all
  --fps F           movie playback rate (default: the scene's frame rate)

View (default: the whole animation framed, tilted slightly, seen from +z):
  --view NAME       use the scene's view element NAME (its -follow, -trajectory
                    and expressions of time or state move it frame by frame)
  --rot AX,AY,AZ    rotation of the scene, a rotation vector in degrees
  --scale S         zoom (1: the whole scene fits)
  --center X,Y,Z    centre of rotation and scaling (scene units)
  --pan X,Y,Z       translation after the rotation (scene units)
  --follow BODY     the centre of rotation and scaling follows BODY's centre
                    of mass (camera motion)

  --quiet           no messages or progress bar
  -h, --help        this help

Exit status 0 on success, 1 on scene errors, solver or write failures, 2 on
bad usage.
)";

const char* const kExportHelp = R"(Usage: asgard export FILE --format F -o OUT [options]

Simulates the scene script FILE and writes it for another program:
  --format rayshade   Rayshade input (the dissertation's ray tracer), at time T
  --format povray     POV-Ray 3.7 scene, at time T
                      (render it with: povray +IOUT +W640 +H480 +A)
  --format gltf       glTF 2.0 binary (.glb): meshes, camera, lights and the
                      simulated motion as an animation (Blender, web viewers)
The format may be left out when OUT ends in .ray, .pov or .glb.

Options:
  -t T              time of the still scene (default: the start time)
  --frames START:END:COUNT   animation samples for glTF (default: every frame
                    at the scene's frame rate)
  --until T         simulate to T instead of the simulator's -finish
  --size WxH        picture size the camera is set up for (default 640x480)
  --view NAME, --rot AX,AY,AZ, --scale S, --center X,Y,Z, --pan X,Y,Z,
  --follow BODY     the view, as for asgard render (at time T)
  --quiet           no messages
  -h, --help        this help

Exit status 0 on success, 1 on scene errors, solver or write failures, 2 on
bad usage.
)";

namespace {

// "a,b,c" (also "a b c" or "a:b:c" with the given separator).
bool ParseList(const std::string& s, char sep, std::vector<double>& out) {
  out.clear();
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep)) {
    double v;
    if (!ParseNumber(item, v)) return false;
    out.push_back(v);
  }
  return true;
}

bool ParseVec3(const std::string& s, Eigen::Vector3d& v) {
  std::vector<double> xs;
  if (!ParseList(s, ',', xs) || xs.size() != 3) return false;
  v = Eigen::Vector3d(xs[0], xs[1], xs[2]);
  return true;
}

class FrameProgress {
 public:
  FrameProgress(int total, bool enabled) : total_(total), enabled_(enabled && total > 1) {}
  void Step(int done) {
    if (!enabled_) return;
    const int width = 40;
    const int filled = total_ > 0 ? done * width / total_ : width;
    std::fprintf(stderr, "\r[%s%s] frame %d/%d", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), done, total_);
    if (done >= total_) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  int total_;
  bool enabled_;
};

// Options shared by render and export.
struct Common {
  std::string file, out;
  std::optional<double> t, until;
  std::optional<std::array<double, 3>> frames;  // start, end, count
  int width = 640, height = 480;
  std::string view_name;
  std::optional<Eigen::Vector3d> rot_degrees, center, pan;
  std::optional<double> scale;
  std::string follow;  // body whose centre of mass the view centre tracks
  bool quiet = false;
};

// Consumes args[i] (and its value) when it is a shared option.  Returns
// 1 when consumed, 0 when not a shared option, -1 on a usage error (message set).
int ParseCommon(const std::vector<std::string>& args, size_t& i, Common& c, std::string& message) {
  const std::string& a = args[i];
  auto value = [&]() -> std::optional<std::string> {
    if (i + 1 >= args.size()) return std::nullopt;
    return args[++i];
  };
  auto fail = [&](const std::string& m) {
    message = m;
    return -1;
  };
  if (a == "-o" || a == "--out") {
    auto v = value();
    if (!v || v->empty()) return fail(a + " needs a file name");
    c.out = *v;
  } else if (a == "-t" || a == "--until" || a == "--scale") {
    auto v = value();
    double d;
    if (!v || !ParseNumber(*v, d)) return fail(a + " needs a number");
    if (a == "-t")
      c.t = d;
    else if (a == "--until")
      c.until = d;
    else if (d <= 0)
      return fail("--scale must be positive");
    else
      c.scale = d;
  } else if (a == "--frames") {
    auto v = value();
    std::vector<double> xs;
    if (!v || !ParseList(*v, ':', xs) || xs.size() != 3 || xs[2] < 1 ||
        xs[2] != std::floor(xs[2]) || xs[2] > 1e6)
      return fail("--frames needs START:END:COUNT with a whole COUNT >= 1");
    c.frames = std::array<double, 3>{xs[0], xs[1], xs[2]};
  } else if (a == "--size") {
    auto v = value();
    int w = 0, h = 0;
    char extra = 0;
    constexpr int kMax = protocol::kMaxRenditionSide;
    if (!v || std::sscanf(v->c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 1 || h < 1 ||
        w > kMax || h > kMax)
      return fail("--size needs WxH, e.g. 640x480 (at most " + std::to_string(kMax) + " each way)");
    c.width = w, c.height = h;
  } else if (a == "--view") {
    auto v = value();
    if (!v) return fail("--view needs the name of a view element");
    c.view_name = *v;
  } else if (a == "--follow") {
    auto v = value();
    if (!v || v->empty()) return fail("--follow needs a body name");
    c.follow = *v;
  } else if (a == "--rot" || a == "--center" || a == "--pan") {
    auto v = value();
    Eigen::Vector3d x;
    if (!v || !ParseVec3(*v, x)) return fail(a + " needs three numbers X,Y,Z");
    if (a == "--rot")
      c.rot_degrees = x;
    else if (a == "--center")
      c.center = x;
    else
      c.pan = x;
  } else if (a == "--quiet") {
    c.quiet = true;
  } else if (!a.empty() && a[0] == '-') {
    return 0;
  } else if (!c.file.empty()) {
    return fail("only one FILE is accepted");
  } else {
    c.file = a;
  }
  return 1;
}

// Everything after argument parsing: the simulated run and its sampler.
struct Loaded {
  pipeline::Run run;
  std::unique_ptr<render::SceneSampler> sampler;
  std::optional<render::ViewMotion> motion;  // the scene's view (or the framing) over time
  Common overrides;                          // --rot --scale --center --pan --follow
  std::vector<double> times;
  int follow = -1;  // body index for --follow
  std::string file;

  // The view at time t: the scene's view element as it moves (its
  // -follow, -trajectory and expressions), the command line's options
  // over it.  An expression unusable at t is reported once.
  render::ViewState ViewAt(double t) const {
    std::string problem;
    render::ViewState v = motion->At(t, &problem);
    if (!problem.empty() && !warned) {
      std::cerr << "asgard: " << file << ": warning: " << problem
                << " (its default is used where it is)\n";
      warned = true;
    }
    const Common& c = overrides;
    if (c.rot_degrees) {
      const Eigen::Vector3d r = *c.rot_degrees * (M_PI / 180.0);
      v.rotation = r.norm() > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(r.norm(), r.normalized()))
                                : Eigen::Quaterniond::Identity();
    }
    if (c.scale) v.scale = *c.scale;
    if (c.center) v.center = *c.center;
    if (c.pan) v.position = *c.pan;
    if (follow >= 0) v.center = sampler->Poses(t)[follow].p;
    return v;
  }
  render::Camera CameraAt(double t, int width, int height) const {
    return render::MakeCamera(ViewAt(t), width, height);
  }

 private:
  mutable bool warned = false;
};

// Handles args[i] when it is -h/--help or an option both commands take.
// Returns an exit status (0 after the help, 2 after a usage error), or
// kConsumed, or kOwnOption when the command must look at args[i] itself.
constexpr int kConsumed = -1, kOwnOption = -2;
int TakeShared(const std::vector<std::string>& args, size_t& i, Common& c,
               const std::string& command, const char* help) {
  if (args[i] == "-h" || args[i] == "--help") {
    std::cout << help;
    return 0;
  }
  std::string message;
  const int r = ParseCommon(args, i, c, message);
  if (r < 0) return Usage(command + ": " + message, help);
  return r > 0 ? kConsumed : kOwnOption;
}

// Simulates and prepares the view and times.  Returns an exit status, or -1
// to continue.
int Load(const Common& c, const char* help, bool movie, Loaded& l) {
  std::string text;
  if (!ReadFile(c.file, text)) return 1;
  pipeline::RunOptions opts;
  opts.until = c.until;
  opts.solver.threads = solver::MachineThreads();
  l.run = pipeline::Simulate(text, opts);
  for (const auto& d : l.run.diagnostics) std::cerr << lang::FormatDiagnostic(c.file, d) << "\n";
  if (!l.run.solver_error.empty())
    std::cerr << "asgard: " << c.file << ": " << l.run.solver_error << "\n";
  if (!l.run.ok) return 1;
  l.sampler =
      std::make_unique<render::SceneSampler>(l.run.scene, *l.run.equations, *l.run.simulation);
  for (const auto& name : l.sampler->unknown_colors())
    std::cerr << "asgard: " << c.file << ": warning: unknown colour '" << name
              << "' (a palette colour is used)\n";
  const double t0 = l.sampler->t0(), t1 = l.sampler->t1();
  auto in_range = [&](double t) { return t >= t0 - 1e-12 && t <= t1 + 1e-12; };
  auto range = [&]() {
    std::ostringstream s;
    s << t0 << " .. " << t1;
    return s.str();
  };
  if (c.t && c.frames) return Usage("give either -t or --frames, not both", help);
  if (c.t) {
    if (!in_range(*c.t)) return Usage("-t must be within the simulated time " + range(), help);
    l.times = {std::clamp(*c.t, t0, t1)};
  } else if (c.frames) {
    const auto& f = *c.frames;
    if (!in_range(f[0]) || !in_range(f[1]))
      return Usage("--frames must lie within the simulated time " + range(), help);
    l.times = render::SceneSampler::FrameTimes(std::clamp(f[0], t0, t1), std::clamp(f[1], t0, t1),
                                               static_cast<int>(f[2]));
  } else if (movie) {
    l.times = l.sampler->FrameTimes();
  } else {
    l.times = {t0};
  }
  const scene::View* element = l.sampler->FindView(c.view_name);
  if (!c.view_name.empty() && !element)
    return Usage("the scene has no view element named '" + c.view_name + "'", help);
  l.motion.emplace(*l.sampler, element);
  l.overrides = c;
  l.file = c.file;
  // --follow on the command line wins over the element's -follow or
  // -trajectory (it sets the centre last).
  if (!c.follow.empty()) {
    const auto& bodies = l.sampler->bodies();
    for (size_t b = 0; b < bodies.size(); ++b)
      if (bodies[b].name == c.follow) l.follow = static_cast<int>(b);
    if (l.follow < 0) return Usage("--follow: the scene has no body '" + c.follow + "'", help);
  } else if (!l.motion->error().empty()) {
    std::cerr << "asgard: " << c.file << ": " << l.motion->error() << "\n";
    return 1;
  }
  return -1;
}

bool ParseOverlays(const std::string& list, render::Overlays& o) {
  std::istringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item == "handles")
      o.handles = true;
    else if (item == "links")
      o.links = true;
    else if (item == "forces")
      o.forces = true;
    else if (item == "paths")
      o.paths = true;
    else if (item == "all")
      o.handles = o.links = o.forces = o.paths = true;
    else
      return false;
  }
  return true;
}

}  // namespace

int RenderCommand(const std::vector<std::string>& args) {
  Common c;
  std::string style;
  render::Overlays overlays;
  int aa = 2;
  std::optional<double> fps;
  for (size_t i = 0; i < args.size(); ++i) {
    if (const int r = TakeShared(args, i, c, "render", kRenderHelp); r != kOwnOption) {
      if (r == kConsumed) continue;
      return r;
    }
    const std::string& a = args[i];
    const bool has_value = i + 1 < args.size();
    if (a == "--style") {
      if (!has_value || (args[i + 1] != "wire" && args[i + 1] != "shaded"))
        return Usage("render: --style must be wire or shaded", kRenderHelp);
      style = args[++i];
    } else if (a == "--overlay") {
      if (!has_value || !ParseOverlays(args[++i], overlays))
        return Usage("render: --overlay takes handles, links, forces, paths or all", kRenderHelp);
    } else if (a == "--aa") {
      double d;
      if (!has_value || !ParseNumber(args[++i], d) || d < 1 || d > 4 || d != std::floor(d))
        return Usage("render: --aa must be 1, 2, 3 or 4", kRenderHelp);
      aa = static_cast<int>(d);
    } else if (a == "--fps") {
      double d;
      if (!has_value || !ParseNumber(args[++i], d) || d <= 0 || d > 1000)
        return Usage("render: --fps needs a positive number", kRenderHelp);
      fps = d;
    } else {
      return Usage("render: unknown option '" + a + "'", kRenderHelp);
    }
  }
  if (c.file.empty()) return Usage("render: FILE is required", kRenderHelp);
  if (c.out.empty()) return Usage("render: -o OUT is required", kRenderHelp);
  const std::string ext = document::Extension(c.out);
  const bool movie = formats::MovieWriter::IsMovie(c.out);
  const bool vector = ext == "svg" || ext == "pdf" || ext == "ps";
  if (!movie && !vector && ext != "png" && ext != "ppm")
    return Usage("render: OUT must end in .png, .ppm, .svg, .pdf, .ps, .mp4, .webm or .gif",
                 kRenderHelp);
  if (vector && style == "shaded")
    return Usage("render: ." + ext + " holds line drawings; use --style wire or a raster format",
                 kRenderHelp);
  const bool shaded = !vector && style != "wire";

  Loaded l;
  if (const int status = Load(c, kRenderHelp, movie, l); status >= 0) return status;
  const auto lights = l.sampler->SceneLights();
  std::vector<std::vector<Eigen::Vector3d>> paths;
  if (overlays.paths) paths = l.sampler->Paths(l.sampler->FrameTimes());
  auto frame_input = [&](double t) {
    render::FrameInput f;
    f.sampler = l.sampler.get();
    f.t = t;
    f.poses = l.sampler->Poses(t);
    const render::ViewState view = l.ViewAt(t);
    f.camera = render::MakeCamera(view, c.width, c.height);
    f.view_radius = view.radius / view.scale;
    f.paths = &paths;
    return f;
  };
  std::unique_ptr<render::ShadedRenderer> renderer;
  if (shaded) {
    render::ShadedStyle st;
    st.supersample = aa;
    renderer = std::make_unique<render::ShadedRenderer>(c.width, c.height, st);
    if (!renderer->ok()) {
      std::cerr << "asgard: " << renderer->error() << "\n";
      return 1;
    }
  }
  auto raster = [&](const render::FrameInput& f) {
    if (!shaded) return render::RenderWire(f, overlays);
    render::Image img = renderer->Render(*l.sampler, f.poses, f.camera, lights);
    render::OverlayImage(img, f, overlays);
    return img;
  };

  const int n = static_cast<int>(l.times.size());
  FrameProgress progress(n, !c.quiet && isatty(STDERR_FILENO));
  std::string error;
  int written = 0;
  if (movie) {
    formats::MovieWriter writer;
    if (!writer.Open(c.out, c.width, c.height, fps.value_or(l.sampler->frame_rate()))) {
      std::cerr << "asgard: " << writer.error() << "\n";
      return 1;
    }
    for (int k = 0; k < n; ++k) {
      if (!writer.AddFrame(raster(frame_input(l.times[k])))) break;
      progress.Step(++written);
    }
    if (!writer.Finish() || written < n) {
      std::cerr << "asgard: " << writer.error() << "\n";
      return 1;
    }
  } else if (ext == "pdf" || ext == "ps") {
    render::VectorDocument doc(
        c.out,
        ext == "pdf" ? render::VectorDocument::Format::kPdf : render::VectorDocument::Format::kPs,
        c.width, c.height);
    if (!doc.ok()) {
      std::cerr << "asgard: " << doc.error() << "\n";
      return 1;
    }
    for (int k = 0; k < n; ++k) {
      doc.AddPage(frame_input(l.times[k]), overlays);
      progress.Step(++written);
    }
    if (!doc.Finish()) {
      std::cerr << "asgard: cannot write '" << c.out << "': " << doc.error() << "\n";
      return 1;
    }
  } else {
    for (int k = 0; k < n; ++k) {
      const std::string path = n == 1 ? c.out : formats::FramePath(c.out, k, n);
      const auto f = frame_input(l.times[k]);
      bool ok = true;
      if (ext == "svg") {
        render::VectorDocument doc(path, render::VectorDocument::Format::kSvg, c.width, c.height);
        if (doc.ok()) doc.AddPage(f, overlays);
        ok = doc.ok() && doc.Finish();
        if (!ok) error = "cannot write '" + path + "'";
      } else {
        const render::Image img = raster(f);
        ok = ext == "png" ? render::WritePng(img, path, &error)
                          : render::WritePpm(img, path, &error);
      }
      if (!ok) {
        std::cerr << "asgard: " << error << "\n";
        return 1;
      }
      progress.Step(++written);
    }
  }
  if (!c.quiet)
    std::cout << c.file << ": wrote " << written << (written == 1 ? " frame" : " frames") << " ("
              << (shaded ? "shaded" : "line drawing") << ", " << c.width << "x" << c.height
              << ") to " << c.out << (n > 1 && !movie && !vector ? " (numbered)" : "") << "\n";
  return 0;
}

int ExportCommand(const std::vector<std::string>& args) {
  Common c;
  std::string format;
  for (size_t i = 0; i < args.size(); ++i) {
    if (const int r = TakeShared(args, i, c, "export", kExportHelp); r != kOwnOption) {
      if (r == kConsumed) continue;
      return r;
    }
    const std::string& a = args[i];
    if (a == "--format") {
      if (i + 1 >= args.size()) return Usage("export: --format needs a value", kExportHelp);
      format = args[++i];
      if (format != "rayshade" && format != "povray" && format != "gltf")
        return Usage("export: --format must be rayshade, povray or gltf", kExportHelp);
    } else {
      return Usage("export: unknown option '" + a + "'", kExportHelp);
    }
  }
  if (c.file.empty()) return Usage("export: FILE is required", kExportHelp);
  if (c.out.empty()) return Usage("export: -o OUT is required", kExportHelp);
  if (format.empty()) {
    const std::string ext = document::Extension(c.out);
    format = ext == "ray" ? "rayshade" : ext == "pov" ? "povray" : ext == "glb" ? "gltf" : "";
    if (format.empty())
      return Usage(
          "export: give --format (rayshade, povray or gltf) or name OUT .ray, .pov or .glb",
          kExportHelp);
  }
  const bool gltf = format == "gltf";
  if (!gltf && c.frames)
    return Usage("export: --frames applies to --format gltf only", kExportHelp);
  Loaded l;
  if (const int status = Load(c, kExportHelp, gltf, l); status >= 0) return status;
  formats::StillScene s;
  s.sampler = l.sampler.get();
  s.t = c.t.value_or(l.sampler->t0());
  s.camera = l.CameraAt(s.t, c.width, c.height);
  s.lights = l.sampler->SceneLights();
  std::string error;
  bool ok = false;
  if (format == "rayshade")
    ok = formats::WriteRayshade(c.out, s, &error);
  else if (format == "povray")
    ok = formats::WritePovray(c.out, s, &error);
  else
    ok = formats::WriteGltf(c.out, s, c.t ? std::vector<double>{} : l.times, &error);
  if (!ok) {
    std::cerr << "asgard: " << error << "\n";
    return 1;
  }
  if (!c.quiet) {
    std::cout << c.file << ": wrote " << format << " scene to " << c.out;
    if (gltf && !c.t)
      std::cout << " (" << l.times.size() << " animation samples)";
    else
      std::cout << " at t = " << s.t;
    std::cout << "\n";
  }
  return 0;
}

}  // namespace asgard::app
