// Bullet (double precision) on the contact suite's scenes: the same bodies
// as Asgard's scene text, boxes and spheres with Bullet's default collision
// margins, a static floor or six static walls, restitution and friction as
// in the scene (Bullet multiplies the bodies' coefficients, as Asgard does
// for restitution), fixed steps h without substeps, sleeping on.

#include <memory>

#include "bench/bullet_world.h"
#include "bench/contact.h"
#include "bench/harness.h"

namespace asgard::bench {

ContactResult RunBulletContact(const ContactScene& s, double h) {
  ContactResult out;
  const double c0 = ThreadCpuSeconds();
  BulletWorld bullet;
  btDiscreteDynamicsWorld& world = bullet.world;
  world.setGravity(btVector3(0, -s.gravity, 0));
  btBoxShape cube(btVector3(0.5, 0.5, 0.5));
  btSphereShape ball(0.2);
  std::vector<std::unique_ptr<btCollisionShape>> wall_shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  auto add = [&](btCollisionShape* shape, double mass, const btTransform& x) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    states.push_back(std::make_unique<btDefaultMotionState>(x));
    btRigidBody::btRigidBodyConstructionInfo info(mass, states.back().get(), shape, inertia);
    info.m_restitution = s.restitution;
    info.m_friction = s.friction;
    bodies.push_back(std::make_unique<btRigidBody>(info));
    world.addRigidBody(bodies.back().get());
    return bodies.back().get();
  };
  if (s.box) {
    const double w = s.box_half + 0.5, l = s.box_half + 1;
    for (int k = 0; k < 6; ++k) {
      btVector3 half(l, l, l), p(0, 0, 0);
      half[k / 2] = 0.5;
      p[k / 2] = k % 2 ? w : -w;
      wall_shapes.push_back(std::make_unique<btBoxShape>(half));
      btTransform x;
      x.setIdentity();
      x.setOrigin(p);
      add(wall_shapes.back().get(), 0.0, x);
    }
  } else {
    wall_shapes.push_back(std::make_unique<btBoxShape>(btVector3(30, 0.5, 30)));
    btTransform x;
    x.setIdentity();
    x.setOrigin(btVector3(0, -0.5, 0));
    add(wall_shapes.back().get(), 0.0, x);
  }
  std::vector<btRigidBody*> moving;
  for (const ContactBody& b : s.bodies) {
    btTransform x;
    x.setIdentity();
    x.setOrigin(btVector3(b.p.x(), b.p.y(), b.p.z()));
    const double angle = b.rot.norm();
    if (angle > 0) {
      const Eigen::Vector3d axis = b.rot / angle;
      x.setRotation(btQuaternion(btVector3(axis.x(), axis.y(), axis.z()), angle));
    }
    btRigidBody* body = add(b.cube ? static_cast<btCollisionShape*>(&cube) : &ball, 1.0, x);
    body->setLinearVelocity(btVector3(b.v.x(), b.v.y(), b.v.z()));
    body->setDamping(0, 0);
    moving.push_back(body);
  }
  auto energy = [&]() {
    double e = 0;
    for (size_t i = 0; i < moving.size(); ++i) {
      const btRigidBody* b = moving[i];
      const btVector3 w = b->getAngularVelocity();
      const btVector3 I = b->getLocalInertia();
      const btVector3 wl = w * b->getWorldTransform().getBasis();  // body frame
      e += 0.5 * b->getLinearVelocity().length2() +
           0.5 * (I.x() * wl.x() * wl.x() + I.y() * wl.y() * wl.y() + I.z() * wl.z() * wl.z());
    }
    return e;
  };
  const double e0 = energy();
  const double measuring = StepAndMeasure(
      s, h,
      [&] {
        world.stepSimulation(h, 0, h);
        return true;
      },
      [&](size_t i, Eigen::Vector3d& p, Eigen::Quaterniond& q) {
        const btTransform& x = moving[i]->getWorldTransform();
        const btQuaternion r = x.getRotation();
        p = {x.getOrigin().x(), x.getOrigin().y(), x.getOrigin().z()};
        q = Eigen::Quaterniond(r.w(), r.x(), r.y(), r.z());
      },
      out);
  out.final_kinetic = energy();
  out.energy_drift = std::abs(out.final_kinetic - e0) / std::max(e0, 1e-300);
  out.cpu = ThreadCpuSeconds() - c0 - measuring;
  for (auto& b : bodies) world.removeRigidBody(b.get());
  return out;
}

}  // namespace asgard::bench
