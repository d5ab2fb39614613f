// ToString: readable infix text that Parse reads back to the same node.
//
// Design.  Printing is iterative (an explicit stack of pending text pieces and
// nodes), so arbitrarily deep expressions cannot overflow the stack.  Each
// node is formatted into a short list of pieces plus its precedence; a node
// whose precedence is below what its position requires is parenthesised, so
// parentheses are minimal.  Precedence follows Tcl's expr, in particular unary
// minus binds tighter than ** (-x**2 is (-x)**2), so negated powers print as
// -(x**2).  For readability a power's base is parenthesised unless it is a
// primary (name, number, call or parenthesised group).
//
// Sums print their constant last and subtract negative terms (a - 2*b);
// products print the coefficient first and negative integer powers as a
// denominator (2*a/b**2).  Numbers use the shortest text that reads back to
// the same double; infinity prints as 1e999 and NaN as (0/0).  Extern(fn, d)
// prints as ext<fn> for d = 0 and ext<fn>.d<d> otherwise.
#include <charconv>
#include <cmath>
#include <string>

#include "core/expr/expr.h"
#include "core/expr/ops.h"

namespace asgard::expr {
namespace {

std::string NumberText(double v) {
  if (std::isnan(v)) return "(0/0)";
  if (std::isinf(v)) return v > 0 ? "1e999" : "-1e999";
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

struct Piece {
  bool is_node = false;
  std::string text;
  NodeId id = 0;
  int min_prec = 0;
  bool negate = false;
};

Piece Text(std::string s) { return Piece{false, std::move(s), 0, 0, false}; }
Piece Sub(NodeId id, int min_prec, bool negate = false) {
  return Piece{true, {}, id, min_prec, negate};
}

bool IsNegativeTerm(const Pool& pool, NodeId id) {
  const Node& n = pool.node(id);
  if (n.op == Op::kConst) return n.value < 0;
  if (n.op == Op::kMul) {
    auto c = pool.ConstValue(n.args[0]);
    return c && *c < 0;
  }
  return false;
}

class Printer {
 public:
  Printer(const Pool& pool, const std::function<std::string(int)>& var_name)
      : pool_(pool), var_name_(var_name) {}

  std::string Print(NodeId root) {
    std::string out;
    std::vector<Piece> stack{Sub(root, kNoPrec)};
    std::vector<Piece> pieces;
    while (!stack.empty()) {
      Piece p = std::move(stack.back());
      stack.pop_back();
      if (!p.is_node) {
        out += p.text;
        continue;
      }
      pieces.clear();
      const int prec = Format(p.id, p.negate, pieces);
      const bool wrap = prec < p.min_prec;
      if (wrap) stack.push_back(Text(")"));
      for (auto it = pieces.rbegin(); it != pieces.rend(); ++it) stack.push_back(std::move(*it));
      if (wrap) stack.push_back(Text("("));
    }
    return out;
  }

 private:
  // Appends the pieces of node `id` (negated if `negate`) and returns its
  // precedence.
  int Format(NodeId id, bool negate, std::vector<Piece>& out) {
    const Node& n = pool_.node(id);
    if (n.op == Op::kConst) {
      const double v = negate ? -n.value : n.value;
      out.push_back(Text(NumberText(v)));
      return (std::isnan(v) || !(v < 0)) ? kPrimary : kUnary;
    }
    const OpInfo& info = Info(n.op);
    if (negate && info.notation != Notation::kProduct) {  // products print their sign
      out.push_back(Text("-"));
      out.push_back(Sub(id, kUnary));
      return kUnary;
    }
    switch (info.notation) {
      case Notation::kLeaf:
        out.push_back(Text(LeafText(n)));
        return kPrimary;
      case Notation::kSum: {
        // Constant (first in canonical order) goes last.
        std::vector<NodeId> terms(n.args.begin(), n.args.end());
        if (pool_.IsConst(terms.front())) {
          terms.push_back(terms.front());
          terms.erase(terms.begin());
        }
        out.push_back(Sub(terms[0], kAdditive));
        for (size_t i = 1; i < terms.size(); ++i) {
          const bool neg = IsNegativeTerm(pool_, terms[i]);
          out.push_back(Text(neg ? " - " : " + "));
          out.push_back(Sub(terms[i], kMultiplicative, neg));
        }
        return kAdditive;
      }
      case Notation::kProduct:
        return FormatProduct(n, negate, out);
      case Notation::kPower: {
        auto k = pool_.ConstValue(n.args[1]);
        if (k && *k < 0 && *k == std::floor(*k) && std::isfinite(*k)) {
          out.push_back(Text("1/"));
          AppendPower(n.args[0], -*k, out);
          return kMultiplicative;
        }
        out.push_back(Sub(n.args[0], kPrimary));
        out.push_back(Text("**"));
        out.push_back(Sub(n.args[1], kPower));
        return kPower;
      }
      case Notation::kSelect:
        out.push_back(Sub(n.args[0], kOrPrec));
        out.push_back(Text(" ? "));
        out.push_back(Sub(n.args[1], kNoPrec));
        out.push_back(Text(" : "));
        out.push_back(Sub(n.args[2], kTernary));
        return kTernary;
      case Notation::kPrefix:
        out.push_back(Text(info.name));
        out.push_back(Sub(n.args[0], info.prec));
        return info.prec;
      case Notation::kInfix:
        out.push_back(Sub(n.args[0], info.prec));
        out.push_back(Text(std::string(" ").append(info.name).append(" ")));
        out.push_back(Sub(n.args[1], info.prec + 1));
        return info.prec;
      case Notation::kCall:
        break;
    }
    out.push_back(Text(std::string(info.name) + "("));
    for (size_t i = 0; i < n.args.size(); ++i) {
      if (i > 0) out.push_back(Text(", "));
      out.push_back(Sub(n.args[i], kNoPrec));
    }
    out.push_back(Text(")"));
    return kPrimary;
  }

  // t, a variable or an external function.
  std::string LeafText(const Node& n) const {
    if (n.op == Op::kTime) return "t";
    // (append, not "x" + string: GCC 12 -O3 warns falsely, -Wrestrict)
    if (n.op == Op::kVar)
      return var_name_ ? var_name_(n.index) : std::string("x").append(std::to_string(n.index));
    std::string s = std::string("ext").append(std::to_string(n.index));
    if (n.order != 0) s.append(".d").append(std::to_string(n.order));
    return s;
  }

  // base ** exponent with a positive numeric exponent, as an operand of * or /.
  void AppendPower(NodeId base, double exponent, std::vector<Piece>& out) {
    if (exponent == 1.0) {
      out.push_back(Sub(base, kPower));
    } else {
      out.push_back(Sub(base, kPrimary));
      out.push_back(Text("**" + NumberText(exponent)));
    }
  }

  int FormatProduct(const Node& n, bool negate, std::vector<Piece>& out) {
    double coef = 1.0;
    size_t first = 0;
    if (auto c = pool_.ConstValue(n.args[0])) {
      coef = *c;
      first = 1;
    }
    if (negate) coef = -coef;
    std::vector<NodeId> num;
    std::vector<std::pair<NodeId, double>> den;
    for (size_t i = first; i < n.args.size(); ++i) {
      const Node& f = pool_.node(n.args[i]);
      if (f.op == Op::kPow) {
        auto k = pool_.ConstValue(f.args[1]);
        if (k && *k < 0 && *k == std::floor(*k) && std::isfinite(*k)) {
          den.emplace_back(f.args[0], -*k);
          continue;
        }
      }
      num.push_back(n.args[i]);
    }
    int operators = 0;
    if (coef == -1.0) {
      out.push_back(Text("-"));
      if (num.empty()) {
        out.push_back(Text("1"));
      } else {
        out.push_back(Sub(num[0], kUnary));
      }
    } else if (coef == 1.0) {
      if (num.empty()) {
        out.push_back(Text("1"));
      } else {
        out.push_back(Sub(num[0], kPower));
      }
    } else {
      out.push_back(Text(NumberText(coef)));
      if (!num.empty()) {
        out.push_back(Text("*"));
        out.push_back(Sub(num[0], kPower));
        ++operators;
      }
    }
    for (size_t i = 1; i < num.size(); ++i) {
      out.push_back(Text("*"));
      out.push_back(Sub(num[i], kPower));
      ++operators;
    }
    if (!den.empty()) {
      ++operators;
      out.push_back(Text(den.size() > 1 ? "/(" : "/"));
      for (size_t i = 0; i < den.size(); ++i) {
        if (i > 0) out.push_back(Text("*"));
        AppendPower(den[i].first, den[i].second, out);
      }
      if (den.size() > 1) out.push_back(Text(")"));
    }
    if (operators > 0) return kMultiplicative;
    if (coef == -1.0) return kUnary;
    return kMultiplicative;
  }

  const Pool& pool_;
  const std::function<std::string(int)>& var_name_;
};

}  // namespace

std::string Pool::ToString(NodeId e, const std::function<std::string(int)>& var_name) const {
  if (e >= nodes_.size()) return "<invalid>";
  return Printer(*this, var_name).Print(e);
}

}  // namespace asgard::expr
