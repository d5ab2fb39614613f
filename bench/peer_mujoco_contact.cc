// MuJoCo on the contact suite's scenes: the same bodies as Asgard's scene
// text, boxes and spheres of mass 1 on free joints, a static floor or six
// static walls as box geoms, fixed steps h with MuJoCo's defaults otherwise
// (Euler integrator, pyramidal cones, Newton solver; no sleeping — MuJoCo
// has none).  MuJoCo's contacts are soft: a contact is a damped spring in
// acceleration units (solref), with no coefficient of restitution.  The
// piles keep MuJoCo's default, critically damped (solref 0.02 1: no
// bounce); the damping ratio whose free bounce gives their e = 0.5
// (ζ = −ln e / √(π² + ln² e) ≈ 0.215) made the pile of 100 blow up (final
// kinetic energy 5.7e4).  The balls' e = 1 is an undamped contact (solref
// −10⁴ 0: stiffness 10⁴ s⁻², about 15 steps per contact at h = 1/240).
// Friction μ on every geom (MuJoCo takes the larger of two).
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "bench/contact.h"
#include "bench/harness.h"

namespace asgard::bench {

namespace {

std::string ContactXml(const ContactScene& s, double h) {
  std::ostringstream x;
  x.precision(17);
  const bool elastic = s.restitution >= 1.0;
  // Constraint rows (4 per contact, pyramidal): up to 8 contacts per cube
  // in a pile, about one per ball in the box.  MuJoCo 2.2 allocates
  // njmax² doubles, so the bound is kept near what the scene uses; a full
  // buffer fails the run.
  size_t cubes = 0;
  for (const ContactBody& b : s.bodies) cubes += b.cube;
  const size_t rows = 32 * cubes + 4 * (s.bodies.size() - cubes) + 400;
  x << "<mujoco><option timestep=\"" << h << "\" gravity=\"0 " << -s.gravity << " 0\"/>"
    << "<default><geom friction=\"" << s.friction << " 0.005 0.0001\" solref=\""
    << (elastic ? "-10000 0" : "0.02 1") << "\"/></default>"
    << "<size nconmax=\"" << rows / 4 + 100 << "\" njmax=\"" << rows << "\"/><worldbody>";
  if (s.box) {
    const double w = s.box_half + 0.5, l = s.box_half + 1;
    for (int k = 0; k < 6; ++k) {
      double half[3] = {l, l, l}, p[3] = {0, 0, 0};
      half[k / 2] = 0.5;
      p[k / 2] = k % 2 ? w : -w;
      x << "<geom type=\"box\" size=\"" << half[0] << " " << half[1] << " " << half[2]
        << "\" pos=\"" << p[0] << " " << p[1] << " " << p[2] << "\"/>";
    }
  } else {
    x << "<geom type=\"box\" size=\"30 0.5 30\" pos=\"0 -0.5 0\"/>";
  }
  for (const ContactBody& b : s.bodies) {
    const double angle = b.rot.norm();
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    if (angle > 0) q = Eigen::AngleAxisd(angle, b.rot / angle);
    x << "<body pos=\"" << b.p.x() << " " << b.p.y() << " " << b.p.z() << "\" quat=\"" << q.w()
      << " " << q.x() << " " << q.y() << " " << q.z() << "\"><freejoint/>";
    if (b.cube)
      x << "<geom type=\"box\" size=\"0.5 0.5 0.5\" mass=\"1\"/>";
    else
      x << "<geom type=\"sphere\" size=\"" << b.radius << "\" mass=\"1\"/>";
    x << "</body>";
  }
  x << "</worldbody></mujoco>";
  return x.str();
}

}  // namespace

ContactResult RunMujocoContact(const ContactScene& s, double h) {
  ContactResult out;
  const std::string path = "/tmp/asgard_bench_mujoco_contact_" + std::to_string(getpid()) + ".xml";
  {
    std::ofstream f(path);
    f << ContactXml(s, h);
  }
  char err[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, err, sizeof err);
  unlink(path.c_str());
  if (!m) {
    out.status = "failed";
    out.error = std::string("mj_loadXML: ") + err;
    return out;
  }
  const double c0 = ThreadCpuSeconds();
  mjData* d = mj_makeData(m);
  const int n = static_cast<int>(s.bodies.size());
  // Body b + 1 is the scene's body b (the world is body 0); its free joint's
  // velocities are qvel[6b .. 6b + 5]: linear in the world frame, angular in
  // the body's.
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < 3; ++a) d->qvel[6 * b + a] = s.bodies[size_t(b)].v[a];
  mj_forward(m, d);
  auto energy = [&]() {
    double e = 0.0;
    for (int b = 0; b < n; ++b) {
      const double* v = d->qvel + 6 * b;
      const double* inertia = m->body_inertia + 3 * (b + 1);
      e += 0.5 * m->body_mass[b + 1] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
           0.5 * (inertia[0] * v[3] * v[3] + inertia[1] * v[4] * v[4] + inertia[2] * v[5] * v[5]);
    }
    return e;
  };
  const double e0 = energy();
  const double measuring = StepAndMeasure(
      s, h,
      [&] {
        mj_step(m, d);
        if (d->warning[mjWARN_BADQACC].number == 0) return true;
        out.status = "failed";
        out.error = "MuJoCo reset the simulation at an unstable step (bad qacc)";
        return false;
      },
      [&](size_t b, Eigen::Vector3d& p, Eigen::Quaterniond& q) {
        const double* x = d->xpos + 3 * (b + 1);
        const double* r = d->xquat + 4 * (b + 1);
        p = {x[0], x[1], x[2]};
        q = Eigen::Quaterniond(r[0], r[1], r[2], r[3]);
      },
      out);
  if (d->warning[mjWARN_CONTACTFULL].number > 0 || d->warning[mjWARN_CNSTRFULL].number > 0) {
    out.status = "failed";
    out.error = "MuJoCo's contact or constraint buffer filled";
  }
  out.final_kinetic = energy();
  out.energy_drift = std::abs(out.final_kinetic - e0) / std::max(e0, 1e-300);
  out.cpu = ThreadCpuSeconds() - c0 - measuring;
  mj_deleteData(d);
  mj_deleteModel(m);
  return out;
}

}  // namespace asgard::bench
