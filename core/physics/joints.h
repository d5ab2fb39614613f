// Exact joints: the forces that keep linked points together, solved from the
// constraints at every evaluation of the rates.
//
// A joint j holds point s_a of body a on point s_b of body b (or on a point
// p(t) of space).  With R the rotation, ω the angular velocity (body axes)
// and r = R s the anchor's arm in world axes:
//
//   C   = x_a + R_a s_a − (x_b + R_b s_b)                      position error
//   Ċ   = v_a + R_a (ω_a × s_a) − (…)_b                         velocity error
//   C̈   = a_a + R_a (ω̇_a × s_a + ω_a × (ω_a × s_a)) − (…)_b
//
// A force λ_j at the joint (+λ on a, −λ on b) changes the accelerations by
// a = λ/m and ω̇ = I⁻¹ (s × Rᵀλ), so C̈ = C̈_free + Σ_k K_jk λ_k with
//
//   K_jk = Σ over bodies B that j and k share  σ_jB σ_kB W_B(s_jB, s_kB),
//   W(s, s') = I₃/m − R [s]× I⁻¹ [s']× Rᵀ        (symmetric positive definite)
//
// where σ = +1 on a's side, −1 on b's.  The forces make the error decay as a
// critically damped oscillator (Baumgarte stabilization, so the drift that
// integration leaves in C is pulled back smoothly, and a step still depends
// only on its starting sample):
//
//   C̈ + 2Ω Ċ + Ω² C = 0   ⇒   (K + εD) λ = −(C̈_free + 2Ω Ċ + Ω² C)
//
// ε D (a tiny multiple of K's diagonal) regularizes redundant and closed-loop
// constraints, which would otherwise make K singular.
//
// K is block sparse (3×3 blocks, one block row per joint, nonzero where two
// joints share a body).  It is factored as L D Lᵀ in blocks, in an
// elimination order chosen once (minimum degree on the joint graph): a chain
// or a tree is eliminated from its leaves with no fill, so a solve costs time
// linear in the number of joints.  A closed loop fills in only along the loop.
//
// Rejected: (1) stiff penalty springs (the seed's links) — their stiff
// directions turn with the bodies, so implicit steps need fresh Jacobians
// every step and explicit ones tiny steps; (2) reduced (joint-angle)
// coordinates — exact and cheap for trees, but they would replace the 13
// variables per body that the whole system (trajectories, collisions,
// editing) is built on; (3) projection after each step — exact, but it
// makes a sample depend on a correction outside the integration.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/expr/expr.h"
#include "core/physics/equations.h"

namespace asgard::physics {

class JointSolver {
 public:
  // `joints`: indices into sys.joints.  `local_first(b)` (b a body of sys)
  // is the index of body b's first state variable in the rate array that
  // Apply corrects, or -1 when b's state is not there.
  JointSolver(const EquationSystem& sys, std::vector<int> joints,
              const std::function<int(int)>& local_first);

  // Adds the joint forces' effect to `rates` (accelerations and angular
  // accelerations of the bodies involved).  `values` holds every state
  // variable (global indices) at time t; `rates` the free rates.  Rows set in
  // `prescribed` (local; null: none) are values, not rates, and are left
  // alone; a body whose velocity is prescribed moves as prescribed (infinite
  // mass).
  // `magnitude` (optional, local rows like `rates`): each row gets the sum of
  // the magnitudes of the joint terms added to it — the size of the
  // cancellation's rounding where the joint forces balance others (a chain
  // hanging at rest: each body's rate is a difference of the forces that
  // carry the weight below it).
  // `refinements`: steps of iterative refinement of the joint forces (one
  // leaves a relative error of ε², enough for integration; the rest test
  // asks for two, as a long chain's K is less well conditioned).
  // `x_offset`: values[v − x_offset] is variable v (as for Tape::Evaluate),
  // so that a component's own state array serves when every body is in it.
  void Apply(double t, const double* values, double* rates, const char* prescribed,
             const expr::ExternFn* externs, double* magnitude = nullptr, int refinements = 1,
             int32_t x_offset = 0);

  // An impulsive joint response: after velocities jumped (a collision),
  // impulses at the joints make every joint's relative velocity zero again
  // (K Λ = −Ċ), so an impact on one body of an articulated group moves the
  // group as joined bodies do.  `state` is the component-local state (the
  // velocities there are changed); `values` the global state with it loaded.
  void ProjectVelocities(double t, const double* values, double* state, const char* prescribed,
                         const expr::ExternFn* externs);

  int joint_count() const { return static_cast<int>(joints_.size()); }

 private:
  struct BodyData {
    int body;   // index in sys.bodies
    int local;  // first local state index
    double inv_mass;
    Eigen::Matrix3d inv_inertia;  // body axes
    // c when inv_inertia is c·I (a sphere, a cube): the world inverse
    // inertia is then the same matrix and needs no rotation; else 0.
    double isotropic = 0;
    // per evaluation
    Eigen::Matrix3d R;
    Eigen::Matrix3d inv_inertia_world;  // R I⁻¹ Rᵀ
    Eigen::Vector3d w;                  // angular velocity, body axes
    bool kinematic;
  };
  struct End {
    int body = -1;  // index into bodies_, -1: point of space
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    Eigen::Vector3d arm = Eigen::Vector3d::Zero();       // R s, per evaluation
    Eigen::Matrix3d arm_skew = Eigen::Matrix3d::Zero();  // [R s]×, per evaluation
  };
  struct JointData {
    End a, b;
    int point = -1;  // first output of the point tape (b.body < 0)
  };
  // One 3×3 block of the factor: row block i, column (pivot) block p.
  struct Update {
    int target;  // block slot updated: A_ik −= L_ip A_pk
    int lhs;     // slot of L_ip
    int rhs;     // slot of A_pk (stored as A_kp, transposed on use)
  };
  struct Pivot {
    int joint;
    int diag;                // slot of A_pp
    std::vector<int> rows;   // later joints coupled to p (after fill)
    std::vector<int> slots;  // slot of A_ip for each row
    std::vector<Update> updates;
  };

  void Symbolic();
  void Prepare(double t, const double* values, const char* prescribed,
               const expr::ExternFn* externs, int32_t x_offset = 0);
  // Factors K + εD at the prepared state and overwrites rhs_ with the
  // solution of K λ = rhs_, refined `refinements` times against K.
  void Solve(int refinements = 1);
  static Eigen::Matrix3d Regularized(const Eigen::Matrix3d& K);
  void Substitute(std::vector<Eigen::Vector3d>& v) const;
  // Adds the effect of forces (or impulses) rhs_ to `out` (rates or velocities).
  void Distribute(double* out, const char* prescribed, double* magnitude = nullptr) const;
  int Slot(int i, int j);
  Eigen::Matrix3d Coupling(int i, int k) const;

  const EquationSystem& sys_;
  std::vector<BodyData> bodies_;
  std::vector<JointData> joints_;
  expr::Tape point_tape_;         // unused when points_constant_
  bool points_constant_ = false;  // every joint point is a constant
  bool any_anisotropic_ = false;  // some body's arms need their skew matrices (Coupling)
  std::vector<double> point_values_;
  // block structure
  std::vector<Pivot> pivots_;                   // in elimination order
  std::vector<std::pair<int, int>> slot_keys_;  // (row, col) of each slot
  std::vector<Eigen::Matrix3d> blocks_;         // K + εD, then its factor
  std::vector<Eigen::Matrix3d> coupling_;       // K, per slot
  std::vector<Eigen::Vector3d> residual_;       // per joint
  std::vector<Eigen::Matrix3d> dinv_;           // per pivot
  std::vector<Eigen::Vector3d> rhs_;            // per joint
  std::vector<Eigen::Vector3d> b_;              // per joint: the right side solved
};

}  // namespace asgard::physics
