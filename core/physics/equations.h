// Physics: scene elements → first-order state equations (seed 5.1).
//
// Every free body contributes 13 state variables and one equation each:
//
//   position (centre of mass)   x y z        ẋ = dx
//   velocity                    dx dy dz     d(dx)/dt = ΣF_x / m
//   orientation (quaternion)    qw qx qy qz  q̇ = ½ q ⊗ (0, ω)
//   angular velocity, body axes w1 w2 w3     ω̇ = I⁻¹ (τ_B − ω × I ω)
//
//   ΣF: the body's forces (expressions), link springs, gravitational forces.
//   τ_B = Rᵀ τ_W with τ_W = Σ r × F for off-centre forces and links, plus
//   torques; R = R(q) in the homogeneous form (valid for any q ≠ 0, so a slowly
//   drifting quaternion norm never distorts the geometry).
//
// Why body-axis angular velocity: the Euler equations then have constant
// coefficients, and the gyroscopic term ω × I ω is built from numeric
// coefficients in which a sphere's (I = cE) cancel exactly, so a lone sphere's
// axes stay decoupled and partition finely (seed Figure 5.8).  World-axis ω
// would put the time-varying I_W into every equation.
//
// A link without -tightness is an exact joint (a ball joint: the two points
// coincide).  Its force is not an expression: it is solved from the
// constraint at every evaluation of the rates (physics/joints.h), so the
// equations hold the free rates and `joints` lists what the solver must add.
// A link with -tightness K keeps the seed's meaning (5.1.2), a critically
// damped spring:
//   F = −k (p₁ − p₂) − 2 √(k m) (ṗ₁ − ṗ₂)
// with m the attached body's mass (object–point) or the reduced mass
// m₁m₂/(m₁+m₂) (object–object), so the relative motion of two free bodies is
// critically damped.
//
// Trajectories attached to a body prescribe state over [from, to) as
// overrides of the state equations (seed 5.1.3):
//   pos   x := p(t),  dx := ṗ(t)            (values; the force law is ignored)
//   dpos  dx := v(t)                         (value; x still integrates dx)
//   rot   q := exp(r(t)/2),  ω := 2 vec(q* ⊗ q̇)
//   drot  ω := Rᵀ ω_W(t)
// Entering an interval makes the state jump to the prescribed value (a
// breakpoint); leaving it lets the equations take over from where it ended.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "core/expr/expr.h"
#include "core/geometry/geometry.h"
#include "core/scene/scene.h"

namespace asgard::physics {

// How one state variable is defined over [from, to).
struct Override {
  enum class Kind : uint8_t { kValue, kRate };
  Kind kind = Kind::kValue;  // kValue: x = expr;  kRate: dx/dt = expr
  double from = 0.0;
  double to = 0.0;
  expr::NodeId expr = 0;
};

struct StateVariable {
  std::string name;   // "b1.x", "b1.qw", "b1.w1"
  int body = -1;      // index into EquationSystem::bodies
  double initial = 0.0;
  expr::NodeId rhs = 0;              // dx/dt outside every override
  std::vector<Override> overrides;   // disjoint, sorted by `from`
  // Times in [t0, t1] where this variable's equation is not smooth: override
  // ends, comparisons of t with constants, trajectory knots it reads.
  std::vector<double> breakpoints;
};

// A convex piece of a body, in body coordinates (origin at the centre of mass,
// axes of the shape).
struct BodyPiece {
  bool is_sphere = false;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // sphere centre
  double radius = 0.0;
  geometry::ConvexHull hull;                          // when !is_sphere
  std::string color;
};

// Index of a body's first state variable; the rest follow in this order.
enum BodySlot : int {
  kX = 0, kY, kZ, kDx, kDy, kDz, kQw, kQx, kQy, kQz, kW1, kW2, kW3, kBodySlots
};

struct BodyModel {
  std::string name;
  std::string artbody;
  bool is_static = false;
  bool collision_test = true;
  double restitution = 1.0;
  double friction = 0.0;
  double mass = 1.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();  // about CoM, body axes
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();     // CoM in shape coords
  std::vector<BodyPiece> pieces;
  std::string color;
  int first_var = -1;  // -1 for static bodies (no state)
  // The largest rate √(k/m) of the springs (links with a tightness) that
  // act on the body, 0 for none: the spectral radius they give its motion.
  double spring_rate = 0.0;
  // Initial state (also the constant state of a static body).
  Eigen::Vector3d x0, v0, w0_body;
  Eigen::Quaterniond q0;
};

struct TrajectoryCurve;  // piecewise cubic Bézier, see trajectory.h

// Each trajectory curve is three external functions of time (expr::Extern),
// one per axis: this is the one place that numbers them.
constexpr int CurveFunction(int curve, int axis) { return 3 * curve + axis; }
constexpr int CurveOfFunction(int fn) { return fn / 3; }
constexpr int AxisOfFunction(int fn) { return fn % 3; }

// An exact ball joint: point s_a of body a coincides with point s_b of body b,
// or (body_b < 0) with the point p(t) of space.  Anchors are in body axes
// from the centre of mass.
struct Joint {
  int body_a = -1;
  Eigen::Vector3d s_a = Eigen::Vector3d::Zero();
  int body_b = -1;
  Eigen::Vector3d s_b = Eigen::Vector3d::Zero();
  // body_b < 0: the point and its first two time derivatives (functions of t
  // only: constants, expressions of t, trajectories).
  std::array<expr::NodeId, 3> p{}, p_dot{}, p_ddot{};
  scene::SourceSpan span;  // the link command
};

// The whole system: variables, equations, and what the solver needs to know
// about time (breakpoints) and about bodies (for collisions and output).
struct EquationSystem {
  expr::Pool pool;
  std::vector<StateVariable> variables;
  std::vector<BodyModel> bodies;
  std::vector<std::shared_ptr<const TrajectoryCurve>> curves;  // see CurveFunction
  std::vector<std::pair<int, int>> body_links;  // bodies joined by a link (for artbody rules)
  std::vector<Joint> joints;                      // exact links
  double t0 = 0.0;
  double t1 = 10.0;
  std::vector<scene::Diagnostic> diagnostics;

  // External-function table for Tape::Evaluate (trajectory components).
  expr::ExternFn externs() const;
  bool has_errors() const;
  int FindBody(const std::string& name) const;
};

// A body's initial state from its element (-init_pos is where the shape's
// origin goes; the state tracks the centre of mass), into m.x0 q0 v0 w0_body,
// and the 13 initial values of its state variables in BodySlot order.
void SetInitialState(BodyModel& m, const scene::Body& b);
std::array<double, kBodySlots> InitialValues(const BodyModel& m);

// Forms the equations of `scene`.  Problems (bad expressions, unknown names,
// degenerate hulls) become diagnostics located at the offending element, and
// that element is left out; never throws.
EquationSystem FormEquations(const scene::Scene& scene);

}  // namespace asgard::physics
