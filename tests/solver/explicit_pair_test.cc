// Order conditions of the explicit pairs (core/solver/explicit_pair.h),
// checked on rooted trees (Butcher): for every tree t of up to p nodes,
// Σ_i w_i Φ_i(t) = 1/γ(t), with Φ_i(t) = Π over t's subtrees s of
// Σ_j a_ij Φ_j(s).  Tolerances: the sums are evaluated in doubles from
// 17-digit coefficients, so each may be off by a few ulps of Σ |w_i Φ_i(t)|
// (the absolute sum, which is up to ~20 for Tsitouras' large coefficients);
// we allow 64 ulps of it.  A wrong digit in a table moves a sum by far more.
#include "core/solver/explicit_pair.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace asgard::solver {
namespace {

// A rooted tree as the list of its root's subtrees.
struct Tree {
  std::vector<Tree> kids;
  int Order() const {
    int n = 1;
    for (const Tree& k : kids) n += k.Order();
    return n;
  }
  double Gamma() const {
    double g = Order();
    for (const Tree& k : kids) g *= k.Gamma();
    return g;
  }
};

// All trees with n nodes: a root over a multiset of subtrees whose orders sum
// to n − 1 (each multiset once: subtrees in non-increasing (order, index)).
std::vector<Tree> Trees(int n);

void Multisets(int left, int max_order, int max_index, std::vector<Tree>& kids,
               std::vector<Tree>& out) {
  if (left == 0) {
    out.push_back(Tree{kids});
    return;
  }
  for (int o = std::min(left, max_order); o >= 1; --o) {
    const std::vector<Tree> ts = Trees(o);
    const int top = o == max_order ? max_index : static_cast<int>(ts.size()) - 1;
    for (int i = top; i >= 0; --i) {
      kids.push_back(ts[i]);
      Multisets(left - o, o, i, kids, out);
      kids.pop_back();
    }
  }
}

std::vector<Tree> Trees(int n) {
  std::vector<Tree> out;
  if (n == 1) return {Tree{}};
  std::vector<Tree> kids;
  Multisets(n - 1, n - 1, static_cast<int>(Trees(n - 1).size()) - 1, kids, out);
  return out;
}

// Φ_i(t) for every stage i.
std::vector<double> Phi(const ExplicitPair& p, const Tree& t) {
  std::vector<double> v(7, 1.0);
  for (const Tree& k : t.kids) {
    const std::vector<double> w = Phi(p, k);
    for (int i = 0; i < 7; ++i) {
      double s = 0.0;
      for (int j = 0; j < i; ++j) s += p.a[i][j] * w[j];
      v[i] *= s;
    }
  }
  return v;
}

struct Sum {
  double value, scale;
};
Sum Weighted(const std::vector<double>& w, const std::vector<double>& phi) {
  Sum s{0.0, 0.0};
  for (int i = 0; i < 7; ++i) {
    s.value += w[i] * phi[i];
    s.scale += std::abs(w[i] * phi[i]);
  }
  return s;
}

constexpr double kUlps = 64 * std::numeric_limits<double>::epsilon();

void CheckPair(const ExplicitPair& p) {
  std::vector<double> b(p.a[6], p.a[6] + 7), bhat(7), d(p.d, p.d + 7);
  for (int i = 0; i < 7; ++i) bhat[i] = b[i] - p.e[i];
  EXPECT_EQ(b[6], 0.0);
  EXPECT_EQ(p.c[5], 1.0);
  EXPECT_EQ(p.c[6], 1.0);
  // Rows sum to c.
  for (int i = 1; i < 7; ++i) {
    double s = 0.0, scale = 0.0;
    for (int j = 0; j < i; ++j) s += p.a[i][j], scale += std::abs(p.a[i][j]);
    EXPECT_NEAR(s, p.c[i], kUlps * scale) << "row " << i;
  }
  const int counts[] = {0, 1, 1, 2, 4, 9};
  double embedded_order5 = 0.0;  // the embedded formula's largest order-5 defect
  for (int n = 1; n <= 5; ++n) {
    const std::vector<Tree> ts = Trees(n);
    ASSERT_EQ(static_cast<int>(ts.size()), counts[n]);
    for (const Tree& t : ts) {
      const std::vector<double> phi = Phi(p, t);
      const double exact = 1.0 / t.Gamma();
      const Sum s5 = Weighted(b, phi);
      EXPECT_NEAR(s5.value, exact, kUlps * s5.scale) << "order 5, tree of " << n << " nodes";
      const Sum s4 = Weighted(bhat, phi);
      if (n <= 4)
        EXPECT_NEAR(s4.value, exact, kUlps * s4.scale) << "embedded, tree of " << n << " nodes";
      else
        embedded_order5 = std::max(embedded_order5, std::abs(s4.value - exact));
      // Continuous extension: Σ d_i Φ_i(t) = 0 up to 3 nodes, 1/γ(t) for 4
      // (the Hermite cubic carries orders ≤ 3; θ⁴ − its cubic is θ²(1−θ)²).
      if (n <= 4) {
        const Sum sd = Weighted(d, phi);
        EXPECT_NEAR(sd.value, n == 4 ? exact : 0.0, kUlps * sd.scale)
            << "dense output, tree of " << n << " nodes";
      }
    }
  }
  // The embedded formula is of order 4, not 5: the estimate is not zero.
  EXPECT_GT(embedded_order5, 1e-5);
}

TEST(ExplicitPair, TreeCountsAreThoseOfButcher) {
  // 1, 1, 2, 4, 9, 20 rooted trees with 1 … 6 nodes.
  const int counts[] = {1, 1, 2, 4, 9, 20};
  for (int n = 1; n <= 6; ++n) EXPECT_EQ(static_cast<int>(Trees(n).size()), counts[n - 1]);
}

TEST(ExplicitPair, DormandPrinceMeetsItsOrderConditions) { CheckPair(kDormandPrince); }

TEST(ExplicitPair, TsitourasMeetsItsOrderConditions) { CheckPair(kTsitouras); }

TEST(ExplicitPair, TsitourasHasSmallerErrorConstantsThanDormandPrince) {
  // The reason for the pair: its 6th-order defects (the leading error of the
  // 5th-order solution) are smaller.
  auto norm6 = [](const ExplicitPair& p) {
    std::vector<double> b(p.a[6], p.a[6] + 7);
    double s = 0.0;
    for (const Tree& t : Trees(6)) {
      const double r = Weighted(b, Phi(p, t)).value - 1.0 / t.Gamma();
      s += r * r;
    }
    return std::sqrt(s);
  };
  EXPECT_LT(norm6(kTsitouras), norm6(kDormandPrince));
}

}  // namespace
}  // namespace asgard::solver
