// Physics: the equations formed from scenes — mass properties, off-centre
// forces and torques, links, decoupling, and errors.
#include <gtest/gtest.h>

#include "core/lang/lang.h"
#include "core/pipeline/pipeline.h"

namespace asgard::physics {
namespace {

EquationSystem Form(const std::string& text) {
  const scene::Scene s = lang::Evaluate(text);
  for (const auto& d : s.diagnostics) ADD_FAILURE() << d.span.line << ": " << d.message;
  return FormEquations(s);
}

// Evaluates every right-hand side at the initial state.
std::vector<double> InitialRates(const EquationSystem& eq) {
  std::vector<double> x(eq.variables.size()), out(eq.variables.size());
  std::vector<expr::NodeId> rhs;
  for (size_t i = 0; i < eq.variables.size(); ++i) {
    x[i] = eq.variables[i].initial;
    rhs.push_back(eq.variables[i].rhs);
  }
  const auto tape = expr::Tape::Compile(eq.pool, rhs);
  const auto ext = eq.externs();
  tape.Evaluate(eq.t0, x.data(), out.data(), &ext);
  return out;
}

const char* kBox =
    "shape_set box -desc {-sub {-pos {0 0 0} -box {2 4 6}}}\n";  // 2 × 4 × 6

TEST(MassProperties, UnitDensityUnlessGivenAndInertiaScalesWithMass) {
  const auto eq = Form(std::string(kBox) + "body a -shape box\nbody b -shape box -mass 3\n");
  ASSERT_TRUE(eq.diagnostics.empty());
  EXPECT_NEAR(eq.bodies[0].mass, 48.0, 1e-12);
  EXPECT_NEAR(eq.bodies[0].inertia(0, 0), 48.0 * (16 + 36) / 12, 1e-9);
  EXPECT_NEAR(eq.bodies[1].mass, 3.0, 1e-12);
  EXPECT_NEAR(eq.bodies[1].inertia(2, 2), 3.0 * (4 + 16) / 12, 1e-12);
  EXPECT_EQ(eq.bodies[1].inertia(0, 1), 0.0);  // round-off cleaned: axes stay decoupled
}

TEST(MassProperties, InitPosPlacesTheShapeOriginAndStateTracksTheCentreOfMass) {
  // A box whose centroid is at (1, 0, 0) in shape coordinates, rotated 90° about z.
  const auto eq = Form(
      "shape_set s -desc {-sub {-pos {1 0 0} -box {1 1 1}}}\n"
      "body b -shape s -init_pos {5 0 0} -init_rot {0 0 1.5707963267948966}\n");
  const auto& v = eq.variables;
  EXPECT_NEAR(v[kX].initial, 5.0, 1e-12);
  EXPECT_NEAR(v[kY].initial, 1.0, 1e-12);
}

TEST(Equations, AFreeSphereHasNoGyroscopicCoupling) {
  const auto eq = Form(
      "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 1}}\n"
      "body s -shape ball -init_drot {1 2 3}\n");
  for (int a = 0; a < 3; ++a) {
    const auto c = eq.pool.ConstValue(eq.variables[kW1 + a].rhs);
    ASSERT_TRUE(c.has_value()) << eq.pool.ToString(eq.variables[kW1 + a].rhs);
    EXPECT_EQ(*c, 0.0);
  }
}

TEST(Equations, AnAsymmetricBodyHasTheEulerGyroscopicTerm) {
  const auto eq = Form(std::string(kBox) + "body b -shape box -mass 1 -init_drot {1 2 3}\n");
  const auto f = InitialRates(eq);
  const Eigen::Matrix3d I = eq.bodies[0].inertia;
  const Eigen::Vector3d w(1, 2, 3);
  const Eigen::Vector3d expected = -I.inverse() * w.cross(I * w);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(f[kW1 + a], expected[a], 1e-12);
}

TEST(Equations, AnOffCentreForceAddsATorque) {
  const auto eq = Form(std::string(kBox) +
                       "body b -shape box -mass 2\n"
                       "force -body b -x 0 -y 10 -z 0 -offset {1 0 0}\n");
  const auto f = InitialRates(eq);
  EXPECT_NEAR(f[kDy], 5.0, 1e-12);
  // τ = r × F = (1,0,0) × (0,10,0) = (0,0,10); ω̇_z = τ / I_zz.
  EXPECT_NEAR(f[kW3], 10.0 / eq.bodies[0].inertia(2, 2), 1e-12);
  EXPECT_NEAR(f[kW1], 0.0, 1e-15);
}

TEST(Equations, ATorqueAboutAnOffCentreAxisAddsAForce) {
  const auto eq = Form(std::string(kBox) +
                       "body b -shape box -mass 2\n"
                       "torque -body b -x 0 -y 0 -z 4 -offset {0 1 0}\n");
  const auto f = InitialRates(eq);
  // F = d × T = (0,1,0) × (0,0,4) = (4,0,0) (seed 5.1.1).
  EXPECT_NEAR(f[kDx], 2.0, 1e-12);
  EXPECT_NEAR(f[kW3], 4.0 / eq.bodies[0].inertia(2, 2), 1e-12);
}

TEST(Equations, ALinkIsACriticallyDampedSpringWithTheReducedMass) {
  const auto eq = Form(std::string(kBox) +
                       "body a -shape box -mass 1 -init_pos {0 0 0}\n"
                       "body b -shape box -mass 3 -init_pos {2 0 0} -init_dpos {1 0 0}\n"
                       "link -body1 a -body2 b -tightness 100\n");
  const auto f = InitialRates(eq);
  const double k = 100, mu = 0.75, c = 2 * std::sqrt(k * mu);
  // x = p_a − p_b = (−2, 0, 0), ẋ = (−1, 0, 0): F_a = −k x − c ẋ.
  const double Fa = 2 * k + c;
  EXPECT_NEAR(f[kDx], Fa / 1.0, 1e-9);
  EXPECT_NEAR(f[kBodySlots + kDx], -Fa / 3.0, 1e-9);
}

TEST(Equations, ExpressionsReadOtherBodiesAndTime) {
  const auto eq = Form(std::string(kBox) +
                       "body a -shape box -mass 2 -init_pos {1 2 3}\n"
                       "body b -shape box -mass 1 -init_pos {0 0 0}\n"
                       "force -body b -x {a.x * a.mass + sin(t)} -y {b.y} -z {a.z - b.z}\n");
  const auto f = InitialRates(eq);
  EXPECT_NEAR(f[kBodySlots + kDx], 2.0, 1e-12);
  EXPECT_NEAR(f[kBodySlots + kDz], 3.0, 1e-12);
  const auto vars = eq.pool.Variables(eq.variables[kBodySlots + kDx].rhs);
  EXPECT_EQ(vars, std::vector<int>{kX});
}

TEST(Errors, UnknownNamesInExpressionsAreReportedWithTheirLine) {
  const scene::Scene s = lang::Evaluate(std::string(kBox) +
                                        "body b -shape box\n"
                                        "force -body b -x 0 -y {-10 * b9.mass} -z 0\n");
  const auto eq = FormEquations(s);
  ASSERT_EQ(eq.diagnostics.size(), 1u);
  EXPECT_EQ(eq.diagnostics[0].span.line, 3);
  EXPECT_NE(eq.diagnostics[0].message.find("b9.mass"), std::string::npos)
      << eq.diagnostics[0].message;
}

TEST(Errors, ADegenerateHullIsReportedAtItsShapeSet) {
  const scene::Scene s = lang::Evaluate(
      "\nshape_set flat -desc {-sub {-vertices {{0 0 0} {1 0 0} {0 1 0} {1 1 0}}}}\n"
      "body b -shape flat\n");
  const auto eq = FormEquations(s);
  ASSERT_FALSE(eq.diagnostics.empty());
  EXPECT_EQ(eq.diagnostics[0].span.line, 2);
  EXPECT_NE(eq.diagnostics[0].message.find("coplanar"), std::string::npos)
      << eq.diagnostics[0].message;
  EXPECT_TRUE(eq.bodies.empty());
}

TEST(Errors, ABadExpressionDropsOnlyItsElement) {
  const scene::Scene s = lang::Evaluate(std::string(kBox) +
                                        "body b -shape box\n"
                                        "force -body b -x {1 +} -y 0 -z 0\n"
                                        "force -body b -x 0 -y 1 -z 0\n");
  const auto eq = FormEquations(s);
  ASSERT_EQ(eq.diagnostics.size(), 1u);
  const auto f = InitialRates(eq);
  EXPECT_NEAR(f[kDy], 1.0 / 48.0, 1e-12);
  EXPECT_EQ(f[kDx], 0.0);
}

}  // namespace
}  // namespace asgard::physics
