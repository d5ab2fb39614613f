// Impulse response: conservation laws and analytic cases.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "tests/collide/shapes.h"

namespace asgard::collide {
namespace {

using testing::RandomRotation;

BodyState Body(double mass, const Eigen::Matrix3d& inertia, const Eigen::Vector3d& com,
               const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  BodyState b;
  b.inv_mass = 1.0 / mass;
  b.inv_inertia = inertia.inverse();
  b.com = com;
  b.v = v;
  b.w = w;
  return b;
}

BodyState Fixed() { return BodyState{}; }

Eigen::Matrix3d SphereInertia(double m, double r) {
  return 0.4 * m * r * r * Eigen::Matrix3d::Identity();
}

double Energy(const BodyState& b) {
  if (b.inv_mass == 0.0) return 0.0;
  return 0.5 * b.v.squaredNorm() / b.inv_mass + 0.5 * b.w.dot(b.inv_inertia.inverse() * b.w);
}

Eigen::Vector3d Momentum(const BodyState& b) { return b.v / b.inv_mass; }

Eigen::Vector3d AngularMomentum(const BodyState& b) {
  return b.com.cross(b.v / b.inv_mass) + b.inv_inertia.inverse() * b.w;
}

Eigen::Vector3d PointVelocity(const BodyState& b, const Eigen::Vector3d& x) {
  return b.v + b.w.cross(x - b.com);
}

void ExpectVector(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << " expected " << expected.transpose();
}

TEST(ApplyImpulse, HeadOnElasticCollisionOfOneAgainstThreeAtRest) {
  BodyState a = Body(1.0, SphereInertia(1, 1), {0, 0, 0}, {2, 0, 0}, {0, 0, 0});
  BodyState b = Body(3.0, SphereInertia(3, 1), {2, 0, 0}, {0, 0, 0}, {0, 0, 0});
  const double j = ApplyImpulse(a, b, {1, 0, 0}, {1, 0, 0}, 1.0, 0.0);
  EXPECT_NEAR(j, 3.0, 1e-15);
  ExpectVector(a.v, {-1, 0, 0}, 1e-15);
  ExpectVector(b.v, {1, 0, 0}, 1e-15);
  EXPECT_EQ(a.w, Eigen::Vector3d::Zero());
  EXPECT_EQ(b.w, Eigen::Vector3d::Zero());
}

TEST(ApplyImpulse, ObliqueEqualSpheresLeaveAtRightAngles) {
  const double angle = std::numbers::pi / 6;
  const Eigen::Vector3d n(std::cos(angle), std::sin(angle), 0);
  BodyState a = Body(1.0, SphereInertia(1, 1), {0, 0, 0}, {1, 0, 0}, {0, 0, 0});
  BodyState b = Body(1.0, SphereInertia(1, 1), 2.0 * n, {0, 0, 0}, {0, 0, 0});
  ApplyImpulse(a, b, n, n, 1.0, 0.0);
  const double vn = std::cos(angle);
  ExpectVector(b.v, vn * n, 1e-15);
  ExpectVector(a.v, Eigen::Vector3d(1, 0, 0) - vn * n, 1e-15);
  EXPECT_NEAR(a.v.dot(b.v), 0.0, 1e-15);
  EXPECT_LE(a.w.norm() + b.w.norm(), 1e-15);
}

TEST(ApplyImpulse, RandomPairsConserveEnergyAndMomentaAndReverseTheNormalVelocity) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto vec = [&] { return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)); };
  auto random_body = [&] {
    const double m = 0.5 + 4.5 * uniform(rng);
    const Eigen::Matrix3d Q = RandomRotation(rng);
    const Eigen::Vector3d d(0.2 + 1.8 * uniform(rng), 0.2 + 1.8 * uniform(rng),
                            0.2 + 1.8 * uniform(rng));
    return Body(m, Q * (m * d).asDiagonal() * Q.transpose(), vec(), vec(), vec());
  };
  for (int trial = 0; trial < 1000; ++trial) {
    for (const double e : {1.0, 0.5}) {
      BodyState a = random_body();
      BodyState b = random_body();
      const Eigen::Vector3d point = 0.5 * (a.com + b.com) + 0.3 * vec();
      Eigen::Vector3d n = vec().normalized();
      double un = n.dot(PointVelocity(b, point) - PointVelocity(a, point));
      if (un > 0.0) {
        n = -n;
        un = -un;
      }
      const double energy = Energy(a) + Energy(b);
      const Eigen::Vector3d p = Momentum(a) + Momentum(b);
      const Eigen::Vector3d l = AngularMomentum(a) + AngularMomentum(b);
      const double j = ApplyImpulse(a, b, point, n, e, 0.0);
      EXPECT_GT(j, 0.0);
      const double un_after = n.dot(PointVelocity(b, point) - PointVelocity(a, point));
      EXPECT_NEAR(un_after, -e * un, 1e-12 * std::abs(un) + 1e-14) << "trial " << trial;
      ExpectVector(Momentum(a) + Momentum(b), p, 1e-12 * (p.norm() + j));
      ExpectVector(AngularMomentum(a) + AngularMomentum(b), l, 1e-12 * (l.norm() + j));
      if (e == 1.0) {
        EXPECT_NEAR(Energy(a) + Energy(b), energy, 1e-12 * energy) << "trial " << trial;
      } else {
        EXPECT_LT(Energy(a) + Energy(b), energy);
      }
    }
  }
}

TEST(ApplyImpulse, CubeFallingCornerFirstOnAStaticFloorMatchesTheLinearConditions) {
  const double m = 2.0, side = 1.0;
  const Eigen::Matrix3d inertia = m * side * side / 6.0 * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 0.3, 0).normalized()) *
                            Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // The lowest corner touches the floor z = 0.
  Eigen::Vector3d lowest(0, 0, 1e300);
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c =
        R * Eigen::Vector3d((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
    if (c.z() < lowest.z()) lowest = c;
  }
  const Eigen::Vector3d com(1.0, -2.0, -lowest.z());
  const Eigen::Vector3d point = com + lowest;
  ASSERT_NEAR(point.z(), 0.0, 1e-15);
  const Eigen::Vector3d v0(0.3, -0.1, -2.0), w0(0.5, -0.2, 0.1);
  BodyState floor = Fixed();
  BodyState cube = Body(m, R * inertia * R.transpose(), com, v0, w0);
  const double energy = Energy(cube);
  const double j = ApplyImpulse(floor, cube, point, {0, 0, 1}, 1.0, 0.0);

  // Independent solution: 6 linear conditions on (v', ω').  No tangential
  // impulse (v'_x, v'_y unchanged); angular momentum about the contact point
  // unchanged (the impulse acts there); the normal contact velocity reverses.
  const Eigen::Vector3d r = point - com;
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> rhs;
  A(0, 0) = 1;
  A(1, 1) = 1;
  rhs(0) = v0.x();
  rhs(1) = v0.y();
  // L_c = m (com − point) × v + I ω.
  Eigen::Matrix3d cross_rc;
  const Eigen::Vector3d rc = com - point;
  cross_rc << 0, -rc.z(), rc.y(), rc.z(), 0, -rc.x(), -rc.y(), rc.x(), 0;
  const Eigen::Matrix3d I_world = R * inertia * R.transpose();
  A.block<3, 3>(2, 0) = m * cross_rc;
  A.block<3, 3>(2, 3) = I_world;
  rhs.segment<3>(2) = m * rc.cross(v0) + I_world * w0;
  // n·(v' + ω' × r) = −n·(v + ω × r);  n·(ω' × r) = ω'·(r × n).
  const Eigen::Vector3d n(0, 0, 1);
  A.block<1, 3>(5, 0) = n.transpose();
  A.block<1, 3>(5, 3) = r.cross(n).transpose();
  rhs(5) = -n.dot(v0 + w0.cross(r));
  const Eigen::Matrix<double, 6, 1> x = A.fullPivLu().solve(rhs);
  ExpectVector(cube.v, x.head<3>(), 1e-13);
  ExpectVector(cube.w, x.tail<3>(), 1e-13);
  EXPECT_NEAR(j, m * (x(2) - v0.z()), 1e-13);
  EXPECT_GT(cube.w.cross(Eigen::Vector3d::UnitZ()).norm(), 0.1);  // it spins
  EXPECT_NEAR(Energy(cube), energy, 1e-13 * energy);
  EXPECT_EQ(floor.v, Eigen::Vector3d::Zero());
  EXPECT_EQ(floor.w, Eigen::Vector3d::Zero());
}

TEST(ApplyImpulse, IdenticalAlignedCubesFaceToFaceSwapVelocitiesWithoutSpin) {
  const Eigen::Matrix3d inertia = 1.0 / 6.0 * Eigen::Matrix3d::Identity();
  BodyState a = Body(1.0, inertia, {0, 0, 0}, {1, 0.2, 0}, {0, 0, 0});
  BodyState b = Body(1.0, inertia, {1, 0, 0}, {-0.5, 0.2, 0}, {0, 0, 0});
  ApplyImpulse(a, b, {0.5, 0, 0}, {1, 0, 0}, 1.0, 0.0);
  ExpectVector(a.v, {-0.5, 0.2, 0}, 1e-15);
  ExpectVector(b.v, {1, 0.2, 0}, 1e-15);
  EXPECT_EQ(a.w, Eigen::Vector3d::Zero());
  EXPECT_EQ(b.w, Eigen::Vector3d::Zero());
}

TEST(ApplyImpulse, SeparatingOrDoublyInfiniteContactsChangeNothing) {
  BodyState a = Body(1.0, SphereInertia(1, 1), {0, 0, 0}, {-1, 0, 0}, {0, 0, 0});
  BodyState b = Body(1.0, SphereInertia(1, 1), {2, 0, 0}, {1, 0, 0}, {0, 0, 0});
  EXPECT_EQ(ApplyImpulse(a, b, {1, 0, 0}, {1, 0, 0}, 1.0, 0.5), 0.0);
  ExpectVector(a.v, {-1, 0, 0}, 0.0);
  BodyState f1 = Fixed(), f2 = Fixed();
  f1.v = {1, 0, 0};
  EXPECT_EQ(ApplyImpulse(f1, f2, {1, 0, 0}, {1, 0, 0}, 1.0, 0.5), 0.0);
  ExpectVector(f1.v, {1, 0, 0}, 0.0);
}

TEST(ApplyImpulse, SlidingSphereWithLargeFrictionSticksAndWithSmallFrictionSlides) {
  const double m = 1.0, radius = 0.5;
  const Eigen::Vector3d com(0, 0, radius), point(0, 0, 0), n(0, 0, 1);
  {
    BodyState floor = Fixed();
    BodyState ball = Body(m, SphereInertia(m, radius), com, {2, 0, -3}, {0, 0, 0});
    const double j = ApplyImpulse(floor, ball, point, n, 1.0, 10.0);
    const Eigen::Vector3d u = PointVelocity(ball, point);
    EXPECT_NEAR(u.x(), 0.0, 1e-14);
    EXPECT_NEAR(u.y(), 0.0, 1e-14);
    EXPECT_NEAR(u.z(), 3.0, 1e-14);
    EXPECT_NEAR(j, 6.0, 1e-14);
    // Rolling: ω_y = v_x / r; the tangential impulse is within the cone.
    EXPECT_NEAR(ball.w.y(), ball.v.x() / radius, 1e-14);
    EXPECT_LE(std::abs(m * (ball.v.x() - 2.0)), 10.0 * j);
  }
  {
    // Sticking would need |P_t| / P_n = (2 / 3.5) / 6 ≈ 0.095 > μ.
    const double mu = 0.05;
    BodyState floor = Fixed();
    BodyState ball = Body(m, SphereInertia(m, radius), com, {2, 0, -3}, {0, 0, 0});
    const double j = ApplyImpulse(floor, ball, point, n, 1.0, mu);
    EXPECT_NEAR(j, 6.0, 1e-14);
    EXPECT_NEAR(m * (ball.v.x() - 2.0), -mu * j, 1e-14);  // tangential impulse μ j
    EXPECT_NEAR(ball.v.z(), 3.0, 1e-14);
    EXPECT_GT(PointVelocity(ball, point).x(), 0.0);  // still sliding forward
  }
}

}  // namespace
}  // namespace asgard::collide
