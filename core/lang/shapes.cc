// shape_set NAME -desc DESC
//
// Design: DESC is a Tcl list of `-key value` pairs.  `-sub PIECE` adds an
// explicit piece; any other key at the top level goes to one implicit piece
// (this is how Figure 4.6 builds its box and rod: a run of `-face` items whose
// points all end up in a single hull).  Inside a piece:
//   -pos {x y z}        offset added to the piece's points / sphere centre
//   -sphere R           a sphere (R > 0) centred at -pos
//   -face {?-color C? P1 P2 P3 ...}   points added to the piece's hull
//   -vertices {P1 P2 ...}             points added to the piece's hull
//   -box {sx sy sz}     the 8 corners of an axis-aligned box centred at -pos
//   -color C            the piece's colour (else the first face colour)
// A piece is a sphere or a hull, never both; a hull needs at least 4 points.
// Whether the points span a volume is checked later by the geometry module.
// Errors name the piece and point at the -desc word.
#include <tcl.h>

#include <optional>

#include "core/lang/elements.h"
#include "core/lang/options.h"

namespace asgard::lang {
namespace {

class PieceBuilder {
 public:
  PieceBuilder(std::string context, int arg) : context_(std::move(context)), arg_(arg) {}

  [[noreturn]] void Fail(const std::string& what) const {
    throw ElementError{context_ + ": " + what, arg_};
  }

  void Apply(const std::string& key, Tcl_Obj* value) {
    if (key == "-pos") {
      pos_ = ToVec3(value, context_ + ": -pos", arg_);
    } else if (key == "-sphere") {
      if (sphere_) Fail("-sphere is given twice");
      sphere_ = ToNumber(value, context_ + ": -sphere", arg_);
    } else if (key == "-face") {
      AddFace(value);
    } else if (key == "-vertices") {
      for (Tcl_Obj* p : Elements(value, "-vertices")) AddPoint(p, "-vertices");
    } else if (key == "-box") {
      Vec3Box(ToVec3(value, context_ + ": -box", arg_));
    } else if (key == "-color") {
      color_ = ObjString(value);
    } else {
      Fail("unknown key '" + key + "' (expected one of: -sub, -pos, -sphere, -face, -vertices, " +
           "-box, -color)");
    }
  }

  bool HasGeometry() const { return sphere_.has_value() || !points_.empty(); }
  bool HasAnything() const { return HasGeometry() || pos_ || !color_.empty(); }

  scene::ShapePiece Build() const {
    scene::ShapePiece piece;
    scene::Vec3 pos = pos_.value_or(scene::Vec3{0, 0, 0});
    piece.color = color_.empty() ? face_color_ : color_;
    if (sphere_ && !points_.empty()) Fail("a piece is either a -sphere or a hull, not both");
    if (sphere_) {
      if (!(*sphere_ > 0)) Fail("-sphere radius must be greater than 0");
      piece.kind = scene::ShapePiece::Kind::kSphere;
      piece.radius = *sphere_;
      piece.center = pos;
      return piece;
    }
    if (points_.size() < 4) {
      Fail("a hull piece needs at least 4 points, got " + std::to_string(points_.size()));
    }
    piece.kind = scene::ShapePiece::Kind::kHull;
    for (scene::Vec3 p : points_) {
      for (int i = 0; i < 3; ++i) p[i] += pos[i];
      piece.points.push_back(p);
    }
    return piece;
  }

 private:
  std::vector<Tcl_Obj*> Elements(Tcl_Obj* value, const char* what) const {
    int n = 0;
    Tcl_Obj** elems = nullptr;
    if (Tcl_ListObjGetElements(nullptr, value, &n, &elems) != TCL_OK) {
      Fail(std::string(what) + " is not a valid list");
    }
    return std::vector<Tcl_Obj*>(elems, elems + n);
  }

  void AddPoint(Tcl_Obj* p, const char* what) {
    points_.push_back(ToVec3(p, context_ + ": " + what + " point", arg_));
  }

  void AddFace(Tcl_Obj* value) {
    std::vector<Tcl_Obj*> items = Elements(value, "-face");
    int count = 0;
    for (size_t i = 0; i < items.size(); ++i) {
      if (ObjString(items[i]) == "-color") {
        if (i + 1 >= items.size()) Fail("-face: -color needs a value");
        if (face_color_.empty()) face_color_ = ObjString(items[i + 1]);
        ++i;
        continue;
      }
      AddPoint(items[i], "-face");
      ++count;
    }
    if (count < 3) Fail("a -face needs at least 3 points, got " + std::to_string(count));
  }

  void Vec3Box(const scene::Vec3& size) {
    for (double s : size) {
      if (!(s > 0)) Fail("-box side lengths must be greater than 0");
    }
    for (int i = 0; i < 8; ++i) {
      points_.push_back({(i & 1 ? 0.5 : -0.5) * size[0], (i & 2 ? 0.5 : -0.5) * size[1],
                         (i & 4 ? 0.5 : -0.5) * size[2]});
    }
  }

  std::string context_;
  int arg_;
  std::optional<scene::Vec3> pos_;
  std::optional<double> sphere_;
  std::vector<scene::Vec3> points_;
  std::string color_;
  std::string face_color_;
};

std::vector<std::pair<std::string, Tcl_Obj*>> Pairs(Tcl_Obj* list, const PieceBuilder& where) {
  int n = 0;
  Tcl_Obj** elems = nullptr;
  if (Tcl_ListObjGetElements(nullptr, list, &n, &elems) != TCL_OK) {
    where.Fail("is not a valid list");
  }
  std::vector<std::pair<std::string, Tcl_Obj*>> out;
  for (int i = 0; i < n; i += 2) {
    std::string key = ObjString(elems[i]);
    if (key.empty() || key[0] != '-')
      where.Fail("expected a key (-sub, -face, ...) but got '" + key.substr(0, 40) + "'");
    if (i + 1 >= n) where.Fail("key '" + key + "' needs a value");
    out.emplace_back(key, elems[i + 1]);
  }
  return out;
}

}  // namespace

void ShapeSetCommand(EvalContext& ctx, const Invocation& inv, std::string& name) {
  name = RequireName(inv, false);
  Options o(inv, 2, {"desc"});
  for (const auto& s : ctx.scene.shape_sets) {
    if (s.name == name) {
      throw ElementError{
          "shape_set: '" + name + "' is already defined" +
              (s.command.known() ? " at line " + std::to_string(s.command.line) : std::string()),
          1};
    }
  }
  const OptionValue* desc = o.Get("desc");
  if (desc == nullptr) {
    throw ElementError{"shape_set '" + name + "': missing required option -desc", -1};
  }
  const std::string context = "shape_set '" + name + "': -desc";
  PieceBuilder implicit(context, desc->arg);
  std::vector<scene::ShapePiece> pieces;
  int sub_count = 0;
  for (const auto& [key, value] : Pairs(desc->obj, implicit)) {
    if (key == "-sub") {
      ++sub_count;
      PieceBuilder piece(context + " piece " + std::to_string(sub_count), desc->arg);
      for (const auto& [k, v] : Pairs(value, piece)) {
        if (k == "-sub") piece.Fail("-sub cannot be nested");
        piece.Apply(k, v);
      }
      pieces.push_back(piece.Build());
    } else {
      implicit.Apply(key, value);
    }
  }
  if (implicit.HasGeometry()) {
    pieces.insert(pieces.begin(), implicit.Build());
  } else if (implicit.HasAnything()) {
    implicit.Fail(
        "-pos/-color outside -sub apply to top-level -face/-vertices/-box/-sphere, "
        "but there are none");
  }
  if (pieces.empty()) implicit.Fail("describes no pieces");
  scene::ShapeSet s;
  FillBase(inv, s);
  s.name = name;
  s.pieces = std::move(pieces);
  RecordOptions(inv, o, s);
  ctx.scene.shape_sets.push_back(std::move(s));
}

}  // namespace asgard::lang
