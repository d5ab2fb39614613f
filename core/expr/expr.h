// Expressions: force, torque and link-point formulas as a hash-consed DAG.
//
//   text ──Parse──▶ NodeId ──Derivative──▶ NodeId ──Tape::Compile──▶ Tape
//                    │  (every node is unique: equal subtrees share one id,
//                    │   so common subexpressions are evaluated once)
//                    └─ Variables / DependsOnTime / TimeBreakpoints (analysis)
//
// A Pool owns all nodes.  Node constructors simplify as they build (constant
// folding, x+0, x*1, x*0, x-x, flattening and canonical ordering of sums and
// products with numeric coefficients collected), so two algebraically
// identical forms built in different orders usually get the same id.  In
// particular c*a*b - c*b*a folds to 0, which keeps a sphere's rotational axes
// decoupled.
//
// Leaves:
//   Const(v)                 a number
//   Time()                   the independent variable t
//   Var(i)                   state variable i (index into the value array
//                            passed to Tape::Evaluate)
//   Extern(fn, d)            d-th time derivative of external function fn at t
//                            (trajectory components); d/dt Extern(fn,d) =
//                            Extern(fn,d+1)
//
// Rejected alternatives: (1) Tcl's own expr — no derivatives, no reference
// graph; (2) a tree without sharing — link forces repeat the rotation matrix
// dozens of times, the DAG evaluates it once; (3) generated C now — the tape is
// within a small factor and needs no compiler at run time (may come later
// behind Tape's interface).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace asgard::expr {

using NodeId = uint32_t;

// Every Op has a row in the operator table (ops.h) with its name, arity,
// notation and precedence; kSelect stays last.
enum class Op : uint8_t {
  // leaves
  kConst,
  kTime,
  kVar,
  kExtern,
  // arithmetic (kAdd and kMul are n-ary, canonical order)
  kAdd,
  kMul,
  kPow,  // a - b is Add(a, Mul(-1, b)); a / b is Mul(a, Pow(b, -1))
  // functions of one argument
  kSin,
  kCos,
  kTan,
  kAsin,
  kAcos,
  kAtan,
  kSinh,
  kCosh,
  kTanh,
  kExp,
  kLog,
  kSqrt,
  kAbs,
  kFloor,
  kCeil,
  kSign,
  // functions of two arguments
  kAtan2,
  kMin,
  kMax,
  kFmod,
  kHypot,
  // comparisons and logic: 1.0 for true, 0.0 for false; derivative 0
  kLt,
  kLe,
  kGt,
  kGe,
  kEq,
  kNe,
  kAnd,
  kOr,
  kNot,
  // Select(c, a, b): c != 0 ? a : b
  kSelect,
};

const char* OpName(Op op);

struct Node {
  Op op = Op::kConst;
  double value = 0.0;        // kConst
  int32_t index = 0;         // kVar: variable; kExtern: function
  int32_t order = 0;         // kExtern: derivative order
  std::vector<NodeId> args;  // operands (kAdd/kMul: canonical order)
};

// Thrown by Parse on bad expression text.  `offset` is a byte offset into the
// parsed text where the problem was found.
class ParseError : public std::runtime_error {
 public:
  ParseError(const std::string& message, int offset)
      : std::runtime_error(message), offset_(offset) {}
  int offset() const { return offset_; }

 private:
  int offset_;
};

class Pool {
 public:
  Pool();
  ~Pool();
  // Copies are deep (nodes, intern table and caches); moves are cheap.
  Pool(const Pool& other);
  Pool& operator=(const Pool& other);
  Pool(Pool&& other) noexcept;
  Pool& operator=(Pool&& other) noexcept;

  // Leaves.
  NodeId Const(double v);
  NodeId Time();
  NodeId Var(int index);
  NodeId Extern(int fn, int order);

  // Arithmetic (simplifying).
  NodeId Add(NodeId a, NodeId b);
  NodeId Sub(NodeId a, NodeId b);
  NodeId Mul(NodeId a, NodeId b);
  NodeId Div(NodeId a, NodeId b);
  NodeId Neg(NodeId a);
  NodeId Pow(NodeId a, NodeId b);
  NodeId Sum(std::span<const NodeId> terms);
  NodeId Product(std::span<const NodeId> factors);
  // Tcl's a % b extended to reals: fmod(a, b), shifted by b when its sign
  // differs from b's (so -7 % 3 == 2 as in Tcl).
  NodeId Mod(NodeId a, NodeId b);
  // Apply a function or comparison op to its arguments (arity checked).
  NodeId Apply(Op op, std::span<const NodeId> args);
  NodeId Select(NodeId cond, NodeId a, NodeId b);

  const Node& node(NodeId id) const { return nodes_[id]; }
  size_t size() const { return nodes_.size(); }

  bool IsConst(NodeId id) const { return nodes_[id].op == Op::kConst; }
  // The constant value of `id` if it is a constant.
  std::optional<double> ConstValue(NodeId id) const;

  // Symbolic derivatives (simplified).
  NodeId Derivative(NodeId e, int var_index);  // d e / d Var(var_index)
  NodeId TimeDerivative(NodeId e);             // partial d e / d t (Var held fixed)

  // Analysis.
  std::vector<int> Variables(NodeId e) const;  // sorted, unique
  // The variables of all of `roots` (one walk over their shared nodes).
  std::vector<int> Variables(std::span<const NodeId> roots) const;
  bool DependsOnTime(NodeId e) const;  // Time or Extern inside
  // Times at which `e` may jump: every comparison between t and a constant
  // (t > 2, t <= 0.5 ...), also floor/ceil/sign/fmod/abs of an affine function
  // of t where the jump or kink time can be solved for within [t0, t1].
  std::vector<double> TimeBreakpoints(NodeId e, double t0, double t1) const;

  // Replace Var(i) by replacement[i] where present (used to substitute
  // prescribed values); returns the simplified result.
  NodeId Substitute(NodeId e, const std::function<std::optional<NodeId>(int)>& replacement);

  // Readable infix form, variables named by `var_name` (default "x<i>").
  std::string ToString(NodeId e, const std::function<std::string(int)>& var_name = {}) const;

 private:
  NodeId Intern(Node n);
  // Builds a node of `op` over `args` through the simplifying constructors
  // (used to rebuild a node whose operands changed).
  NodeId Rebuild(const Node& proto, std::span<const NodeId> args);
  NodeId DerivativeImpl(NodeId e, int var_index);  // var_index < 0: time
  NodeId DerivativeStep(NodeId e, int var_index, std::span<const NodeId> dargs);

  std::vector<Node> nodes_;
  // Intern table, per-node flags and the derivative cache (see pool.cc).
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Resolves a name in expression text ("b1.x", "tr1.y", "g") to a node, or
// returns nullopt if the name is unknown.  "t", "pi" and "e" are built in and
// never reach the resolver.
using Resolver = std::function<std::optional<NodeId>(std::string_view name, Pool& pool)>;

// Parses Tcl-expr-like infix text:
//   numbers (1, 2.5, 1e-3), names ([A-Za-z_][A-Za-z0-9_]* with '.' parts,
//   e.g. b1.x), + - * / % ** (right assoc), unary - + !, comparisons
//   < <= > >= == !=, && ||, ?: , parentheses, and calls
//   sin cos tan asin acos atan atan2 sinh cosh tanh exp log sqrt abs floor
//   ceil sign min max fmod hypot pow.
// Precedence is Tcl's: unary - + ! bind tighter than ** (-2**2 == 4); all
// numbers are doubles (7/2 == 3.5); a % b has the sign of b as in Tcl.
// Nesting deeper than 200 levels is rejected.
// Throws ParseError with the offset of the problem (unknown name, bad token,
// unbalanced parenthesis, wrong argument count, trailing text, empty text).
NodeId Parse(std::string_view text, Pool& pool, const Resolver& resolve);

// Values of external functions (trajectory components) at time t.
using ExternFn = std::function<double(int fn, int order, double t)>;

// A straight-line program evaluating several output expressions at once;
// shared subexpressions are computed once.
//   Evaluate(t, x, out, ext, x_offset, lane): x[i − x_offset] is the value
//   of Var(i) (the caller owns a value array covering every variable the
//   outputs use); out receives one value per output in the order given to
//   Compile.  Each lane has a register file of its own: one thread per lane
//   may evaluate the same tape at once (the solver's threads share tapes
//   among components with the same equations).  Lane 0's is made by
//   Compile, another's by the first evaluation in it.
class Tape {
 public:
  static constexpr int kLanes = 4;

  static Tape Compile(const Pool& pool, std::span<const NodeId> outputs);

  Tape() = default;
  Tape(const Tape& o);
  Tape& operator=(const Tape& o);
  Tape(Tape&&) noexcept = default;
  Tape& operator=(Tape&&) noexcept = default;

  void Evaluate(double t, const double* x, double* out, const ExternFn* ext = nullptr,
                int32_t x_offset = 0, int lane = 0) const;

  size_t instruction_count() const { return loads_.size() + code_.size(); }
  size_t output_count() const { return outputs_.size(); }

 private:
  // Register 0 holds t; constants are preloaded into their registers by
  // Compile and never written by Evaluate.
  struct Instr {
    uint8_t code = 0;  // tape.cc's instruction code
    int32_t dst = 0;   // destination register
    int32_t a = 0;     // register operand / var index / extern fn / operands_ start
    int32_t b = 0;     // register operand / extern order / operand count
    int32_t c = 0;     // third register operand (Select, 3-ary Add/Mul)
  };
  struct Load {
    int32_t dst;    // register
    int32_t index;  // variable
  };
  std::vector<Load> loads_;  // the variables read, copied into registers first
  std::vector<Instr> code_;
  std::vector<int32_t> operands_;  // operand registers of n-ary Add/Mul
  std::vector<int32_t> outputs_;   // register per output
  // Lane 0's register file; its image as Compile left it (t, constants,
  // zeros), from which other lanes' files are made; theirs.
  mutable std::vector<double> regs_;
  std::vector<double> initial_;
  mutable std::unique_ptr<double[]> lane_regs_[kLanes - 1];
  bool uses_extern_ = false;
};

}  // namespace asgard::expr
