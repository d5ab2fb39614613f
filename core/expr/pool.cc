// Pool: node interning and the simplifying constructors.
//
// Design.  Every node lives in `nodes_` and is identified by its index; an
// operand always has a smaller id than its user, so id order is a topological
// order.  Interning uses an open-addressing table of node ids keyed on a hash
// of (op, value bits, index, order, args); equal nodes therefore share one id.
//
// Canonical forms built by the constructors:
//   Add  — flattened; terms written as coefficient * base; terms with the same
//          base are merged (c1*X + c2*X -> (c1+c2)*X, zero terms dropped);
//          the numeric constant (if nonzero) comes first, the other terms are
//          ordered by base id.
//   Mul  — flattened; factors written as base ** exponent with numeric
//          exponents merged (X^a * X^b -> X^(a+b), X^0 dropped); the numeric
//          coefficient (if not 1) comes first, the other factors are ordered
//          by base id.  A coefficient times a single sum is distributed, so
//          -(a+b) is -a - b and sums cancel term by term.
//   Pow  — x**1 -> x, x**0 -> 1, 1**y -> 1, (x**i)**j -> x**(i*j) for integer
//          i and j, (a*b)**j -> a**j * b**j for integer j.
// Everything whose operands are all constants is folded with the same scalar
// functions the tape uses (internal.h), so folding never changes a result.
// Constants are normalised: -0 becomes +0 and every NaN the same quiet NaN.
// The only value-changing rewrites are x*0 -> 0, x-x -> 0 and x/x -> 1, which
// differ only where x is infinite, NaN or (for x/x) zero.
#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/expr/expr.h"
#include "core/expr/internal.h"

namespace asgard::expr {
namespace {

uint64_t Mix(uint64_t h, uint64_t x) {
  h ^= x + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  return h;
}

uint64_t Finish(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

uint64_t HashNode(const Node& n) {
  uint64_t h = static_cast<uint64_t>(n.op) + 1;
  h = Mix(h, std::bit_cast<uint64_t>(n.value));
  h = Mix(h, static_cast<uint32_t>(n.index));
  h = Mix(h, static_cast<uint32_t>(n.order));
  for (NodeId a : n.args) h = Mix(h, a);
  return Finish(h);
}

bool SameNode(const Node& a, const Node& b) {
  return a.op == b.op && std::bit_cast<uint64_t>(a.value) == std::bit_cast<uint64_t>(b.value) &&
         a.index == b.index && a.order == b.order && a.args == b.args;
}

bool IsInteger(double v) { return std::isfinite(v) && v == std::floor(v); }

// A term coef * base of a sum, or a factor base ** exponent of a product.
struct Weighted {
  NodeId base;
  double weight;
};

// Sorts `items` by base (stably), adds up the weights of equal bases (left to
// right) and drops the bases whose weight comes to 0.
void MergeByBase(std::vector<Weighted>& items) {
  std::stable_sort(items.begin(), items.end(),
                   [](const Weighted& x, const Weighted& y) { return x.base < y.base; });
  size_t out = 0;
  for (size_t i = 0; i < items.size();) {
    Weighted merged = items[i++];
    while (i < items.size() && items[i].base == merged.base) merged.weight += items[i++].weight;
    if (merged.weight != 0.0) items[out++] = merged;
  }
  items.resize(out);
}

// Calls add(x) for each of `ids`, and for the operands of those that are
// `flat` nodes instead of the node itself.  add may grow the pool.
template <class Add>
void Flatten(const std::vector<Node>& nodes, std::span<const NodeId> ids, Op flat, const char* who,
             Add&& add) {
  for (NodeId id : ids) {
    if (id >= nodes.size())
      throw std::invalid_argument(std::string("expr::Pool::") + who + ": id out of range");
    if (nodes[id].op != flat) {
      add(id);
      continue;
    }
    for (size_t k = 0; k < nodes[id].args.size(); ++k) add(nodes[id].args[k]);
  }
}

}  // namespace

const char* OpName(Op op) { return Info(op).name; }

Pool::Pool() : impl_(std::make_unique<Impl>()) { impl_->table.assign(256, Impl::kEmpty); }
Pool::~Pool() = default;
Pool::Pool(const Pool& other) : nodes_(other.nodes_), impl_(std::make_unique<Impl>(*other.impl_)) {}
Pool& Pool::operator=(const Pool& other) {
  if (this != &other) {
    nodes_ = other.nodes_;
    impl_ = std::make_unique<Impl>(*other.impl_);
  }
  return *this;
}
Pool::Pool(Pool&& other) noexcept = default;
Pool& Pool::operator=(Pool&& other) noexcept = default;

NodeId Pool::Intern(Node n) {
  Impl& im = *impl_;
  uint8_t flags = 0;
  for (NodeId a : n.args) {
    if (a >= nodes_.size()) throw std::invalid_argument("expr::Pool: operand id out of range");
    flags |= im.flags[a];
  }
  if (n.op == Op::kTime) flags |= kHasTime;
  if (n.op == Op::kVar) flags |= kHasVar;
  if (n.op == Op::kExtern) flags |= kHasTime | kHasExtern;

  const uint64_t h = HashNode(n);
  size_t mask = im.table.size() - 1;
  size_t i = h & mask;
  while (im.table[i] != Impl::kEmpty) {
    NodeId id = im.table[i];
    if (im.hashes[id] == h && SameNode(nodes_[id], n)) return id;
    i = (i + 1) & mask;
  }
  if (nodes_.size() >= Impl::kEmpty - 1) throw std::length_error("expr::Pool: too many nodes");
  const NodeId id = static_cast<NodeId>(nodes_.size());
  nodes_.push_back(std::move(n));
  im.hashes.push_back(h);
  im.flags.push_back(flags);
  im.table[i] = id;
  if (++im.used * 2 > im.table.size()) {
    std::vector<uint32_t> bigger(im.table.size() * 2, Impl::kEmpty);
    mask = bigger.size() - 1;
    for (uint32_t old : im.table) {
      if (old == Impl::kEmpty) continue;
      size_t j = im.hashes[old] & mask;
      while (bigger[j] != Impl::kEmpty) j = (j + 1) & mask;
      bigger[j] = old;
    }
    im.table.swap(bigger);
  }
  return id;
}

NodeId Pool::Const(double v) {
  if (v == 0.0) v = 0.0;  // -0 -> +0
  if (std::isnan(v)) v = std::numeric_limits<double>::quiet_NaN();
  Node n;
  n.op = Op::kConst;
  n.value = v;
  return Intern(std::move(n));
}

NodeId Pool::Time() {
  Node n;
  n.op = Op::kTime;
  return Intern(std::move(n));
}

NodeId Pool::Var(int index) {
  if (index < 0) throw std::invalid_argument("expr::Pool::Var: negative index");
  Node n;
  n.op = Op::kVar;
  n.index = index;
  return Intern(std::move(n));
}

NodeId Pool::Extern(int fn, int order) {
  if (fn < 0 || order < 0) throw std::invalid_argument("expr::Pool::Extern: negative fn or order");
  Node n;
  n.op = Op::kExtern;
  n.index = fn;
  n.order = order;
  return Intern(std::move(n));
}

std::optional<double> Pool::ConstValue(NodeId id) const {
  if (nodes_[id].op != Op::kConst) return std::nullopt;
  return nodes_[id].value;
}

NodeId Pool::Add(NodeId a, NodeId b) {
  const NodeId terms[2] = {a, b};
  return Sum(terms);
}

NodeId Pool::Sub(NodeId a, NodeId b) { return Add(a, Neg(b)); }

NodeId Pool::Mul(NodeId a, NodeId b) {
  const NodeId factors[2] = {a, b};
  return Product(factors);
}

NodeId Pool::Neg(NodeId a) { return Mul(Const(-1.0), a); }

NodeId Pool::Div(NodeId a, NodeId b) {
  if (IsConst(a) && IsConst(b)) return Const(nodes_[a].value / nodes_[b].value);
  return Mul(a, Pow(b, Const(-1.0)));
}

NodeId Pool::Sum(std::span<const NodeId> terms) {
  double constant = 0.0;
  std::vector<Weighted> items;  // coefficient * base
  items.reserve(terms.size() + 4);
  Flatten(nodes_, terms, Op::kAdd, "Sum", [&](NodeId x) {
    const Node& n = nodes_[x];
    if (n.op == Op::kConst) {
      constant += n.value;
    } else if (n.op == Op::kMul && nodes_[n.args[0]].op == Op::kConst) {
      const double c = nodes_[n.args[0]].value;
      if (n.args.size() == 2) {
        items.push_back({n.args[1], c});
      } else {
        Node rest;
        rest.op = Op::kMul;
        rest.args.assign(n.args.begin() + 1, n.args.end());
        items.push_back({Intern(std::move(rest)), c});  // may reallocate nodes_
      }
    } else {
      items.push_back({x, 1.0});
    }
  });
  if (std::isnan(constant)) return Const(constant);
  MergeByBase(items);
  if (items.empty()) return Const(constant);

  std::vector<NodeId> args;
  args.reserve(items.size() + 1);
  if (constant != 0.0) args.push_back(Const(constant));
  for (const Weighted& term : items) {
    if (term.weight == 1.0) {
      args.push_back(term.base);
      continue;
    }
    // coefficient * base, in Product's canonical form (base is never a
    // constant, a sum, or a product with a coefficient).
    Node m;
    m.op = Op::kMul;
    m.args.push_back(Const(term.weight));
    if (nodes_[term.base].op == Op::kMul) {
      const std::vector<NodeId>& fa = nodes_[term.base].args;
      m.args.insert(m.args.end(), fa.begin(), fa.end());
    } else {
      m.args.push_back(term.base);
    }
    args.push_back(Intern(std::move(m)));
  }
  if (args.size() == 1) return args[0];
  Node n;
  n.op = Op::kAdd;
  n.args = std::move(args);
  return Intern(std::move(n));
}

NodeId Pool::Product(std::span<const NodeId> factors) {
  double coef = 1.0;
  std::vector<Weighted> items;  // base ** exponent
  items.reserve(factors.size() + 4);
  Flatten(nodes_, factors, Op::kMul, "Product", [&](NodeId x) {  // does not intern
    const Node& n = nodes_[x];
    if (n.op == Op::kConst) {
      coef *= n.value;
    } else if (n.op == Op::kPow && nodes_[n.args[1]].op == Op::kConst) {
      items.push_back({n.args[0], nodes_[n.args[1]].value});
    } else {
      items.push_back({x, 1.0});
    }
  });
  if (coef == 0.0 || std::isnan(coef)) return Const(coef);
  MergeByBase(items);
  std::vector<NodeId> built;
  built.reserve(items.size() + 1);
  for (const Weighted& item : items) {
    NodeId f = item.weight == 1.0 ? item.base : Pow(item.base, Const(item.weight));
    if (nodes_[f].op == Op::kConst) {  // a collapsed power such as (x**2)**0
      coef *= nodes_[f].value;
      continue;
    }
    built.push_back(f);
  }
  if (coef == 0.0 || std::isnan(coef)) return Const(coef);
  if (built.empty()) return Const(coef);
  for (NodeId f : built) {
    if (nodes_[f].op == Op::kMul) {  // a merged power such as (x*y)**0.5 * (x*y)**0.5
      built.push_back(Const(coef));
      return Product(built);
    }
  }
  if (built.size() == 1) {
    if (coef == 1.0) return built[0];
    if (nodes_[built[0]].op == Op::kAdd) {  // distribute c * (a + b + ...)
      const std::vector<NodeId> inner = nodes_[built[0]].args;
      std::vector<NodeId> scaled;
      scaled.reserve(inner.size());
      const NodeId c = Const(coef);
      for (NodeId u : inner) scaled.push_back(Mul(c, u));
      return Sum(scaled);
    }
  }
  Node n;
  n.op = Op::kMul;
  if (coef != 1.0) n.args.push_back(Const(coef));
  n.args.insert(n.args.end(), built.begin(), built.end());
  return Intern(std::move(n));
}

NodeId Pool::Pow(NodeId a, NodeId b) {
  if (a >= nodes_.size() || b >= nodes_.size())
    throw std::invalid_argument("expr::Pool::Pow: id out of range");
  const bool ca = IsConst(a), cb = IsConst(b);
  if (ca && cb) return Const(internal::PowValue(nodes_[a].value, nodes_[b].value));
  if (ca && nodes_[a].value == 1.0) return a;
  if (cb) {
    const double k = nodes_[b].value;
    if (k == 1.0) return a;
    if (k == 0.0) return Const(1.0);
    if (IsInteger(k)) {
      const Node& base = nodes_[a];
      if (base.op == Op::kPow && IsConst(base.args[1]) && IsInteger(nodes_[base.args[1]].value)) {
        const NodeId inner = base.args[0];
        return Pow(inner, Const(nodes_[base.args[1]].value * k));
      }
      if (base.op == Op::kMul) {
        const std::vector<NodeId> fs = base.args;
        std::vector<NodeId> powered;
        powered.reserve(fs.size());
        for (NodeId f : fs) powered.push_back(Pow(f, b));
        return Product(powered);
      }
    }
  }
  Node n;
  n.op = Op::kPow;
  n.args = {a, b};
  return Intern(std::move(n));
}

NodeId Pool::Mod(NodeId a, NodeId b) {
  const NodeId r = Apply(Op::kFmod, std::array<NodeId, 2>{a, b});
  NodeId wrong_sign;
  if (auto cb = ConstValue(b)) {
    const NodeId zero = Const(0.0);
    wrong_sign = *cb > 0 ? Apply(Op::kLt, std::array<NodeId, 2>{r, zero})
                         : Apply(Op::kGt, std::array<NodeId, 2>{r, zero});
  } else {
    wrong_sign = Apply(Op::kLt, std::array<NodeId, 2>{Mul(r, b), Const(0.0)});
  }
  return Select(wrong_sign, Add(r, b), r);
}

NodeId Pool::Select(NodeId cond, NodeId a, NodeId b) {
  if (cond >= nodes_.size() || a >= nodes_.size() || b >= nodes_.size())
    throw std::invalid_argument("expr::Pool::Select: id out of range");
  if (auto c = ConstValue(cond)) return *c != 0.0 ? a : b;
  if (a == b) return a;
  Node n;
  n.op = Op::kSelect;
  n.args = {cond, a, b};
  return Intern(std::move(n));
}

NodeId Pool::Apply(Op op, std::span<const NodeId> args) {
  const OpInfo& info = Info(op);
  const int arity = info.arity;
  if (arity == 0)
    throw std::invalid_argument("expr::Pool::Apply: leaf op " + std::string(OpName(op)));
  if (arity == -1) return op == Op::kAdd ? Sum(args) : Product(args);
  if (static_cast<size_t>(arity) != args.size())
    throw std::invalid_argument(std::string("expr::Pool::Apply: wrong number of operands for ") +
                                OpName(op));
  for (NodeId a : args)
    if (a >= nodes_.size()) throw std::invalid_argument("expr::Pool::Apply: id out of range");
  if (op == Op::kPow) return Pow(args[0], args[1]);
  if (op == Op::kSelect) return Select(args[0], args[1], args[2]);

  bool all_const = true;
  for (NodeId a : args) all_const = all_const && IsConst(a);
  if (all_const) {
    return Const(arity == 1
                     ? internal::UnaryValue(op, nodes_[args[0]].value)
                     : internal::BinaryValue(op, nodes_[args[0]].value, nodes_[args[1]].value));
  }
  if (info.Has(kIdempotent)) {
    if (arity == 1 && nodes_[args[0]].op == op) return args[0];  // f(f(x)) = f(x)
    if (arity == 2 && args[0] == args[1]) return args[0];        // x op x = x
  }
  switch (op) {
    case Op::kAnd:
      for (NodeId a : args)
        if (auto v = ConstValue(a); v && *v == 0.0) return Const(0.0);
      break;
    case Op::kOr:
      for (NodeId a : args)
        if (auto v = ConstValue(a); v && *v != 0.0) return Const(1.0);
      break;
    case Op::kNot: {
      // !!c == c when c is already 0 or 1.
      const Node& inner = nodes_[args[0]];
      if (inner.op == Op::kNot) {
        if (Info(nodes_[inner.args[0]].op).Has(kBoolean)) return inner.args[0];
      }
      break;
    }
    default:
      break;
  }
  Node n;
  n.op = op;
  n.args.assign(args.begin(), args.end());
  return Intern(std::move(n));
}

NodeId Pool::Rebuild(const Node& proto, std::span<const NodeId> args) {
  switch (proto.op) {
    case Op::kConst:
      return Const(proto.value);
    case Op::kTime:
      return Time();
    case Op::kVar:
      return Var(proto.index);
    case Op::kExtern:
      return Extern(proto.index, proto.order);
    case Op::kAdd:
      return Sum(args);
    case Op::kMul:
      return Product(args);
    default:
      return Apply(proto.op, args);
  }
}

}  // namespace asgard::expr
