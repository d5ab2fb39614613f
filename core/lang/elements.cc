// Element commands: simulator body link force torque trajectory lightsource
// view (shape_set is in shapes.cc).
//
// Design: every command is a Tcl object command in the master interpreter
// exposed to the child as an alias.  The shared entry point (RunElement)
// locates the command in the source, counts the run, calls the handler and
// converts every failure into a diagnostic -- it always returns TCL_OK (so an
// enclosing loop or proc keeps going and the other elements are still made),
// except when an evaluation limit was hit, which must stop the script.
// Handlers validate everything before appending, so a failed command leaves
// no partial element behind.  Cross references (shape, bodies, trajectory)
// are checked later in FinishScene, so forward references work.
#include "core/lang/elements.h"

#include <tcl.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>

#include "core/expr/expr.h"
#include "core/lang/options.h"
#include "core/lang/source_map.h"

namespace asgard::lang {

scene::SourceSpan Invocation::ArgSpan(int i) const {
  if (const SourceWord* w = ArgWord(i)) return w->span;
  return site.command;
}

const SourceWord* Invocation::ArgWord(int i) const {
  if (!site.words_matched || i < 0 || i >= objc) return nullptr;
  return &site.source->words[i];
}

std::string Invocation::Arg(int i) const { return ObjString(objv[i]); }

namespace {
constexpr size_t kMaxDiagnostics = 200;

void AddDiagnostic(scene::Scene& s, scene::Severity severity, std::string message,
                   const scene::SourceSpan& span) {
  if (s.diagnostics.size() > kMaxDiagnostics) return;
  if (s.diagnostics.size() == kMaxDiagnostics) {
    s.diagnostics.push_back(
        {scene::Severity::kError, "too many errors; the rest are not reported", span});
    return;
  }
  s.diagnostics.push_back({severity, std::move(message), span});
}
}  // namespace

void EvalContext::AddError(std::string message, const scene::SourceSpan& span) {
  AddDiagnostic(scene, scene::Severity::kError, std::move(message), span);
}

void EvalContext::AddWarning(std::string message, const scene::SourceSpan& span) {
  AddDiagnostic(scene, scene::Severity::kWarning, std::move(message), span);
}

namespace {

bool StartsWithDash(const std::string& s) { return !s.empty() && s[0] == '-'; }

bool IsIdentifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return true;
}

template <typename T>
void CheckUnique(const std::vector<T>& existing, const Invocation& inv, const std::string& name) {
  for (const T& e : existing) {
    if (!name.empty() && e.name == name) {
      throw ElementError{
          inv.kind + ": '" + name + "' is already defined" +
              (e.command.known() ? " at line " + std::to_string(e.command.line) : std::string()),
          1};
    }
  }
}

// Optional name for lightsource/view: returns the index of the first option.
int OptionalName(const Invocation& inv, std::string& name) {
  if (inv.objc > 1 && !StartsWithDash(inv.Arg(1))) {
    name = inv.Arg(1);
    return 2;
  }
  return 1;
}

}  // namespace

std::string RequireName(const Invocation& inv, bool expression_name) {
  if (inv.objc < 2 || StartsWithDash(inv.Arg(1)) || inv.Arg(1).empty()) {
    throw ElementError{inv.kind + ": missing name (" + inv.kind + " NAME ?-option value ...?)", -1};
  }
  std::string name = inv.Arg(1);
  if (expression_name) {
    if (!IsIdentifier(name)) {
      throw ElementError{inv.kind + ": name '" + name +
                             "' must be letters, digits and _ (it is used in expressions as " +
                             name + ".x)",
                         1};
    }
    if (name == "t" || name == "pi" || name == "e") {
      throw ElementError{inv.kind + ": name '" + name + "' is reserved in expressions", 1};
    }
  }
  return name;
}

void FillBase(const Invocation& inv, scene::ElementBase& base) {
  base.command = inv.site.command;
  base.call_site = inv.site.call_site;
  base.in_proc = inv.site.in_proc;
  base.in_eval = inv.site.in_eval;
  base.run_count = 1;
}

// Time spans and step sizes a run can actually cover, checked here so that
// `check` refuses what would make `simulate` loop forever or exhaust memory.
constexpr double kMaxFrames = 1e7;
constexpr double kMaxSteps = 1e9;
// Steps must stay distinguishable: the span at least this fraction of the
// largest time's magnitude (a double resolves about 1e-16 of it).
constexpr double kMinRelativeSpan = 1e-9;

void ValidateSpan(const Options& o, const scene::Simulator& s) {
  auto where = [&](std::initializer_list<const char*> names) {
    for (const char* n : names)
      if (o.Has(n)) return o.Get(n)->arg;
    return -1;
  };
  const double span = s.finish - s.start;
  if (!std::isfinite(span)) {
    throw ElementError{"simulator: the time span from -start (" + FormatNumber(s.start) +
                           ") to -finish (" + FormatNumber(s.finish) + ") is not finite",
                       where({"finish", "start"})};
  }
  const double magnitude = std::max(std::abs(s.start), std::abs(s.finish));
  if (span < kMinRelativeSpan * magnitude) {
    throw ElementError{"simulator: the time span " + FormatNumber(span) +
                           " is too short to be resolved at times near " + FormatNumber(magnitude) +
                           " (steps would not advance the time)",
                       where({"finish", "start"})};
  }
  if (span * s.frame_rate > kMaxFrames) {
    throw ElementError{"simulator: " + FormatNumber(span * s.frame_rate) +
                           " frames (the time span " + FormatNumber(span) + " times -frames " +
                           FormatNumber(s.frame_rate) + ") is above the limit of " +
                           FormatNumber(kMaxFrames),
                       where({"frames", "finish", "start"})};
  }
  if (s.max_step && span / *s.max_step > kMaxSteps) {
    throw ElementError{"simulator: -maxstep " + FormatNumber(*s.max_step) +
                           " would take more than " + FormatNumber(kMaxSteps) +
                           " steps over the time span " + FormatNumber(span),
                       where({"maxstep"})};
  }
}

void SimulatorCommand(EvalContext& ctx, const Invocation& inv, std::string&) {
  Options o(inv, 1, {"start", "finish", "step", "maxstep", "rtol", "atol", "collisions", "frames"});
  scene::Simulator s;
  FillBase(inv, s);
  s.start = o.Number("start").value_or(s.start);
  s.finish = o.Number("finish").value_or(s.finish);
  if (!(s.finish > s.start)) {
    const OptionValue* v = o.Has("finish") ? o.Get("finish") : o.Get("start");
    throw ElementError{"simulator: -finish (" + FormatNumber(s.finish) +
                           ") must be greater than -start (" + FormatNumber(s.start) + ")",
                       v->arg};
  }
  s.step = o.Positive("step");
  s.max_step = o.Positive("maxstep");
  s.rtol = o.Positive("rtol");
  s.atol = o.Positive("atol");
  s.collisions = o.Bool("collisions").value_or(true);
  s.frame_rate = o.Positive("frames").value_or(s.frame_rate);
  ValidateSpan(o, s);
  RecordOptions(inv, o, s);
  ctx.scene.simulator = std::move(s);
}

void BodyCommand(EvalContext& ctx, const Invocation& inv, std::string& name) {
  name = RequireName(inv, true);
  int first = 2;
  bool positional_shape = inv.objc > 2 && !StartsWithDash(inv.Arg(2));
  if (positional_shape) first = 3;
  Options o(inv, first,
            {"shape", "artbody", "init_pos", "init_rot", "init_dpos", "init_drot", "mass", "moment",
             "color", "ct", "restitution", "friction", "static"});
  CheckUnique(ctx.scene.bodies, inv, name);
  scene::Body b;
  FillBase(inv, b);
  b.name = name;
  if (positional_shape) {
    if (o.Has("shape")) {
      throw ElementError{
          inv.kind + " '" + name + "': the shape is given twice (" + inv.Arg(2) + " and -shape)",
          o.Get("shape")->arg};
    }
    b.shape = inv.Arg(2);
  } else if (auto s = o.String("shape")) {
    b.shape = *s;
  } else {
    throw ElementError{inv.kind + " '" + name + "': missing required option -shape", -1};
  }
  b.artbody = o.String("artbody").value_or("");
  b.init_pos = o.Vector("init_pos").value_or(b.init_pos);
  b.init_rot = o.Rotation("init_rot").value_or(b.init_rot);
  b.init_dpos = o.Vector("init_dpos").value_or(b.init_dpos);
  b.init_drot = o.Vector("init_drot").value_or(b.init_drot);
  b.mass = o.Positive("mass");
  b.moment = o.Moment("moment");
  b.color = o.String("color").value_or("");
  b.collision_test = o.Bool("ct").value_or(true);
  b.restitution = o.NonNegative("restitution");
  if (b.restitution && *b.restitution > 1.0) {
    o.Fail(*o.Get("restitution"), "must be between 0 and 1");
  }
  b.friction = o.NonNegative("friction");
  b.is_static = o.Bool("static").value_or(false);
  if (positional_shape) b.options.emplace_back("shape", MakeWord(inv, 2));
  RecordOptions(inv, o, b);
  ctx.scene.bodies.push_back(std::move(b));
}

void LinkCommand(EvalContext& ctx, const Invocation& inv, std::string&) {
  Options o(inv, 1,
            {"body1", "offset1", "body2", "offset2", "x", "y", "z", "trajectory", "tightness"});
  scene::Link l;
  FillBase(inv, l);
  auto body1 = o.String("body1");
  if (!body1) throw ElementError{"link: missing required option -body1", -1};
  l.body1 = *body1;
  l.offset1 = o.Vector("offset1").value_or(l.offset1);
  l.body2 = o.String("body2").value_or("");
  l.offset2 = o.Vector("offset2").value_or(l.offset2);
  bool has_point = o.Has("x") || o.Has("y") || o.Has("z");
  const char* axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) l.point[i] = o.Expression(axes[i]).value_or("0");
  l.trajectory = o.String("trajectory").value_or("");
  int targets = (l.body2.empty() ? 0 : 1) + (has_point ? 1 : 0) + (l.trajectory.empty() ? 0 : 1);
  if (targets > 1) {
    throw ElementError{"link: give only one of -body2, -x/-y/-z and -trajectory", -1};
  }
  if (o.Has("offset2") && l.body2.empty()) {
    o.Fail(*o.Get("offset2"), "needs -body2");
  }
  if (!l.body2.empty() && l.body2 == l.body1) {
    o.Fail(*o.Get("body2"), "links body '" + l.body1 + "' to itself");
  }
  l.tightness = o.Positive("tightness").value_or(l.tightness);
  RecordOptions(inv, o, l);
  ctx.scene.links.push_back(std::move(l));
}

namespace {

// A force or torque: the options both take (-body, -x/-y/-z, -offset).
template <typename T>
T VectorElement(const Invocation& inv, const Options& o, const std::string& body) {
  T element;
  FillBase(inv, element);
  element.body = body;
  const char* axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) element.components[i] = o.Expression(axes[i]).value_or("0");
  element.offset = o.Vector("offset");
  RecordOptions(inv, o, element);
  return element;
}

}  // namespace

void ForceCommand(EvalContext& ctx, const Invocation& inv, std::string&) {
  Options o(inv, 1, {"body", "x", "y", "z", "offset", "gravitational", "torque"});
  auto body = o.String("body");
  if (!body) throw ElementError{inv.kind + ": missing required option -body", -1};
  bool gravitational = o.Bool("gravitational").value_or(false);
  if (o.Bool("torque").value_or(false)) {
    if (gravitational) o.Fail(*o.Get("gravitational"), "cannot be used with -torque 1");
    ctx.scene.torques.push_back(VectorElement<scene::Torque>(inv, o, *body));
    return;
  }
  scene::Force f = VectorElement<scene::Force>(inv, o, *body);
  f.gravitational = gravitational;
  ctx.scene.forces.push_back(std::move(f));
}

void TorqueCommand(EvalContext& ctx, const Invocation& inv, std::string&) {
  Options o(inv, 1, {"body", "x", "y", "z", "offset"});
  auto body = o.String("body");
  if (!body) throw ElementError{"torque: missing required option -body", -1};
  ctx.scene.torques.push_back(VectorElement<scene::Torque>(inv, o, *body));
}

void TrajectoryCommand(EvalContext& ctx, const Invocation& inv, std::string& name) {
  name = RequireName(inv, true);
  Options o(inv, 2, {"points", "body", "state", "from", "to"});
  CheckUnique(ctx.scene.trajectories, inv, name);
  scene::Trajectory tr;
  FillBase(inv, tr);
  tr.name = name;
  const OptionValue* pts = o.Get("points");
  if (pts == nullptr) {
    throw ElementError{"trajectory '" + name + "': missing required option -points", -1};
  }
  int n = 0;
  Tcl_Obj** elems = nullptr;
  if (Tcl_ListObjGetElements(nullptr, pts->obj, &n, &elems) != TCL_OK) {
    o.Fail(*pts, "expects a list of {t x y z} points");
  }
  if (n == 0) o.Fail(*pts, "needs at least one {t x y z} point");
  const std::string context = "trajectory: option '-points'";
  for (int i = 0; i < n; ++i) {
    std::vector<double> v = ToNumbers(elems[i], context, pts->arg);
    if (v.size() != 4) {
      o.Fail(*pts, "point " + std::to_string(i + 1) + " must be {t x y z}, got " +
                       std::to_string(v.size()) + " numbers");
    }
    if (!tr.knots.empty() && !(v[0] > tr.knots.back().t)) {
      o.Fail(*pts, "times must increase strictly (point " + std::to_string(i + 1) + " has t=" +
                       FormatNumber(v[0]) + " after t=" + FormatNumber(tr.knots.back().t) + ")");
    }
    tr.knots.push_back({v[0], {v[1], v[2], v[3]}});
  }
  tr.body = o.String("body").value_or("");
  if (const OptionValue* st = o.Get("state")) {
    std::string s = ObjString(st->obj);
    using State = scene::Trajectory::State;
    if (s == "pos")
      tr.state = State::kPos;
    else if (s == "rot")
      tr.state = State::kRot;
    else if (s == "dpos")
      tr.state = State::kDpos;
    else if (s == "drot")
      tr.state = State::kDrot;
    else
      o.Fail(*st, "expects pos, rot, dpos or drot but got '" + s + "'");
    if (tr.body.empty()) o.Fail(*st, "needs -body");
  } else if (!tr.body.empty()) {
    tr.state = scene::Trajectory::State::kPos;
  }
  tr.from = o.Number("from");
  tr.to = o.Number("to");
  if ((tr.from || tr.to) && tr.body.empty()) {
    o.Fail(*(o.Has("from") ? o.Get("from") : o.Get("to")), "needs -body");
  }
  if (tr.from && tr.to && !(*tr.to > *tr.from)) {
    o.Fail(*o.Get("to"), "must be greater than -from");
  }
  RecordOptions(inv, o, tr);
  ctx.scene.trajectories.push_back(std::move(tr));
}

void LightSourceCommand(EvalContext& ctx, const Invocation& inv, std::string& name) {
  int first = OptionalName(inv, name);
  Options o(inv, first, {"type", "pos", "dir", "color", "intensity"});
  CheckUnique(ctx.scene.lights, inv, name);
  scene::LightSource l;
  FillBase(inv, l);
  l.name = name;
  if (const OptionValue* t = o.Get("type")) {
    std::string s = ObjString(t->obj);
    if (s == "point")
      l.type = scene::LightSource::Type::kPoint;
    else if (s == "directional")
      l.type = scene::LightSource::Type::kDirectional;
    else
      o.Fail(*t, "expects point or directional but got '" + s + "'");
  }
  l.position = o.Vector("pos").value_or(l.position);
  l.direction = o.Vector("dir").value_or(l.direction);
  if (l.direction[0] == 0 && l.direction[1] == 0 && l.direction[2] == 0) {
    o.Fail(*o.Get("dir"), "must not be the zero vector");
  }
  l.color = o.String("color").value_or(l.color);
  l.intensity = o.NonNegative("intensity").value_or(l.intensity);
  RecordOptions(inv, o, l);
  ctx.scene.lights.push_back(std::move(l));
}

namespace {

// A view's -pos or -rot given as components that are not all numbers: the
// component texts (expressions, checked by CheckViewExpressions once every
// body and trajectory is known); nullopt when the option is absent or a
// list of numbers (the constant, parsed as before).
std::optional<std::vector<std::string>> ExpressionComponents(const Options& o, const char* name,
                                                             std::initializer_list<int> counts,
                                                             const char* form) {
  const OptionValue* v = o.Get(name);
  if (v == nullptr) return std::nullopt;
  int n = 0;
  Tcl_Obj** elems = nullptr;
  if (Tcl_ListObjGetElements(nullptr, v->obj, &n, &elems) != TCL_OK) return std::nullopt;
  bool numbers = true;
  for (int i = 0; i < n && numbers; ++i) {
    double d = 0;
    numbers = Tcl_GetDoubleFromObj(nullptr, elems[i], &d) == TCL_OK;
  }
  if (numbers) return std::nullopt;
  if (std::find(counts.begin(), counts.end(), n) == counts.end()) {
    o.Fail(*v, std::string("expects ") + form +
                   " (numbers or expressions of time and state), got " + std::to_string(n) +
                   " components");
  }
  std::vector<std::string> texts;
  for (int i = 0; i < n; ++i) {
    texts.push_back(ObjString(elems[i]));
    if (TrimCommandText(texts.back()).empty())
      o.Fail(*v, "component " + std::to_string(i + 1) + " is empty");
  }
  return texts;
}

constexpr const char* kViewExpressionReason = "an expression of time or state (the view moves)";

}  // namespace

void ViewCommand(EvalContext& ctx, const Invocation& inv, std::string& name) {
  int first = OptionalName(inv, name);
  Options o(inv, first, {"pos", "rot", "scale", "center", "follow", "trajectory"});
  CheckUnique(ctx.scene.views, inv, name);
  scene::View v;
  FillBase(inv, v);
  v.name = name;
  if (auto e = ExpressionComponents(o, "pos", {3}, "3 components {x y z}"))
    v.position_expr = std::move(*e);
  else
    v.position = o.Vector("pos").value_or(v.position);
  if (auto e = ExpressionComponents(o, "rot", {3, 4},
                                    "a rotation vector {x y z} or a quaternion {w x y z}"))
    v.rotation_expr = std::move(*e);
  else
    v.rotation = o.Rotation("rot").value_or(v.rotation);
  if (const OptionValue* s = o.Get("scale"); s != nullptr && !IsNumericLiteral(ObjString(s->obj))) {
    v.scale_expr = ObjString(s->obj);
    if (TrimCommandText(v.scale_expr).empty()) o.Fail(*s, "needs a number or an expression");
  } else {
    v.scale = o.Positive("scale").value_or(v.scale);
  }
  v.center = o.Vector("center");
  v.follow = o.String("follow").value_or("");
  v.trajectory = o.String("trajectory").value_or("");
  if (!v.follow.empty() && !v.trajectory.empty())
    throw ElementError{"view: give -follow or -trajectory, not both", o.Get("trajectory")->arg};
  RecordOptions(inv, o, v);
  // An expression is not a literal a handle can rewrite: say why.
  for (auto& [key, word] : v.options)
    if ((key == "pos" && !v.position_expr.empty()) || (key == "rot" && !v.rotation_expr.empty()) ||
        (key == "scale" && !v.scale_expr.empty())) {
      word.literal = false;
      word.reason = kViewExpressionReason;
    }
  ctx.scene.views.push_back(std::move(v));
}

namespace {

// Names a view expression may use, as the force expressions have them
// (docs/language.md, Expressions): a body's state, mass and inertia, a
// trajectory's value and derivatives.
bool ViewNameKnown(const scene::Scene& s, std::string_view name) {
  const size_t dot = name.find('.');
  if (dot == std::string_view::npos) return false;
  const std::string owner(name.substr(0, dot));
  const std::string_view field = name.substr(dot + 1);
  static constexpr std::string_view kBody[] = {
      "x",  "y",  "z",  "dx", "dy", "dz", "vx",   "vy",  "vz",  "qw",  "qx",  "qy",  "qz",
      "wx", "wy", "wz", "w1", "w2", "w3", "mass", "Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"};
  static constexpr std::string_view kCurve[] = {"x",  "y",   "z",   "dx", "dy",
                                                "dz", "ddx", "ddy", "ddz"};
  auto in = [&](const auto& names) {
    return std::find(std::begin(names), std::end(names), field) != std::end(names);
  };
  if (s.FindBody(owner)) return in(kBody);
  if (s.FindTrajectory(owner)) return in(kCurve);
  return false;
}

// Where component `k` of a view option is in the source: the option's word
// narrowed to the component's text when it can be found there (the words
// before it skipped), and to the character `offset` into it.
scene::SourceSpan ComponentSpan(const EvalContext& ctx, const scene::Word* word,
                                const std::vector<std::string>& texts, size_t k, int offset) {
  if (word == nullptr || !word->span.known()) return {};
  const std::string_view source =
      ctx.map.text().substr(word->span.begin, word->span.end - word->span.begin);
  size_t from = 0;
  for (size_t i = 0; i <= k; ++i) {
    const size_t at = source.find(texts[i], from);
    if (at == std::string_view::npos) return word->span;
    if (i == k) {
      const int begin = word->span.begin + static_cast<int>(at) + offset;
      return ctx.map.lines().Span(
          begin, std::max(begin + 1, word->span.begin + static_cast<int>(at + texts[i].size())));
    }
    from = at + texts[i].size();
  }
  return word->span;
}

}  // namespace

void CheckViewExpressions(EvalContext& ctx) {
  scene::Scene& s = ctx.scene;
  expr::Pool pool;
  const expr::Resolver resolve = [&s](std::string_view name, expr::Pool& p) {
    return ViewNameKnown(s, name) ? std::optional<expr::NodeId>(p.Var(0)) : std::nullopt;
  };
  auto bad = [&](const scene::View& v) {
    bool failed = false;
    auto check = [&](const char* key, const std::vector<std::string>& texts) {
      for (size_t k = 0; k < texts.size(); ++k) {
        try {
          expr::Parse(texts[k], pool, resolve);
        } catch (const expr::ParseError& e) {
          std::string what = "view";
          if (!v.name.empty()) what += " '" + v.name + "'";
          what += std::string(": in -") + key;
          if (texts.size() > 1) what += " component " + std::to_string(k + 1);
          const scene::SourceSpan span = ComponentSpan(ctx, v.option(key), texts, k, e.offset());
          ctx.AddError(what + " expression '" + texts[k] + "': " + e.what(),
                       span.known() ? span : v.command);
          failed = true;
        }
      }
    };
    check("pos", v.position_expr);
    check("rot", v.rotation_expr);
    if (!v.scale_expr.empty()) check("scale", {v.scale_expr});
    return failed;
  };
  s.views.erase(std::remove_if(s.views.begin(), s.views.end(), bad), s.views.end());
}

// ---------------------------------------------------------------------------
// Registration and the shared command procedure.

namespace {

using Handler = void (*)(EvalContext&, const Invocation&, std::string&);

struct CommandEntry {
  EvalContext* ctx;
  const char* kind;
  scene::ElementKind element;
  Handler handler;
};

int RunElement(ClientData data, Tcl_Interp* interp, int objc, Tcl_Obj* const objv[]) {
  auto* entry = static_cast<CommandEntry*>(data);
  EvalContext& ctx = *entry->ctx;
  Tcl_ResetResult(interp);
  try {
    Invocation inv;
    inv.kind = entry->kind;
    inv.objc = objc;
    inv.objv = objv;
    inv.site = LocateCommand(ctx, objc, objv);
    if (Tcl_LimitExceeded(ctx.child)) {
      Tcl_SetObjResult(interp, Tcl_NewStringObj("evaluation limit exceeded", -1));
      return TCL_ERROR;
    }
    ++ctx.run_counts[inv.site.command.begin];
    std::string name;
    try {
      entry->handler(ctx, inv, name);
      Tcl_SetObjResult(interp, Tcl_NewStringObj(name.data(), static_cast<int>(name.size())));
    } catch (const ElementError& e) {
      ctx.AddError(e.message, inv.ArgSpan(e.arg));
      if (!name.empty()) ctx.failed[entry->element].insert(name);
    }
  } catch (const std::exception& e) {
    ctx.AddError(std::string(entry->kind) + ": internal error: " + e.what(), ctx.TopCommand().span);
  } catch (...) {
    ctx.AddError(std::string(entry->kind) + ": internal error", ctx.TopCommand().span);
  }
  return TCL_OK;
}

}  // namespace

void InstallElementCommands(EvalContext& ctx) {
  using K = scene::ElementKind;
  static constexpr struct {
    const char* name;
    K kind;
    Handler handler;
  } kTable[] = {
      {"simulator", K::kSimulator, SimulatorCommand},
      {"shape_set", K::kShapeSet, ShapeSetCommand},
      {"body", K::kBody, BodyCommand},
      {"instance", K::kBody, BodyCommand},
      {"link", K::kLink, LinkCommand},
      {"force", K::kForce, ForceCommand},
      {"torque", K::kTorque, TorqueCommand},
      {"trajectory", K::kTrajectory, TrajectoryCommand},
      {"lightsource", K::kLightSource, LightSourceCommand},
      {"view", K::kView, ViewCommand},
  };
  for (const auto& row : kTable) {
    auto entry =
        std::make_shared<CommandEntry>(CommandEntry{&ctx, row.name, row.kind, row.handler});
    std::string target = std::string("asgard_") + row.name;
    Tcl_CreateObjCommand(ctx.master, target.c_str(), RunElement, entry.get(), nullptr);
    Tcl_CreateAlias(ctx.child, row.name, ctx.master, target.c_str(), 0, nullptr);
    ctx.keep_alive.push_back(std::move(entry));
  }
}

}  // namespace asgard::lang
