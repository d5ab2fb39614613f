// Peer integrators and engines.  Each is compiled only when its library was
// found (see bench/CMakeLists.txt); Peers() lists the ones built in.
//
//   same equations (Asgard's equations and symbolic Jacobian, via TapeOde):
//     cvode_bdf_klu     SUNDIALS CVODE, BDF, KLU, analytic Jacobian
//     arkode_trbdf2     SUNDIALS ARKODE ARKStep, TR-BDF2 (ARKODE_TRBDF2_3_3_2), KLU
//     odeint_dopri5     Boost.Odeint Dormand–Prince 5(4), dense output
//     odeint_rosenbrock4  Boost.Odeint Rosenbrock 4(3), dense Jacobian
//   same scene (rigid joints, fixed step):
//     mujoco_euler, mujoco_rk4   MuJoCo 2.2
//     bullet            Bullet 3.24 (float64 build), btRigidBody + constraints
//     ode               ODE 0.16 (double), dWorldStep
#pragma once

#include <string>
#include <vector>

#include "bench/harness.h"
#include "bench/model.h"

namespace asgard::bench {

struct PeerRun {
  bool ok = false;
  std::string error;
  Trajectory traj;
  double cpu = 0.0;
  long steps = 0, rejected = 0, rhs = 0, jac = 0, factorizations = 0;
};

struct OdePeer {
  std::string name;
  PeerRun (*run)(const TapeOde& ode, double rtol, double atol, const std::vector<double>& times);
};
struct EnginePeer {
  std::string name;
  // Whether the engine can model the scene; then a fixed-step run.
  bool (*fits)(const WpScene& scene);
  PeerRun (*run)(const WpScene& scene, double h, const std::vector<double>& times);
};

std::vector<OdePeer> OdePeers();
std::vector<EnginePeer> EnginePeers();
// Human-readable notes on what was built (and what was not, and why).
std::vector<std::string> PeerNotes();

// Registration hooks implemented by each peer file (or absent).
void AddSundialsPeers(std::vector<OdePeer>& out);
void AddOdeintPeers(std::vector<OdePeer>& out);
void AddMujocoPeers(std::vector<EnginePeer>& out);
void AddBulletPeers(std::vector<EnginePeer>& out);
void AddOdePeers(std::vector<EnginePeer>& out);

}  // namespace asgard::bench
