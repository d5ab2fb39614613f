// Tape: straight-line evaluation of a set of expressions.
//
// Design.  Compile walks the DAG below the outputs in post order (iteratively)
// and gives every reachable node one register: register 0 holds t, constants
// are stored into their registers once at compile time, and every other node
// becomes one instruction writing its own register, so shared subexpressions
// are computed once per Evaluate.  The variables read are copied into their
// registers first, in one tight loop.  Instructions are small PODs dispatched
// by threaded code (below, Evaluate); binary and ternary Add/Mul (c·x·y, the commonest product of
// the equations of motion), squares and reciprocals have their own codes,
// longer sums and products read an operand list.  (A torque-free top's
// rates, 29 tape instructions: 920 machine instructions per evaluation
// with every variable a dispatched load and every c·x·y a loop over an
// operand list, 476 before lanes, which add a test and a branch — callgrind
// over 10 000 calls of Evaluate alone; bench/notes.md.)  Evaluate allocates nothing (but a lane's
// register file, at its first evaluation there) and uses the scalar functions of internal.h, so its
// results are bit-identical to constant folding (sums and products accumulate left to right in the
// canonical operand order).  The register files are mutable scratch, one per
// lane: two threads may evaluate one Tape at once only in different lanes.
#include <algorithm>
#include <iterator>
#include <stdexcept>

#include "core/expr/expr.h"
#include "core/expr/internal.h"
#include "core/expr/ops.h"

namespace asgard::expr {
namespace {

// Instruction codes: an Op's own value for leaves, functions, comparisons,
// logic and Select; the extra codes below for specialised arithmetic, numbered
// on from kSelect.  Evaluate gives every function, comparison and logic
// operation a label of its own, so the dispatch jumps straight to its scalar
// function: a generic dispatch through the operator table measured about 40%
// slower on function-heavy tapes.  An operation without a label (one newly
// added to ops.h) is still evaluated correctly, through the generic case.
constexpr uint8_t C(Op op) { return static_cast<uint8_t>(op); }
constexpr uint8_t kFirstSpecial = C(Op::kSelect) + 1;
constexpr uint8_t kAdd2 = kFirstSpecial;
constexpr uint8_t kAddN = kFirstSpecial + 1;
constexpr uint8_t kMul2 = kFirstSpecial + 2;
constexpr uint8_t kMulN = kFirstSpecial + 3;
constexpr uint8_t kSquare = kFirstSpecial + 4;
constexpr uint8_t kRecip = kFirstSpecial + 5;
constexpr uint8_t kAdd3 = kFirstSpecial + 6;
constexpr uint8_t kMul3 = kFirstSpecial + 7;

}  // namespace

Tape Tape::Compile(const Pool& pool, std::span<const NodeId> outputs) {
  for (NodeId out : outputs)
    if (out >= pool.size()) throw std::invalid_argument("expr::Tape::Compile: id out of range");
  Tape tape;
  tape.regs_.push_back(0.0);  // t
  // Each compiled node's register (-1: not compiled yet).
  struct RegisterTag;
  internal::NodeScratch<RegisterTag, int32_t, -1> regs(pool.size());
  auto fresh = [&tape](double init) {
    tape.regs_.push_back(init);
    return static_cast<int32_t>(tape.regs_.size() - 1);
  };
  auto visit = [&](NodeId id) {
    const Node& n = pool.node(id);  // PostOrder visits each node once
    if (n.op == Op::kConst) {
      regs.set(id, fresh(n.value));
      return;
    }
    if (n.op == Op::kTime) {
      regs.set(id, 0);
      return;
    }
    Instr in;
    if (n.op == Op::kVar) {
      const int32_t dst = fresh(0.0);
      tape.loads_.push_back({dst, n.index});
      regs.set(id, dst);
      return;
    }
    in.code = C(n.op);
    switch (n.op) {
      case Op::kExtern:
        in.a = n.index;
        in.b = n.order;
        tape.uses_extern_ = true;
        break;
      case Op::kAdd:
      case Op::kMul:
        if (n.args.size() == 2) {
          in.code = n.op == Op::kAdd ? kAdd2 : kMul2;
          in.a = regs.get(n.args[0]);
          in.b = regs.get(n.args[1]);
        } else if (n.args.size() == 3) {
          in.code = n.op == Op::kAdd ? kAdd3 : kMul3;
          in.a = regs.get(n.args[0]);
          in.b = regs.get(n.args[1]);
          in.c = regs.get(n.args[2]);
        } else {
          in.code = n.op == Op::kAdd ? kAddN : kMulN;
          in.a = static_cast<int32_t>(tape.operands_.size());
          in.b = static_cast<int32_t>(n.args.size());
          for (NodeId arg : n.args) tape.operands_.push_back(regs.get(arg));
        }
        break;
      case Op::kPow: {
        in.a = regs.get(n.args[0]);
        in.b = regs.get(n.args[1]);
        auto k = pool.ConstValue(n.args[1]);
        if (k && *k == 2.0) in.code = kSquare;
        if (k && *k == -1.0) in.code = kRecip;
        break;
      }
      default:
        in.a = regs.get(n.args[0]);
        if (n.args.size() > 1) in.b = regs.get(n.args[1]);
        if (n.args.size() > 2) in.c = regs.get(n.args[2]);
        break;
    }
    in.dst = fresh(0.0);
    regs.set(id, in.dst);
    tape.code_.push_back(in);
  };
  for (NodeId out : outputs) {
    internal::PostOrder(
        pool, out, [&](NodeId id) { return regs.get(id) >= 0; }, visit);
    tape.outputs_.push_back(regs.get(out));
  }
  tape.initial_ = tape.regs_;
  return tape;
}

Tape::Tape(const Tape& o)
    : loads_(o.loads_),
      code_(o.code_),
      operands_(o.operands_),
      outputs_(o.outputs_),
      regs_(o.initial_),
      initial_(o.initial_),
      uses_extern_(o.uses_extern_) {}

Tape& Tape::operator=(const Tape& o) {
  if (this != &o) *this = Tape(o);
  return *this;
}

// Evaluate dispatches by threaded code (GCC's and Clang's labels as values):
// each operation's code ends by jumping straight to the next one's through
// kDispatch, indexed by the instruction code.  A switch in a loop costs a
// range check and a jump back to the loop's head per instruction besides
// the table jump: a c·x·y took 21 machine instructions, 16 now (a
// torque-free top's rates, 19 instructions: 573 → 476 per evaluation).
// kDispatch lists a label per code in code order: the operations of Op up
// to kSelect, then the codes above (kFirstSpecial on).  A code with no
// operation of its own (Const, Time, Var, Add, Mul never become
// instructions) goes to the generic case.
static_assert(C(Op::kExtern) == 3 && C(Op::kPow) == 6 && C(Op::kSign) == 22 &&
                  C(Op::kHypot) == 27 && C(Op::kNot) == 36 && C(Op::kSelect) == 37 &&
                  kMul3 == kFirstSpecial + 7,
              "kDispatch lists the codes in this order");

#define ASGARD_EXPR_UNARY(op)                                    \
  op_##op : r[in->dst] = internal::UnaryValue(Op::op, r[in->a]); \
  ASGARD_NEXT;
#define ASGARD_EXPR_BINARY(op)                                              \
  op_##op : r[in->dst] = internal::BinaryValue(Op::op, r[in->a], r[in->b]); \
  ASGARD_NEXT;
#define ASGARD_NEXT             \
  do {                          \
    if (++in == end) goto done; \
    goto* kDispatch[in->code];  \
  } while (false)

void Tape::Evaluate(double t, const double* x, double* out, const ExternFn* ext, int32_t x_offset,
                    int lane) const {
  // clang-format off
  static void* const kDispatch[] = {
      // Const, Time, Var, Extern, Add, Mul
      &&generic, &&generic, &&generic, &&op_kExtern, &&generic, &&generic,
      &&op_kPow, &&op_kSin, &&op_kCos, &&op_kTan, &&op_kAsin, &&op_kAcos, &&op_kAtan, &&op_kSinh,
      &&op_kCosh, &&op_kTanh, &&op_kExp, &&op_kLog, &&op_kSqrt, &&op_kAbs, &&op_kFloor, &&op_kCeil,
      &&op_kSign,                                                            // Pow … Sign
      &&op_kAtan2, &&op_kMin, &&op_kMax, &&op_kFmod, &&op_kHypot,            // Atan2 … Hypot
      &&op_kLt, &&op_kLe, &&op_kGt, &&op_kGe, &&op_kEq, &&op_kNe, &&op_kAnd, &&op_kOr, &&op_kNot,
      &&op_kSelect,                                                          // 37
      &&add2, &&addn, &&mul2, &&muln, &&square, &&recip, &&add3, &&mul3};    // kFirstSpecial …
  // clang-format on
  static_assert(std::size(kDispatch) == kMul3 + 1);
  if (uses_extern_ && (ext == nullptr || !*ext))
    throw std::invalid_argument("expr::Tape::Evaluate: expression uses external functions");
  double* r = regs_.data();
  if (lane != 0) {
    if (lane < 0 || lane >= kLanes)
      throw std::invalid_argument("expr::Tape::Evaluate: no such lane");
    std::unique_ptr<double[]>& file = lane_regs_[lane - 1];
    if (!file) {
      file.reset(new double[initial_.size()]);
      std::copy(initial_.begin(), initial_.end(), file.get());
    }
    r = file.get();
  }
  const int32_t* ops = operands_.data();
  r[0] = t;
  for (const Load& l : loads_) r[l.dst] = x[l.index - x_offset];
  const Instr* in = code_.data();
  const Instr* const end = in + code_.size();
  if (in == end) goto done;
  goto* kDispatch[in->code];
op_kExtern:
  r[in->dst] = (*ext)(in->a, in->b, t);
  ASGARD_NEXT;
add2:
  r[in->dst] = r[in->a] + r[in->b];
  ASGARD_NEXT;
mul2:
  r[in->dst] = r[in->a] * r[in->b];
  ASGARD_NEXT;
add3:  // left to right, as kAddN
  r[in->dst] = r[in->a] + r[in->b] + r[in->c];
  ASGARD_NEXT;
mul3:
  r[in->dst] = r[in->a] * r[in->b] * r[in->c];
  ASGARD_NEXT;
addn : {
  const int32_t* p = ops + in->a;
  double v = r[p[0]];
  for (int32_t k = 1; k < in->b; ++k) v += r[p[k]];
  r[in->dst] = v;
  ASGARD_NEXT;
}
muln : {
  const int32_t* p = ops + in->a;
  double v = r[p[0]];
  for (int32_t k = 1; k < in->b; ++k) v *= r[p[k]];
  r[in->dst] = v;
  ASGARD_NEXT;
}
square:
  r[in->dst] = r[in->a] * r[in->a];
  ASGARD_NEXT;
recip:
  r[in->dst] = 1.0 / r[in->a];
  ASGARD_NEXT;
op_kSelect:
  r[in->dst] = r[in->a] != 0.0 ? r[in->b] : r[in->c];
  ASGARD_NEXT;
  ASGARD_EXPR_UNARY(kSin)
  ASGARD_EXPR_UNARY(kCos)
  ASGARD_EXPR_UNARY(kTan)
  ASGARD_EXPR_UNARY(kAsin)
  ASGARD_EXPR_UNARY(kAcos)
  ASGARD_EXPR_UNARY(kAtan)
  ASGARD_EXPR_UNARY(kSinh)
  ASGARD_EXPR_UNARY(kCosh)
  ASGARD_EXPR_UNARY(kTanh)
  ASGARD_EXPR_UNARY(kExp)
  ASGARD_EXPR_UNARY(kLog)
  ASGARD_EXPR_UNARY(kSqrt)
  ASGARD_EXPR_UNARY(kAbs)
  ASGARD_EXPR_UNARY(kFloor)
  ASGARD_EXPR_UNARY(kCeil)
  ASGARD_EXPR_UNARY(kSign)
  ASGARD_EXPR_UNARY(kNot)
  ASGARD_EXPR_BINARY(kPow)
  ASGARD_EXPR_BINARY(kAtan2)
  ASGARD_EXPR_BINARY(kMin)
  ASGARD_EXPR_BINARY(kMax)
  ASGARD_EXPR_BINARY(kFmod)
  ASGARD_EXPR_BINARY(kHypot)
  ASGARD_EXPR_BINARY(kLt)
  ASGARD_EXPR_BINARY(kLe)
  ASGARD_EXPR_BINARY(kGt)
  ASGARD_EXPR_BINARY(kGe)
  ASGARD_EXPR_BINARY(kEq)
  ASGARD_EXPR_BINARY(kNe)
  ASGARD_EXPR_BINARY(kAnd)
  ASGARD_EXPR_BINARY(kOr)
generic : {  // an operation without a label of its own above
  const Op op = static_cast<Op>(in->code);
  r[in->dst] = Info(op).arity == 1 ? internal::UnaryValue(op, r[in->a])
                                   : internal::BinaryValue(op, r[in->a], r[in->b]);
  ASGARD_NEXT;
}
done:
  const int32_t* o = outputs_.data();
  for (size_t i = 0, n = outputs_.size(); i < n; ++i) out[i] = r[o[i]];
}

#undef ASGARD_NEXT
#undef ASGARD_EXPR_UNARY
#undef ASGARD_EXPR_BINARY

}  // namespace asgard::expr
