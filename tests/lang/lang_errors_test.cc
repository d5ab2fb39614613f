// Scene language: a catalogue of bad inputs.  Each must evaluate without
// crashing or hanging and report an error at the expected place.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "core/lang/lang.h"

namespace asgard::lang {
namespace {

using scene::Scene;

constexpr const char* kBox = "shape_set box -desc {-sub {-box {1 1 1}}}\n";

struct BadInput {
  const char* name;
  std::string text;
  int line;          // expected line of the diagnostic
  int column;        // expected column, 0 = not checked
  const char* what;  // substring of the message
  // The evaluation's time limit.  Cases about a size or command limit get a
  // long one so that on a loaded machine (or under a sanitizer) the time
  // limit cannot be what stops them first.
  int time_limit_ms = 300;
};

constexpr int kOtherLimit = 20000;

std::string B(const char* rest) { return std::string(kBox) + rest; }

std::vector<BadInput> Catalogue() {
  return {
      {"UnknownCommand", B("nosuchcmd 1 2\nbody b1 -shape box\n"), 2, 1,
       "invalid command name \"nosuchcmd\""},
      {"UnknownOption", B("body b1 -shape box -foo 1\n"), 2, 20,
       "body: unknown option '-foo' (expected one of: -shape,"},
      {"MissingOptionValue", B("body b1 -shape box -init_pos\n"), 2, 20,
       "body: option '-init_pos' needs a value"},
      {"BodyWithoutShape", "body b1 -init_pos {1 2 3}\n", 1, 1, "missing required option -shape"},
      {"UnknownShape", "body b1 -shape nope\n", 1, 16, "unknown shape_set 'nope'"},
      {"UnknownBodyInLink", B("link -body1 zz -x 0\n"), 2, 13, "link: unknown body 'zz'"},
      {"UnknownBodyInForce", B("force -body qq -y 1\n"), 2, 13, "force: unknown body 'qq'"},
      {"NonNumericVector", B("body b1 -shape box -init_pos {a b c}\n"), 2, 30,
       "expects a number but got 'a'"},
      {"VectorOfWrongLength", B("body b1 -shape box -init_pos {1 2}\n"), 2, 30,
       "expects 3 numbers"},
      {"ZeroMass", B("body b1 -shape box -mass 0\n"), 2, 26, "must be greater than 0"},
      {"NegativeMass", B("body b1 -shape box -mass -1\n"), 2, 26, "must be greater than 0"},
      {"NanInVector", B("body b1 -shape box -init_pos {NaN 0 0}\n"), 2, 30,
       "must be a finite number"},
      {"InfInVector", B("body b1 -shape box -init_dpos {0 Inf 0}\n"), 2, 31,
       "must be a finite number"},
      {"ZeroQuaternion", B("body b1 -shape box -init_rot {0 0 0 0}\n"), 2, 30, "zero quaternion"},
      {"NegativeMoment", B("body b1 -shape box -moment -1\n"), 2, 28, "positive definite"},
      {"MomentBreakingTheTriangleInequality", B("body b1 -shape box -moment {1 1 5}\n"), 2, 28,
       "triangle inequality"},
      {"AsymmetricMoment", B("body b1 -shape box -moment {1 2 3 4 5 6 7 8 9}\n"), 2, 28,
       "symmetric"},
      {"SphereRadiusZero", "shape_set s -desc {-sub {-sphere 0}}\n", 1, 19,
       "radius must be greater than 0"},
      {"PieceWithThreePoints", "shape_set s -desc {-sub {-vertices {{0 0 0} {1 0 0} {0 1 0}}}}\n",
       1, 19, "at least 4 points, got 3"},
      {"UnknownDescKey", "shape_set s -desc {-sub {-cone 1}}\n", 1, 19, "unknown key '-cone'"},
      {"EndlessLoop", B("\nwhile 1 {}\nbody b1 -shape box\n"), 3, 1,
       "scene exceeded its time limit (0.3 s)"},
      {"EndlessCountingLoop", B("set i 0\nwhile 1 {incr i}\n"), 3, 0,
       "scene exceeded its command limit (100000 commands)", kOtherLimit},
      {"DeepRecursion", B("proc f {} {f}; f\n"), 2, 16, "too many nested evaluations"},
      {"UnbalancedOpenBrace", B("body b1 -shape box -init_pos {1 2\n  3\nset b 2\n"), 2, 30,
       "missing close-brace"},
      {"MissingCloseBracket", B("body b1 -shape box -init_pos [list 1 2 3\nset b 2\n"), 2, 30,
       "missing close-bracket"},
      {"ExtraCloseBracketAfterBrace", B("body b1 -shape box -init_pos {1 2 3}]\n"), 2, 37,
       "extra characters after close-brace"},
      {"ExtraCloseBracketAfterCommand", B("body b1 -shape box -init_pos [list 1 2 3]]\n"), 2, 30,
       "expects a number but got '3]'"},
      {"UnbalancedQuote", B("body b1 -shape \"box\n"), 2, 16, "missing close-quote"},
      {"DuplicateBodyName", B("body b1 -shape box\nbody b1 -shape box\n"), 3, 6,
       "'b1' is already defined at line 2"},
      {"TrajectoryWithDecreasingTimes", "trajectory tr -points {{0 1 2 3} {2 1 2 3} {1 0 0 0}}\n",
       1, 23, "times must increase strictly (point 3 has t=1 after t=2)"},
      {"TrajectoryWithoutPoints", "trajectory tr -points {}\n", 1, 23, "at least one"},
      {"TrajectoryStateWithoutBody", "trajectory tr -points {{0 0 0 0}} -state pos\n", 1, 42,
       "needs -body"},
      {"SimulatorFinishBeforeStart", "simulator -start 5 -finish 1\n", 1, 28,
       "-finish (1) must be greater than -start (5)"},
      {"InfiniteTimeSpan", "simulator -start -1e308 -finish 1e308\n", 1, 33, "is not finite"},
      {"UnresolvableTimeSpan", "simulator -start 1e300 -finish 1.0000000001e300\n", 1, 32,
       "too short to be resolved"},
      {"TooManyFrames", "simulator -finish 1e6 -frames 1e6\n", 1, 31,
       "frames (the time span 1e+06 times -frames 1e+06) is above the limit"},
      {"TooManyFramesByDefault", "simulator -finish 1e9\n", 1, 19, "is above the limit"},
      {"TinyMaxStep", "simulator -finish 10 -maxstep 1e-300\n", 1, 31,
       "would take more than 1e+09 steps"},
      {"ExecIsUnsafe", "exec ls\n", 1, 1, "invalid command name \"exec\""},
      {"OpenIsUnsafe", "open /etc/passwd\n", 1, 1, "invalid command name \"open\""},
      {"NestedInterpretersAreUnavailable", "interp create x\n", 1, 1,
       "invalid command name \"interp\""},
      {"HugeStringRepeat", "set x [string repeat x 1000000000]\n", 1, 8, "above the scene limit",
       kOtherLimit},
      {"HugeListRepeat", "set x [lrepeat 100000000 a]\n", 1, 8, "above the scene limit",
       kOtherLimit},
      {"DoublingString", "set s x\nwhile 1 {append s $s}\n", 2, 0, "above the scene limit",
       kOtherLimit},
      {"ConcatPastTheValueLimit",
       "set t [string repeat x 10000000]\nset all [concat {*}[lrepeat 300 $t]]\n", 2, 0,
       "lrepeat: the result would come to 3000000900 bytes as text", kOtherLimit},
      {"ConcatOfManyLargeArguments",
       "set t [string repeat x 10000000]\nset all [concat $t $t $t $t $t $t $t]\n", 2, 0,
       "the arguments of \"concat\" come to more than 64 MB in all", kOtherLimit},
      {"JoinWithAHugeSeparator",
       "set s [string repeat x 10000000]\nset l [lrepeat 1000 a]\nset j [join $l $s]\n", 3, 0,
       "the result of \"join\" could reach", kOtherLimit},
      {"StringMapBlowUp",
       "set s [string repeat a 10000000]\nset m [string map [list a [string repeat b 1000]] $s]\n",
       2, 0, "the result of \"string\" could reach", kOtherLimit},
      {"RegsubBlowUp",
       "set s [string repeat a 1000000]\nregsub -all a $s [string repeat & 300] r\n", 2, 0,
       "the result of \"regsub\" could reach", kOtherLimit},
      // Found by fuzz_scene: a NUL in the substitution spec ended the text
      // the bound read, which then saw no & (606 MB made, 3.4 s, exit 0).
      {"RegsubBlowUpBehindANul",
       std::string("set s [string repeat a 1000000]\nregsub -all a $s ") + '\0' +
           "[string repeat & 300] r\n",
       2, 0, "the result of \"regsub\" could reach", kOtherLimit},
      // The same class in the other bounds that read a value's text: a NUL
      // before a format width, regexp groups, split separators.
      {"HugeFormatWidthBehindANul", std::string("set s [format \"") + '\0' + "%900000000s\" x]\n",
       1, 0, "field width is above the scene limit", kOtherLimit},
      {"RegexpGroupsBehindANul",
       std::string("set s [string repeat x 2000000]\nset m [regexp -all -inline -- \"") + '\0' +
           "?(.)(.)\" $s]\n",
       2, 8, "the result of \"regexp\" could have 6000003 elements", kOtherLimit},
      {"SplitSeparatorsBehindANul",
       std::string("set s [string repeat \"x,\" 8000000]\nset l [split $s \"") + '\0' + ",\"]\n", 2,
       8, "the result of \"split\" could have 8000001 elements", kOtherLimit},
      {"NestedListsWhoseStringWouldBeHuge",
       "set l [lrepeat 4000 [lrepeat 4000 [string repeat x 1000]]]\nstring length $l\n", 1, 0,
       "lrepeat: the result would come to 16048012000 bytes as text, above the scene limit of "
       "64 MB",
       kOtherLimit},
      // Found by fuzz_scene (1.6 GB of text made inside one word's
      // substitution, 3.3 GB in all, before any check could run).
      {"RepeatedListSubstitutedIntoAWord",
       "set l [lrepeat 4000 [lrepeat 4000 [string repeat x 100]]0t]s\n", 1, 0,
       "lrepeat: the result would come to 1616016000 bytes as text", kOtherLimit},
      // Found by fuzz_scene: Tcl looks a command name up as a C string, so
      // "lrepeat" with NULs after it runs lrepeat; the guard compared the
      // whole word and let the 1.6 GB of text through.  Guards now know a
      // command by its token, under any name.
      {"RepeatedListBehindANulInItsName",
       std::string("set l [lrepeat") + std::string(3, '\0') +
           " 4000 [lrepeat 4000 [string repeat x 100]]]s\n",
       1, 0, "lrepeat: the result would come to 1648012000 bytes as text", kOtherLimit},
      {"RepeatedListUnderAnotherName",
       "rename lrepeat rep\nset l [rep 4000 [rep 4000 [string repeat x 100]]]s\n", 2, 0,
       "lrepeat: the result would come to 1648012000 bytes as text", kOtherLimit},
      {"StringMapBlowUpThroughItsNamespace",
       "set s [string repeat a 10000000]\n"
       "set m [::tcl::string::map [list a [string repeat b 1000]] $s]\n",
       2, 0, "could reach", kOtherLimit},
      {"HugeBinaryFormatThroughItsNamespace", "set s [::tcl::binary::format a900000000 x]\n", 1, 0,
       "field width is above the scene limit", kOtherLimit},
      {"HugeFormatWidth", "set s [format %900000000s x]\n", 1, 0, "above the scene limit",
       kOtherLimit},
      {"DeeplyNestedBrackets", "set x " + std::string(300, '[') + std::string(300, ']') + "\n", 1,
       263, "nested more than 256 deep"},
      {"DeeplyNestedBracketsBuiltAtRunTime",
       "set o [string repeat \"\\[\" 5000]\neval \"set x ${o}\"\n", 1, 0,
       "nested more than 256 deep"},
      {"BadCollisionFlag", B("body b1 -shape box -ct maybe\n"), 2, 24, "expects 0 or 1"},
      {"LinkWithTwoTargets",
       B("body a -shape box\nbody b -shape box\n"
         "link -body1 a -body2 b -x 0\n"),
       4, 1, "only one of -body2"},
      {"LinkToTheSameBody", B("body a -shape box\nlink -body1 a -body2 a\n"), 3, 22, "to itself"},
      {"BodyNameNotUsableInExpressions", B("body a.b -shape box\n"), 2, 6,
       "must be letters, digits and _"},
      {"BreakOutsideALoop", "break\n", 1, 1, "outside of a loop"},
      {"ForceOnABodyThatFailed", B("body a -shape box -mass 0\nforce -body a -y 1\n"), 3, 13,
       "body 'a' was not created because of an earlier error"},
      {"ZeroLightDirection", "lightsource -dir {0 0 0}\n", 1, 18, "zero vector"},
      {"ViewScaleZero", "view -scale 0\n", 1, 13, "must be greater than 0"},
      // View options given as expressions (seed 4.1.7): checked once every
      // body is known, each error at its component.
      {"ViewExpressionWithAnUnknownName", B("body b -shape box\nview -pos {0 0 {10 + q}}\n"), 3, 22,
       "view: in -pos component 3 expression '10 + q': unknown name 'q'"},
      {"ViewExpressionOfAnUnknownBody", B("view v -pos {{nobody.x} 0 0}\n"), 2, 15,
       "view 'v': in -pos component 1 expression 'nobody.x': unknown name 'nobody.x'"},
      {"ViewScaleExpressionCutShort", "view -scale {1 +}\n", 1, 17, "in -scale expression '1 +'"},
      {"ViewRotationExpressionOfTwoComponents", "view -rot {0 {t}}\n", 1, 11,
       "expects a rotation vector {x y z} or a quaternion {w x y z} (numbers or expressions of "
       "time and state), got 2 components"},
      {"OptionNameExpected", B("body b1 -shape box 12\n"), 2, 20, "expected an option name"},
      // Element options and their values.
      {"RestitutionAboveOne", B("body b1 -shape box -restitution 2\n"), 2, 33,
       "must be between 0 and 1"},
      {"Offset2WithoutBody2", B("body a -shape box\nlink -body1 a -offset2 {1 0 0} -x 0\n"), 3, 24,
       "needs -body2"},
      {"GravitationalTorque", B("body a -shape box\nforce -body a -torque 1 -gravitational 1\n"), 3,
       40, "cannot be used with -torque 1"},
      {"TrajectoryPointOfThreeNumbers", "trajectory tr -points {{0 1 2}}\n", 1, 23,
       "point 1 must be {t x y z}, got"},
      {"TrajectoryUnknownState",
       B("body b -shape box\ntrajectory tr -points {{0 0 0 0}} -body b -state vel\n"), 3, 50,
       "expects pos, rot, dpos or drot but got 'vel'"},
      {"TrajectoryFromWithoutBody", "trajectory tr -points {{0 0 0 0}} -from 1\n", 1, 41,
       "needs -body"},
      {"TrajectoryToBeforeFrom",
       B("body b -shape box\ntrajectory tr -points {{0 0 0 0}} -body b -state pos -from 2 -to 1\n"),
       3, 66, "must be greater than -from"},
      {"LightsourceUnknownType", "lightsource -type spot\n", 1, 19,
       "expects point or directional but got 'spot'"},
      {"ViewFollowAndTrajectory",
       B("body b -shape box\ntrajectory tr -points {{0 0 0 0}}\nview -follow b -trajectory tr\n"),
       4, 0, "give -follow or -trajectory, not both"},
      {"ShapeSetWithoutDesc", "shape_set s\n", 1, 1, "missing required option -desc"},
      {"TrajectoryWithoutPointsOption", "trajectory tr\n", 1, 1, "missing required option -points"},
      {"ForceWithoutBody", "force -y 1\n", 1, 1, "missing required option -body"},
      {"TorqueWithoutBody", "torque -x 1\n", 1, 1, "torque: missing required option -body"},
      {"LinkWithoutBody1", "link -x 0\n", 1, 1, "link: missing required option -body1"},
      {"BodyWithoutName", "body\n", 1, 1, "body: missing name (body NAME ?-option value ...?)"},
      {"BodyNamedLikeAConstant", B("body pi -shape box\n"), 2, 6,
       "name 'pi' is reserved in expressions"},
      {"EmptyForceExpression", B("body a -shape box\nforce -body a -y {}\n"), 3, 18,
       "needs an expression"},
      {"RotationOfTwoNumbers", B("body a -shape box -init_rot {1 2}\n"), 2, 29,
       "expects a rotation vector {x y z} or a quaternion {w x y z}, got"},
      {"MomentOfTwoNumbers", B("body a -shape box -moment {1 2}\n"), 2, 27,
       "expects 1, 3 or 9 numbers, got 2"},
      {"VectorThatIsNotAList", B("body a -shape box -init_pos \"\\{1 2 3\"\n"), 2, 29,
       "expects a list of numbers but got"},
      // Shape descriptions.
      {"FaceOfTwoPoints", "shape_set s -desc {-face {{0 0 0} {1 0 0}}}\n", 1, 19,
       "a -face needs at least 3 points, got 2"},
      {"BoxSideZero", "shape_set s -desc {-sub {-box {1 0 1}}}\n", 1, 19,
       "-box side lengths must be greater than 0"},
      {"NestedSub", "shape_set s -desc {-sub {-sub {-sphere 1}}}\n", 1, 19,
       "-sub cannot be nested"},
      {"DescKeyWithoutValue", "shape_set s -desc {-sub {-sphere}}\n", 1, 19,
       "key '-sphere' needs a value"},
      {"FaceColorWithoutValue", "shape_set s -desc {-face {{0 0 0} {1 0 0} {0 1 0} -color}}\n", 1,
       19, "-face: -color needs a value"},
      // Tcl commands that build far more than their arguments hold.
      {"SplitPastTheElementLimit", "set s [string repeat \"x,\" 8000000]\nset l [split $s ,]\n", 2,
       1, "the result of \"split\" could have 8000001 elements, above the scene limit of 4194304",
       kOtherLimit},
      {"SplitIntoCharactersPastTheElementLimit",
       "set s [string repeat ab 3000000]\nset l [split $s {}]\n", 2, 1,
       "the result of \"split\" could have 6000001 elements", kOtherLimit},
      {"RegexpAllInlinePastTheElementLimit",
       "set s [string repeat x 16000000]\nset m [regexp -all -inline . $s]\n", 2, 1,
       "the result of \"regexp\" could have 16000001 elements", kOtherLimit},
      {"RegexpAllInlineWithGroups",
       "set s [string repeat x 2000000]\nset m [regexp -all -inline -- {(.)(.)} $s]\n", 2, 1,
       "the result of \"regexp\" could have 6000003 elements", kOtherLimit},
      {"ListRepeatOfTwoValuesPastTheElementLimit", "set x [lrepeat 3000000 a b]\n", 1, 8,
       "lrepeat: result of 6000000 elements is above the scene limit", kOtherLimit},
      {"BinaryFormatHugeCount", "set x [binary format a900000000 x]\n", 1, 1,
       "field width is above the scene limit", kOtherLimit},
      {"FormatHugeStarWidth", "set x [format %*s 900000000 x]\n", 1, 1,
       "field width is above the scene limit", kOtherLimit},
      {"StringCatPastTheCommandLimit",
       "set s [string repeat x 16000000]\nset t [string cat $s $s $s $s $s]\n", 2, 1,
       "the arguments of \"string\" come to more than 64 MB in all", kOtherLimit},
      {"ListExpansionPastTheCommandLimit",
       "set l [lrepeat 3500000 xxxxxxxxxxxxxxx]\nset m [list {*}$l {*}$l]\n", 2, 1,
       "the arguments of \"list\" come to more than 64 MB in all", kOtherLimit},
      {"LmapPastTheCommandLimit",
       "set l [lrepeat 200000 a]\nset m [lmap x $l {string length $x}]\n", 2, 0,
       "scene exceeded its command limit (100000 commands)", kOtherLimit},
      {"ExponentTooLarge", "set x [expr {10**1000000000}]\n", 1, 8, "exponent too large"},
      // Big integers are computed inside one `expr`, out of reach of the time
      // limit: each would run for minutes (or, made into text, for hours).
      {"PowerPastTheIntegerLimit", "set x [expr {7**99999999}]\n", 1, 0,
       "an integer would have about 199999998 bits; the scene limit is 32768 bits"},
      {"ShiftPastTheIntegerLimit", "set x [expr {1<<99999999}]\nstring length $x\n", 1, 0,
       "the scene limit is 32768 bits"},
      {"LongIntegerLiteral", "set x [string repeat 9 1000000]\nset y [expr {$x+1}]\n", 2, 0,
       "the scene limit is 32768 bits"},
      {"RepeatedSquaringPastTheIntegerLimit", "set x 3\nwhile 1 {set x [expr {$x*$x}]}\n", 2, 0,
       "the scene limit is 32768 bits"},
      {"DivisionByZero", "set x [expr {1/0}]\n", 1, 8, "divide by zero"},
      // Commands a safe interpreter does not have.
      {"SocketIsUnsafe", "socket localhost 80\n", 1, 1, "invalid command name \"socket\""},
      {"SourceIsUnsafe", "source /etc/passwd\n", 1, 1, "invalid command name \"source\""},
      {"ExitIsUnsafe", "exit 3\n", 1, 1, "invalid command name \"exit\""},
      {"FileIsUnsafe", "file delete x\n", 1, 1, "invalid command name \"file\""},
      {"LoadIsUnsafe", "load libx.so\n", 1, 1, "invalid command name \"load\""},
      {"AfterIsUnavailable", "after 100000\n", 1, 1, "invalid command name \"after\""},
      {"GlobIsUnsafe", "glob *\n", 1, 1, "invalid command name \"glob\""},
      {"CdIsUnsafe", "cd /\n", 1, 1, "invalid command name \"cd\""},
      {"EncodingIsUnsafe", "encoding system\n", 1, 1, "invalid command name \"encoding\""},
  };
}

class LangBadInput : public ::testing::TestWithParam<BadInput> {};

void PrintTo(const BadInput& in, std::ostream* os) { *os << in.name; }

TEST_P(LangBadInput, ReportsAnErrorAtTheRightPlaceWithoutCrashing) {
  const BadInput& in = GetParam();
  EvalLimits limits;
  limits.command_limit = 100000;
  limits.time_limit_ms = in.time_limit_ms;
  auto start = std::chrono::steady_clock::now();
  Scene s = Evaluate(in.text, limits);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 3.0 + in.time_limit_ms / 1000.0);
  ASSERT_TRUE(s.has_errors()) << in.text;
  std::string all;
  bool found = false;
  for (const auto& d : s.diagnostics) {
    all += FormatDiagnostic("scene", d) + "\n";
    EXPECT_GT(d.span.line, 0) << d.message;
    EXPECT_GT(d.span.column, 0) << d.message;
    if (d.message.find(in.what) == std::string::npos) continue;
    if (d.span.line != in.line) continue;
    if (in.column != 0 && d.span.column != in.column) continue;
    found = true;
  }
  EXPECT_TRUE(found) << "expected line " << in.line << " col " << in.column << " '" << in.what
                     << "', got:\n"
                     << all;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, LangBadInput, ::testing::ValuesIn(Catalogue()),
                         [](const ::testing::TestParamInfo<BadInput>& info) {
                           return std::string(info.param.name);
                         });

// Integers below the limit are computed as Tcl computes them: the wrapped
// primitives forward.  3**20000 has ⌊20000 log10 3⌋ + 1 = 9543 digits.
TEST(LangLimits, LargeIntegersBelowTheLimitAreExact) {
  Scene s = Evaluate(
      "set x [expr {3**20000}]\n"
      "if {[string length $x] != 9543} {error \"length [string length $x]\"}\n"
      "if {[expr {$x % 1000}] != 1} {error \"last digits [expr {$x % 1000}]\"}\n"
      "if {[expr {2**200 * 2**200 == 2**400}] != 1} {error product}\n"
      "if {[expr {(1 << 30000) >> 29999}] != 2} {error shift}\n");
  EXPECT_FALSE(s.has_errors()) << (s.diagnostics.empty() ? "" : s.diagnostics[0].message);
}

// Copies of a big list add no string bytes, but they take memory: they are
// counted towards the memory check (they were not, and grew without bound).
TEST(LangLimits, ListCopiesCountTowardsTheMemoryLimit) {
  EvalLimits limits;
  limits.time_limit_ms = 20000;
  limits.memory_limit_mb = 256;
  Scene s =
      Evaluate("set l [lrepeat 4000000 a]\nwhile 1 {lappend all [lrange $l 0 end]}\n", limits);
  ASSERT_EQ(s.diagnostics.size(), 1u);
  EXPECT_EQ(s.diagnostics[0].message, "scene exceeded its memory limit (256 MB)");
  EXPECT_EQ(s.diagnostics[0].span.line, 2);
}

// A word built from many references to a large value passes Tcl's 2 GB
// value limit inside the substitution, before any command runs: Tcl panics,
// which used to abort the process.  It is now an error at the command.
TEST(LangLimits, AValuePastTclsMaximumSizeIsAnErrorNotAnAbort) {
  std::string text = "set s [string repeat x 16000000]\nset t \"";
  for (int i = 0; i < 140; ++i) text += "$s";
  text += "\"\nshape_set b -desc {-sub {-sphere 1}}\n";
  EvalLimits limits;
  limits.time_limit_ms = 30000;
  Scene s = Evaluate(text, limits);
  ASSERT_EQ(s.diagnostics.size(), 1u);
  EXPECT_NE(s.diagnostics[0].message.find("exceeded the limits of the Tcl interpreter"),
            std::string::npos)
      << s.diagnostics[0].message;
  EXPECT_EQ(s.diagnostics[0].span.line, 2);
  // The next evaluation runs in fresh interpreters as usual.
  Scene next = Evaluate("shape_set b -desc {-sub {-sphere 1}}\n", limits);
  EXPECT_FALSE(next.has_errors());
}

// The value limit is a parameter (the fuzzer runs with 1 MB, so that
// mutated scenes reach it in microseconds, not after making 16 MB): every
// bound derived from it follows, and one evaluation's limits do not reach
// the next's.
TEST(LangLimits, TheValueLimitIsAParameterThatEachEvaluationSets) {
  EvalLimits small;
  small.value_bytes = size_t{1} << 20;
  Scene fits = Evaluate("set s [string repeat x 1000000]\n", small);
  EXPECT_FALSE(fits.has_errors()) << (fits.diagnostics.empty() ? "" : fits.diagnostics[0].message);
  Scene refused = Evaluate("set x 1\nset s [string repeat x 1100000]\n", small);
  ASSERT_EQ(refused.diagnostics.size(), 1u);
  EXPECT_NE(refused.diagnostics[0].message.find("above the scene limit of 1 MB"), std::string::npos)
      << refused.diagnostics[0].message;
  EXPECT_EQ(refused.diagnostics[0].span.line, 2);
  // 4 MB of arguments to one command (4 × the value limit) are refused.
  Scene words = Evaluate("set s [string repeat x 900000]\nset l [list $s $s $s $s $s]\n", small);
  ASSERT_EQ(words.diagnostics.size(), 1u);
  EXPECT_NE(words.diagnostics[0].message.find("4 MB in all, above the scene limit"),
            std::string::npos)
      << words.diagnostics[0].message;
  // The default again: 16 MB.
  EXPECT_FALSE(Evaluate("set s [string repeat x 1100000]\n").has_errors());
}

// The split bound counts separators exactly: a long string with few of
// them (or a regexp without -inline) is not refused.
TEST(LangLimits, LongStringsWithFewPartsStillSplitAndMatch) {
  EvalLimits limits;
  limits.time_limit_ms = 20000;
  Scene s = Evaluate(
      "set s [string repeat x 6000000]\n"
      "if {[llength [split \"$s,a,b\" ,]] != 3} { error \"split gave the wrong count\" }\n"
      "if {[regexp -all x $s] != 6000000} { error \"regexp gave the wrong count\" }\n"
      "shape_set b -desc {-sub {-sphere 1}}\n",
      limits);
  EXPECT_FALSE(s.has_errors()) << (s.diagnostics.empty() ? "" : s.diagnostics[0].message);
  EXPECT_EQ(s.shape_sets.size(), 1u);
}

// A scene with one error: evaluation reports it, at `line`, and goes on
// (check reads what else the scene must give).
struct OneError {
  const char* name;
  std::string text;
  int line;
  std::function<void(const Scene& s)> check;
};

class LangOneError : public ::testing::TestWithParam<OneError> {};

void PrintTo(const OneError& c, std::ostream* os) { *os << c.name; }

TEST_P(LangOneError, IsReportedAndEvaluationGoesOn) {
  const OneError& c = GetParam();
  Scene s = Evaluate(c.text);
  ASSERT_EQ(s.diagnostics.size(), 1u);
  EXPECT_EQ(s.diagnostics[0].span.line, c.line);
  c.check(s);
}

std::vector<OneError> OneErrorCases() {
  return {
      {"ASceneWithABadBodyStillYieldsTheOtherBodies",
       B("body b1 -shape box -init_pos {1 0 0}\n"
         "body b2 -shape box -init_pos {oops 0 0}\n"
         "body b3 -shape box -init_pos {3 0 0}\n"),
       3,
       [](const Scene& s) {
         ASSERT_EQ(s.bodies.size(), 2u);
         EXPECT_EQ(s.bodies[0].name, "b1");
         EXPECT_EQ(s.bodies[1].name, "b3");
       }},
      {"AnErrorInALoopBodyDoesNotStopTheLoop",
       B("foreach m {1 0 2} {\n"
         "  body b$m -shape box -mass $m\n"
         "}\n"),
       3, [](const Scene& s) { EXPECT_EQ(s.bodies.size(), 2u); }},
      {"CommandsBeforeAParseErrorStillMakeElements",
       B("body b1 -shape box\n"
         "body b2 -shape box -init_pos {1 2 3\n"
         "body b3 -shape box\n"),
       3,
       [](const Scene& s) {
         EXPECT_EQ(s.diagnostics[0].span.column, 30);
         ASSERT_EQ(s.bodies.size(), 1u);
         EXPECT_EQ(s.bodies[0].name, "b1");
       }},
      {"ATclErrorAbortsOnlyItsOwnTopLevelCommand",
       B("foreach i {1 2 3} {\n"
         "  body b$i -shape box\n"
         "  if {$i == 2} { error \"stop here\" }\n"
         "}\n"
         "body after -shape box\n"),
       4,
       [](const Scene& s) {
         EXPECT_EQ(s.diagnostics[0].message, "stop here");
         EXPECT_EQ(s.bodies.size(), 3u);  // b1 b2 after
       }},
  };
}

INSTANTIATE_TEST_SUITE_P(Recovery, LangOneError, ::testing::ValuesIn(OneErrorCases()),
                         [](const ::testing::TestParamInfo<OneError>& info) {
                           return std::string(info.param.name);
                         });

TEST(LangRecovery, ManyErrorsAreCapped) {
  std::string text = "for {set i 0} {$i < 1000} {incr i} { body b$i -shape box -mass 0 }\n";
  Scene s = Evaluate(text);
  EXPECT_LE(s.diagnostics.size(), 201u);
  EXPECT_GE(s.diagnostics.size(), 200u);
}

// fuzz_scene once saw Tcl read past the end of a scene held in a buffer of
// exactly its size (AddressSanitizer: heap-buffer-overflow in
// Tcl_NewStringObj under Tcl_EvalEx; the input did not fail again alone, see
// docs/fuzzing.md).  Evaluate now hands Tcl a NUL-terminated copy.  Each
// text here sits in a buffer of exactly its size and ends inside an
// unfinished word; under AddressSanitizer a read past it fails the test.
TEST(LangRecovery, TextsThatEndWithoutANulAreNotReadPastTheirEnd) {
  const std::pair<std::string, int> cases[] = {
      {"set x \"abc", 1},
      {"set y {abc", 1},
      {"set z [list a", 1},
      {"body b1 -shape nope", 1},
      {"set w \"a\n\"\nset v \"\n", 3},
  };
  for (const auto& [text, line] : cases) {
    std::unique_ptr<char[]> exact(new char[text.size()]);
    std::memcpy(exact.get(), text.data(), text.size());
    Scene s = Evaluate(std::string_view(exact.get(), text.size()));
    ASSERT_TRUE(s.has_errors()) << text;
    EXPECT_EQ(s.diagnostics[0].span.line, line) << text;
  }
}

TEST(LangRecovery, EmptyAndCommentOnlyScenesAreFine) {
  EXPECT_TRUE(Evaluate("").diagnostics.empty());
  EXPECT_TRUE(Evaluate("# nothing here\n\n   \n").diagnostics.empty());
}

TEST(LangRecovery, BinaryAndOddTextDoesNotCrash) {
  std::string junk;
  for (int i = 0; i < 2000; ++i) junk.push_back(static_cast<char>((i * 7919) % 251 + 1));
  Scene s = Evaluate(junk);
  SUCCEED();
  std::string nul_text("body a -shape b\0c\n", 18);
  s = Evaluate(nul_text);
  EXPECT_TRUE(s.has_errors());
}

}  // namespace
}  // namespace asgard::lang
