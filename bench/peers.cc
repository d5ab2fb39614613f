#include "bench/peers.h"

namespace asgard::bench {

std::vector<OdePeer> OdePeers() {
  std::vector<OdePeer> out;
#ifdef ASGARD_BENCH_SUNDIALS
  AddSundialsPeers(out);
#endif
#ifdef ASGARD_BENCH_ODEINT
  AddOdeintPeers(out);
#endif
  return out;
}

std::vector<EnginePeer> EnginePeers() {
  std::vector<EnginePeer> out;
#ifdef ASGARD_BENCH_MUJOCO
  AddMujocoPeers(out);
#endif
#ifdef ASGARD_BENCH_BULLET
  AddBulletPeers(out);
#endif
#ifdef ASGARD_BENCH_ODE
  AddOdePeers(out);
#endif
  return out;
}

std::vector<std::string> PeerNotes() {
  std::vector<std::string> n;
#ifdef ASGARD_BENCH_SUNDIALS
  n.push_back("SUNDIALS " ASGARD_BENCH_SUNDIALS
              ": CVODE BDF and ARKODE TR-BDF2, KLU, Asgard's Jacobian");
#else
  n.push_back("SUNDIALS not found: CVODE/ARKODE not built (run scripts/bench-setup.sh)");
#endif
#ifdef ASGARD_BENCH_ODEINT
  n.push_back("Boost.Odeint " ASGARD_BENCH_ODEINT ": dopri5, rosenbrock4");
#else
  n.push_back("Boost not found: odeint peers not built");
#endif
#ifdef ASGARD_BENCH_MUJOCO
  n.push_back("MuJoCo " ASGARD_BENCH_MUJOCO ": Euler and RK4, hinge joints");
#else
  n.push_back("MuJoCo not found: not built");
#endif
#ifdef ASGARD_BENCH_BULLET
  n.push_back("Bullet " ASGARD_BENCH_BULLET " (" ASGARD_BENCH_BULLET_PRECISION
              "): btDiscreteDynamicsWorld, point-to-point constraints");
#else
  n.push_back("Bullet (float64) not found: not built");
#endif
#ifdef ASGARD_BENCH_ODE
  n.push_back("ODE " ASGARD_BENCH_ODE ": dWorldStep, hinge joints");
#else
  n.push_back("ODE not found: not built");
#endif
  return n;
}

}  // namespace asgard::bench
