// Contact scenes of the benchmark suite (issue 14): the bodies of each scene
// as plain data, so that Asgard (through its scene text) and the Bullet peer
// (through its API) run exactly the same bodies.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

namespace asgard::bench {

struct ContactBody {
  bool cube = true;  // unit cube (side 1), else a ball of radius `radius`
  double radius = 0.5;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d rot = Eigen::Vector3d::Zero();  // rotation vector
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
};

struct ContactScene {
  std::string name;
  std::vector<ContactBody> bodies;
  double t1 = 5.0;
  double gravity = 9.81;     // along −y
  double restitution = 0.5;  // of every body (and walls)
  double friction = 0.5;
  bool box =
      false;  // a closed box of six walls (interior half-size box_half); else a floor at y = 0
  double box_half = 5.0;
};

// What a run measured.  Penetrations are of the floor or walls only (the
// deepest vertex or ball surface beyond them at any 30 Hz frame).
struct ContactResult {
  std::string status = "ok";  // ok, failed, timeout, crash, skipped
  std::string error;
  double cpu = 0.0;
  double max_penetration = 0.0;
  double final_kinetic = 0.0;  // total kinetic energy at t1
  double energy_drift = 0.0;   // |E(t1) − E(0)| / E(0) (balls in a box, restitution 1)
  double impacts = 0.0, windows = 0.0, broad_pairs = 0.0, narrow_queries = 0.0,
         distance_queries = 0.0;
};

// Deepest penetration of the scene's floor (y = 0) or box walls by one body
// at position p, orientation q (0 when clear).
double FloorOrWallPenetration(const ContactScene& s, const ContactBody& shape,
                              const Eigen::Vector3d& p, const Eigen::Quaterniond& q);

// A fixed-step peer's run: t1/h steps of `step` (false: the run failed,
// stop), and at every 30 Hz frame and the last step each body's pose
// (`pose(i, p, q)`) measured for penetration into out.max_penetration.
// Returns the CPU seconds the measuring took, which the peer leaves out of
// its time.
double StepAndMeasure(
    const ContactScene& s, double h, const std::function<bool()>& step,
    const std::function<void(size_t, Eigen::Vector3d&, Eigen::Quaterniond&)>& pose,
    ContactResult& out);

#ifdef ASGARD_BENCH_BULLET
// Bullet in double precision at fixed steps h (no substeps); its default
// sequential-impulse solver and sleeping.
ContactResult RunBulletContact(const ContactScene& scene, double h);
#endif

#ifdef ASGARD_BENCH_MUJOCO
// MuJoCo at fixed steps h: soft contacts, restitution as a damping ratio
// (peer_mujoco_contact.cc), no sleeping.
ContactResult RunMujocoContact(const ContactScene& scene, double h);
#endif

}  // namespace asgard::bench
