// FormEquations: scene → state equations (design note in equations.h).
//
// Stages, in order:
//   ShapeModels      hulls and unit-density mass properties per shape set
//   BodyModels       mass, inertia, centroid, initial state per body
//   AllocateState    13 variables per free body, named "b.x" ... "b.w3"
//   Kinematics       symbolic p, v, q, ω, R per body (variables or constants)
//   Loads            forces, torques, links → ΣF (world) and Στ (world)
//   StateEquations   ẋ = v, v̇ = F/m, q̇ = ½ q⊗ω, ω̇ = I⁻¹(Rᵀτ − ω×Iω)
//   Trajectories     overrides of the state equations over intervals
//   Breakpoints      where each equation is not smooth
#include "core/physics/equations.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/physics/trajectory.h"

namespace asgard::physics {
namespace {

using expr::NodeId;
using V3 = std::array<NodeId, 3>;
using M3 = std::array<std::array<NodeId, 3>, 3>;

// The spring constant of a link without -tightness whose point cannot be an
// exact joint (it moves with other bodies' state); the seed's default.
constexpr double kFallbackTightness = 1000.0;

constexpr const char* kSlotNames[kBodySlots] = {"x",  "y",  "z",  "dx", "dy", "dz", "qw",
                                                "qx", "qy", "qz", "w1", "w2", "w3"};

Eigen::Vector3d ToEigen(const scene::Vec3& v) { return {v[0], v[1], v[2]}; }

struct Kinematics {
  V3 p, v, w_body;
  std::array<NodeId, 4> q;
  M3 R;  // body → world
};

struct Loads {
  std::vector<NodeId> force[3];   // world-frame terms
  std::vector<NodeId> torque[3];  // world-frame terms about the CoM
};

class Builder {
 public:
  Builder(const scene::Scene& scene, EquationSystem& sys) : scene_(scene), sys_(sys), P(sys.pool) {}

  void Run() {
    if (scene_.simulator) {
      sys_.t0 = scene_.simulator->start;
      sys_.t1 = scene_.simulator->finish;
    }
    ShapeModels();
    BodyModels();
    AllocateState();
    for (size_t b = 0; b < sys_.bodies.size(); ++b) kin_.push_back(MakeKinematics(b));
    loads_.resize(sys_.bodies.size());
    Curves();
    for (const auto& f : scene_.forces) AddForce(f);
    for (const auto& t : scene_.torques) AddTorque(t);
    for (const auto& l : scene_.links) AddLink(l);
    StateEquations();
    for (const auto& t : scene_.trajectories) AttachTrajectory(t);
    Breakpoints();
  }

 private:
  // ---- diagnostics -------------------------------------------------------
  void Error(const scene::ElementBase& e, const std::string& message,
             const scene::Word* word = nullptr) {
    scene::Diagnostic d;
    d.message = message;
    d.span = (word && word->span.known()) ? word->span : e.command;
    sys_.diagnostics.push_back(std::move(d));
  }

  // ---- shapes and bodies -------------------------------------------------
  struct ShapeModel {
    std::vector<BodyPiece> pieces;  // shape coordinates
    geometry::MassProperties mass;
    bool ok = false;
  };

  void ShapeModels() {
    for (const auto& s : scene_.shape_sets) {
      ShapeModel m;
      std::vector<geometry::MassProperties> parts;
      try {
        for (const auto& piece : s.pieces) {
          BodyPiece bp;
          bp.color = piece.color;
          if (piece.kind == scene::ShapePiece::Kind::kSphere) {
            bp.is_sphere = true;
            bp.center = ToEigen(piece.center);
            bp.radius = piece.radius;
            parts.push_back(geometry::SphereMassProperties(bp.center, bp.radius));
          } else {
            std::vector<Eigen::Vector3d> pts;
            for (const auto& p : piece.points) pts.push_back(ToEigen(p));
            bp.hull = geometry::ComputeHull(pts);
            parts.push_back(geometry::HullMassProperties(bp.hull));
          }
          m.pieces.push_back(std::move(bp));
        }
        if (parts.empty()) throw geometry::GeometryError("the shape set has no pieces");
        m.mass = geometry::CombineMassProperties(parts);
        m.ok = true;
      } catch (const std::exception& e) {
        Error(s, "shape_set " + s.name + ": " + e.what());
      }
      shapes_[s.name] = std::move(m);
    }
  }

  static Eigen::Matrix3d CleanInertia(Eigen::Matrix3d I) {
    // Round-off from the hull integrals must not couple axes that the shape
    // leaves uncoupled: entries far below the trace are set to exactly zero,
    // and nearly equal diagonal entries are made equal.
    const double scale = I.trace();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (std::abs(I(r, c)) < 1e-12 * scale) I(r, c) = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int b = a + 1; b < 3; ++b)
        if (std::abs(I(a, a) - I(b, b)) < 1e-12 * scale) I(b, b) = I(a, a);
    return 0.5 * (I + I.transpose());
  }

  void BodyModels() {
    for (const auto& b : scene_.bodies) {
      auto it = shapes_.find(b.shape);
      if (it == shapes_.end()) {
        Error(b, "body " + b.name + ": unknown shape '" + b.shape + "'", b.option("shape"));
        continue;
      }
      if (!it->second.ok) continue;  // the shape's own error was reported
      const ShapeModel& shape = it->second;
      BodyModel m;
      m.name = b.name;
      m.artbody = b.artbody;
      m.is_static = b.is_static;
      m.collision_test = b.collision_test;
      m.restitution = b.restitution.value_or(1.0);
      m.friction = b.friction.value_or(0.0);
      m.color = b.color;
      m.centroid = shape.mass.centroid;
      const double volume = shape.mass.volume;
      m.mass = b.mass.value_or(volume);  // unit density
      Eigen::Matrix3d I = shape.mass.inertia * (m.mass / volume);
      if (b.moment) {
        const auto& v = *b.moment;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) I(r, c) = v[3 * r + c];
      }
      m.inertia = CleanInertia(I);
      for (BodyPiece piece : shape.pieces) {
        if (piece.is_sphere) {
          piece.center -= m.centroid;
        } else {
          for (auto& v : piece.hull.vertices) v -= m.centroid;
          for (auto& f : piece.hull.faces) f.offset -= f.normal.dot(m.centroid);
        }
        m.pieces.push_back(std::move(piece));
      }
      SetInitialState(m, b);
      sys_.bodies.push_back(std::move(m));
    }
  }

  void AllocateState() {
    for (size_t b = 0; b < sys_.bodies.size(); ++b) {
      BodyModel& m = sys_.bodies[b];
      if (m.is_static) continue;
      m.first_var = static_cast<int>(sys_.variables.size());
      const auto init = InitialValues(m);
      for (int s = 0; s < kBodySlots; ++s) {
        StateVariable v;
        v.name = m.name + "." + kSlotNames[s];
        v.body = static_cast<int>(b);
        v.initial = init[s];
        sys_.variables.push_back(std::move(v));
      }
    }
  }

  // ---- symbolic vector helpers ------------------------------------------
  V3 Add(const V3& a, const V3& b) { return {P.Add(a[0], b[0]), P.Add(a[1], b[1]), P.Add(a[2], b[2])}; }
  V3 Sub(const V3& a, const V3& b) { return {P.Sub(a[0], b[0]), P.Sub(a[1], b[1]), P.Sub(a[2], b[2])}; }
  V3 Scale(NodeId s, const V3& a) { return {P.Mul(s, a[0]), P.Mul(s, a[1]), P.Mul(s, a[2])}; }
  V3 Cross(const V3& a, const V3& b) {
    return {P.Sub(P.Mul(a[1], b[2]), P.Mul(a[2], b[1])),
            P.Sub(P.Mul(a[2], b[0]), P.Mul(a[0], b[2])),
            P.Sub(P.Mul(a[0], b[1]), P.Mul(a[1], b[0]))};
  }
  V3 Const(const Eigen::Vector3d& v) { return {P.Const(v.x()), P.Const(v.y()), P.Const(v.z())}; }
  V3 Rotate(const M3& R, const V3& v) {
    V3 out;
    for (int r = 0; r < 3; ++r) {
      NodeId terms[3] = {P.Mul(R[r][0], v[0]), P.Mul(R[r][1], v[1]), P.Mul(R[r][2], v[2])};
      out[r] = P.Sum(terms);
    }
    return out;
  }
  V3 RotateT(const M3& R, const V3& v) {
    V3 out;
    for (int c = 0; c < 3; ++c) {
      NodeId terms[3] = {P.Mul(R[0][c], v[0]), P.Mul(R[1][c], v[1]), P.Mul(R[2][c], v[2])};
      out[c] = P.Sum(terms);
    }
    return out;
  }

  // R(q) in homogeneous form: exact rotation for any q ≠ 0.
  M3 RotationMatrix(const std::array<NodeId, 4>& q) {
    const NodeId w = q[0], x = q[1], y = q[2], z = q[3];
    auto sq = [&](NodeId a) { return P.Mul(a, a); };
    auto two = [&](NodeId a, NodeId b) { return P.Mul(P.Const(2.0), P.Mul(a, b)); };
    NodeId terms[4] = {sq(w), sq(x), sq(y), sq(z)};
    const NodeId inv_s = P.Div(P.Const(1.0), P.Sum(terms));
    M3 M;
    M[0][0] = P.Sub(P.Add(sq(w), sq(x)), P.Add(sq(y), sq(z)));
    M[1][1] = P.Sub(P.Add(sq(w), sq(y)), P.Add(sq(x), sq(z)));
    M[2][2] = P.Sub(P.Add(sq(w), sq(z)), P.Add(sq(x), sq(y)));
    M[0][1] = P.Sub(two(x, y), two(w, z));
    M[1][0] = P.Add(two(x, y), two(w, z));
    M[0][2] = P.Add(two(x, z), two(w, y));
    M[2][0] = P.Sub(two(x, z), two(w, y));
    M[1][2] = P.Sub(two(y, z), two(w, x));
    M[2][1] = P.Add(two(y, z), two(w, x));
    for (auto& row : M)
      for (auto& e : row) e = P.Mul(e, inv_s);
    return M;
  }

  Kinematics MakeKinematics(size_t b) {
    const BodyModel& m = sys_.bodies[b];
    Kinematics k;
    if (m.is_static) {
      k.p = Const(m.x0);
      k.v = Const(Eigen::Vector3d::Zero());
      k.w_body = Const(Eigen::Vector3d::Zero());
      k.q = {P.Const(m.q0.w()), P.Const(m.q0.x()), P.Const(m.q0.y()), P.Const(m.q0.z())};
      const Eigen::Matrix3d R = m.q0.toRotationMatrix();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) k.R[r][c] = P.Const(R(r, c));
      return k;
    }
    auto var = [&](int slot) { return P.Var(m.first_var + slot); };
    k.p = {var(kX), var(kY), var(kZ)};
    k.v = {var(kDx), var(kDy), var(kDz)};
    k.q = {var(kQw), var(kQx), var(kQy), var(kQz)};
    k.w_body = {var(kW1), var(kW2), var(kW3)};
    k.R = RotationMatrix(k.q);
    return k;
  }

  // World position and velocity of a point given in shape coordinates.
  std::pair<V3, V3> BodyPoint(size_t b, const scene::Vec3& offset_shape) {
    const Kinematics& k = kin_[b];
    const V3 r_body = Const(ToEigen(offset_shape) - sys_.bodies[b].centroid);
    const V3 r_world = Rotate(k.R, r_body);
    const V3 p = Add(k.p, r_world);
    const V3 v = Add(k.v, Rotate(k.R, Cross(k.w_body, r_body)));
    return {p, v};
  }

  // ---- expressions ------------------------------------------------------
  void Curves() {
    for (const auto& t : scene_.trajectories) {
      curve_index_[t.name] = static_cast<int>(sys_.curves.size());
      sys_.curves.push_back(std::make_shared<TrajectoryCurve>(t.knots));
    }
  }

  std::optional<NodeId> Resolve(std::string_view name) {
    const size_t dot = name.find('.');
    if (dot == std::string_view::npos) return std::nullopt;
    const std::string owner(name.substr(0, dot));
    const std::string field(name.substr(dot + 1));
    if (auto c = curve_index_.find(owner); c != curve_index_.end()) {
      static const std::map<std::string, std::pair<int, int>> kCurveFields = {
          {"x", {0, 0}},   {"y", {1, 0}},   {"z", {2, 0}},   {"dx", {0, 1}},
          {"dy", {1, 1}},  {"dz", {2, 1}},  {"ddx", {0, 2}}, {"ddy", {1, 2}},
          {"ddz", {2, 2}}};
      auto f = kCurveFields.find(field);
      if (f == kCurveFields.end()) return std::nullopt;
      return P.Extern(CurveFunction(c->second, f->second.first), f->second.second);
    }
    const int b = sys_.FindBody(owner);
    if (b < 0) return std::nullopt;
    const Kinematics& k = kin_[b];
    const BodyModel& m = sys_.bodies[b];
    if (field == "mass") return P.Const(m.mass);
    static const std::map<std::string, int> kSlots = {
        {"x", kX},   {"y", kY},   {"z", kZ},   {"dx", kDx}, {"dy", kDy},
        {"dz", kDz}, {"vx", kDx}, {"vy", kDy}, {"vz", kDz}, {"qw", kQw},
        {"qx", kQx}, {"qy", kQy}, {"qz", kQz}, {"w1", kW1}, {"w2", kW2},
        {"w3", kW3}};
    if (auto s = kSlots.find(field); s != kSlots.end()) {
      const int slot = s->second;
      if (slot <= kZ) return k.p[slot - kX];
      if (slot <= kDz) return k.v[slot - kDx];
      if (slot <= kQz) return k.q[slot - kQw];
      return k.w_body[slot - kW1];
    }
    if (field == "wx" || field == "wy" || field == "wz") {
      return Rotate(k.R, k.w_body)[field[1] - 'x'];
    }
    static const std::map<std::string, std::pair<int, int>> kInertia = {
        {"Ixx", {0, 0}}, {"Iyy", {1, 1}}, {"Izz", {2, 2}},
        {"Ixy", {0, 1}}, {"Ixz", {0, 2}}, {"Iyz", {1, 2}}};
    if (auto i = kInertia.find(field); i != kInertia.end()) {
      return P.Const(m.inertia(i->second.first, i->second.second));
    }
    return std::nullopt;
  }

  // Parses one expression option; reports errors against `element`.
  std::optional<NodeId> ParseExpr(const scene::ElementBase& element, const char* kind,
                                  const std::string& what, const std::string& text,
                                  const scene::Word* word) {
    try {
      return expr::Parse(text, P, [this](std::string_view n, expr::Pool&) { return Resolve(n); });
    } catch (const expr::ParseError& e) {
      scene::Diagnostic d;
      d.message = std::string(kind) + ": in " + what +
                  " expression '" + text + "': " + e.what();
      d.span = element.command;
      if (word && word->span.known()) {
        d.span = word->span;
        // Point at the offending character when the word is the text itself
        // (possibly in braces or quotes) on one line.
        const int lead = (word->span.end - word->span.begin) - static_cast<int>(text.size());
        if (lead >= 0 && lead <= 2 && text.find('\n') == std::string::npos) {
          d.span.column += lead / 2 + e.offset();
          d.span.begin += lead / 2 + e.offset();
        }
      }
      sys_.diagnostics.push_back(std::move(d));
      return std::nullopt;
    }
  }

  static const char* KindName(const scene::Force&) { return "force"; }
  static const char* KindName(const scene::Torque&) { return "torque"; }
  static const char* KindName(const scene::Link&) { return "link"; }
  static const char* KindName(const scene::Trajectory&) { return "trajectory"; }

  template <typename E>
  std::optional<V3> ParseVector(const E& element, const std::array<std::string, 3>& texts) {
    static const char* kAxes[3] = {"x", "y", "z"};
    V3 out;
    for (int a = 0; a < 3; ++a) {
      auto e = ParseExpr(element, KindName(element), std::string("-") + kAxes[a], texts[a],
                         element.option(kAxes[a]));
      if (!e) return std::nullopt;
      out[a] = *e;
    }
    return out;
  }

  template <typename E>
  int BodyIndex(const E& e, const std::string& name, const char* option) {
    const int b = sys_.FindBody(name);
    if (b < 0 && !name.empty()) {
      // Bodies dropped for their own errors are not reported twice.
      if (!scene_.FindBody(name))
        Error(e, std::string(KindName(e)) + ": unknown body '" + name + "'",
              e.option(option));
    }
    return b;
  }

  // ---- loads ------------------------------------------------------------
  void ApplyForce(int b, const V3& F, const std::optional<V3>& r_world) {
    if (sys_.bodies[b].is_static) return;
    for (int a = 0; a < 3; ++a) loads_[b].force[a].push_back(F[a]);
    if (r_world) {
      const V3 tau = Cross(*r_world, F);
      for (int a = 0; a < 3; ++a) loads_[b].torque[a].push_back(tau[a]);
    }
  }

  void AddForce(const scene::Force& f) {
    const int b = BodyIndex(f, f.body, "body");
    if (b < 0) return;
    auto F = ParseVector(f, f.components);
    if (!F) return;
    if (f.gravitational) *F = Scale(P.Const(sys_.bodies[b].mass), *F);
    std::optional<V3> r;
    if (f.offset) {
      r = Rotate(kin_[b].R, Const(ToEigen(*f.offset) - sys_.bodies[b].centroid));
    }
    ApplyForce(b, *F, r);
  }

  void AddTorque(const scene::Torque& t) {
    const int b = BodyIndex(t, t.body, "body");
    if (b < 0 || sys_.bodies[b].is_static) return;
    auto T = ParseVector(t, t.components);
    if (!T) return;
    for (int a = 0; a < 3; ++a) loads_[b].torque[a].push_back((*T)[a]);
    if (t.offset) {
      // A torque about an axis through d (off the centre of mass) also pushes
      // the body: F = d⊥ × T (seed 5.1.1), and d⊥ × T = d × T since T × T = 0.
      const V3 d = Rotate(kin_[b].R, Const(ToEigen(*t.offset) - sys_.bodies[b].centroid));
      const V3 F = Cross(d, *T);
      for (int a = 0; a < 3; ++a) loads_[b].force[a].push_back(F[a]);
    }
  }

  void AddLink(const scene::Link& l) {
    const int b1 = BodyIndex(l, l.body1, "body1");
    if (b1 < 0) {
      if (l.body1.empty()) Error(l, "link: -body1 is required");
      return;
    }
    auto [p1, v1] = BodyPoint(b1, l.offset1);
    V3 p2, v2;
    double m = sys_.bodies[b1].mass;
    int b2 = -1;
    Joint joint;
    joint.span = l.command;
    if (!l.body2.empty()) {
      b2 = BodyIndex(l, l.body2, "body2");
      if (b2 < 0) return;
      std::tie(p2, v2) = BodyPoint(b2, l.offset2);
      const double m2 = sys_.bodies[b2].mass;
      if (sys_.bodies[b1].is_static) m = m2;
      else if (!sys_.bodies[b2].is_static) m = m * m2 / (m + m2);
      joint.p = p2;
      joint.p_dot = v2;
      joint.p_ddot = {P.Const(0.0), P.Const(0.0), P.Const(0.0)};
    } else if (!l.trajectory.empty()) {
      auto c = curve_index_.find(l.trajectory);
      if (c == curve_index_.end()) {
        Error(l, "link: unknown trajectory '" + l.trajectory + "'", l.option("trajectory"));
        return;
      }
      for (int a = 0; a < 3; ++a) {
        p2[a] = P.Extern(CurveFunction(c->second, a), 0);
        v2[a] = P.Extern(CurveFunction(c->second, a), 1);
        joint.p_ddot[a] = P.Extern(CurveFunction(c->second, a), 2);
      }
      joint.p = p2;
      joint.p_dot = v2;
    } else {
      auto pt = ParseVector(l, l.point);
      if (!pt) return;
      p2 = *pt;
      for (int a = 0; a < 3; ++a) {
        v2[a] = KinematicRate(p2[a]);
        joint.p_ddot[a] = P.TimeDerivative(P.TimeDerivative(p2[a]));
      }
      joint.p = p2;
      joint.p_dot = v2;
    }
    if (b2 >= 0) sys_.body_links.emplace_back(b1, b2);
    if (l.tightness == 0.0 && AddJoint(joint, b1, l.offset1, b2, l.offset2)) return;
    // A spring: the link's own constant, or (exact link whose point moves
    // with other bodies' state) the seed's default.
    const double k = l.tightness > 0.0 ? l.tightness : kFallbackTightness;
    const double c = 2.0 * std::sqrt(k * m);
    for (const int b : {b1, b2})
      if (b >= 0 && !sys_.bodies[b].is_static)
        sys_.bodies[b].spring_rate = std::max(sys_.bodies[b].spring_rate, std::sqrt(k / m));
    const V3 F = Sub(Scale(P.Const(-k), Sub(p1, p2)), Scale(P.Const(c), Sub(v1, v2)));
    ApplyForce(b1, F, Sub(p1, kin_[b1].p));
    if (b2 >= 0) ApplyForce(b2, Scale(P.Const(-1.0), F), Sub(p2, kin_[b2].p));
  }

  // Records an exact joint; false when it cannot be one (both ends fixed, or
  // a point that depends on state, whose second derivative is not known).
  bool AddJoint(Joint j, int b1, const scene::Vec3& offset1, int b2, const scene::Vec3& offset2) {
    auto anchor = [&](int b, const scene::Vec3& off) {
      return Eigen::Vector3d(ToEigen(off) - sys_.bodies[b].centroid);
    };
    if (b2 >= 0 && sys_.bodies[b2].is_static) {
      // A static partner is a fixed point of space.
      const BodyModel& s = sys_.bodies[b2];
      const Eigen::Vector3d p = s.x0 + s.q0.toRotationMatrix() * anchor(b2, offset2);
      for (int a = 0; a < 3; ++a) {
        j.p[a] = P.Const(p[a]);
        j.p_dot[a] = j.p_ddot[a] = P.Const(0.0);
      }
      b2 = -1;
    }
    if (sys_.bodies[b1].is_static) {
      if (b2 < 0) return true;  // both ends fixed: nothing moves
      std::swap(b1, b2);
      const Eigen::Vector3d p =
          sys_.bodies[b2].x0 + sys_.bodies[b2].q0.toRotationMatrix() * anchor(b2, offset1);
      j.body_a = b1;
      j.s_a = anchor(b1, offset2);
      for (int a = 0; a < 3; ++a) {
        j.p[a] = P.Const(p[a]);
        j.p_dot[a] = j.p_ddot[a] = P.Const(0.0);
      }
      j.body_b = -1;
      sys_.joints.push_back(j);
      return true;
    }
    j.body_a = b1;
    j.s_a = anchor(b1, offset1);
    j.body_b = b2;
    if (b2 >= 0) {
      j.s_b = anchor(b2, offset2);
    } else {
      for (int a = 0; a < 3; ++a)
        if (!P.Variables(j.p[a]).empty() || !P.Variables(j.p_ddot[a]).empty()) return false;
    }
    sys_.joints.push_back(j);
    return true;
  }

  // d/dt of an expression point: explicit time dependence plus the chain rule
  // through positions and orientations (whose rates are known without
  // forces).  Dependence on velocities is not differentiated (documented).
  NodeId KinematicRate(NodeId e) {
    NodeId rate = P.TimeDerivative(e);
    for (int v : P.Variables(e)) {
      const int slot = (v - sys_.bodies[sys_.variables[v].body].first_var);
      NodeId vdot;
      if (slot <= kZ) {
        vdot = P.Var(v + 3);
      } else if (slot >= kQw && slot <= kQz) {
        vdot = QuaternionRate(sys_.variables[v].body)[slot - kQw];
      } else {
        continue;
      }
      rate = P.Add(rate, P.Mul(P.Derivative(e, v), vdot));
    }
    return rate;
  }

  std::array<NodeId, 4> QuaternionRate(int b) {
    const Kinematics& k = kin_[b];
    const NodeId w = k.q[0], x = k.q[1], y = k.q[2], z = k.q[3];
    const NodeId o1 = k.w_body[0], o2 = k.w_body[1], o3 = k.w_body[2];
    const NodeId half = P.Const(0.5);
    auto sum3 = [&](NodeId a, NodeId b, NodeId c) {
      NodeId t[3] = {a, b, c};
      return P.Mul(half, P.Sum(t));
    };
    return {sum3(P.Neg(P.Mul(x, o1)), P.Neg(P.Mul(y, o2)), P.Neg(P.Mul(z, o3))),
            sum3(P.Mul(w, o1), P.Mul(y, o3), P.Neg(P.Mul(z, o2))),
            sum3(P.Mul(w, o2), P.Mul(z, o1), P.Neg(P.Mul(x, o3))),
            sum3(P.Mul(w, o3), P.Mul(x, o2), P.Neg(P.Mul(y, o1)))};
  }

  // ---- state equations ---------------------------------------------------
  void StateEquations() {
    for (size_t b = 0; b < sys_.bodies.size(); ++b) {
      const BodyModel& m = sys_.bodies[b];
      if (m.is_static) continue;
      const Kinematics& k = kin_[b];
      auto& vars = sys_.variables;
      const int v0 = m.first_var;
      for (int a = 0; a < 3; ++a) {
        vars[v0 + kX + a].rhs = k.v[a];
        const NodeId F = P.Sum(loads_[b].force[a]);
        vars[v0 + kDx + a].rhs = P.Mul(P.Const(1.0 / m.mass), F);
      }
      const auto qdot = QuaternionRate(static_cast<int>(b));
      for (int i = 0; i < 4; ++i) vars[v0 + kQw + i].rhs = qdot[i];
      const auto wdot = EulerEquations(m, k, loads_[b]);
      for (int a = 0; a < 3; ++a) vars[v0 + kW1 + a].rhs = wdot[a];
    }
  }

  // ω̇ = I⁻¹ (Rᵀ τ_W − ω × I ω), with the gyroscopic term as a quadratic form
  // in ω whose numeric coefficients are symmetrised (they cancel exactly for
  // isotropic inertia).
  V3 EulerEquations(const BodyModel& m, const Kinematics& k, const Loads& loads) {
    V3 tau_world;
    for (int a = 0; a < 3; ++a) tau_world[a] = P.Sum(loads.torque[a]);
    const V3 tau_body = RotateT(k.R, tau_world);
    const Eigen::Matrix3d& I = m.inertia;
    const Eigen::Matrix3d Iinv = I.inverse();
    // G[i](l, n): coefficient of ω_l ω_n in (ω × Iω)_i.
    std::array<Eigen::Matrix3d, 3> G;
    for (int i = 0; i < 3; ++i) {
      G[i].setZero();
      for (int l = 0; l < 3; ++l)
        for (int mm = 0; mm < 3; ++mm) {
          const int eps = Levi(i, l, mm);
          if (eps == 0) continue;
          for (int n = 0; n < 3; ++n) G[i](l, n) += eps * I(mm, n);
        }
    }
    V3 out;
    for (int a = 0; a < 3; ++a) {
      std::vector<NodeId> terms;
      for (int i = 0; i < 3; ++i) {
        if (Iinv(a, i) != 0.0) terms.push_back(P.Mul(P.Const(Iinv(a, i)), tau_body[i]));
      }
      for (int l = 0; l < 3; ++l)
        for (int n = l; n < 3; ++n) {
          double c = 0.0;
          for (int i = 0; i < 3; ++i) {
            const double g = (l == n) ? G[i](l, l) : G[i](l, n) + G[i](n, l);
            c += Iinv(a, i) * g;
          }
          if (c == 0.0) continue;
          terms.push_back(P.Mul(P.Const(-c), P.Mul(k.w_body[l], k.w_body[n])));
        }
      out[a] = P.Sum(terms);
    }
    return out;
  }

  static int Levi(int i, int j, int k) {
    if (i == j || j == k || i == k) return 0;
    return ((i == 0 && j == 1) || (i == 1 && j == 2) || (i == 2 && j == 0)) ? 1 : -1;
  }

  // ---- trajectories ------------------------------------------------------
  void AttachTrajectory(const scene::Trajectory& t) {
    if (t.state == scene::Trajectory::State::kNone) return;
    const int b = BodyIndex(t, t.body, "body");
    if (b < 0) return;
    const BodyModel& m = sys_.bodies[b];
    if (m.is_static) {
      Error(t, "trajectory " + t.name + ": body '" + m.name + "' is static");
      return;
    }
    if (t.knots.empty()) return;
    const double from = t.from.value_or(t.knots.front().t);
    const double to = t.to.value_or(t.knots.back().t);
    if (!(to > from)) {
      Error(t, "trajectory " + t.name + ": the interval [from, to] is empty");
      return;
    }
    const int c = curve_index_.at(t.name);
    auto ext = [&](int axis, int order) { return P.Extern(CurveFunction(c, axis), order); };
    const int v0 = m.first_var;
    std::vector<std::pair<int, NodeId>> values;
    using State = scene::Trajectory::State;
    switch (t.state) {
      case State::kPos:
        for (int a = 0; a < 3; ++a) {
          values.emplace_back(v0 + kX + a, ext(a, 0));
          values.emplace_back(v0 + kDx + a, ext(a, 1));
        }
        break;
      case State::kDpos:
        for (int a = 0; a < 3; ++a) values.emplace_back(v0 + kDx + a, ext(a, 0));
        break;
      case State::kRot: {
        const std::array<NodeId, 4> q = QuaternionOfRotationVector({ext(0, 0), ext(1, 0), ext(2, 0)});
        std::array<NodeId, 4> qd;
        for (int i = 0; i < 4; ++i) qd[i] = P.TimeDerivative(q[i]);
        // ω_B = 2 vec(q* ⊗ q̇) = 2 (q_w q̇_v − q̇_w q_v − q_v × q̇_v)
        const V3 qv{q[1], q[2], q[3]}, qdv{qd[1], qd[2], qd[3]};
        const V3 w = Scale(P.Const(2.0),
                           Sub(Sub(Scale(q[0], qdv), Scale(qd[0], qv)), Cross(qv, qdv)));
        for (int i = 0; i < 4; ++i) values.emplace_back(v0 + kQw + i, q[i]);
        for (int a = 0; a < 3; ++a) values.emplace_back(v0 + kW1 + a, w[a]);
        break;
      }
      case State::kDrot: {
        const V3 w = RotateT(kin_[b].R, {ext(0, 0), ext(1, 0), ext(2, 0)});
        for (int a = 0; a < 3; ++a) values.emplace_back(v0 + kW1 + a, w[a]);
        break;
      }
      case State::kNone:
        break;
    }
    for (auto [var, e] : values) {
      auto& ov = sys_.variables[var].overrides;
      for (const Override& o : ov) {
        if (from < o.to && o.from < to) {
          Error(t, "trajectory " + t.name + ": overlaps another trajectory on " +
                       sys_.variables[var].name);
          return;
        }
      }
    }
    for (auto [var, e] : values) {
      auto& ov = sys_.variables[var].overrides;
      ov.push_back({Override::Kind::kValue, from, to, e});
      std::sort(ov.begin(), ov.end(),
                [](const Override& a, const Override& b) { return a.from < b.from; });
    }
  }

  std::array<NodeId, 4> QuaternionOfRotationVector(const V3& r) {
    NodeId sq[3] = {P.Mul(r[0], r[0]), P.Mul(r[1], r[1]), P.Mul(r[2], r[2])};
    const NodeId theta2 = P.Sum(sq);
    const NodeId theta = P.Apply(expr::Op::kSqrt, std::array<NodeId, 1>{theta2});
    const NodeId half = P.Mul(P.Const(0.5), theta);
    const NodeId s = P.Apply(expr::Op::kSin, std::array<NodeId, 1>{half});
    const NodeId cw = P.Apply(expr::Op::kCos, std::array<NodeId, 1>{half});
    // sin(θ/2)/θ, with its series near θ = 0 (0/0 otherwise).
    const NodeId small =
        P.Apply(expr::Op::kLt, std::array<NodeId, 2>{theta2, P.Const(1e-12)});
    const NodeId series = P.Sub(P.Const(0.5), P.Mul(P.Const(1.0 / 48.0), theta2));
    const NodeId k = P.Select(small, series, P.Div(s, theta));
    return {cw, P.Mul(k, r[0]), P.Mul(k, r[1]), P.Mul(k, r[2])};
  }

  // ---- breakpoints -------------------------------------------------------
  void CollectExterns(NodeId e, std::set<int>& fns, std::set<NodeId>& seen) {
    if (!seen.insert(e).second) return;
    const expr::Node& n = P.node(e);
    if (n.op == expr::Op::kExtern) fns.insert(n.index);
    for (NodeId a : n.args) CollectExterns(a, fns, seen);
  }

  void Breakpoints() {
    const double t0 = sys_.t0, t1 = sys_.t1;
    // A joint's point acts on the rates of its body's velocity rows.
    std::map<int, std::vector<NodeId>> joint_exprs;
    for (const Joint& j : sys_.joints) {
      if (j.body_b >= 0) continue;
      const int v0 = sys_.bodies[j.body_a].first_var;
      for (int slot : {kDx, kDy, kDz, kW1, kW2, kW3})
        for (int a = 0; a < 3; ++a)
          for (NodeId e : {j.p[a], j.p_dot[a], j.p_ddot[a]}) joint_exprs[v0 + slot].push_back(e);
    }
    for (size_t vi = 0; vi < sys_.variables.size(); ++vi) {
      auto& v = sys_.variables[vi];
      std::vector<NodeId> exprs{v.rhs};
      if (auto it = joint_exprs.find(static_cast<int>(vi)); it != joint_exprs.end())
        exprs.insert(exprs.end(), it->second.begin(), it->second.end());
      std::vector<double> bps;
      for (const Override& o : v.overrides) {
        exprs.push_back(o.expr);
        bps.push_back(o.from);
        bps.push_back(o.to);
      }
      std::set<int> fns;
      std::set<NodeId> seen;
      for (NodeId e : exprs) {
        for (double t : P.TimeBreakpoints(e, t0, t1)) bps.push_back(t);
        CollectExterns(e, fns, seen);
      }
      for (int fn : fns) {
        for (double t : sys_.curves[CurveOfFunction(fn)]->times) bps.push_back(t);
      }
      std::erase_if(bps, [&](double t) { return !(t > t0 && t < t1); });
      std::sort(bps.begin(), bps.end());
      bps.erase(std::unique(bps.begin(), bps.end()), bps.end());
      v.breakpoints = std::move(bps);
    }
  }

  const scene::Scene& scene_;
  EquationSystem& sys_;
  expr::Pool& P;
  std::map<std::string, ShapeModel> shapes_;
  std::map<std::string, int> curve_index_;
  std::vector<Kinematics> kin_;
  std::vector<Loads> loads_;
};

}  // namespace

void SetInitialState(BodyModel& m, const scene::Body& b) {
  m.q0 = Eigen::Quaterniond(b.init_rot[0], b.init_rot[1], b.init_rot[2], b.init_rot[3]).normalized();
  const Eigen::Matrix3d R0 = m.q0.toRotationMatrix();
  m.x0 = ToEigen(b.init_pos) + R0 * m.centroid;
  m.v0 = ToEigen(b.init_dpos);
  m.w0_body = R0.transpose() * ToEigen(b.init_drot);
}

std::array<double, kBodySlots> InitialValues(const BodyModel& m) {
  return {m.x0.x(), m.x0.y(), m.x0.z(), m.v0.x(), m.v0.y(), m.v0.z(), m.q0.w(),
          m.q0.x(), m.q0.y(), m.q0.z(), m.w0_body.x(), m.w0_body.y(), m.w0_body.z()};
}

expr::ExternFn EquationSystem::externs() const {
  auto curves_copy = curves;
  return [curves_copy](int fn, int order, double t) {
    return curves_copy[CurveOfFunction(fn)]->Evaluate(AxisOfFunction(fn), order, t);
  };
}

bool EquationSystem::has_errors() const {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [](const scene::Diagnostic& d) { return d.severity == scene::Severity::kError; });
}

int EquationSystem::FindBody(const std::string& name) const {
  for (size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == name) return static_cast<int>(i);
  return -1;
}

EquationSystem FormEquations(const scene::Scene& scene) {
  EquationSystem sys;
  Builder(scene, sys).Run();
  return sys;
}

}  // namespace asgard::physics
