// Bullet 3.24 (Debian's float64 build, BT_USE_DOUBLE_PRECISION) on the same
// scenes: rigid bodies joined by point-to-point constraints (sequential
// impulse solver, default 10 iterations), the top as a free body with the
// implicit gyroscopic term.  Fixed steps.

#include <cmath>
#include <memory>

#include "bench/bullet_world.h"
#include "bench/peers.h"

#ifndef BT_USE_DOUBLE_PRECISION
#error "the Bullet peer expects the double-precision (float64) build"
#endif

namespace asgard::bench {

namespace {

bool Fits(const WpScene& s) { return s.rigid.has_value() || s.top.has_value(); }

PeerRun Run(const WpScene& s, double h, const std::vector<double>& times) {
  PeerRun out;
  const double c0 = ThreadCpuSeconds();
  BulletWorld bullet;
  btDiscreteDynamicsWorld& world = bullet.world;
  world.setGravity(btVector3(0, s.rigid ? -s.rigid->g : 0.0, 0));
  btSphereShape shape(0.5);
  std::vector<std::unique_ptr<btDefaultMotionState>> states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::unique_ptr<btTypedConstraint>> joints;
  auto make = [&](double mass, const btVector3& inertia, const btVector3& pos) {
    btTransform tr;
    tr.setIdentity();
    tr.setOrigin(pos);
    states.push_back(std::make_unique<btDefaultMotionState>(tr));
    btRigidBody::btRigidBodyConstructionInfo info(mass, states.back().get(), &shape, inertia);
    bodies.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody* b = bodies.back().get();
    b->setActivationState(DISABLE_DEACTIVATION);
    b->setDamping(0, 0);
    world.addRigidBody(b, 0, 0);  // no collision group: never collides
    return b;
  };
  if (s.rigid) {
    const RigidChain& c = *s.rigid;
    for (int i = 0; i < c.bodies; ++i) {
      const auto pv = c.Pivot0(i);
      const btVector3 u(std::sin(c.theta0[i]), -std::cos(c.theta0[i]), 0);
      btRigidBody* b = make(c.mass[i], btVector3(c.inertia[i], c.inertia[i], c.inertia[i]),
                            btVector3(pv[0], pv[1], 0) + c.arm[i] * u);
      if (const int p = c.Parent(i); p < 0) {
        joints.push_back(std::make_unique<btPoint2PointConstraint>(*b, -c.arm[i] * u));
      } else {
        const btVector3 up(std::sin(c.theta0[p]), -std::cos(c.theta0[p]), 0);
        joints.push_back(std::make_unique<btPoint2PointConstraint>(
            *bodies[p], *b, (c.joint[p] - c.arm[p]) * up, -c.arm[i] * u));
      }
      world.addConstraint(joints.back().get(), true);
    }
  } else if (s.top) {
    const auto& t = *s.top;
    btRigidBody* b = make(1.0, btVector3(t[0], t[1], t[2]), btVector3(0, 0, 0));
    b->setAngularVelocity(btVector3(t[3], t[4], t[5]));
    b->setFlags(b->getFlags() | BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
  }
  out.traj.times = times;
  double t = times.front();
  for (double tf : times) {
    while (t < tf - 0.5 * h) {
      world.stepSimulation(h, 0);
      t += h;
      ++out.steps;
    }
    std::vector<Pose> row;
    for (const auto& b : bodies) {
      const btTransform& tr = b->getCenterOfMassTransform();
      const btQuaternion q = tr.getRotation();
      Pose p;
      for (int a = 0; a < 3; ++a) p.p[a] = tr.getOrigin()[a];
      p.q[0] = q.getW(), p.q[1] = q.getX(), p.q[2] = q.getY(), p.q[3] = q.getZ();
      row.push_back(p);
    }
    out.traj.poses.push_back(row);
  }
  for (auto& j : joints) world.removeConstraint(j.get());
  for (auto& b : bodies) world.removeRigidBody(b.get());
  out.cpu = ThreadCpuSeconds() - c0;
  out.ok = true;
  return out;
}

}  // namespace

void AddBulletPeers(std::vector<EnginePeer>& out) { out.push_back({"bullet", Fits, Run}); }

}  // namespace asgard::bench
