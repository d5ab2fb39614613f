// The operator table: one row per Op with every fact about it that is not
// its evaluation or its derivative.  The parser (function names, infix
// symbols, precedence), the printer (notation, precedence), the pool (arity,
// simplification flags), the derivative (piecewise-constant operations) and
// the analysis (where an operation may jump in time) all read this table.
//
// Adding an operator: an Op enumerator (expr.h), a row below, its scalar value
// (internal.h's UnaryValue / BinaryValue, which the tape and constant folding
// share) and its derivative rule (derivative.cc, unless it is piecewise
// constant).
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string_view>

#include "core/expr/expr.h"

namespace asgard::expr {

// Precedence of expression text, lowest first, as in Tcl's expr.  Unary
// operators bind tighter than ** (-2**2 is 4).
enum Prec : int {
  kNoPrec = 0,
  kTernary = 1,  // c ? a : b, right associative
  kOrPrec = 2,
  kAndPrec = 3,
  kEquality = 4,
  kRelational = 5,
  kAdditive = 6,
  kMultiplicative = 7,
  kPower = 8,  // right associative
  kUnary = 9,
  kPrimary = 10,  // number, name, call, parenthesised group
};

// How a node is written in expression text.
enum class Notation : uint8_t {
  kLeaf,     // number, t, variable or external name
  kSum,      // a + b - c
  kProduct,  // 2*a/b
  kPower,    // a**b (also callable as pow(a, b))
  kCall,     // name(a, ...)
  kInfix,    // a <name> b, left associative at `prec`
  kPrefix,   // <name>a
  kSelect,   // c ? a : b
};

// Where an operation's value or slope may jump as its operands change (read
// by Pool::TimeBreakpoints for operands affine in t).
enum class Jump : uint8_t {
  kNone,
  kDifference,  // where lhs - rhs crosses 0 (comparisons, min, max)
  kOperands,    // where any operand crosses 0 (sign, abs, !, &&, ||)
  kCondition,   // where the first operand crosses 0 (select)
  kIntegers,    // where the operand crosses an integer (floor, ceil)
  kModulus,     // where p / |q| crosses an integer, q constant (fmod)
};

// Facts an operation may have (OpInfo::flags).
enum OpFlag : uint8_t {
  kCallable = 1,            // name(args) is accepted in expression text
  kVariadic = 2,            // as a call: one or more arguments, folded left
  kBoolean = 4,             // the value is always 0 or 1 (comparisons and logic)
  kPiecewiseConstant = 8,   // derivative 0 wherever it exists
  kIdempotent = 16,         // f(f(x)) == f(x); with two operands x op x == x
};

struct OpInfo {
  Op op;
  const char* name;   // OpName; the function name or operator symbol in text
  int arity;          // operands of a node: -1 n-ary (Add, Mul), 0 for leaves
  Notation notation;  // how it is written
  int prec;           // precedence of that notation (Prec)
  uint8_t flags;      // OpFlag bits
  Jump jump;          // where it may jump in time

  constexpr bool Has(OpFlag flag) const { return (flags & flag) != 0; }
};

namespace ops_detail {
using N = Notation;
// The flag combinations of the rows below.
inline constexpr uint8_t kFunction = kCallable;
inline constexpr uint8_t kKink = kCallable | kIdempotent;
inline constexpr uint8_t kStep = kCallable | kPiecewiseConstant | kIdempotent;
inline constexpr uint8_t kChoice = kCallable | kVariadic | kIdempotent;
inline constexpr uint8_t kTruth = kBoolean | kPiecewiseConstant;

// Indexed by Op.
// clang-format off
inline constexpr OpInfo kOps[] = {
    // op          name     arity notation      precedence        flags       jump
    {Op::kConst,   "const",    0, N::kLeaf,     kPrimary,         0,          Jump::kNone},
    {Op::kTime,    "t",        0, N::kLeaf,     kPrimary,         0,          Jump::kNone},
    {Op::kVar,     "var",      0, N::kLeaf,     kPrimary,         0,          Jump::kNone},
    {Op::kExtern,  "extern",   0, N::kLeaf,     kPrimary,         0,          Jump::kNone},
    {Op::kAdd,     "add",     -1, N::kSum,      kAdditive,        0,          Jump::kNone},
    {Op::kMul,     "mul",     -1, N::kProduct,  kMultiplicative,  0,          Jump::kNone},
    {Op::kPow,     "pow",      2, N::kPower,    kPower,           kFunction,  Jump::kNone},
    {Op::kSin,     "sin",      1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kCos,     "cos",      1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kTan,     "tan",      1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kAsin,    "asin",     1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kAcos,    "acos",     1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kAtan,    "atan",     1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kSinh,    "sinh",     1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kCosh,    "cosh",     1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kTanh,    "tanh",     1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kExp,     "exp",      1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kLog,     "log",      1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kSqrt,    "sqrt",     1, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kAbs,     "abs",      1, N::kCall,     kPrimary,         kKink,      Jump::kOperands},
    {Op::kFloor,   "floor",    1, N::kCall,     kPrimary,         kStep,      Jump::kIntegers},
    {Op::kCeil,    "ceil",     1, N::kCall,     kPrimary,         kStep,      Jump::kIntegers},
    {Op::kSign,    "sign",     1, N::kCall,     kPrimary,         kStep,      Jump::kOperands},
    {Op::kAtan2,   "atan2",    2, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kMin,     "min",      2, N::kCall,     kPrimary,         kChoice,    Jump::kDifference},
    {Op::kMax,     "max",      2, N::kCall,     kPrimary,         kChoice,    Jump::kDifference},
    {Op::kFmod,    "fmod",     2, N::kCall,     kPrimary,         kFunction,  Jump::kModulus},
    {Op::kHypot,   "hypot",    2, N::kCall,     kPrimary,         kFunction,  Jump::kNone},
    {Op::kLt,      "<",        2, N::kInfix,    kRelational,      kTruth,     Jump::kDifference},
    {Op::kLe,      "<=",       2, N::kInfix,    kRelational,      kTruth,     Jump::kDifference},
    {Op::kGt,      ">",        2, N::kInfix,    kRelational,      kTruth,     Jump::kDifference},
    {Op::kGe,      ">=",       2, N::kInfix,    kRelational,      kTruth,     Jump::kDifference},
    {Op::kEq,      "==",       2, N::kInfix,    kEquality,        kTruth,     Jump::kDifference},
    {Op::kNe,      "!=",       2, N::kInfix,    kEquality,        kTruth,     Jump::kDifference},
    {Op::kAnd,     "&&",       2, N::kInfix,    kAndPrec,         kTruth,     Jump::kOperands},
    {Op::kOr,      "||",       2, N::kInfix,    kOrPrec,          kTruth,     Jump::kOperands},
    {Op::kNot,     "!",        1, N::kPrefix,   kUnary,           kTruth,     Jump::kOperands},
    {Op::kSelect,  "select",   3, N::kSelect,   kTernary,         0,          Jump::kCondition},
};
// clang-format on

}  // namespace ops_detail

using ops_detail::kOps;

inline constexpr size_t kOpCount = std::size(kOps);

constexpr bool OpsInOrder() {
  for (size_t i = 0; i < kOpCount; ++i)
    if (static_cast<size_t>(kOps[i].op) != i) return false;
  return true;
}
static_assert(OpsInOrder(), "kOps must have one row per Op, in Op order");
static_assert(kOpCount == static_cast<size_t>(Op::kSelect) + 1,
              "kOps must cover every Op (kSelect is the last)");

constexpr const OpInfo& Info(Op op) { return kOps[static_cast<size_t>(op)]; }

// The callable operation named `name` in expression text, or nullptr.
constexpr const OpInfo* FindCallable(std::string_view name) {
  for (const OpInfo& info : kOps)
    if (info.Has(kCallable) && name == info.name) return &info;
  return nullptr;
}

}  // namespace asgard::expr
