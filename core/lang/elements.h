// Element command handlers (internal).  Each parses one invocation and
// appends its element to ctx.scene, or throws ElementError.  `name` is set as
// soon as the element's name is known so that a failure can be remembered.
#pragma once

#include <string>

#include "core/lang/eval_context.h"

namespace asgard::lang {

void SimulatorCommand(EvalContext& ctx, const Invocation& inv, std::string& name);
void ShapeSetCommand(EvalContext& ctx, const Invocation& inv, std::string& name);
void BodyCommand(EvalContext& ctx, const Invocation& inv, std::string& name);
void LinkCommand(EvalContext& ctx, const Invocation& inv, std::string& name);
void ForceCommand(EvalContext& ctx, const Invocation& inv, std::string& name);
void TorqueCommand(EvalContext& ctx, const Invocation& inv, std::string& name);
void TrajectoryCommand(EvalContext& ctx, const Invocation& inv, std::string& name);
void LightSourceCommand(EvalContext& ctx, const Invocation& inv, std::string& name);
void ViewCommand(EvalContext& ctx, const Invocation& inv, std::string& name);

// After the script ran (bodies and trajectories known): parses the
// expressions of every view's -pos, -rot and -scale, reports each error at
// its component and drops views that have one.
void CheckViewExpressions(EvalContext& ctx);

// Fills the ElementBase fields common to all elements.
void FillBase(const Invocation& inv, scene::ElementBase& base);

// Reads the element name at argument 1 (required) -- `expression_name` also
// demands an identifier usable in expressions (bodies, trajectories).
std::string RequireName(const Invocation& inv, bool expression_name);

}  // namespace asgard::lang
