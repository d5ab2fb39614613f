// Analysis queries: variables used, time dependence, time breakpoints.
//
// Design.  DependsOnTime reads the per-node flags computed at intern time
// (O(1)).  Variables and TimeBreakpoints visit each reachable node once with
// an explicit stack.  Breakpoints come from operations whose value or slope
// jumps where an operand crosses a threshold; they are solved for only when
// that operand is an affine function a + b t of time (constants and t only —
// no Var, no Extern), which covers the scripted cases "t > 2", "floor(t/0.5)",
// "abs(t - 1)", "fmod(t, 0.25)".  Each reachable node contributes, by the
// Jump rule of its row in the operator table (ops.h):
//   comparisons, min, max   lhs - rhs = 0
//   sign, abs, !, &&, ||    operand = 0
//   Select                  condition = 0 (a comparison condition is handled
//                           as a comparison node of its own)
//   floor, ceil             operand = k for every integer k in range
//   fmod(p, q), q constant  p / |q| = k for every integer k in range
// At most kMaxBreakpoints times are produced; the result is sorted, unique and
// inside [t0, t1].
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "core/expr/expr.h"
#include "core/expr/internal.h"
#include "core/expr/ops.h"

namespace asgard::expr {
namespace {

constexpr size_t kMaxBreakpoints = 10000;

struct Affine {
  double a = 0.0;  // value at t = 0
  double b = 0.0;  // slope
};

// a + b t if `id` is affine in t; nullopt otherwise.  Canonical forms keep
// affine expressions shallow (sums of constant multiples of t), so the depth
// cap only guards against pathological inputs.
std::optional<Affine> AffineInTime(const Pool& pool, NodeId id, int depth = 0) {
  if (depth > 32) return std::nullopt;
  const Node& n = pool.node(id);
  switch (n.op) {
    case Op::kConst:
      return Affine{n.value, 0.0};
    case Op::kTime:
      return Affine{0.0, 1.0};
    case Op::kAdd: {
      Affine sum;
      for (NodeId arg : n.args) {
        auto term = AffineInTime(pool, arg, depth + 1);
        if (!term) return std::nullopt;
        sum.a += term->a;
        sum.b += term->b;
      }
      return sum;
    }
    case Op::kMul: {
      Affine prod{1.0, 0.0};
      for (NodeId arg : n.args) {
        auto f = AffineInTime(pool, arg, depth + 1);
        if (!f) return std::nullopt;
        if (prod.b != 0.0 && f->b != 0.0) return std::nullopt;  // quadratic
        prod = Affine{prod.a * f->a, prod.a * f->b + prod.b * f->a};
      }
      return prod;
    }
    default:
      return std::nullopt;
  }
}

class BreakpointCollector {
 public:
  BreakpointCollector(double t0, double t1) : t0_(t0), t1_(t1) {}

  bool full() const { return times_.size() >= kMaxBreakpoints; }

  // Time where f(t) = level.
  void Crossing(const Affine& f, double level) {
    if (f.b == 0.0 || full()) return;
    Add((level - f.a) / f.b);
  }

  // Times where f(t) passes an integer.
  void IntegerCrossings(const Affine& f) {
    if (f.b == 0.0 || !std::isfinite(f.a) || !std::isfinite(f.b)) return;
    const double v0 = f.a + f.b * t0_, v1 = f.a + f.b * t1_;
    const double lo = std::ceil(std::min(v0, v1)), hi = std::floor(std::max(v0, v1));
    if (!(lo <= hi)) return;
    for (double k = lo; k <= hi && !full(); k += 1.0) {
      Add((k - f.a) / f.b);
      if (k + 1.0 == k) break;  // beyond integer resolution
    }
  }

  std::vector<double> Take() {
    std::sort(times_.begin(), times_.end());
    times_.erase(std::unique(times_.begin(), times_.end()), times_.end());
    return std::move(times_);
  }

 private:
  void Add(double t) {
    if (std::isfinite(t) && t >= t0_ && t <= t1_) times_.push_back(t == 0.0 ? 0.0 : t);
  }

  double t0_, t1_;
  std::vector<double> times_;
};

std::optional<Affine> Difference(const Pool& pool, NodeId x, NodeId y) {
  auto fx = AffineInTime(pool, x), fy = AffineInTime(pool, y);
  if (!fx || !fy) return std::nullopt;
  return Affine{fx->a - fy->a, fx->b - fy->b};
}

}  // namespace

std::vector<int> Pool::Variables(NodeId e) const {
  return Variables(std::span<const NodeId>(&e, 1));
}

std::vector<int> Pool::Variables(std::span<const NodeId> roots) const {
  for (NodeId e : roots)
    if (e >= nodes_.size()) throw std::invalid_argument("expr::Pool::Variables: id out of range");
  std::vector<int> vars;
  struct SeenTag;
  internal::NodeScratch<SeenTag, char, 0> seen(nodes_.size());
  std::vector<NodeId> stack(roots.begin(), roots.end());
  while (!stack.empty()) {
    const NodeId id = stack.back();
    stack.pop_back();
    if ((impl_->flags[id] & kHasVar) == 0 || seen.get(id)) continue;
    seen.set(id, 1);
    const Node& n = nodes_[id];
    if (n.op == Op::kVar) vars.push_back(n.index);
    stack.insert(stack.end(), n.args.begin(), n.args.end());
  }
  std::sort(vars.begin(), vars.end());
  vars.erase(std::unique(vars.begin(), vars.end()), vars.end());
  return vars;
}

bool Pool::DependsOnTime(NodeId e) const {
  if (e >= nodes_.size()) throw std::invalid_argument("expr::Pool::DependsOnTime: id out of range");
  return (impl_->flags[e] & kHasTime) != 0;
}

std::vector<double> Pool::TimeBreakpoints(NodeId e, double t0, double t1) const {
  if (e >= nodes_.size())
    throw std::invalid_argument("expr::Pool::TimeBreakpoints: id out of range");
  if (!(t0 <= t1)) return {};
  BreakpointCollector out(t0, t1);
  std::unordered_set<NodeId> seen;
  std::vector<NodeId> stack{e};
  while (!stack.empty() && !out.full()) {
    const NodeId id = stack.back();
    stack.pop_back();
    if ((impl_->flags[id] & kHasTime) == 0 || !seen.insert(id).second) continue;
    const Node& n = nodes_[id];
    stack.insert(stack.end(), n.args.begin(), n.args.end());
    switch (Info(n.op).jump) {
      case Jump::kNone:
        break;
      case Jump::kDifference:
        if (auto d = Difference(*this, n.args[0], n.args[1])) out.Crossing(*d, 0.0);
        break;
      case Jump::kOperands:
        for (NodeId arg : n.args)
          if (auto f = AffineInTime(*this, arg)) out.Crossing(*f, 0.0);
        break;
      case Jump::kCondition:
        if (auto f = AffineInTime(*this, n.args[0])) out.Crossing(*f, 0.0);
        break;
      case Jump::kIntegers:
        if (auto f = AffineInTime(*this, n.args[0])) out.IntegerCrossings(*f);
        break;
      case Jump::kModulus: {
        auto q = ConstValue(n.args[1]);
        auto f = AffineInTime(*this, n.args[0]);
        if (q && f && *q != 0.0 && std::isfinite(*q)) {
          const double s = std::fabs(*q);
          out.IntegerCrossings(Affine{f->a / s, f->b / s});
        }
        break;
      }
    }
  }
  return out.Take();
}

}  // namespace asgard::expr
