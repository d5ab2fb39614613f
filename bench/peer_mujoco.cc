// MuJoCo 2.2 on the same scenes: planar pendulum chains and trees with hinge
// joints, and the torque-free top as a free body.  Fixed steps, Euler
// (semi-implicit) and RK4 integrators, contacts disabled.
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "bench/peers.h"

namespace asgard::bench {

namespace {

std::string ModelXml(const WpScene& s, double h, bool rk4) {
  std::ostringstream x;
  x.precision(17);
  x << "<mujoco><option timestep=\"" << h << "\" integrator=\"" << (rk4 ? "RK4" : "Euler")
    << "\" gravity=\"0 " << (s.rigid ? -s.rigid->g : 0.0) << " 0\">"
    << "<flag contact=\"disable\"/></option><worldbody>";
  if (s.rigid) {
    const RigidChain& c = *s.rigid;
    // Bodies nest as the tree does; a body's frame sits at its joint.
    std::function<void(int)> body = [&](int i) {
      const double ux = std::sin(c.theta0[i]), uy = -std::cos(c.theta0[i]);
      x << "<body name=\"b" << i << "\"";
      if (const int p = c.Parent(i); p >= 0) {
        const double px = std::sin(c.theta0[p]) * c.joint[p];
        const double py = -std::cos(c.theta0[p]) * c.joint[p];
        x << " pos=\"" << px << " " << py << " 0\"";
      }
      x << "><joint type=\"hinge\" axis=\"0 0 1\"/><inertial pos=\"" << c.arm[i] * ux << " "
        << c.arm[i] * uy << " 0\" mass=\"" << c.mass[i] << "\" diaginertia=\"" << c.inertia[i]
        << " " << c.inertia[i] << " " << c.inertia[i] << "\"/>";
      for (int k = i + 1; k < c.bodies; ++k)
        if (c.Parent(k) == i) body(k);
      x << "</body>";
    };
    for (int i = 0; i < c.bodies; ++i)
      if (c.Parent(i) < 0) body(i);
  } else if (s.top) {
    const auto& t = *s.top;
    x << "<body name=\"top\"><freejoint/><inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"" << t[0]
      << " " << t[1] << " " << t[2] << "\"/></body>";
  }
  x << "</worldbody></mujoco>";
  return x.str();
}

bool Fits(const WpScene& s) { return s.rigid.has_value() || s.top.has_value(); }

PeerRun Run(const WpScene& s, double h, const std::vector<double>& times, bool rk4) {
  PeerRun out;
  const std::string path = "/tmp/asgard_bench_mujoco_" + std::to_string(getpid()) + ".xml";
  {
    std::ofstream f(path);
    f << ModelXml(s, h, rk4);
  }
  char err[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, err, sizeof err);
  unlink(path.c_str());
  if (!m) {
    out.error = std::string("mj_loadXML: ") + err;
    return out;
  }
  const double c0 = ThreadCpuSeconds();
  mjData* d = mj_makeData(m);
  if (s.top) {
    for (int a = 0; a < 3; ++a) d->qvel[3 + a] = (*s.top)[3 + a];
  }
  const int nb = s.rigid ? s.rigid->bodies : 1;
  // MuJoCo numbers bodies depth first; ours are looked up by name.
  std::vector<int> id(nb, 1);
  for (int b = 0; s.rigid && b < nb; ++b)
    id[b] = mj_name2id(m, mjOBJ_BODY, ("b" + std::to_string(b)).c_str());
  out.traj.times = times;
  mj_forward(m, d);
  for (double tf : times) {
    while (d->time < tf - 0.5 * h) {
      mj_step(m, d);
      ++out.steps;
      // An unstable step makes MuJoCo reset the state (and its clock) to the
      // start: report the failure rather than restart forever.
      if (d->warning[mjWARN_BADQACC].number > 0) {
        out.error = "MuJoCo reset the simulation at an unstable step (bad qacc)";
        mj_deleteData(d);
        mj_deleteModel(m);
        return out;
      }
    }
    std::vector<Pose> row(nb);
    for (int b = 0; b < nb; ++b) {
      for (int a = 0; a < 3; ++a) row[b].p[a] = d->xipos[3 * id[b] + a];
      for (int a = 0; a < 4; ++a) row[b].q[a] = d->xquat[4 * id[b] + a];
    }
    out.traj.poses.push_back(row);
  }
  out.cpu = ThreadCpuSeconds() - c0;
  out.rhs = out.steps * (rk4 ? 4 : 1);
  out.ok = true;
  mj_deleteData(d);
  mj_deleteModel(m);
  return out;
}

PeerRun RunEuler(const WpScene& s, double h, const std::vector<double>& t) {
  return Run(s, h, t, false);
}
PeerRun RunRk4(const WpScene& s, double h, const std::vector<double>& t) {
  return Run(s, h, t, true);
}

}  // namespace

void AddMujocoPeers(std::vector<EnginePeer>& out) {
  out.push_back({"mujoco_euler", Fits, RunEuler});
  out.push_back({"mujoco_rk4", Fits, RunRk4});
}

}  // namespace asgard::bench
