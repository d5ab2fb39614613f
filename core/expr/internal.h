// Internal helpers shared by the expression module's translation units: the
// scalar semantics of every operation (used both by constant folding and by
// the tape, so a folded constant is bit-identical to the value the tape would
// compute) and an iterative post-order walk over the DAG (no recursion, so
// arbitrarily deep expressions cannot overflow the stack).  The other facts
// about each operation are in the operator table, ops.h.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "core/expr/expr.h"
#include "core/expr/ops.h"

namespace asgard::expr::internal {

// a ** b.  Squares and reciprocals are computed exactly (x*x, 1/x).
inline double PowValue(double a, double b) {
  if (b == 2.0) return a * a;
  if (b == -1.0) return 1.0 / a;
  return std::pow(a, b);
}

inline double SignValue(double a) { return a > 0.0 ? 1.0 : (a < 0.0 ? -1.0 : a); }

inline double UnaryValue(Op op, double a) {
  switch (op) {
    case Op::kSin:
      return std::sin(a);
    case Op::kCos:
      return std::cos(a);
    case Op::kTan:
      return std::tan(a);
    case Op::kAsin:
      return std::asin(a);
    case Op::kAcos:
      return std::acos(a);
    case Op::kAtan:
      return std::atan(a);
    case Op::kSinh:
      return std::sinh(a);
    case Op::kCosh:
      return std::cosh(a);
    case Op::kTanh:
      return std::tanh(a);
    case Op::kExp:
      return std::exp(a);
    case Op::kLog:
      return std::log(a);
    case Op::kSqrt:
      return std::sqrt(a);
    case Op::kAbs:
      return std::fabs(a);
    case Op::kFloor:
      return std::floor(a);
    case Op::kCeil:
      return std::ceil(a);
    case Op::kSign:
      return SignValue(a);
    case Op::kNot:
      return a == 0.0 ? 1.0 : 0.0;
    default:
      return std::nan("");
  }
}

inline double BinaryValue(Op op, double a, double b) {
  switch (op) {
    case Op::kPow:
      return PowValue(a, b);
    case Op::kAtan2:
      return std::atan2(a, b);
    case Op::kMin:
      return b < a ? b : a;
    case Op::kMax:
      return a < b ? b : a;
    case Op::kFmod:
      return std::fmod(a, b);
    case Op::kHypot:
      return std::hypot(a, b);
    case Op::kLt:
      return a < b ? 1.0 : 0.0;
    case Op::kLe:
      return a <= b ? 1.0 : 0.0;
    case Op::kGt:
      return a > b ? 1.0 : 0.0;
    case Op::kGe:
      return a >= b ? 1.0 : 0.0;
    case Op::kEq:
      return a == b ? 1.0 : 0.0;
    case Op::kNe:
      return a != b ? 1.0 : 0.0;
    case Op::kAnd:
      return (a != 0.0 && b != 0.0) ? 1.0 : 0.0;
    case Op::kOr:
      return (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
    default:
      return std::nan("");
  }
}

// A value per node id for the length of one walk over a pool (`kUnset`
// for nodes the walk has not set): a scratch array over the ids, one per
// thread and per Tag, kept between walks and cleared at the walk's end from
// the list of the ids it set, so that a walk costs what it visits, not what
// the pool holds (a hash map or set in its place was most of compiling a
// rigid body's rates).  One walk per Tag and thread at a time.
template <class Tag, class T, T kUnset>
class NodeScratch {
 public:
  explicit NodeScratch(size_t pool_size) {
    if (busy()) throw std::logic_error("expr::NodeScratch: nested walk");
    if (values().size() < pool_size) values().resize(pool_size, kUnset);
    busy() = true;  // after the resize: a constructor that throws leaves it free
  }
  ~NodeScratch() {
    for (NodeId id : set_) values()[id] = kUnset;
    busy() = false;
  }
  NodeScratch(const NodeScratch&) = delete;
  NodeScratch& operator=(const NodeScratch&) = delete;
  T get(NodeId id) const { return values()[id]; }
  void set(NodeId id, T v) {
    if (values()[id] == kUnset) set_.push_back(id);
    values()[id] = v;
  }

 private:
  static std::vector<T>& values() {
    thread_local std::vector<T> v;
    return v;
  }
  static bool& busy() {
    thread_local bool b = false;
    return b;
  }
  std::vector<NodeId> set_;
};

// Calls done(id) to skip finished nodes and visit(id) after all operands of
// id were visited.  visit must make done(id) true.  The pool may grow during
// the walk (visit may build nodes); no node reference is held across visit.
template <class Done, class Visit>
void PostOrder(const Pool& pool, NodeId root, Done&& done, Visit&& visit) {
  struct Frame {
    NodeId id;
    uint32_t next;
  };
  if (done(root)) return;
  std::vector<Frame> stack;
  stack.push_back({root, 0});
  while (!stack.empty()) {
    Frame& top = stack.back();
    const std::vector<NodeId>& args = pool.node(top.id).args;
    if (top.next < args.size()) {
      NodeId child = args[top.next++];
      if (!done(child)) stack.push_back({child, 0});
    } else {
      NodeId id = top.id;
      stack.pop_back();
      visit(id);
    }
  }
}

}  // namespace asgard::expr::internal

namespace asgard::expr {

// Per-node facts computed when a node is interned.
enum NodeFlags : uint8_t {
  kHasTime = 1,    // Time or Extern somewhere below (Extern depends on t)
  kHasVar = 2,     // some Var below
  kHasExtern = 4,  // some Extern below
};

struct Pool::Impl {
  std::vector<uint64_t> hashes;  // per node
  std::vector<uint8_t> flags;    // per node, NodeFlags
  std::vector<uint32_t> table;   // open addressing over node ids; kEmpty = free
  size_t used = 0;
  // Derivative cache: key (var_index + 1) << 32 | node, var_index -1 = time.
  std::unordered_map<uint64_t, NodeId> derivs;
  static constexpr uint32_t kEmpty = 0xFFFFFFFFu;
};

}  // namespace asgard::expr
