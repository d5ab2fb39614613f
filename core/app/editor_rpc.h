// asgard-core methods for the browser editor (web/server/, seed chapter 4): what a
// graphical viewer and a language viewer need from the session that owns an
// animation, without drawing anything in the slave.
//
//   scene_state {}  → {text, diagnostics: [{line, column, end_line, end_column,
//                      severity, message}], parameters: [{kind, element, param,
//                      value, editable, reason, line, column, end_line,
//                      end_column}], elements: [{kind, element, editable,
//                      reason}], can_undo, can_redo}
//   meshes {}       → {bodies: [{name, static, centroid (shape coordinates),
//                      radius, pieces: [{sphere, center, radius} |
//                      {vertices: [x y z …], triangles: [i j k …]}, color]}],
//                      lights: [{directional, position, direction, color,
//                      intensity}]}
//   poses {}        → {t0, t1, frame_rate, times: [...], bodies: [names],
//                      poses: [[x y z qx qy qz qw per body] per frame],
//                      velocities: [[vx vy vz wx wy wz per body] per frame]
//                      (ω in world axes; differences of the poses over
//                      1e-5 of the run),
//                      forces: [[[fx fy fz] | null per scene force] per frame],
//                      links: [[ax ay az bx by bz per link] per frame] (the
//                      two attachment points in world coordinates),
//                      arrows: [[bx by bz fx fy fz per scene force] per
//                      frame] (point of application and world vector; zero
//                      where the force cannot be evaluated), arrow_length
//                      (the longest arrow's drawn length, scene units),
//                      trajectories: [{name, values: [[x y z] per frame]}],
//                      framing: {center, radius, eye_distance, tan_half_fov}
//                      (asgard render's default view and camera),
//                      views: [{name, fov_y, moves, expressions: [the
//                      options among pos rot scale given as expressions],
//                      cameras: [[eye target up] per frame], problem (only
//                      when an expression had no usable value somewhere)}],
//                      camera: {eye, target, up, tan_half_fov} (the scene's
//                      view as a rendition draws it, for a square picture)}
//
// meshes and poses need a successful simulate; before it they answer
// {ok: false, error}.
//
// PlayerData is what an exported page needs to play the motion in WebGL
// (the medium's "player" command, host-shim/html.cc): meshes' bodies and
// lights as above, the poses, links and arrows (as poses has them) at
// `rate` frames per second over the run (at most kMaxPlayerFrames), and the
// camera `view` gives for a square picture
// {eye, target, up, tan_half_fov}; with a `motion` that moves (the scene's
// view with -follow, -trajectory or expressions) also cameras: [[eye target
// up] per frame], that view's camera at each of the times.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace asgard {
namespace session {
class Session;
}
namespace render {
class SceneSampler;
struct ViewState;
class ViewMotion;
}  // namespace render
}  // namespace asgard

namespace asgard::editor_rpc {

// The answer to `method`, or nullopt when it is not one of the editor's.
// `session` and `sampler` may be null (nothing loaded, not simulated).
std::optional<nlohmann::json> Dispatch(const std::string& method, const nlohmann::json& params,
                                       const session::Session* session,
                                       const render::SceneSampler* sampler);

inline constexpr int kMaxPlayerFrames = 3000;
nlohmann::json PlayerData(const render::SceneSampler& sampler, const render::ViewState& view,
                          double rate, const render::ViewMotion* motion = nullptr);

}  // namespace asgard::editor_rpc
