// Reference problems shared by the solver tests and the benchmarks: each is a
// scene script with a known solution (closed form or a classical formula).
#pragma once

#include <cmath>
#include <string>

#include "core/pipeline/pipeline.h"

namespace asgard::testing {

// A sphere of radius 0.5 named `name` with the given initial state.
inline std::string Ball(const std::string& name, const std::string& pos,
                        const std::string& vel = "0 0 0", const std::string& extra = "") {
  return "body " + name + " -shape ball -init_pos {" + pos + "} -init_dpos {" + vel + "} " +
         extra + "\n";
}

inline const char* kBallShape = "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n";

// Projectile: x = x0 + v0 t, y = y0 + v0 t − g t²/2.
inline std::string Projectile(double finish = 10.0) {
  return std::string(kBallShape) + Ball("p", "0 0 0", "3 20 -1") +
         "force -body p -x 0 -y -9.81 -z 0 -gravitational 1\n"
         "simulator -finish " + std::to_string(finish) + "\n";
}

// Undamped harmonic oscillator along x: m ẍ = −k x, x(0) = 1.
inline std::string Oscillator(double k, double mass, double finish) {
  return std::string(kBallShape) + Ball("o", "1 0 0", "0 0 0", "-mass " + std::to_string(mass)) +
         "force -body o -x {-" + std::to_string(k) + " * o.x} -y 0 -z 0\n"
         "simulator -finish " + std::to_string(finish) + "\n";
}

// Critically damped link to the origin: x(t) = (x0 + (v0 + ω x0) t) e^{−ωt}.
inline std::string DampedLink(double k, double mass, double x0, double finish) {
  return std::string(kBallShape) +
         Ball("d", std::to_string(x0) + " 0 0", "0 0 0", "-mass " + std::to_string(mass)) +
         "link -body1 d -offset1 {0 0 0} -x 0 -y 0 -z 0 -tightness " + std::to_string(k) + "\n"
         "simulator -finish " + std::to_string(finish) + "\n";
}
inline double DampedLinkExact(double k, double mass, double x0, double t) {
  const double w = std::sqrt(k / mass);
  return (x0 + w * x0 * t) * std::exp(-w * t);
}

// Pendulum: a ball (radius 0.5, mass 1, I_cm = 0.1) whose point at distance
// L from its centre is linked to the origin — links have zero rest length, so
// the link is a stiff ball joint (seed 5.1.2) and the ball swings as a
// physical pendulum, released at angle θ0 from the vertical.  k = 0: the
// link is an exact joint (no -tightness).
inline std::string Pendulum(double length, double theta0, double g, double k, double finish) {
  const double sx = std::sin(theta0), cy = std::cos(theta0);
  return std::string(kBallShape) + "body m -shape ball -mass 1 -init_pos {" +
         std::to_string(length * sx) + " " + std::to_string(-length * cy) + " 0}\n" +
         "link -body1 m -offset1 {" + std::to_string(-length * sx) + " " +
         std::to_string(length * cy) + " 0} -x 0 -y 0 -z 0" +
         (k > 0 ? " -tightness " + std::to_string(k) : std::string()) + "\n" +
         "force -body m -x 0 -y -" + std::to_string(g) + " -z 0 -gravitational 1\n" +
         "simulator -finish " + std::to_string(finish) + "\n";
}
// Period of that physical pendulum: 4 √(L_eq/g) K(sin(θ0/2)) with the
// equivalent length L_eq = (I_cm + m L²) / (m L).
inline double PendulumPeriod(double length, double theta0, double g, double i_cm = 0.1) {
  const double l_eq = (i_cm + length * length) / length;
  return 4.0 * std::sqrt(l_eq / g) * std::comp_ellint_1(std::sin(theta0 / 2));
}

// Torque-free rigid body with principal moments I1 < I2 < I3 (given with
// -moment), spinning mostly about the intermediate axis.
inline std::string Top(double i1, double i2, double i3, const std::string& omega,
                       double finish) {
  return std::string(kBallShape) + "body top -shape ball -mass 1 -moment {" +
         std::to_string(i1) + " " + std::to_string(i2) + " " + std::to_string(i3) +
         "} -init_drot {" + omega + "}\nsimulator -finish " + std::to_string(finish) + "\n";
}

// Period of the body-frame angular velocity of a torque-free top
// (Landau & Lifshitz §37): T = 4 K(k) / λ.
inline double TopPeriod(double I1, double I2, double I3, double w1, double w2, double w3) {
  const double E2 = I1 * w1 * w1 + I2 * w2 * w2 + I3 * w3 * w3;  // 2E
  const double M2 = I1 * I1 * w1 * w1 + I2 * I2 * w2 * w2 + I3 * I3 * w3 * w3;
  if (M2 < E2 * I2) std::swap(I1, I3);  // motion about the axis of I1: swap roles
  const double lambda = std::sqrt((I3 - I2) * (M2 - E2 * I1) / (I1 * I2 * I3));
  const double k2 = (I2 - I1) * (E2 * I3 - M2) / ((I3 - I2) * (M2 - E2 * I1));
  return 4.0 * std::comp_ellint_1(std::sqrt(k2)) / lambda;
}

// The scene of seed 5.2.4 / Figure 5.11: two pendulums (balls of mass 1 on
// stiff ball joints 3 below their pivots at x = ±3) and a free ball of mass 1
// between them, thrown at the right one at speed 2, no gravity on it.  Equal
// masses swap velocities: the ball stops at the right bob (t ≈ 1), the bob
// swings out and back and sends the ball left (t ≈ 2.75), the ball stops at
// the left bob (t ≈ 4.75).  So by t = 5.5 the ball has hit the right
// pendulum twice and the left one once.  `idle` more balls rest far away
// (z = 10, spaced 2 apart along x): they never take part.
inline std::string SeedFigure511(int idle, double finish = 5.5) {
  std::string s = kBallShape;
  for (const char* side : {"left", "right"}) {
    const double x = side[0] == 'l' ? -3.0 : 3.0;
    s += std::string("body ") + side + " -shape ball -mass 1 -init_pos {" + std::to_string(x) +
         " 0 0}\n" + "link -body1 " + side + " -offset1 {0 3 0} -x " + std::to_string(x) +
         " -y 3 -z 0 -tightness 1e5\n" + "force -body " + side +
         " -x 0 -y -9.81 -z 0 -gravitational 1\n";
  }
  s += "body ball -shape ball -mass 1 -init_pos {0 0 0} -init_dpos {2 0 0}\n";
  for (int i = 0; i < idle; ++i)
    s += "body idle" + std::to_string(i) + " -shape ball -init_pos {" + std::to_string(2.0 * i) +
         " 0 10}\n";
  s += "simulator -finish " + std::to_string(finish) + "\n";
  return s;
}

}  // namespace asgard::testing
