// Benchmark scenes, the Asgard runner, Asgard's equations as a plain ODE
// (for the peer integrators: "the same equations"), and exact references.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/harness.h"
#include "core/expr/expr.h"
#include "core/pipeline/pipeline.h"

namespace asgard::physics {
class JointSolver;
}

namespace asgard::bench {

// The ideal (rigid-joint) form of a pendulum scene, for the engines that
// model joints as constraints (MuJoCo, Bullet, ODE).  Planar compound
// pendulums: body i is a ball (mass, I_cm) whose centre hangs `arm[i]` below
// its joint; joint i+1 sits `joint[i]` below joint i on body i.  Angles from
// the downward vertical, released at rest at `theta0`.  A tree: `parent[i]`
// is the body whose joint point (`joint[parent]` below its own joint) body i
// hangs from, or −1 for the fixed pivot at the origin; parents come before
// their children.  An empty `parent` is a chain (parent i − 1).
struct RigidChain {
  int bodies = 0;
  std::vector<double> mass, inertia, arm, joint, theta0;
  std::vector<int> parent;
  double g = 9.81;
  int Parent(int i) const { return parent.empty() ? i - 1 : parent[i]; }
  // Joint i's position (x, y) at t = 0.
  std::array<double, 2> Pivot0(int i) const;
  // Length of the longest path from the pivot (the scene size).
  double Reach() const;
};

struct WpScene {
  std::string name;
  std::string text;  // Asgard scene text
  double t1 = 10.0;
  double size = 1.0;          // scene size for the error metric
  std::vector<double> radii;  // per body
  // Exact solution of Asgard's equations where one exists (else the
  // reference is computed with CVODE at 1e-12 on the same equations).
  std::function<Trajectory(const std::vector<double>& times)> exact;
  std::string exact_name;           // how `exact` was obtained
  std::optional<RigidChain> rigid;  // engines' model of the scene, if any
  // Torque-free top (engines: a free body with these moments and ω0).
  std::optional<std::array<double, 6>> top;  // I1 I2 I3 w1 w2 w3
  bool collisions = false;
};

// The work–precision scenes.
WpScene SimplePendulumScene();
WpScene DoublePendulumScene();
WpScene TopScene();
WpScene ChainScene(int n, double t1 = 3.0);
// A planar binary tree of n rods (each a unit-length rod of mass 1 hinged at
// its parent's end; body i's parent is (i − 1) / 2), released at rest from
// spread angles.  Asgard's text is written from the rigid model.
WpScene TreeScene(int n, double t1);
// Asgard scene text of a rigid planar model: balls with the model's moments,
// joined by exact links at the joints, under gravity, until t1.
std::string RigidChainText(const RigidChain& c, double t1);
WpScene StiffLinkScene(double k);
WpScene BallsInBoxScene(int n);

// Scene text helpers shared by the suites.
std::string BallShape();
// A ball pendulum named `name`: its point `len` from the centre is linked to
// `pivot`, released at angle theta0 (radians) in the x–y plane.
std::string PendulumText(const std::string& name, const double* pivot, double len, double theta0,
                         double g, double k, double mass = 1.0);

// One Asgard run: frames at 30 Hz, CPU time of the solver phase, counters.
struct AsgardRun {
  bool ok = false;
  std::string error;
  Trajectory traj;
  double cpu = 0.0;        // solver CPU seconds (Simulate minus scene setup)
  double total_cpu = 0.0;  // whole Simulate call
  double solver_wall = 0.0;
  solver::Counters counters;
  int components = 0;
  long impacts = 0;
};
AsgardRun RunAsgard(const std::string& text, const pipeline::RunOptions& options,
                    const std::vector<double>& frame_times, double setup_cpu = 0.0);
// Median CPU time of evaluating the scene and forming its equations.
double SetupCpu(const std::string& text, int repeats);
Trajectory SampleAsgard(const pipeline::Run& run, const std::vector<double>& times);

// Asgard's equations as an ODE y' = f(t, y) with its symbolic Jacobian
// (compressed sparse columns), compiled to tapes.  Valid for scenes without
// trajectories and collisions.
class TapeOde {
 public:
  explicit TapeOde(const std::string& text);
  bool ok() const { return ok_; }
  int size() const { return n_; }
  const std::vector<double>& initial() const { return y0_; }
  double t0() const { return t0_; }
  double t1() const { return t1_; }
  void Rhs(double t, const double* y, double* f) const;
  // Jacobian values in CSC order (col_ptr, row_index below).
  void Jacobian(double t, const double* y, double* values) const;
  const std::vector<int>& col_ptr() const { return col_ptr_; }
  const std::vector<int>& row_index() const { return row_index_; }
  int nnz() const { return static_cast<int>(row_index_.size()); }
  // Poses of every body from a state vector.
  std::vector<Pose> Poses(const double* y) const;
  mutable long rhs_count = 0;
  mutable long jac_count = 0;

 private:
  bool ok_ = false;
  int n_ = 0;
  double t0_ = 0, t1_ = 0;
  std::vector<double> y0_;
  std::unique_ptr<expr::Tape> rhs_, jac_;
  std::vector<int> col_ptr_, row_index_;
  struct BodyInfo {
    int first_var;
    double fixed[7];
  };
  std::vector<BodyInfo> bodies_;
  std::unique_ptr<physics::EquationSystem> eq_;
  expr::ExternFn ext_;
  std::shared_ptr<physics::JointSolver> joints_;  // exact links, if any
  std::vector<char> prescribed_;
};

// Exact references.
// Physical pendulum released at rest at theta0: θ(t) = 2 asin(k sn(K − ω t, k)).
double PendulumAngle(double theta0, double omega, double t);
// Rigid planar chain or tree integrated with classical RK4 at a fine fixed
// step h in absolute angles (an independent code and model; used for the
// engines).
Trajectory RigidChainReference(const RigidChain& c, const std::vector<double>& times,
                               double h = 2e-5);
// Hard spheres in a box, event-driven and exact (no gravity).
struct HardSpheres {
  double box = 10.0;  // cube [−box/2, box/2]³ (inner faces)
  double radius = 0.5;
  std::vector<std::array<double, 3>> p, v;
};
Trajectory HardSpheresExact(const HardSpheres& s, const std::vector<double>& times,
                            long* collisions = nullptr);

}  // namespace asgard::bench
