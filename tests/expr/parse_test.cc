// Parser: Tcl compatibility, printing round trips, errors and fuzzing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "core/expr/expr.h"
#include "tests/expr/test_util.h"

namespace asgard::expr {
namespace {

using testing::EvalTape;
using testing::P;

struct TclCase {
  const char* text;
  double expected;
};

// Expected values computed by Tcl 8.6.13 (`puts [expr {...}]` in tclsh).  The
// table avoids Tcl's integer division (all divisions have a real operand).
// Note Tcl's precedence: unary minus binds tighter than **, so -2**2 is 4.
constexpr TclCase kTclCases[] = {
    {"-2**2", 4},
    {"2**3**2", 512},
    {"2**-2**2", 16},
    {"-2.0**-2", 0.25},
    {"2*-2**2", 8},
    {"-1**2", 1},
    {"-(1**2)", -1},
    {"!0+1", 2},
    {"!2", 0},
    {"!!3", 1},
    {"!1==0", 1},
    {"-7%3", 2},
    {"7%-3", -2},
    {"-7%-3", -1},
    {"7%3", 1},
    {"5 % 3 * 2", 4},
    {"2 * 5 % 3", 1},
    {"17 % 5 % 3", 2},
    {"1-2-3", -4},
    {"8.0/2/2", 2.0},
    {"2*3+4*5", 26},
    {"1+2*3**2", 19},
    {"2-3*4+5", -5},
    {"3-2+1", 2},
    {"1-(2-3)", 2},
    {"1 - -1", 2},
    {"2.0*3/4", 1.5},
    {"1/4.0*2", 0.5},
    {"1<2==1", 1},
    {"1==1<2", 1},
    {"3>2>1", 0},
    {"5>4>=4", 0},
    {"1!=2==1", 1},
    {"1 < 2 < 3", 1},
    {"1||0&&0", 1},
    {"0&&1||1", 1},
    {"0||0||3", 1},
    {"2&&3", 1},
    {"1?2:3?4:5", 2},
    {"0?2:0?4:5", 5},
    {"1+2<4?10:20", 10},
    {"1-1?5:6", 6},
    {"2>1?3>4?5:6:7", 6},
    {"0?1:2+3", 5},
    {"--3", 3},
    {"-+-3", 3},
    {"-(2)**2", 4},
    {"2**0.5", 1.4142135623730951},
    {"2**2**-1.0", 1.4142135623730951},
    {"2.0**-1", 0.5},
    {"1.5+2.5e1", 26.5},
    {"1e-3*1000", 1.0},
    {".5*4", 2.0},
    {"sin(1)+cos(2)*2", 0.009177311713611691},
    {"atan2(1,2)", 0.4636476090008061},
    {"hypot(3,4)", 5.0},
    {"fmod(7.5,2)", 1.5},
    {"fmod(-7.5,2)", -1.5},
    {"pow(2,10)", 1024.0},
    {"abs(-3.5)", 3.5},
    {"floor(-2.5)", -3.0},
    {"ceil(-2.5)", -2.0},
    {"min(3,1,2)", 1},
    {"max(3,1,2)", 3},
    {"exp(1)", 2.718281828459045},
    {"log(10)", 2.302585092994046},
    {"sqrt(2)", 1.4142135623730951},
    {"tanh(0.5)", 0.46211715726000974},
    {"-sqrt(4)**2", 4.0},
    {"2**3*2", 16},
    {"2*3**2", 18},
    {"-3**2*2", 18},
    {"10.0-2**3/4.0", 8.0},
};

TEST(Parse, PrecedenceAndAssociativityMatchTcl) {
  Pool pool;
  for (const TclCase& c : kTclCases) {
    const NodeId e = P(pool, c.text);
    ASSERT_TRUE(pool.IsConst(e)) << c.text;
    EXPECT_NEAR(*pool.ConstValue(e), c.expected, 1e-15 * std::fabs(c.expected)) << c.text;
    // The same through variables (no constant folding): x = 1.
    std::string with_var = std::string("x*(") + c.text + ")";
    const NodeId v = P(pool, with_var);
    EXPECT_NEAR(EvalTape(pool, v, 0.0, {1.0}), c.expected, 1e-15 * std::fabs(c.expected))
        << with_var;
  }
}

TEST(Parse, ModMatchesTclSignConventionForVariableOperands) {
  Pool pool;
  const NodeId e = P(pool, "x % y");
  // Values from tclsh: -7%3 = 2, 7%-3 = -2, -7%-3 = -1, 7%3 = 1, 6%3 = 0.
  EXPECT_EQ(EvalTape(pool, e, 0, {-7, 3}), 2.0);
  EXPECT_EQ(EvalTape(pool, e, 0, {7, -3}), -2.0);
  EXPECT_EQ(EvalTape(pool, e, 0, {-7, -3}), -1.0);
  EXPECT_EQ(EvalTape(pool, e, 0, {7, 3}), 1.0);
  EXPECT_EQ(EvalTape(pool, e, 0, {6, 3}), 0.0);
  EXPECT_EQ(EvalTape(pool, P(pool, "x % 49"), 0, {49}), 0.0);
}

TEST(Parse, BuiltInNamesNumbersAndDottedNames) {
  Pool pool;
  EXPECT_EQ(P(pool, "t"), pool.Time());
  EXPECT_EQ(pool.ConstValue(P(pool, "pi")), std::numbers::pi);
  EXPECT_EQ(pool.ConstValue(P(pool, "e")), std::numbers::e);
  EXPECT_EQ(pool.ConstValue(P(pool, "2*e")), 2 * std::numbers::e);
  EXPECT_EQ(pool.ConstValue(P(pool, "1e-3")), 1e-3);
  EXPECT_EQ(pool.ConstValue(P(pool, "1E+3")), 1e3);
  EXPECT_EQ(pool.ConstValue(P(pool, "2.5e2")), 250.0);
  EXPECT_EQ(pool.ConstValue(P(pool, "1.")), 1.0);
  EXPECT_EQ(pool.ConstValue(P(pool, "1e-400")), 0.0);
  EXPECT_TRUE(std::isinf(*pool.ConstValue(P(pool, "1e999"))));
  EXPECT_EQ(pool.ConstValue(P(pool, "g")), 9.81);
  EXPECT_EQ(P(pool, "b1.x"), pool.Var(3));
  EXPECT_EQ(P(pool, "tr1.dy"), pool.Var(5));
  EXPECT_EQ(P(pool, " \t\n x \n"), pool.Var(0));
  EXPECT_EQ(P(pool, "pow(x, y)"), pool.Pow(pool.Var(0), pool.Var(1)));
  // The resolver sees the full dotted name and nothing built in.
  std::vector<std::string> seen;
  Resolver spy = [&](std::string_view name, Pool& p) -> std::optional<NodeId> {
    seen.emplace_back(name);
    return p.Var(static_cast<int>(seen.size()));
  };
  Parse("a.b.c + t*pi*e + _x1", pool, spy);
  EXPECT_EQ(seen, (std::vector<std::string>{"a.b.c", "_x1"}));
}

const char* const kRoundTrip[] = {
    "x + y*z",
    "(x + y)*z",
    "x - y - z",
    "x - (y - z)",
    "-x",
    "-(x**2)",
    "(-x)**2",
    "x**y**z",
    "(x**y)**z",
    "x**-2",
    "x**-0.5",
    "2*x/(y*z**2)",
    "-3*x*y",
    "1/x",
    "-1/x",
    "x/y + 0.1",
    "sin(x)**2 + cos(x)**2",
    "atan2(y, x) - hypot(x, 2)",
    "x < y == (y < x)",
    "x < y && y <= z || !(x != z)",
    "!x + !!(x > 1)",
    "x > 1 ? y : z > 2 ? 1 : 2",
    "(x ? y : z) ? 1 : 2",
    "x ? (y ? 1 : 2) : 3",
    "x % 3 + fmod(y, -2)",
    "min(x, y, z) + max(x, 1)",
    "ext0 + 2*ext1.d2 - t",
    "floor(t/0.5) + ceil(t) + sign(t - 1) + abs(-t)",
    "exp(-x) + log(y) + sqrt(z) + sinh(x) + cosh(y) + tanh(z) + asin(x) + acos(y) + atan(z)",
    "1e-20*x + 1e+300*y",
    "1/0*x + (0/0)*y",
    "(x - 1)**0.5 + (2*x)**-1.5 + 3**x + (-2)**x",
    "-(x + y)*z",
    "-x**2*y",
    "x*(y > 1) - (z < 2)*3",
};

TEST(Parse, PrintedTextParsesBackToTheSameNode) {
  Pool pool;
  for (const char* text : kRoundTrip) {
    const NodeId e = P(pool, text);
    const std::string printed = pool.ToString(e);
    NodeId again = 0;
    ASSERT_NO_THROW(again = P(pool, printed)) << text << " printed as " << printed;
    EXPECT_EQ(again, e) << text << " printed as " << printed;
    EXPECT_EQ(pool.ToString(again), printed);
  }
}

TEST(Parse, PrintingIsReadableWithMinimalParentheses) {
  Pool pool;
  const NodeId x = pool.Var(0);
  pool.Var(1);
  EXPECT_EQ(pool.ToString(P(pool, "x - y")), "x0 - x1");
  EXPECT_EQ(pool.ToString(P(pool, "x + 1")), "x0 + 1");
  EXPECT_EQ(pool.ToString(P(pool, "1 - x")), "-x0 + 1");
  EXPECT_EQ(pool.ToString(P(pool, "-(x**2)")), "-(x0**2)");
  EXPECT_EQ(pool.ToString(P(pool, "(-x)**0.5")), "(-x0)**0.5");
  EXPECT_EQ(pool.ToString(P(pool, "(-x)**2")), "x0**2");
  EXPECT_EQ(pool.ToString(P(pool, "2*x/y**2")), "2*x0/x1**2");
  EXPECT_EQ(pool.ToString(P(pool, "(x + 1)*y")), "x1*(x0 + 1)");  // factors in id order
  EXPECT_EQ(pool.ToString(P(pool, "sin(x)")), "sin(x0)");
  EXPECT_EQ(pool.ToString(P(pool, "x < y ? 1 : 2")), "x0 < x1 ? 1 : 2");
  EXPECT_EQ(pool.ToString(P(pool, "t")), "t");
  EXPECT_EQ(pool.ToString(pool.Extern(1, 2)), "ext1.d2");
  EXPECT_EQ(pool.ToString(x, [](int i) { return "q" + std::to_string(i); }), "q0");
  EXPECT_EQ(pool.ToString(pool.Const(0.1)), "0.1");
  EXPECT_EQ(pool.ToString(pool.Const(-2.5)), "-2.5");
}

struct ErrorCase {
  const char* text;
  const char* message;  // substring of the message
  int offset;
};

const ErrorCase kErrors[] = {
    {"", "empty expression", 0},
    {"   ", "empty expression", 0},
    {"b9.x + 1", "unknown name 'b9.x'", 0},
    {"1 + b9.x", "unknown name 'b9.x'", 4},
    {"(x + 1", "expected ')'", 6},
    {"sin(x", "expected ')'", 5},
    {"sin(x, y)", "function 'sin' takes 1 argument", 0},
    {"2*atan2(x)", "function 'atan2' takes 2 arguments", 2},
    {"min()", "function 'min' takes at least 1 argument", 0},
    {"x +", "unexpected end of expression", 3},
    {"x + * y", "unexpected '*'", 4},
    {"x y", "unexpected 'y'", 2},
    {"x)", "unexpected ')'", 1},
    {"foo(1)", "unknown function 'foo'", 0},
    {"t(1)", "unknown function 't'", 0},
    {"1 ? 2", "expected ':'", 5},
    {"x = 1", "unexpected character '='", 2},
    {"x & y", "unexpected character '&'", 2},
    {"x | y", "unexpected character '|'", 2},
    {"x # y", "unexpected character '#'", 2},
    {"2x", "malformed number '2x'", 0},
    {"1.2.3", "malformed number", 0},
    {"x + 1e", "malformed number '1e'", 4},
    {"x.", "unexpected character '.'", 1},
    {"nan", "unknown name 'nan'", 0},
    {"inf", "unknown name 'inf'", 0},
    {"()", "unexpected ')'", 1},
    {"sin", "unknown name 'sin'", 0},
    {"x\x01", "unexpected character byte 0x01", 1},
};

TEST(Parse, ErrorsCarryAMessageAndTheOffsetOfTheOffendingToken) {
  Pool pool;
  for (const ErrorCase& c : kErrors) {
    try {
      P(pool, c.text);
      ADD_FAILURE() << "no error for '" << c.text << "'";
    } catch (const ParseError& err) {
      EXPECT_NE(std::string(err.what()).find(c.message), std::string::npos)
          << "'" << c.text << "': " << err.what();
      EXPECT_EQ(err.offset(), c.offset) << "'" << c.text << "': " << err.what();
    }
  }
}

TEST(Parse, NullResolverOnlyKnowsBuiltIns) {
  Pool pool;
  EXPECT_EQ(Parse("t*pi", pool, Resolver{}), pool.Mul(pool.Time(), pool.Const(std::numbers::pi)));
  EXPECT_THROW(Parse("x", pool, Resolver{}), ParseError);
}

TEST(Parse, DeepNestingIsRejectedWithAClearError) {
  Pool pool;
  auto nested = [](int depth, const std::string& open, const std::string& close) {
    std::string s;
    for (int i = 0; i < depth; ++i) s += open;
    s += "x";
    for (int i = 0; i < depth; ++i) s += close;
    return s;
  };
  EXPECT_NO_THROW(P(pool, nested(150, "(", ")")));
  EXPECT_NO_THROW(P(pool, nested(150, "sin(", ")")));
  for (const auto& text :
       {nested(100000, "(", ")"), nested(100000, "-", ""), nested(100000, "sin(", ")"),
        nested(100000, "x**", ""), nested(100000, "1?", ":2")}) {
    try {
      P(pool, text);
      ADD_FAILURE() << "deep nesting accepted";
    } catch (const ParseError& err) {
      EXPECT_NE(std::string(err.what()).find("nested too deeply"), std::string::npos);
    }
  }
  // Long flat chains are not nesting.
  std::string chain = "x";
  for (int i = 0; i < 20000; ++i) chain += (i % 2 ? " + x" : " * y");
  EXPECT_NO_THROW(P(pool, chain));
  std::string compare = "x";
  for (int i = 0; i < 20000; ++i) compare += " < y";
  const NodeId deep = P(pool, compare);
  EXPECT_FALSE(pool.ToString(deep).empty());  // printing is iterative
  EXPECT_EQ(pool.Derivative(deep, 0), pool.Const(0));
}

// Parses `text`; a successful parse must print and re-parse to the same node
// and evaluate without crashing.
void CheckSurvives(Pool& pool, const std::string& text) {
  NodeId e;
  try {
    e = P(pool, text);
  } catch (const ParseError& err) {
    EXPECT_GE(err.offset(), 0);
    EXPECT_LE(err.offset(), static_cast<int>(text.size()));
    return;
  }
  const std::string printed = pool.ToString(e);
  NodeId again = 0;
  ASSERT_NO_THROW(again = P(pool, printed)) << text << " -> " << printed;
  EXPECT_EQ(again, e) << text << " -> " << printed;
  const std::vector<int> vars = pool.Variables(e);
  std::vector<double> x(vars.empty() ? 0 : vars.back() + 1, 0.25);
  EvalTape(pool, e, 0.5, x);
  pool.Derivative(e, 0);
  pool.TimeBreakpoints(e, 0, 10);
}

TEST(Parse, RandomBytesNeverCrashOrHang) {
  Pool pool;
  std::mt19937 rng(42);
  const std::string printable = "0123456789.eE+-*/%!<>=&|?:(),xyztb1._ \t";
  for (int i = 0; i < 20000; ++i) {
    std::string text;
    const int len = std::uniform_int_distribution<int>(0, 24)(rng);
    for (int k = 0; k < len; ++k) {
      if (rng() % 2)
        text += static_cast<char>(rng() % 256);
      else
        text += printable[rng() % printable.size()];
    }
    CheckSurvives(pool, text);
  }
}

TEST(Parse, RandomTokenSoupsNeverCrashOrHang) {
  Pool pool;
  std::mt19937 rng(43);
  const char* const tokens[] = {
      "x",       "y",    "z",     "t",      "pi",    "e",    "b1.x",   "tr1.dy", "ext0",
      "ext1.d1", "1",    "2.5",   "1e-3",   "0",     "(",    ")",      "(",      ")",
      ",",       "+",    "-",     "*",      "/",     "%",    "**",     "!",      "<",
      "<=",      ">",    ">=",    "==",     "!=",    "&&",   "||",     "?",      ":",
      "sin(",    "min(", "pow(",  "atan2(", "fmod(", "abs(", "floor(", "b9.x",   "sign(",
      "hypot(",  "log(", "sqrt(", "max(",   "exp(",  " ",    "1e308",  "3"};
  for (int i = 0; i < 20000; ++i) {
    std::string text;
    const int len = std::uniform_int_distribution<int>(1, 16)(rng);
    for (int k = 0; k < len; ++k) text += tokens[rng() % std::size(tokens)];
    CheckSurvives(pool, text);
  }
}

}  // namespace
}  // namespace asgard::expr
