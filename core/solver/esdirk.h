// The stiff path's method (component.h): a 4-stage ESDIRK of order 3 with an
// embedded formula of order 2 — explicit first stage (the sample's rate),
// three implicit stages that share the diagonal γ and so one iteration
// matrix I − γhJ, stiffly accurate (the last stage is the solution and its
// rate the new sample's), L-stable, stage order 2.  Stage i solves
//
//   z_i = x + h Σ_{j<i} a_ij k_j + γ h f(t + c_i h, z_i),   k_i = f(t + c_i h, z_i)
//
// and the error estimate is h Σ e_i k_i (e = b − b̂), filtered through
// (I − γhJ)⁻¹.  Its order conditions, stage order and stability are checked
// in tests/solver/esdirk_test.cc.
#pragma once

namespace asgard::solver {

struct Esdirk {
  double gamma;    // the diagonal a_ii, i ≥ 1
  double c[4];     // stage times
  double a[4][4];  // strictly lower part; row 3 is b
  double e[4];     // error weights b − b̂
};

// Derived by core/solver/derive_esdirk.py, which writes this table:
// γ the L-stability root of 6γ³ − 18γ² + 9γ − 1, c₃ = 3/5 (near the minimum
// of the 4th-order error coefficients), b̂ of order 2 with Σ b̂ c² = 1/3 + 1/20
// and bounded stability function (|R̂(∞)| = 0.30, A-stable).
inline constexpr Esdirk kEsdirk32 = {
    0.43586652150845900,
    {0.0, 0.87173304301691800, 0.60000000000000000, 1.0000000000000000},
    {{},
     {0.43586652150845900},
     {0.25764824606642725, -0.093514767574886245},
     {0.18764102434672383, -0.59529747357695495, 0.97178992772177212}},
    {-0.10908767092225170, -0.44334762941204642, 0.41488630558149510, 0.13754899475280302}};

}  // namespace asgard::solver
