// Contact manifolds, MPR penetration and the simultaneous contact solve.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/collide/shapes.h"

namespace asgard::collide {
namespace {

using testing::Box;

Pose At(const Eigen::Vector3d& p, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Pose pose;
  pose.p = p;
  pose.R = R;
  return pose;
}

std::vector<ContactPoint> ManifoldOf(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb,
                                     double margin) {
  const DistanceResult d = Distance(a, pa, b, pb);
  return Manifold(a, pa, b, pb, d, d.distance, margin);
}

TEST(Manifold, ACubeFlatOnAFloorTouchesAtItsFourCorners) {
  const Piece floor = Box({10, 0.5, 10}), cube = Box({0.5, 0.5, 0.5});
  const double gap = 1e-4;
  const auto points = ManifoldOf(floor, At({0, -0.5, 0}), cube, At({0.2, 0.5 + gap, -0.1}), 1e-2);
  ASSERT_EQ(points.size(), 4u);
  for (const auto& p : points) {
    EXPECT_NEAR(p.gap, gap, 1e-12);
    EXPECT_NEAR((p.normal - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(p.point.x() - 0.2), 0.5, 1e-12);
    EXPECT_NEAR(std::abs(p.point.z() + 0.1), 0.5, 1e-12);
    EXPECT_NEAR(p.point.y(), 0.5 * gap, 1e-12);  // midway between the surfaces
  }
}

TEST(Manifold, ACubeOnAnEdgeTouchesAtTheEdgesTwoEnds) {
  // Turned 0.3 about z: its lowest edge runs along z; the other bottom
  // corners are sin(0.3) higher, far above the margin.
  const Piece floor = Box({10, 0.5, 10}), cube = Box({0.5, 0.5, 0.5});
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double low = 0.5 * (std::cos(0.3) + std::sin(0.3));  // centre above the edge
  const double gap = 1e-5;
  const auto points = ManifoldOf(cube, At({0, low + gap, 0}, R), floor, At({0, -0.5, 0}), 1e-2);
  ASSERT_EQ(points.size(), 2u);
  for (const auto& p : points) {
    EXPECT_NEAR(p.gap, gap, 1e-12);
    // From the cube (a) to the floor (b): down.
    EXPECT_NEAR((p.normal + Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(p.point.z()), 0.5, 1e-12);
  }
}

TEST(Manifold, SpheresGiveTheirSingleClosestPoint) {
  const Piece ball = Piece::Sphere(Eigen::Vector3d::Zero(), 0.5), cube = Box({0.5, 0.5, 0.5});
  const auto points = ManifoldOf(cube, At({0, 0, 0}), ball, At({0, 1.1, 0}), 1e-2);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].gap, 0.1, 1e-12);
  EXPECT_NEAR(points[0].point.y(), 0.55, 1e-12);
}

TEST(PenetrationMpr, OverlappingCubesGiveDepthAndDirectionThatSeparateThem) {
  const Piece cube = Box({0.5, 0.5, 0.5});
  const Pose pa = At({0, 0, 0}), pb = At({0.9, 0.2, 0.1});
  const auto pen = PenetrationMpr(cube, pa, cube, pb);
  ASSERT_TRUE(pen.has_value());
  // Least overlap is along x: 1 − 0.9.
  EXPECT_NEAR(pen->depth, 0.1, 1e-9);
  EXPECT_NEAR((pen->normal - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-9);
  // Moved by depth × normal (and a hair more) they no longer overlap.
  const Pose moved = At(pb.p + (pen->depth + 1e-9) * pen->normal);
  EXPECT_FALSE(Distance(cube, pa, cube, moved).overlapping);
  EXPECT_FALSE(PenetrationMpr(cube, pa, cube, At({1.2, 0, 0})).has_value());
}

BodyState CubeState(const Eigen::Vector3d& v) {
  BodyState s;
  s.inv_mass = 1.0;
  s.inv_inertia = 6.0 * Eigen::Matrix3d::Identity();  // unit cube, unit mass: I = 1/6
  s.com = Eigen::Vector3d(0, 0.5, 0);
  s.v = v;
  return s;
}

std::vector<SolverContact> Corners(double mu, double target) {
  std::vector<SolverContact> out;
  for (double x : {-0.5, 0.5})
    for (double z : {-0.5, 0.5}) {
      SolverContact c;
      c.a = -1;  // the world
      c.b = 0;
      c.point = {x, 0, z};
      c.normal = Eigen::Vector3d::UnitY();
      c.friction = mu;
      c.target = target;
      out.push_back(c);
    }
  return out;
}

TEST(SolveContacts, ABoxLandingFlatStopsWithoutSpinAndTheImpulsesAddUpToItsMomentum) {
  std::vector<BodyState> bodies = {CubeState({0, -2, 0})};
  auto contacts = Corners(0.0, 0.0);
  SolveContacts(bodies, contacts, 500, 1e-14);
  EXPECT_NEAR(bodies[0].v.norm(), 0.0, 1e-10);
  EXPECT_NEAR(bodies[0].w.norm(), 0.0, 1e-10);
  double total = 0;
  for (const auto& c : contacts) {
    EXPECT_GE(c.normal_impulse, 0.0);
    total += c.normal_impulse;
  }
  EXPECT_NEAR(total, 2.0, 1e-10);
}

// A box landing flat on its four corners while sliding and spinning: the
// cold solve's impulses, given back as the warm start of the same problem,
// are its fixed point — one sweep finds nothing to change and the bodies
// end where the cold solve left them.
TEST(SolveContacts, StartedFromItsSolutionItStopsAfterOneSweepWithTheSameResult) {
  const Eigen::Vector3d v0(0.3, -2, 0.1);
  std::vector<BodyState> cold = {CubeState(v0)};
  cold[0].w = {0.5, 0.0, -0.2};
  auto contacts = Corners(0.5, 0.0);
  const int cold_sweeps = SolveContacts(cold, contacts, 2000, 1e-13);
  EXPECT_GT(cold_sweeps, 1);
  std::vector<BodyState> warm = {CubeState(v0)};
  warm[0].w = {0.5, 0.0, -0.2};
  auto again = Corners(0.5, 0.0);
  for (size_t i = 0; i < again.size(); ++i) {
    again[i].warm_normal = contacts[i].normal_impulse;
    again[i].warm_tangent = contacts[i].tangent_impulse;
  }
  EXPECT_EQ(SolveContacts(warm, again, 2000, 1e-12), 1);
  // The cold solve stopped within 1e-13 per impulse; the velocities differ
  // by at most that many impulses over the unit mass and 1/6 inertia.
  EXPECT_NEAR((warm[0].v - cold[0].v).norm(), 0.0, 1e-11);
  EXPECT_NEAR((warm[0].w - cold[0].w).norm(), 0.0, 1e-10);
  for (size_t i = 0; i < again.size(); ++i)
    EXPECT_NEAR(again[i].normal_impulse, contacts[i].normal_impulse, 1e-12);
}

// A guess that is too large is given back: the accumulated impulse is
// clamped, not the increment, so the warm start changes the path only.
TEST(SolveContacts, AnOversizedWarmStartStillEndsAtTheSolution) {
  std::vector<BodyState> bodies = {CubeState({0, -2, 0})};
  auto contacts = Corners(0.0, 0.0);
  for (auto& c : contacts) c.warm_normal = 3.0;  // six times the share of each corner
  SolveContacts(bodies, contacts, 2000, 1e-14);
  EXPECT_NEAR(bodies[0].v.norm(), 0.0, 1e-10);
  EXPECT_NEAR(bodies[0].w.norm(), 0.0, 1e-10);
  double total = 0;
  for (const auto& c : contacts) total += c.normal_impulse;
  EXPECT_NEAR(total, 2.0, 1e-10);
}

TEST(SolveContacts, FrictionSticksInsideTheConeAndStaysWithinItWhenSliding) {
  // Landing at −1 along y while sliding at 0.3 along x: the normal impulse
  // is about 1 (m Δv_n), so μ = 0.5 can take away up to 0.5 of the sliding
  // speed (it stops), μ = 0.1 at most 0.1 (it keeps sliding).
  for (double mu : {0.5, 0.1}) {
    std::vector<BodyState> bodies = {CubeState({0.3, -1, 0})};
    auto contacts = Corners(mu, 0.0);
    SolveContacts(bodies, contacts, 2000, 1e-15);
    // No contact point approaches any more.
    for (const auto& c : contacts) {
      const Eigen::Vector3d u = bodies[0].v + bodies[0].w.cross(c.point - bodies[0].com);
      EXPECT_GT(u.y(), -1e-9) << mu;
    }
    const Eigen::Vector3d slip = bodies[0].v + bodies[0].w.cross(Eigen::Vector3d(0, -0.5, 0));
    double total = 0;
    for (const auto& c : contacts) total += c.normal_impulse;
    // Coulomb: the tangential impulse never exceeds μ times the normal one.
    EXPECT_LE(0.3 - bodies[0].v.x(), mu * total + 1e-12) << mu;
    if (mu == 0.5) {
      EXPECT_NEAR(slip.x(), 0.0, 1e-9);
    } else {
      // Still sliding: kinetic friction at every point opposes the slip,
      // so it takes exactly μ Σλ_n off the sliding speed (to the solver's
      // tolerance) and pushes nothing sideways.  (Projecting the corner's
      // anisotropic sticking impulse K_t⁻¹ u_t onto the disc instead took
      // 6% less and pushed each corner 20° off the slip.)
      EXPECT_GT(slip.x(), 0.1);
      EXPECT_NEAR(0.3 - bodies[0].v.x(), mu * total, 1e-12);
      EXPECT_NEAR(bodies[0].v.z(), 0.0, 1e-12);
    }
  }
}

// A leaning column of unit cubes, each `lean` to the side of the one below,
// all falling at 0.1 m/s onto a floor, with friction: the exact solve stops
// every cube (each face's four corners push, at most three of them
// independently), and the impulse through the face below cube k carries
// the momentum of the cubes on it.  Gauss–Seidel's error here falls by a
// factor near 1 per sweep (the column's rocking mode): the direct step
// behind the sweeps solves it in a few.
void ExpectALeaningColumnSolvedExactly(int cubes, double lean) {
  std::vector<BodyState> bodies;
  std::vector<SolverContact> contacts;
  std::vector<int> below;  // per contact: the cube above its face
  for (int k = 0; k < cubes; ++k) {
    BodyState s = CubeState({0, -0.1, 0});
    s.com = {lean * k, 0.5 + k, 0};
    bodies.push_back(s);
    const double lo = k == 0 ? -0.5 : lean * k - 0.5, hi = k == 0 ? 0.5 : lean * (k - 1) + 0.5;
    for (double x : {lo, hi})
      for (double z : {-0.5, 0.5}) {
        SolverContact c;
        c.a = k - 1;  // −1: the floor
        c.b = k;
        c.point = {x, double(k), z};
        c.normal = Eigen::Vector3d::UnitY();
        c.friction = 0.5;
        contacts.push_back(c);
        below.push_back(k);
      }
  }
  const int sweeps = SolveContacts(bodies, contacts, 200, 1e-12);
  EXPECT_LT(sweeps, 60);
  for (const BodyState& s : bodies) {
    EXPECT_NEAR(s.v.norm(), 0.0, 1e-10);
    EXPECT_NEAR(s.w.norm(), 0.0, 1e-10);
  }
  std::vector<double> through(size_t(cubes), 0.0);
  for (size_t i = 0; i < contacts.size(); ++i) {
    EXPECT_GE(contacts[i].normal_impulse, 0.0);
    EXPECT_LE(contacts[i].tangent_impulse.norm(),
              contacts[i].friction * contacts[i].normal_impulse + 1e-12);
    through[size_t(below[i])] += contacts[i].normal_impulse;
  }
  for (int k = 0; k < cubes; ++k)
    EXPECT_NEAR(through[size_t(k)], 0.1 * (cubes - k), 1e-10 * cubes) << k;
}

// Six cubes 0.12 apart: a dense Newton step.
TEST(SolveContacts, ALeaningColumnIsSolvedExactlyInAFewSweeps) {
  ExpectALeaningColumnSolvedExactly(6, 0.12);
}

// Thirty cubes 0.02 apart (the centre of mass above every face stays on
// it): 120 points, 360 impulses, solved by the sparse Newton step (the
// quadratic program the step replaced stopped at 150 unknowns and left
// such an island to the sweeps).
TEST(SolveContacts, ALeaningColumnOfThirtyIsSolvedExactlyInAFewSweeps) {
  ExpectALeaningColumnSolvedExactly(30, 0.02);
}

}  // namespace
}  // namespace asgard::collide
