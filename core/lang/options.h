// Option parsing and value conversion for element commands.
//
// Every conversion throws ElementError naming the option and pointing at the
// offending argument; the element command catches it (eval_context.h).
#pragma once

#include <array>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "core/lang/eval_context.h"
#include "core/scene/scene.h"

namespace asgard::lang {

struct OptionValue {
  std::string name;  // without the dash
  int arg = -1;      // argument index of the value
  Tcl_Obj* obj = nullptr;
};

class Options {
 public:
  // Parses arguments [first, objc) as `-name value` pairs; names must be in
  // `allowed` (without dashes).  A repeated option: the last one wins.
  Options(const Invocation& inv, int first, std::initializer_list<const char*> allowed);

  const OptionValue* Get(const char* name) const;
  bool Has(const char* name) const { return Get(name) != nullptr; }
  const std::vector<OptionValue>& values() const { return values_; }

  // Typed access; each returns nullopt when the option is absent.
  std::optional<double> Number(const char* name) const;
  std::optional<double> Positive(const char* name) const;     // > 0
  std::optional<double> NonNegative(const char* name) const;  // >= 0
  std::optional<bool> Bool(const char* name) const;
  std::optional<scene::Vec3> Vector(const char* name) const;
  std::optional<scene::Quat> Rotation(const char* name) const;  // 3 or 4 numbers
  std::optional<std::array<double, 9>> Moment(const char* name) const;
  std::optional<std::string> String(const char* name) const;      // non-empty
  std::optional<std::string> Expression(const char* name) const;  // non-empty text

  [[noreturn]] void Fail(const OptionValue& v, const std::string& what) const;

 private:
  const Invocation& inv_;
  std::vector<OptionValue> values_;
};

// Converts a Tcl value to numbers; throws ElementError(message, arg) with
// `context` ("body: option '-init_pos'") prefixed.
double ToNumber(Tcl_Obj* obj, const std::string& context, int arg);
std::vector<double> ToNumbers(Tcl_Obj* obj, const std::string& context, int arg);
scene::Vec3 ToVec3(Tcl_Obj* obj, const std::string& context, int arg);

// Rotation vector (radians) to unit quaternion.
scene::Quat RotationVectorToQuat(const scene::Vec3& v);

// True if the text is a number or a list of numbers (nested lists allowed).
bool IsNumericLiteral(std::string_view text);

// Records every option of `opts` in `base.options` with its source word.
void RecordOptions(const Invocation& inv, const Options& opts, scene::ElementBase& base);
// The Word for argument `arg` of `inv` (text, span, literal, reason).
scene::Word MakeWord(const Invocation& inv, int arg);

std::string ObjString(Tcl_Obj* obj);
// Shortest readable form of a number ("%g").
std::string FormatNumber(double v);

}  // namespace asgard::lang
