// Shared helpers for the expression tests: a name resolver, an independent
// recursive reference interpreter, and a random expression generator.
#pragma once

#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "core/expr/expr.h"

namespace asgard::expr::testing {

// x, y, z -> Var(0..2); b1.x, b1.y -> Var(3), Var(4); tr1.dy -> Var(5);
// g -> 9.81; x<i> -> Var(i) (ToString's default naming); ext<fn> and
// ext<fn>.d<k> -> Extern(fn, k) (ToString's naming of externals).
inline std::optional<NodeId> TestResolver(std::string_view name, Pool& pool) {
  if (name == "x") return pool.Var(0);
  if (name == "y") return pool.Var(1);
  if (name == "z") return pool.Var(2);
  if (name == "b1.x") return pool.Var(3);
  if (name == "b1.y") return pool.Var(4);
  if (name == "tr1.dy") return pool.Var(5);
  if (name == "g") return pool.Const(9.81);
  auto digits = [](std::string_view s) -> std::optional<int> {
    if (s.empty() || s.size() > 6) return std::nullopt;
    int v = 0;
    for (char c : s) {
      if (c < '0' || c > '9') return std::nullopt;
      v = v * 10 + (c - '0');
    }
    return v;
  };
  if (name.size() > 1 && name[0] == 'x') {
    if (auto i = digits(name.substr(1))) return pool.Var(*i);
  }
  if (name.substr(0, 3) == "ext") {
    std::string_view rest = name.substr(3);
    const size_t dot = rest.find(".d");
    auto fn = digits(rest.substr(0, dot));
    std::optional<int> order = 0;
    if (dot != std::string_view::npos) order = digits(rest.substr(dot + 2));
    if (fn && order) return pool.Extern(*fn, *order);
  }
  return std::nullopt;
}

inline NodeId P(Pool& pool, std::string_view text) { return Parse(text, pool, TestResolver); }

// External test functions: ext fn = sin((fn + 1) t), derivatives exact.
inline double TestExtern(int fn, int order, double t) {
  const double w = fn + 1.0;
  const double phase = order * std::numbers::pi / 2;
  return std::pow(w, order) * std::sin(w * t + phase);
}

// Reference semantics written independently of the library: sums and
// products accumulate left to right in operand order.
class Interpreter {
 public:
  Interpreter(const Pool& pool, double t, const std::vector<double>& x)
      : pool_(pool), t_(t), x_(x) {}

  double Eval(NodeId id) const {
    const Node& n = pool_.node(id);
    auto arg = [&](size_t i) { return Eval(n.args[i]); };
    switch (n.op) {
      case Op::kConst:
        return n.value;
      case Op::kTime:
        return t_;
      case Op::kVar:
        return x_[n.index];
      case Op::kExtern:
        return TestExtern(n.index, n.order, t_);
      case Op::kAdd: {
        double s = arg(0);
        for (size_t i = 1; i < n.args.size(); ++i) s += arg(i);
        return s;
      }
      case Op::kMul: {
        double p = arg(0);
        for (size_t i = 1; i < n.args.size(); ++i) p *= arg(i);
        return p;
      }
      case Op::kPow: {
        const double a = arg(0), b = arg(1);
        if (b == 2.0) return a * a;
        if (b == -1.0) return 1.0 / a;
        return std::pow(a, b);
      }
      case Op::kSin:
        return std::sin(arg(0));
      case Op::kCos:
        return std::cos(arg(0));
      case Op::kTan:
        return std::tan(arg(0));
      case Op::kAsin:
        return std::asin(arg(0));
      case Op::kAcos:
        return std::acos(arg(0));
      case Op::kAtan:
        return std::atan(arg(0));
      case Op::kSinh:
        return std::sinh(arg(0));
      case Op::kCosh:
        return std::cosh(arg(0));
      case Op::kTanh:
        return std::tanh(arg(0));
      case Op::kExp:
        return std::exp(arg(0));
      case Op::kLog:
        return std::log(arg(0));
      case Op::kSqrt:
        return std::sqrt(arg(0));
      case Op::kAbs:
        return std::fabs(arg(0));
      case Op::kFloor:
        return std::floor(arg(0));
      case Op::kCeil:
        return std::ceil(arg(0));
      case Op::kSign: {
        const double a = arg(0);
        return a > 0 ? 1.0 : a < 0 ? -1.0 : a;
      }
      case Op::kAtan2:
        return std::atan2(arg(0), arg(1));
      case Op::kMin: {
        const double a = arg(0), b = arg(1);
        return b < a ? b : a;
      }
      case Op::kMax: {
        const double a = arg(0), b = arg(1);
        return a < b ? b : a;
      }
      case Op::kFmod:
        return std::fmod(arg(0), arg(1));
      case Op::kHypot:
        return std::hypot(arg(0), arg(1));
      case Op::kLt:
        return arg(0) < arg(1) ? 1.0 : 0.0;
      case Op::kLe:
        return arg(0) <= arg(1) ? 1.0 : 0.0;
      case Op::kGt:
        return arg(0) > arg(1) ? 1.0 : 0.0;
      case Op::kGe:
        return arg(0) >= arg(1) ? 1.0 : 0.0;
      case Op::kEq:
        return arg(0) == arg(1) ? 1.0 : 0.0;
      case Op::kNe:
        return arg(0) != arg(1) ? 1.0 : 0.0;
      case Op::kAnd: {
        const double a = arg(0), b = arg(1);
        return a != 0.0 && b != 0.0 ? 1.0 : 0.0;
      }
      case Op::kOr: {
        const double a = arg(0), b = arg(1);
        return a != 0.0 || b != 0.0 ? 1.0 : 0.0;
      }
      case Op::kNot:
        return arg(0) == 0.0 ? 1.0 : 0.0;
      case Op::kSelect:
        return arg(0) != 0.0 ? arg(1) : arg(2);
    }
    return std::nan("");
  }

 private:
  const Pool& pool_;
  double t_;
  const std::vector<double>& x_;
};

// Evaluates `e` through a freshly compiled tape.
inline double EvalTape(const Pool& pool, NodeId e, double t, const std::vector<double>& x) {
  const NodeId outs[1] = {e};
  Tape tape = Tape::Compile(pool, outs);
  ExternFn ext = TestExtern;
  double out = 0.0;
  tape.Evaluate(t, x.data(), &out, &ext);
  return out;
}

// Random expressions over Var(0..nvars-1), t, small constants and Extern(0..1).
class RandomExpr {
 public:
  RandomExpr(Pool& pool, uint32_t seed, int nvars = 4) : pool_(pool), rng_(seed), nvars_(nvars) {}

  NodeId Make(int depth) {
    if (depth <= 0 || Uniform(0, 9) < 2) return Leaf();
    const int kind = Uniform(0, 10);
    if (kind <= 3) {  // arithmetic
      const NodeId a = Make(depth - 1), b = Make(depth - 1);
      switch (Uniform(0, 4)) {
        case 0:
          return pool_.Add(a, b);
        case 1:
          return pool_.Sub(a, b);
        case 2:
          return pool_.Mul(a, b);
        case 3:
          return pool_.Div(a, b);
        default:
          return pool_.Pow(a, pool_.Const(Uniform(-2, 3)));
      }
    }
    if (kind <= 6) {
      static constexpr Op kUnary[] = {Op::kSin,  Op::kCos,  Op::kTan,  Op::kAsin,  Op::kAcos,
                                      Op::kAtan, Op::kSinh, Op::kCosh, Op::kTanh,  Op::kExp,
                                      Op::kLog,  Op::kSqrt, Op::kAbs,  Op::kFloor, Op::kCeil,
                                      Op::kSign, Op::kNot};
      const NodeId a = Make(depth - 1);
      const NodeId args[1] = {a};
      return pool_.Apply(kUnary[Uniform(0, std::size(kUnary) - 1)], args);
    }
    if (kind <= 9) {
      static constexpr Op kBinary[] = {Op::kAtan2, Op::kMin, Op::kMax, Op::kFmod, Op::kHypot,
                                       Op::kLt,    Op::kLe,  Op::kGt,  Op::kGe,   Op::kEq,
                                       Op::kNe,    Op::kAnd, Op::kOr,  Op::kPow};
      const NodeId a = Make(depth - 1), b = Make(depth - 1);
      const NodeId args[2] = {a, b};
      return pool_.Apply(kBinary[Uniform(0, std::size(kBinary) - 1)], args);
    }
    const NodeId c = Make(depth - 1), a = Make(depth - 1), b = Make(depth - 1);
    return pool_.Select(c, a, b);
  }

  NodeId Leaf() {
    switch (Uniform(0, 5)) {
      case 0:
      case 1:
        return pool_.Var(Uniform(0, nvars_ - 1));
      case 2:
        return pool_.Time();
      case 3:
        return pool_.Extern(Uniform(0, 1), Uniform(0, 2));
      default:
        return pool_.Const(Uniform(-4, 4) * 0.5);
    }
  }

  int Uniform(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  double Real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  std::mt19937& rng() { return rng_; }

 private:
  Pool& pool_;
  std::mt19937 rng_;
  int nvars_;
};

// Bitwise equality that treats all NaNs as equal.
inline bool SameDouble(double a, double b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace asgard::expr::testing
