// Symbolic differentiation and substitution.
//
// Design.  Both walk the DAG bottom-up with the iterative PostOrder of
// internal.h and rebuild through the simplifying constructors, so results are
// canonical and shared with everything else in the pool.  Derivatives are
// cached per (node, variable) in Pool::Impl::derivs for the pool's lifetime
// (the pool is append-only, so cached ids stay valid); subtrees without the
// variable (per-node flags) are 0 without any work.  The time derivative is the
// same walk with different leaf rules: d/dt t = 1, d/dt Var = 0,
// d/dt Extern(fn, d) = Extern(fn, d + 1).
//
// Conventions for non-smooth operations: the piecewise-constant operations of
// the operator table (comparisons, logic, floor, ceil, sign) have derivative 0; abs' = sign(x) x';
// min and max select the derivative of the chosen operand with the same comparison the evaluation
// uses; Select(c, a, b)' = Select(c, a', b'); fmod(a, b)' = a' - b' trunc(a/b).
#include <array>
#include <stdexcept>

#include "core/expr/expr.h"
#include "core/expr/internal.h"
#include "core/expr/ops.h"

namespace asgard::expr {
namespace {

uint64_t DerivKey(NodeId id, int var_index) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(var_index + 1)) << 32) | id;
}

}  // namespace

NodeId Pool::Derivative(NodeId e, int var_index) {
  if (var_index < 0) throw std::invalid_argument("expr::Pool::Derivative: negative variable");
  if (e >= nodes_.size()) throw std::invalid_argument("expr::Pool::Derivative: id out of range");
  return DerivativeImpl(e, var_index);
}

NodeId Pool::TimeDerivative(NodeId e) {
  if (e >= nodes_.size())
    throw std::invalid_argument("expr::Pool::TimeDerivative: id out of range");
  return DerivativeImpl(e, -1);
}

NodeId Pool::DerivativeImpl(NodeId e, int var_index) {
  const uint8_t mask = var_index < 0 ? kHasTime : kHasVar;
  auto zero_by_flags = [&](NodeId id) { return (impl_->flags[id] & mask) == 0; };
  auto done = [&](NodeId id) {
    return zero_by_flags(id) || impl_->derivs.count(DerivKey(id, var_index)) != 0;
  };
  std::vector<NodeId> dargs;
  internal::PostOrder(*this, e, done, [&](NodeId id) {
    const std::vector<NodeId> args = nodes_[id].args;
    dargs.clear();
    for (NodeId a : args)
      dargs.push_back(zero_by_flags(a) ? Const(0.0) : impl_->derivs.at(DerivKey(a, var_index)));
    const NodeId d = DerivativeStep(id, var_index, dargs);
    impl_->derivs.emplace(DerivKey(id, var_index), d);
  });
  if (zero_by_flags(e)) return Const(0.0);
  return impl_->derivs.at(DerivKey(e, var_index));
}

NodeId Pool::DerivativeStep(NodeId e, int var_index, std::span<const NodeId> dargs) {
  const Node n = nodes_[e];  // copy: the pool grows below
  const NodeId zero = Const(0.0);
  const NodeId one = Const(1.0);
  auto fn = [&](Op op, NodeId x) { return Apply(op, std::array<NodeId, 1>{x}); };
  auto fn2 = [&](Op op, NodeId x, NodeId y) { return Apply(op, std::array<NodeId, 2>{x, y}); };
  auto square = [&](NodeId x) { return Pow(x, Const(2.0)); };

  switch (n.op) {
    case Op::kConst:
      return zero;
    case Op::kTime:
      return var_index < 0 ? one : zero;
    case Op::kVar:
      return var_index >= 0 && n.index == var_index ? one : zero;
    case Op::kExtern:
      return var_index < 0 ? Extern(n.index, n.order + 1) : zero;
    case Op::kAdd:
      return Sum(dargs);
    case Op::kMul: {
      std::vector<NodeId> terms;
      std::vector<NodeId> factors;
      for (size_t i = 0; i < n.args.size(); ++i) {
        if (dargs[i] == zero) continue;
        factors = n.args;
        factors[i] = dargs[i];
        terms.push_back(Product(factors));
      }
      return Sum(terms);
    }
    default:
      break;
  }

  if (Info(n.op).Has(kPiecewiseConstant)) return zero;  // comparisons, logic, floor ...

  // Functions: a (and b) are the operands, da (and db) their derivatives.
  const NodeId a = n.args[0];
  const NodeId da = dargs[0];
  const NodeId b = n.args.size() > 1 ? n.args[1] : zero;
  const NodeId db = n.args.size() > 1 ? dargs[1] : zero;
  switch (n.op) {
    case Op::kPow: {
      if (auto k = ConstValue(b)) {
        const NodeId factors[3] = {Const(*k), Pow(a, Const(*k - 1.0)), da};
        return Product(factors);
      }
      const NodeId log_a = fn(Op::kLog, a);
      if (da == zero) {
        const NodeId factors[3] = {e, log_a, db};
        return Product(factors);
      }
      // (a^b)' = a^b (b' ln a + b a' / a)
      return Mul(e, Add(Mul(db, log_a), Div(Mul(b, da), a)));
    }
    case Op::kSin:
      return Mul(fn(Op::kCos, a), da);
    case Op::kCos:
      return Neg(Mul(fn(Op::kSin, a), da));
    case Op::kTan:
      return Mul(da, Pow(fn(Op::kCos, a), Const(-2.0)));
    case Op::kAsin:
      return Div(da, fn(Op::kSqrt, Sub(one, square(a))));
    case Op::kAcos:
      return Neg(Div(da, fn(Op::kSqrt, Sub(one, square(a)))));
    case Op::kAtan:
      return Div(da, Add(one, square(a)));
    case Op::kSinh:
      return Mul(fn(Op::kCosh, a), da);
    case Op::kCosh:
      return Mul(fn(Op::kSinh, a), da);
    case Op::kTanh:
      return Mul(da, Sub(one, square(e)));
    case Op::kExp:
      return Mul(e, da);
    case Op::kLog:
      return Div(da, a);
    case Op::kSqrt:
      return Div(da, Mul(Const(2.0), e));
    case Op::kAbs:
      return Mul(fn(Op::kSign, a), da);
    case Op::kAtan2:  // atan2(a, b) = atan(a / b): (b a' - a b') / (a^2 + b^2)
      return Div(Sub(Mul(b, da), Mul(a, db)), Add(square(a), square(b)));
    case Op::kMin:  // min(a, b) = b < a ? b : a
      return Select(fn2(Op::kLt, b, a), db, da);
    case Op::kMax:  // max(a, b) = a < b ? b : a
      return Select(fn2(Op::kLt, a, b), db, da);
    case Op::kFmod: {
      if (db == zero) return da;
      const NodeId q = Div(a, b);
      const NodeId trunc = Select(fn2(Op::kGe, q, zero), fn(Op::kFloor, q), fn(Op::kCeil, q));
      return Sub(da, Mul(db, trunc));
    }
    case Op::kHypot:
      return Div(Add(Mul(a, da), Mul(b, db)), e);
    case Op::kSelect:
      return Select(a, dargs[1], dargs[2]);
    default:
      break;
  }
  throw std::logic_error("expr::Pool::Derivative: unhandled op");
}

NodeId Pool::Substitute(NodeId e, const std::function<std::optional<NodeId>(int)>& replacement) {
  if (e >= nodes_.size()) throw std::invalid_argument("expr::Pool::Substitute: id out of range");
  std::unordered_map<NodeId, NodeId> memo;
  auto unchanged = [&](NodeId id) { return (impl_->flags[id] & kHasVar) == 0; };
  auto mapped = [&](NodeId id) { return unchanged(id) ? id : memo.at(id); };
  internal::PostOrder(
      *this, e, [&](NodeId id) { return unchanged(id) || memo.count(id) != 0; },
      [&](NodeId id) {
        const Node n = nodes_[id];
        NodeId result = id;
        if (n.op == Op::kVar) {
          if (replacement) {
            if (std::optional<NodeId> r = replacement(n.index)) {
              if (*r >= nodes_.size())
                throw std::invalid_argument("expr::Pool::Substitute: replacement out of range");
              result = *r;
            }
          }
        } else {
          std::vector<NodeId> args;
          args.reserve(n.args.size());
          bool changed = false;
          for (NodeId a : n.args) {
            args.push_back(mapped(a));
            changed = changed || args.back() != a;
          }
          if (changed) result = Rebuild(n, args);
        }
        memo.emplace(id, result);
      });
  return mapped(e);
}

}  // namespace asgard::expr
