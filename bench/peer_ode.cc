// ODE 0.16 (double precision) on the same scenes: planar pendulum chains and
// trees with hinge joints (dWorldStep, the direct LCP solver), the top as a free body
// (gyroscopic mode on).  Fixed steps.
#include <ode/ode.h>

#include <cmath>

#include "bench/peers.h"

namespace asgard::bench {

namespace {

bool Fits(const WpScene& s) { return s.rigid.has_value() || s.top.has_value(); }

struct OdeInit {
  OdeInit() { dInitODE2(0); }
  ~OdeInit() { dCloseODE(); }
};

PeerRun Run(const WpScene& s, double h, const std::vector<double>& times) {
  static OdeInit init;
  PeerRun out;
  const double c0 = ThreadCpuSeconds();
  dWorldID world = dWorldCreate();
  dWorldSetGravity(world, 0, s.rigid ? -s.rigid->g : 0.0, 0);
  std::vector<dBodyID> bodies;
  auto make = [&](double mass, double i1, double i2, double i3, double x, double y) {
    dBodyID b = dBodyCreate(world);
    dMass m;
    dMassSetParameters(&m, mass, 0, 0, 0, i1, i2, i3, 0, 0, 0);
    dBodySetMass(b, &m);
    dBodySetPosition(b, x, y, 0);
    dBodySetAutoDisableFlag(b, 0);
    bodies.push_back(b);
    return b;
  };
  if (s.rigid) {
    const RigidChain& c = *s.rigid;
    for (int i = 0; i < c.bodies; ++i) {
      const auto pv = c.Pivot0(i);
      const double ux = std::sin(c.theta0[i]), uy = -std::cos(c.theta0[i]);
      dBodyID b = make(c.mass[i], c.inertia[i], c.inertia[i], c.inertia[i], pv[0] + c.arm[i] * ux,
                       pv[1] + c.arm[i] * uy);
      dJointID j = dJointCreateHinge(world, nullptr);
      const int p = c.Parent(i);
      dJointAttach(j, b, p < 0 ? nullptr : bodies[p]);
      dJointSetHingeAnchor(j, pv[0], pv[1], 0);
      dJointSetHingeAxis(j, 0, 0, 1);
    }
  } else if (s.top) {
    const auto& t = *s.top;
    dBodyID b = make(1.0, t[0], t[1], t[2], 0, 0);
    dBodySetAngularVel(b, t[3], t[4], t[5]);
    dBodySetGyroscopicMode(b, 1);
  }
  out.traj.times = times;
  double t = times.front();
  for (double tf : times) {
    while (t < tf - 0.5 * h) {
      dWorldStep(world, h);
      t += h;
      ++out.steps;
    }
    std::vector<Pose> row;
    for (dBodyID b : bodies) {
      const dReal* p = dBodyGetPosition(b);
      const dReal* q = dBodyGetQuaternion(b);
      Pose pose;
      for (int a = 0; a < 3; ++a) pose.p[a] = p[a];
      for (int a = 0; a < 4; ++a) pose.q[a] = q[a];
      row.push_back(pose);
    }
    out.traj.poses.push_back(row);
  }
  dWorldDestroy(world);
  out.cpu = ThreadCpuSeconds() - c0;
  out.ok = true;
  return out;
}

}  // namespace

void AddOdePeers(std::vector<EnginePeer>& out) { out.push_back({"ode", Fits, Run}); }

}  // namespace asgard::bench
