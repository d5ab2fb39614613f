// Scene sampling: geometry, poses, framing, lights and overlays.
//
// Design: geometry comes from the equation system's BodyModels (already in
// body coordinates, hulls computed once by physics), so a renderer only ever
// applies a rigid transform per body.  Poses come from pipeline::SampleBody.
// Overlay values that depend on expressions (link end points given as
// expressions, force vectors) are evaluated with the expression module: the
// texts are parsed once against a small name table (body state, mass and
// inertia, trajectories) and compiled to one tape; anything the table cannot
// resolve is simply not drawn.
#include "core/render/sampler.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "core/expr/expr.h"
#include "core/physics/trajectory.h"

namespace asgard::render {

namespace {

// Value slots per body in the overlay evaluator.
enum Slot {
  kPx,
  kPy,
  kPz,
  kVx,
  kVy,
  kVz,
  kQw,
  kQx,
  kQy,
  kQz,
  kWx,
  kWy,
  kWz,
  kW1,
  kW2,
  kW3,
  kSlots
};

const std::map<std::string, int, std::less<>>& SlotNames() {
  static const std::map<std::string, int, std::less<>> names = {
      {"x", kPx},  {"y", kPy},  {"z", kPz},  {"dx", kVx}, {"dy", kVy}, {"dz", kVz}, {"vx", kVx},
      {"vy", kVy}, {"vz", kVz}, {"qw", kQw}, {"qx", kQx}, {"qy", kQy}, {"qz", kQz}, {"wx", kWx},
      {"wy", kWy}, {"wz", kWz}, {"w1", kW1}, {"w2", kW2}, {"w3", kW3}};
  return names;
}

Pose ToPose(const pipeline::BodyFrame& f) {
  Pose p;
  p.p = Eigen::Vector3d(f.p[0], f.p[1], f.p[2]);
  p.q = Eigen::Quaterniond(f.q[0], f.q[1], f.q[2], f.q[3]).normalized();
  return p;
}

Eigen::Vector3d ToVec(const scene::Vec3& v) { return {v[0], v[1], v[2]}; }

// The overlay and view expressions' name table: a body's state (Var(b ·
// kSlots + slot), filled by StateValues), mass and inertia (constants), a
// trajectory's value and derivatives (its curve's external functions).
std::optional<expr::NodeId> ResolveName(
    std::string_view name, expr::Pool& pool, const physics::EquationSystem& eq,
    const std::map<std::string, int, std::less<>>& curve_index) {
  const size_t dot = name.rfind('.');
  if (dot == std::string_view::npos) return std::nullopt;
  const std::string owner(name.substr(0, dot));
  const std::string_view field = name.substr(dot + 1);
  if (const int b = eq.FindBody(owner); b >= 0) {
    const auto& m = eq.bodies[b];
    if (field == "mass") return pool.Const(m.mass);
    static const char* kInertia[] = {"Ixx", "Ixy", "Ixz", "Iyx", "Iyy", "Iyz", "Izx", "Izy", "Izz"};
    for (int k = 0; k < 9; ++k)
      if (field == kInertia[k]) return pool.Const(m.inertia(k / 3, k % 3));
    const auto it = SlotNames().find(field);
    if (it == SlotNames().end()) return std::nullopt;
    return pool.Var(b * kSlots + it->second);
  }
  const auto c = curve_index.find(owner);
  if (c == curve_index.end()) return std::nullopt;
  int order = 0;
  std::string_view axis = field;
  while (!axis.empty() && axis[0] == 'd') ++order, axis.remove_prefix(1);
  if (axis.size() != 1 || axis[0] < 'x' || axis[0] > 'z' || order > 2) return std::nullopt;
  return pool.Extern(physics::CurveFunction(c->second, axis[0] - 'x'), order);
}

}  // namespace

Eigen::Matrix4d Pose::Matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<3, 3>(0, 0) = q.toRotationMatrix();
  m.block<3, 1>(0, 3) = p;
  return m;
}

// Overlay expressions: link points and force components, compiled together.
struct SceneSampler::Evaluator {
  expr::Pool pool;
  std::vector<physics::TrajectoryCurve> curves;
  std::map<std::string, int, std::less<>> curve_index;
  std::vector<expr::NodeId> outputs;
  std::vector<int> link_first;    // per link: first output index, or -1
  std::vector<int> force_first;   // per force: first output index, or -1
  std::vector<int> torque_first;  // per torque: first output index, or -1
  std::optional<expr::Tape> tape;
  expr::ExternFn externs;

  std::optional<expr::NodeId> Resolve(std::string_view name, const physics::EquationSystem& eq) {
    return ResolveName(name, pool, eq, curve_index);
  }

  // Parses three texts; on success appends them to `outputs` and returns the
  // index of the first.
  int AddTriple(const std::array<std::string, 3>& texts, const physics::EquationSystem& eq,
                double factor) {
    std::array<expr::NodeId, 3> ids{};
    try {
      for (int a = 0; a < 3; ++a) {
        ids[a] = expr::Parse(texts[a], pool,
                             [&](std::string_view n, expr::Pool&) { return Resolve(n, eq); });
        if (factor != 1.0) ids[a] = pool.Mul(pool.Const(factor), ids[a]);
      }
    } catch (...) {
      return -1;
    }
    const int first = static_cast<int>(outputs.size());
    outputs.insert(outputs.end(), ids.begin(), ids.end());
    return first;
  }
};

SceneSampler::SceneSampler(const scene::Scene& scene, const physics::EquationSystem& equations,
                           const solver::Simulation& simulation)
    : scene_(scene),
      equations_(equations),
      simulation_(simulation),
      frame_rate_(pipeline::FrameRate(scene)),
      eval_(std::make_unique<Evaluator>()) {
  const auto& eq = equations_;
  for (size_t b = 0; b < eq.bodies.size(); ++b) {
    const auto& m = eq.bodies[b];
    BodyShape shape;
    shape.name = m.name;
    shape.is_static = m.is_static || m.first_var < 0;
    shape.centroid = m.centroid;
    std::optional<Rgb> body_color;
    if (!m.color.empty()) {
      body_color = ParseColor(m.color);
      if (!body_color) unknown_colors_.push_back(m.color);
    }
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (const auto& bp : m.pieces) {
      Piece p{bp, {}};
      if (!p.is_sphere) {
        for (const auto& v : p.hull.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
      } else {
        lo = lo.cwiseMin((p.center.array() - p.radius).matrix());
        hi = hi.cwiseMax((p.center.array() + p.radius).matrix());
      }
      std::optional<Rgb> c = body_color;
      if (!c && !bp.color.empty()) {
        c = ParseColor(bp.color);
        if (!c) unknown_colors_.push_back(bp.color);
      }
      p.rgb = c.value_or(PaletteColor(static_cast<int>(b)));
      shape.pieces.push_back(std::move(p));
    }
    if (!shape.pieces.empty()) {
      shape.bound_center = (lo + hi) / 2;
      for (const auto& p : shape.pieces) {
        if (p.is_sphere)
          shape.bound_radius =
              std::max(shape.bound_radius, (p.center - shape.bound_center).norm() + p.radius);
        for (const auto& v : p.hull.vertices)
          shape.bound_radius = std::max(shape.bound_radius, (v - shape.bound_center).norm());
      }
    }
    bodies_.push_back(std::move(shape));
  }
  // Overlay expressions.
  Evaluator& ev = *eval_;
  for (const auto& tr : scene_.trajectories) {
    if (tr.knots.empty()) continue;
    ev.curve_index[tr.name] = static_cast<int>(ev.curves.size());
    ev.curves.emplace_back(tr.knots);
  }
  for (const auto& link : scene_.links)
    ev.link_first.push_back(
        link.body2.empty() && link.trajectory.empty() ? ev.AddTriple(link.point, eq, 1.0) : -1);
  for (const auto& f : scene_.forces) {
    const int b = eq.FindBody(f.body);
    const double factor = f.gravitational && b >= 0 ? eq.bodies[b].mass : 1.0;
    ev.force_first.push_back(b >= 0 ? ev.AddTriple(f.components, eq, factor) : -1);
  }
  for (const auto& tq : scene_.torques)
    ev.torque_first.push_back(eq.FindBody(tq.body) >= 0 ? ev.AddTriple(tq.components, eq, 1.0)
                                                        : -1);
  if (!ev.outputs.empty()) ev.tape = expr::Tape::Compile(ev.pool, ev.outputs);
  ev.externs = [curves = &ev.curves](int fn, int order, double t) {
    return (*curves)[physics::CurveOfFunction(fn)].Evaluate(physics::AxisOfFunction(fn), order, t);
  };
}

SceneSampler::~SceneSampler() = default;

double SceneSampler::t0() const { return equations_.t0; }
double SceneSampler::t1() const { return equations_.t1; }

std::vector<Pose> SceneSampler::Poses(double t) const {
  std::vector<Pose> poses;
  poses.reserve(bodies_.size());
  for (size_t b = 0; b < bodies_.size(); ++b)
    poses.push_back(ToPose(pipeline::SampleBody(equations_, simulation_, static_cast<int>(b), t)));
  return poses;
}

std::vector<double> SceneSampler::FrameTimes() const {
  return pipeline::FrameTimes(t0(), t1(), frame_rate_);
}

std::vector<double> SceneSampler::FrameTimes(double start, double end, int count) {
  std::vector<double> times;
  for (int k = 0; k < count; ++k)
    times.push_back(count == 1 ? start : start + (end - start) * k / (count - 1));
  return times;
}

namespace {

struct Ball {
  Eigen::Vector3d c;
  double r;
};

// The sphere centred on the smallest box around `balls` that holds them all.
Bound Fit(const std::vector<Ball>& balls) {
  Bound bound;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& s : balls) {
    lo = lo.cwiseMin((s.c.array() - s.r).matrix());
    hi = hi.cwiseMax((s.c.array() + s.r).matrix());
  }
  bound.center = (lo + hi) / 2;
  bound.radius = 0;
  for (const auto& s : balls)
    bound.radius = std::max(bound.radius, (s.c - bound.center).norm() + s.r);
  return bound;
}

}  // namespace

Bound SceneSampler::SceneBound() const {
  if (bound_) return *bound_;
  // Frame the scene as it starts, then widen to take in each body's motion
  // until it first strays beyond twice that framing radius: a ball launched
  // far away leaves the picture instead of shrinking everything else to a
  // speck.  A scene of one body keeps its whole path in view.
  const std::vector<double> times = FrameTimes();
  std::vector<std::vector<Ball>> path(bodies_.size());
  for (double t : times) {
    const auto poses = Poses(t);
    for (size_t b = 0; b < bodies_.size(); ++b)
      if (!bodies_[b].pieces.empty())
        path[b].push_back({poses[b].Apply(bodies_[b].bound_center), bodies_[b].bound_radius});
  }
  std::vector<Ball> balls;
  size_t moving = 0;
  for (const auto& p : path)
    if (!p.empty()) {
      balls.push_back(p.front());
      ++moving;
    }
  if (!balls.empty() && moving > 1) {
    const Bound start = Fit(balls);
    for (const auto& p : path)
      for (const Ball& s : p) {
        if ((s.c - start.center).norm() + s.r > 2 * start.radius) break;
        balls.push_back(s);
      }
  } else {
    for (const auto& p : path) balls.insert(balls.end(), p.begin(), p.end());
  }
  Bound bound;
  if (!balls.empty()) {
    bound = Fit(balls);
    if (!(bound.radius > 0) || !std::isfinite(bound.radius)) bound.radius = 1;
  }
  bound_ = bound;
  return bound;
}

const scene::View* SceneSampler::FindView(const std::string& name) const {
  const scene::View* chosen = nullptr;
  for (const auto& e : scene_.views)
    if (name.empty() || e.name == name) chosen = &e;
  return chosen;
}

std::optional<ViewState> SceneSampler::SceneView(const std::string& name) const {
  const scene::View* chosen = FindView(name);
  if (!name.empty() && !chosen) return std::nullopt;
  return ElementView(chosen);
}

ViewMotion SceneSampler::Motion(const scene::View* element) const {
  return ViewMotion(*this, element);
}

ViewState SceneSampler::ElementView(const scene::View* element) const {
  ViewState v;
  const Bound b = SceneBound();
  v.rotation = DefaultTilt();
  v.center = b.center;
  v.radius = b.radius;
  if (element) {
    if (element->option("rot")) {
      const auto& q = element->rotation;
      v.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
    }
    if (element->option("pos")) v.position = ToVec(element->position);
    if (element->option("scale")) v.scale = element->scale;
    if (element->center) v.center = ToVec(*element->center);
  }
  return v;
}

std::vector<Light> SceneSampler::SceneLights() const {
  std::vector<Light> lights;
  for (const auto& s : scene_.lights) {
    Light l;
    l.directional = s.type == scene::LightSource::Type::kDirectional;
    l.position = ToVec(s.position);
    const Eigen::Vector3d d = ToVec(s.direction);
    l.direction = d.norm() > 0 ? d.normalized() : Eigen::Vector3d(0, 0, -1);
    l.color = ParseColor(s.color).value_or(Rgb{1, 1, 1});
    l.intensity = s.intensity;
    lights.push_back(l);
  }
  return lights;
}

namespace {

// Fills the evaluator's value array from the poses (and velocities) at t.
std::vector<double> StateValues(const physics::EquationSystem& eq, const solver::Simulation& sim,
                                double t, size_t nbodies) {
  std::vector<double> x(nbodies * kSlots, 0.0);
  for (size_t b = 0; b < nbodies; ++b) {
    const auto f = pipeline::SampleBody(eq, sim, static_cast<int>(b), t);
    double* s = &x[b * kSlots];
    for (int a = 0; a < 3; ++a) s[kPx + a] = f.p[a], s[kVx + a] = f.v[a], s[kWx + a] = f.w[a];
    for (int a = 0; a < 4; ++a) s[kQw + a] = f.q[a];
    const Eigen::Quaterniond q(f.q[0], f.q[1], f.q[2], f.q[3]);
    const Eigen::Vector3d wb = q.conjugate() * Eigen::Vector3d(f.w[0], f.w[1], f.w[2]);
    for (int a = 0; a < 3; ++a) s[kW1 + a] = wb[a];
  }
  return x;
}

}  // namespace

ViewMotion::ViewMotion(const SceneSampler& sampler, const scene::View* element)
    : sampler_(sampler), base_(sampler.ElementView(element)) {
  if (!element) return;
  label_ = element->name.empty() ? "view" : "view '" + element->name + "'";
  const physics::EquationSystem& eq = sampler.equations_;
  if (!element->follow.empty()) {
    follow_ = eq.FindBody(element->follow);
    if (follow_ < 0) error_ = label_ + ": no body '" + element->follow + "' to follow";
  }
  const auto& curves = sampler.eval_->curve_index;
  if (!element->trajectory.empty()) {
    const auto c = curves.find(element->trajectory);
    if (c == curves.end())
      error_ = label_ + ": no trajectory '" + element->trajectory + "'";
    else
      curve_ = c->second;
  }
  if (!element->animated()) return;
  std::vector<expr::NodeId> outputs;
  auto add = [&](const char* option, const std::vector<std::string>& texts) {
    if (texts.empty()) return -1;
    const int first = static_cast<int>(outputs.size());
    for (const std::string& text : texts) {
      try {
        outputs.push_back(expr::Parse(text, pool_, [&](std::string_view n, expr::Pool& p) {
          return ResolveName(n, p, eq, curves);
        }));
      } catch (const expr::ParseError& e) {
        error_ = label_ + ": -" + option + " expression '" + text + "': " + e.what();
        outputs.push_back(pool_.Const(0));
      }
    }
    return first;
  };
  pos_ = add("pos", element->position_expr);
  rot_ = add("rot", element->rotation_expr);
  rot_count_ = static_cast<int>(element->rotation_expr.size());
  if (!element->scale_expr.empty()) scale_ = add("scale", {element->scale_expr});
  outputs_ = outputs.size();
  tape_ = expr::Tape::Compile(pool_, outputs);
}

ViewState ViewMotion::At(double t, std::string* problem) const {
  ViewState v = base_;
  if (follow_ >= 0) v.center = sampler_.Poses(t)[follow_].p;
  if (curve_ >= 0) v.center = sampler_.eval_->curves[curve_].Value(t);
  if (!tape_) return v;
  const auto x = StateValues(sampler_.equations_, sampler_.simulation_, t, sampler_.bodies_.size());
  std::vector<double> out(outputs_);
  tape_->Evaluate(t, x.data(), out.data(), &sampler_.eval_->externs);
  auto unusable = [&](const char* option, const std::string& why) {
    if (problem && problem->empty()) {
      std::ostringstream s;
      s << label_ << ": -" << option << " " << why << " at t = " << t;
      *problem = s.str();
    }
  };
  if (pos_ >= 0) {
    const Eigen::Vector3d p(out[pos_], out[pos_ + 1], out[pos_ + 2]);
    if (p.allFinite())
      v.position = p;
    else
      unusable("pos", "is not finite");
  }
  if (rot_ >= 0) {
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    bool ok = true;
    if (rot_count_ == 4) {
      const Eigen::Vector4d c(out[rot_], out[rot_ + 1], out[rot_ + 2], out[rot_ + 3]);
      ok = c.allFinite() && c.norm() > 1e-12;
      if (ok) q = Eigen::Quaterniond(c[0], c[1], c[2], c[3]).normalized();
    } else {
      const Eigen::Vector3d r(out[rot_], out[rot_ + 1], out[rot_ + 2]);
      ok = r.allFinite();
      if (ok && r.norm() > 0) q = Eigen::Quaterniond(Eigen::AngleAxisd(r.norm(), r.normalized()));
    }
    if (ok)
      v.rotation = q;
    else
      unusable("rot", rot_count_ == 4 ? "is a zero or non-finite quaternion" : "is not finite");
  }
  if (scale_ >= 0) {
    if (std::isfinite(out[scale_]) && out[scale_] > 0) {
      v.scale = out[scale_];
    } else {
      std::ostringstream s;
      s << "is " << out[scale_] << " (it must be greater than 0)";
      unusable("scale", s.str());
    }
  }
  return v;
}

std::vector<Segment> SceneSampler::LinkSegments(double t, const std::vector<Pose>& poses) const {
  const auto& eq = equations_;
  std::vector<double> out;
  if (eval_->tape) {
    const auto x = StateValues(equations_, simulation_, t, bodies_.size());
    out.resize(eval_->outputs.size());
    eval_->tape->Evaluate(t, x.data(), out.data(), &eval_->externs);
  }
  std::vector<Segment> segs;
  for (size_t i = 0; i < scene_.links.size(); ++i) {
    const auto& link = scene_.links[i];
    const int b1 = eq.FindBody(link.body1);
    if (b1 < 0) continue;
    Segment s;
    s.a = poses[b1].Apply(ToVec(link.offset1) - bodies_[b1].centroid);
    if (!link.body2.empty()) {
      const int b2 = eq.FindBody(link.body2);
      if (b2 < 0) continue;
      s.b = poses[b2].Apply(ToVec(link.offset2) - bodies_[b2].centroid);
    } else if (!link.trajectory.empty()) {
      const auto it = eval_->curve_index.find(link.trajectory);
      if (it == eval_->curve_index.end()) continue;
      s.b = eval_->curves[it->second].Value(t);
    } else {
      const int first = eval_->link_first[i];
      if (first < 0) continue;
      s.b = Eigen::Vector3d(out[first], out[first + 1], out[first + 2]);
    }
    segs.push_back(s);
  }
  return segs;
}

// The vectors whose first outputs are `first` (−1: none), at time t.
std::vector<std::optional<Eigen::Vector3d>> SceneSampler::VectorValues(
    const std::vector<int>& first, double t) const {
  std::vector<std::optional<Eigen::Vector3d>> values(first.size());
  if (!eval_->tape) return values;
  const auto x = StateValues(equations_, simulation_, t, bodies_.size());
  std::vector<double> out(eval_->outputs.size());
  eval_->tape->Evaluate(t, x.data(), out.data(), &eval_->externs);
  for (size_t i = 0; i < first.size(); ++i) {
    if (first[i] < 0) continue;
    const Eigen::Vector3d v(out[first[i]], out[first[i] + 1], out[first[i] + 2]);
    if (v.allFinite()) values[i] = v;
  }
  return values;
}

std::vector<std::optional<Eigen::Vector3d>> SceneSampler::ForceValues(double t) const {
  return VectorValues(eval_->force_first, t);
}

std::vector<std::optional<Eigen::Vector3d>> SceneSampler::TorqueValues(double t) const {
  return VectorValues(eval_->torque_first, t);
}

std::vector<Segment> SceneSampler::ForceVectors(double t, const std::vector<Pose>& poses) const {
  std::vector<Segment> segs;
  const auto values = ForceValues(t);
  for (size_t i = 0; i < scene_.forces.size(); ++i) {
    if (!values[i]) continue;
    const auto& f = scene_.forces[i];
    const int b = equations_.FindBody(f.body);
    const Eigen::Vector3d base =
        f.offset ? poses[b].Apply(ToVec(*f.offset) - bodies_[b].centroid) : poses[b].p;
    segs.push_back({base, base + *values[i]});
  }
  return segs;
}

std::vector<std::vector<Eigen::Vector3d>> SceneSampler::Paths(
    const std::vector<double>& times) const {
  std::vector<std::vector<Eigen::Vector3d>> paths;
  for (size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].is_static) continue;
    std::vector<Eigen::Vector3d> path;
    for (double t : times) {
      const auto f = pipeline::SampleBody(equations_, simulation_, static_cast<int>(b), t);
      path.emplace_back(f.p[0], f.p[1], f.p[2]);
    }
    paths.push_back(std::move(path));
  }
  return paths;
}

}  // namespace asgard::render
