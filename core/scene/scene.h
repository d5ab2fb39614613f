// Scene elements: what a scene script describes, as plain data.
//
// The language module (core/lang) evaluates a scene script and produces a
// Scene; the physics module turns a Scene into state equations; the editing
// model compares two Scenes.  Nothing here knows about Tcl or about solving.
//
//   scene text ──lang::Evaluate──▶ Scene ──physics::FormEquations──▶ equations
//                                    │
//                                    └── every element keeps where it came from
//                                        (SourceSpan) and how often its command
//                                        ran, so that edits can be written back
//
// Conventions (docs/language.md is the user-facing description):
//   * lengths, masses and times are in the scene's own units; angles in radians;
//   * a body's position is the world position of its shape's origin at t=0
//     (-init_pos); its state variables track the centre of mass;
//   * rotations are rotation vectors (axis × angle) or unit quaternions {w x y z};
//   * force, torque and link-point components are expression texts
//     (core/expr syntax), resolved when equations are formed.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/protocol/protocol.h"

namespace asgard::scene {

using Vec3 = std::array<double, 3>;
using Quat = std::array<double, 4>;  // w, x, y, z

// A range of the scene text.  Offsets are bytes from the start of the text,
// end exclusive; line and column (1-based, column counted in bytes) locate
// `begin`.  A default span (line 0) means "location unknown".
struct SourceSpan {
  int begin = 0;
  int end = 0;
  int line = 0;
  int column = 0;

  bool known() const { return line > 0; }
};

// One option value as it appears in the source.
//   text     the value after Tcl substitution (what the element uses)
//   span     where the word is in the source, when it could be located
//   literal  the source word is a plain literal (number or braced/quoted list
//            of numbers with no substitution), so it can be rewritten in place
//   reason   when not literal: why ("computed by an expression", ...)
struct Word {
  std::string text;
  SourceSpan span;
  bool literal = false;
  std::string reason;
};

enum class ElementKind : uint8_t {
  kSimulator,
  kShapeSet,
  kBody,
  kLink,
  kForce,
  kTorque,
  kTrajectory,
  kLightSource,
  kView,
};

const char* ElementKindName(ElementKind kind);

// What every element shares.
//   command    span of the whole command that made it (innermost element
//              command as written in the source, e.g. inside a proc body)
//   call_site  span of the outermost top-level command whose evaluation made
//              it (the `foreach` or proc call); equals `command` when the
//              element command stands at top level
//   run_count  how many times the command at `command` ran in this evaluation
//   in_proc / in_eval  the command was run from a proc body / through eval
//   options    every option as given, by name without the dash ("init_pos")
struct ElementBase {
  std::string name;  // empty for unnamed elements (forces, links, ...)
  SourceSpan command;
  SourceSpan call_site;
  int run_count = 1;
  bool in_proc = false;
  bool in_eval = false;
  std::vector<std::pair<std::string, Word>> options;

  const Word* option(const std::string& key) const;
};

// simulator -start T0 -finish T1 -step H0 -maxstep H -rtol R -atol A
//           -collisions 0|1 -frames F
struct Simulator : ElementBase {
  double start = 0.0;
  double finish = 10.0;
  std::optional<double> step;  // initial step; default chosen by the solver
  std::optional<double> max_step;
  std::optional<double> rtol;
  std::optional<double> atol;
  bool collisions = true;
  double frame_rate = protocol::kDefaultFrameRate;  // output sampling for trajectories and movies
};

// One convex piece of a shape set, in shape coordinates.
struct ShapePiece {
  enum class Kind : uint8_t { kSphere, kHull };
  Kind kind = Kind::kHull;
  Vec3 center{0, 0, 0};      // sphere centre (kSphere)
  double radius = 0.0;       // sphere radius (kSphere)
  std::vector<Vec3> points;  // hull input points (kHull), already offset by -pos
  std::string color;         // optional per-piece colour
};

// shape_set NAME -desc DESC
struct ShapeSet : ElementBase {
  std::vector<ShapePiece> pieces;
};

// body NAME -shape S ?-artbody A? ?-init_pos V? ?-init_rot R? ?-init_dpos V?
//      ?-init_drot V? ?-mass M? ?-moment I? ?-color C? ?-ct 0|1?
//      ?-restitution E? ?-friction MU? ?-static 0|1?
struct Body : ElementBase {
  std::string shape;
  std::string artbody;
  Vec3 init_pos{0, 0, 0};
  Quat init_rot{1, 0, 0, 0};  // normalised
  Vec3 init_dpos{0, 0, 0};
  Vec3 init_drot{0, 0, 0};  // world-frame angular velocity
  std::optional<double> mass;
  // Moment of inertia about the centre of mass, in shape axes: a scalar
  // (isotropic), three principal values, or a full row-major 3x3 tensor.
  std::optional<std::array<double, 9>> moment;
  std::string color;
  bool collision_test = true;  // -ct
  std::optional<double> restitution;
  std::optional<double> friction;  // Coulomb coefficient at impacts (default 0)
  bool is_static = false;
};

// Link: joins a point on body1 to
//   (a) a point on body2                     -body2 B -offset2 V
//   (b) a fixed point or expression point    -x EX -y EY -z EZ
//   (c) a trajectory                         -trajectory T
// exactly (a ball joint) by default, or with -tightness K as the seed's
// critically damped zero-length spring of constant K.
struct Link : ElementBase {
  std::string body1;
  Vec3 offset1{0, 0, 0};
  std::string body2;
  Vec3 offset2{0, 0, 0};
  std::array<std::string, 3> point{"0", "0", "0"};  // expressions (case b)
  std::string trajectory;
  double tightness = 0.0;  // 0 (no -tightness): an exact joint; else a spring constant
};

// force -body B -x EX -y EY -z EZ ?-offset V? ?-gravitational 0|1? ?-torque 0|1?
//   -gravitational 1 multiplies the vector by the body's mass.
//   -torque 1 makes this a torque (the seed's `force -torque` form).
struct Force : ElementBase {
  std::string body;
  std::array<std::string, 3> components{"0", "0", "0"};
  std::optional<Vec3> offset;  // point of application in shape coordinates
  bool gravitational = false;
};

// torque -body B -x EX -y EY -z EZ ?-offset V?
//   With -offset the torque acts about an axis through that point (shape
//   coordinates); the induced force d × T is added (seed 5.1.1).
struct Torque : ElementBase {
  std::string body;
  std::array<std::string, 3> components{"0", "0", "0"};
  std::optional<Vec3> offset;
};

// trajectory NAME -points {{t x y z} ...} ?-body B -state pos|rot|dpos|drot?
//            ?-from T0? ?-to T1?
// The curve passes through each point at its time; consecutive points are
// joined by cubic Bézier segments (C1, Catmull–Rom tangents).  Outside its
// knots a trajectory extrapolates linearly.  When attached to a body it
// prescribes that state over [from, to] (default: first to last knot time).
struct TrajectoryKnot {
  double t = 0.0;
  Vec3 p{0, 0, 0};
};
struct Trajectory : ElementBase {
  enum class State : uint8_t { kNone, kPos, kRot, kDpos, kDrot };
  std::vector<TrajectoryKnot> knots;
  std::string body;
  State state = State::kNone;
  std::optional<double> from;
  std::optional<double> to;
};

// lightsource ?NAME? -type point|directional -pos V -dir V -color C -intensity I
struct LightSource : ElementBase {
  enum class Type : uint8_t { kDirectional, kPoint };
  Type type = Type::kDirectional;
  Vec3 position{0, 0, 10};
  Vec3 direction{0, 0, -1};
  std::string color = "white";
  double intensity = 1.0;
};

// view ?NAME? -pos V -rot R -scale S -center V ?-follow BODY? ?-trajectory T?
//   -follow / -trajectory tie the centre of rotation and scaling to a body's
//   centre of mass or a trajectory's value over time (camera motion, seed 4.1.7).
//   -pos, -rot and -scale may also be expressions of time and state (core/expr
//   syntax, the names of force expressions): -pos a list of three component
//   texts ({0 0 {10 + t}}), -rot of three (rotation vector) or four
//   (quaternion), -scale one text.  Such an option keeps its texts in the
//   *_expr member (numbers among them stay texts) and is evaluated at every
//   frame by whoever draws the view; its constant member keeps the default.
struct View : ElementBase {
  Vec3 position{0, 0, 0};
  Quat rotation{1, 0, 0, 0};
  double scale = 1.0;
  std::optional<Vec3> center;
  std::string follow;
  std::string trajectory;
  std::vector<std::string> position_expr;  // empty, or 3 texts
  std::vector<std::string> rotation_expr;  // empty, or 3 or 4 texts
  std::string scale_expr;                  // empty: -scale is `scale`

  bool animated() const {
    return !position_expr.empty() || !rotation_expr.empty() || !scale_expr.empty();
  }
};

enum class Severity : uint8_t { kError, kWarning };

// A problem found while evaluating a scene.  `span` is the narrowest known
// range (the offending word when known, else the command).
struct Diagnostic {
  Severity severity = Severity::kError;
  std::string message;
  SourceSpan span;
};

struct Scene {
  std::optional<Simulator> simulator;  // the last `simulator` command wins
  std::vector<ShapeSet> shape_sets;
  std::vector<Body> bodies;
  std::vector<Link> links;
  std::vector<Force> forces;
  std::vector<Torque> torques;
  std::vector<Trajectory> trajectories;
  std::vector<LightSource> lights;
  std::vector<View> views;
  std::vector<Diagnostic> diagnostics;

  bool has_errors() const;
  const ShapeSet* FindShapeSet(const std::string& name) const;
  const Body* FindBody(const std::string& name) const;
  const Trajectory* FindTrajectory(const std::string& name) const;
};

}  // namespace asgard::scene
