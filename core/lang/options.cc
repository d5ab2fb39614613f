// Option parsing and value conversion.
//
// Design: an element command first splits its arguments into `-name value`
// pairs against a fixed list of allowed names (unknown names and missing
// values are errors pointing at the option word).  Typed getters convert a
// value on demand with Tcl's own number parser (so `1e-3`, `0x10` and Tcl's
// list quoting behave as in any Tcl script) and reject non-finite numbers.
// Errors are thrown as ElementError and caught by the element command.
#include "core/lang/options.h"

#include <tcl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace asgard::lang {
namespace {

std::string Shorten(std::string s) {
  constexpr size_t kMax = 60;
  if (s.size() > kMax) s = s.substr(0, kMax) + "...";
  return s;
}

// Eigenvalues of a symmetric 3x3 matrix (row-major), ascending.
std::array<double, 3> SymmetricEigenvalues(const std::array<double, 9>& a) {
  double p1 = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
  std::array<double, 3> e;
  if (p1 == 0.0) {
    e = {a[0], a[4], a[8]};
  } else {
    double q = (a[0] + a[4] + a[8]) / 3.0;
    double p2 =
        (a[0] - q) * (a[0] - q) + (a[4] - q) * (a[4] - q) + (a[8] - q) * (a[8] - q) + 2.0 * p1;
    double p = std::sqrt(p2 / 6.0);
    std::array<double, 9> b = a;
    for (int i = 0; i < 3; ++i) b[i * 4] -= q;
    for (double& x : b) x /= p;
    double det = b[0] * (b[4] * b[8] - b[5] * b[7]) - b[1] * (b[3] * b[8] - b[5] * b[6]) +
                 b[2] * (b[3] * b[7] - b[4] * b[6]);
    double r = std::clamp(det / 2.0, -1.0, 1.0);
    double phi = std::acos(r) / 3.0;
    double e1 = q + 2.0 * p * std::cos(phi);
    double e3 = q + 2.0 * p * std::cos(phi + 2.0 * std::numbers::pi / 3.0);
    e = {e1, 3.0 * q - e1 - e3, e3};
  }
  std::sort(e.begin(), e.end());
  return e;
}

bool IsNumericLiteralObj(Tcl_Obj* obj, int depth) {
  double d = 0;
  if (Tcl_GetDoubleFromObj(nullptr, obj, &d) == TCL_OK) return std::isfinite(d);
  if (depth >= 3) return false;
  int n = 0;
  Tcl_Obj** elems = nullptr;
  if (Tcl_ListObjGetElements(nullptr, obj, &n, &elems) != TCL_OK || n == 0) return false;
  if (n == 1 && ObjString(elems[0]) == ObjString(obj)) return false;
  for (int i = 0; i < n; ++i) {
    if (!IsNumericLiteralObj(elems[i], depth + 1)) return false;
  }
  return true;
}

}  // namespace

std::string ObjString(Tcl_Obj* obj) {
  int len = 0;
  const char* s = Tcl_GetStringFromObj(obj, &len);
  return std::string(s, len);
}

std::string FormatNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

double ToNumber(Tcl_Obj* obj, const std::string& context, int arg) {
  double d = 0;
  if (Tcl_GetDoubleFromObj(nullptr, obj, &d) != TCL_OK) {
    std::string text = ObjString(obj);
    std::string lower = text;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower.find("nan") != std::string::npos) {
      throw ElementError{context + " must be a finite number, got '" + Shorten(text) + "'", arg};
    }
    throw ElementError{context + " expects a number but got '" + Shorten(text) + "'", arg};
  }
  if (!std::isfinite(d)) {
    throw ElementError{context + " must be a finite number, got '" + Shorten(ObjString(obj)) + "'",
                       arg};
  }
  return d;
}

std::vector<double> ToNumbers(Tcl_Obj* obj, const std::string& context, int arg) {
  int n = 0;
  Tcl_Obj** elems = nullptr;
  if (Tcl_ListObjGetElements(nullptr, obj, &n, &elems) != TCL_OK) {
    throw ElementError{
        context + " expects a list of numbers but got '" + Shorten(ObjString(obj)) + "'", arg};
  }
  std::vector<double> out;
  out.reserve(n);
  for (int i = 0; i < n; ++i) out.push_back(ToNumber(elems[i], context, arg));
  return out;
}

scene::Vec3 ToVec3(Tcl_Obj* obj, const std::string& context, int arg) {
  std::vector<double> v = ToNumbers(obj, context, arg);
  if (v.size() != 3) {
    throw ElementError{context + " expects 3 numbers {x y z} but got " + std::to_string(v.size()) +
                           " ('" + Shorten(ObjString(obj)) + "')",
                       arg};
  }
  return {v[0], v[1], v[2]};
}

scene::Quat RotationVectorToQuat(const scene::Vec3& v) {
  double angle = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (angle == 0.0) return {1, 0, 0, 0};
  double s = std::sin(angle / 2.0) / angle;
  return {std::cos(angle / 2.0), v[0] * s, v[1] * s, v[2] * s};
}

bool IsNumericLiteral(std::string_view text) {
  Tcl_Obj* obj = Tcl_NewStringObj(text.data(), static_cast<int>(text.size()));
  Tcl_IncrRefCount(obj);
  bool ok = IsNumericLiteralObj(obj, 0);
  Tcl_DecrRefCount(obj);
  return ok;
}

Options::Options(const Invocation& inv, int first, std::initializer_list<const char*> allowed)
    : inv_(inv) {
  for (int i = first; i < inv.objc; i += 2) {
    std::string word = ObjString(inv.objv[i]);
    if (word.size() < 2 || word[0] != '-') {
      throw ElementError{
          inv.kind + ": expected an option name (-name) but got '" + Shorten(word) + "'", i};
    }
    std::string name = word.substr(1);
    bool known =
        std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return name == a; });
    if (!known) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "-" : ", -") + std::string(a);
      throw ElementError{
          inv.kind + ": unknown option '" + Shorten(word) + "' (expected one of: " + list + ")", i};
    }
    if (i + 1 >= inv.objc) {
      throw ElementError{inv.kind + ": option '" + word + "' needs a value", i};
    }
    values_.erase(std::remove_if(values_.begin(), values_.end(),
                                 [&](const OptionValue& v) { return v.name == name; }),
                  values_.end());
    values_.push_back(OptionValue{name, i + 1, inv.objv[i + 1]});
  }
}

const OptionValue* Options::Get(const char* name) const {
  for (const auto& v : values_) {
    if (v.name == name) return &v;
  }
  return nullptr;
}

void Options::Fail(const OptionValue& v, const std::string& what) const {
  throw ElementError{inv_.kind + ": option '-" + v.name + "' " + what, v.arg};
}

namespace {
std::string Context(const std::string& kind, const OptionValue& v) {
  return kind + ": option '-" + v.name + "'";
}
}  // namespace

std::optional<double> Options::Number(const char* name) const {
  const OptionValue* v = Get(name);
  if (v == nullptr) return std::nullopt;
  return ToNumber(v->obj, Context(inv_.kind, *v), v->arg);
}

std::optional<double> Options::Positive(const char* name) const {
  std::optional<double> d = Number(name);
  if (d && !(*d > 0.0))
    Fail(*Get(name), "must be greater than 0, got " + ObjString(Get(name)->obj));
  return d;
}

std::optional<double> Options::NonNegative(const char* name) const {
  std::optional<double> d = Number(name);
  if (d && *d < 0.0) Fail(*Get(name), "must not be negative, got " + ObjString(Get(name)->obj));
  return d;
}

std::optional<bool> Options::Bool(const char* name) const {
  const OptionValue* v = Get(name);
  if (v == nullptr) return std::nullopt;
  int b = 0;
  if (Tcl_GetBooleanFromObj(nullptr, v->obj, &b) != TCL_OK) {
    Fail(*v, "expects 0 or 1 but got '" + Shorten(ObjString(v->obj)) + "'");
  }
  return b != 0;
}

std::optional<scene::Vec3> Options::Vector(const char* name) const {
  const OptionValue* v = Get(name);
  if (v == nullptr) return std::nullopt;
  return ToVec3(v->obj, Context(inv_.kind, *v), v->arg);
}

std::optional<scene::Quat> Options::Rotation(const char* name) const {
  const OptionValue* v = Get(name);
  if (v == nullptr) return std::nullopt;
  std::vector<double> n = ToNumbers(v->obj, Context(inv_.kind, *v), v->arg);
  if (n.size() == 3) return RotationVectorToQuat({n[0], n[1], n[2]});
  if (n.size() != 4) {
    Fail(*v, "expects a rotation vector {x y z} or a quaternion {w x y z}, got " +
                 std::to_string(n.size()) + " numbers");
  }
  double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] + n[3] * n[3]);
  if (!(norm > 1e-12)) Fail(*v, "is a zero quaternion; a rotation needs a non-zero {w x y z}");
  return scene::Quat{n[0] / norm, n[1] / norm, n[2] / norm, n[3] / norm};
}

std::optional<std::array<double, 9>> Options::Moment(const char* name) const {
  const OptionValue* v = Get(name);
  if (v == nullptr) return std::nullopt;
  std::vector<double> n = ToNumbers(v->obj, Context(inv_.kind, *v), v->arg);
  std::array<double, 9> m{};
  if (n.size() == 1) {
    m[0] = m[4] = m[8] = n[0];
  } else if (n.size() == 3) {
    m[0] = n[0];
    m[4] = n[1];
    m[8] = n[2];
  } else if (n.size() == 9) {
    std::copy(n.begin(), n.end(), m.begin());
  } else {
    Fail(*v, "expects 1, 3 or 9 numbers, got " + std::to_string(n.size()));
  }
  double scale = 0;
  for (double x : m) scale = std::max(scale, std::abs(x));
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (std::abs(m[i * 3 + j] - m[j * 3 + i]) > 1e-9 * scale) {
        Fail(*v, "must be a symmetric tensor");
      }
    }
  }
  std::array<double, 3> e = SymmetricEigenvalues(m);
  if (!(e[0] > 1e-12 * scale) || !(scale > 0)) {
    Fail(*v, "must be positive definite (principal moments must all be > 0)");
  }
  if (e[0] + e[1] < e[2] * (1.0 - 1e-9)) {
    Fail(*v, "violates the triangle inequality of principal moments (I1 + I2 >= I3)");
  }
  return m;
}

std::optional<std::string> Options::String(const char* name) const {
  const OptionValue* v = Get(name);
  if (v == nullptr) return std::nullopt;
  std::string s = ObjString(v->obj);
  if (s.empty()) Fail(*v, "needs a non-empty value");
  return s;
}

std::optional<std::string> Options::Expression(const char* name) const {
  const OptionValue* v = Get(name);
  if (v == nullptr) return std::nullopt;
  std::string s = ObjString(v->obj);
  if (TrimCommandText(s).empty()) Fail(*v, "needs an expression");
  return s;
}

scene::Word MakeWord(const Invocation& inv, int arg) {
  scene::Word w;
  w.text = ObjString(inv.objv[arg]);
  const CommandSite& site = inv.site;
  if (!site.words_matched) {
    if (site.in_eval || site.source == nullptr) {
      w.reason = site.in_proc && !site.in_eval ? "made in a proc" : "built by eval";
    } else {
      w.reason = "computed by an expression";
    }
    return w;
  }
  const SourceWord& sw = site.source->words[arg];
  w.span = sw.span;
  if (site.in_proc) {
    w.reason = "made in a proc";
  } else if (!sw.simple) {
    w.reason = "computed by an expression";
  } else if (!IsNumericLiteral(sw.text)) {
    w.reason = "not a literal number";
  } else {
    w.literal = true;
  }
  return w;
}

void RecordOptions(const Invocation& inv, const Options& opts, scene::ElementBase& base) {
  for (const auto& v : opts.values()) base.options.emplace_back(v.name, MakeWord(inv, v.arg));
}

}  // namespace asgard::lang
