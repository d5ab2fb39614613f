// The editor's asgard-core methods (see editor_rpc.h).
#include "core/app/editor_rpc.h"

#include <algorithm>
#include <cmath>

#include "core/physics/trajectory.h"
#include "core/pipeline/pipeline.h"
#include "core/render/sampler.h"
#include "core/render/view.h"
#include "core/session/session.h"

namespace asgard::editor_rpc {
namespace {

using nlohmann::json;

// Six significant digits are far below a pixel at any zoom and keep the
// stream of poses small.
double Round(double v) {
  if (!std::isfinite(v)) return 0.0;
  return std::round(v * 1e6) / 1e6;
}

json SceneState(const session::Session& s) {
  json diagnostics = json::array();
  // The scene's and its equations' problems (an unknown shape_set, a link to
  // a missing body), as asgard check reports them.
  const pipeline::Run check = pipeline::Check(s.scene());
  for (const auto& d : check.diagnostics) {
    int end_line = d.span.line, end_column = d.span.column;
    if (d.span.known() && d.span.end > d.span.begin) {
      session::TextEdit where;  // the span as an edit: Locate finds its end
      where.begin = d.span.begin;
      where.end = d.span.end;
      session::Locate(where, s.text());
      end_line = where.end_line;
      end_column = where.end_column;
    }
    diagnostics.push_back(
        {{"line", d.span.line},
         {"column", d.span.column},
         {"end_line", end_line},
         {"end_column", end_column},
         {"severity", d.severity == scene::Severity::kError ? "error" : "warning"},
         {"message", d.message}});
  }
  json parameters = json::array();
  for (const auto& p : s.Parameters()) {
    session::TextEdit where;  // the word's span as an edit: Locate finds both ends
    where.begin = p.span.begin;
    where.end = p.span.end;
    if (p.span.known()) session::Locate(where, s.text());
    parameters.push_back({{"kind", scene::ElementKindName(p.kind)},
                          {"element", p.element},
                          {"param", p.param},
                          {"value", p.value},
                          {"editable", p.editable},
                          {"reason", p.reason},
                          {"line", p.span.line},
                          {"column", p.span.column},
                          {"end_line", p.span.known() ? where.end_line : 0},
                          {"end_column", p.span.known() ? where.end_column : 0}});
  }
  json elements = json::array();
  for (const auto& e : s.ElementInfos())
    elements.push_back({{"kind", scene::ElementKindName(e.kind)},
                        {"element", e.element},
                        {"editable", e.editable},
                        {"reason", e.reason},
                        {"deleted_with", e.deleted_with}});
  json prescribed = json::array();
  for (const auto& p : s.PrescribedInitials())
    prescribed.push_back({{"body", p.body}, {"param", p.param}, {"reason", p.reason}});
  return {{"ok", true},
          {"text", s.text()},
          {"diagnostics", diagnostics},
          {"parameters", parameters},
          {"elements", elements},
          {"prescribed", prescribed},
          {"can_undo", s.CanUndo()},
          {"can_redo", s.CanRedo()}};
}

json Vec(const Eigen::Vector3d& v) { return {Round(v.x()), Round(v.y()), Round(v.z())}; }

json Meshes(const render::SceneSampler& sampler) {
  json bodies = json::array();
  for (const auto& b : sampler.bodies()) {
    json pieces = json::array();
    for (const auto& p : b.pieces) {
      json piece = {{"color", {p.rgb.r, p.rgb.g, p.rgb.b}}};
      if (p.is_sphere) {
        piece["sphere"] = true;
        piece["center"] = Vec(p.center);
        piece["radius"] = Round(p.radius);
      } else {
        json vertices = json::array(), triangles = json::array();
        for (const auto& v : p.hull.vertices)
          for (int k = 0; k < 3; ++k) vertices.push_back(Round(v[k]));
        for (const auto& t : p.hull.triangles)
          for (int k = 0; k < 3; ++k) triangles.push_back(t[k]);
        piece["sphere"] = false;
        piece["vertices"] = std::move(vertices);
        piece["triangles"] = std::move(triangles);
      }
      pieces.push_back(std::move(piece));
    }
    bodies.push_back({{"name", b.name},
                      {"static", b.is_static},
                      {"centroid", Vec(b.centroid)},
                      {"radius", Round(b.bound_radius)},
                      {"pieces", std::move(pieces)}});
  }
  // The scene's light sources as the renderer takes them (colours parsed).
  json lights = json::array();
  for (const auto& l : sampler.SceneLights())
    lights.push_back({{"directional", l.directional},
                      {"position", Vec(l.position)},
                      {"direction", Vec(l.direction)},
                      {"color", {l.color.r, l.color.g, l.color.b}},
                      {"intensity", Round(l.intensity)}});
  return {{"ok", true}, {"bodies", std::move(bodies)}, {"lights", std::move(lights)}};
}

// [eye target up] of a camera.
json CameraFrame(const render::Camera& c) { return {Vec(c.eye), Vec(c.target), Vec(c.up)}; }

// Each `view` element's camera at the frame times, as asgard render places
// it (render::MakeCamera for a square picture): render::ViewMotion moves the
// centre with -follow's body or -trajectory's curve and evaluates -pos, -rot
// and -scale given as expressions at every frame.  `expressions` names the
// options that are expressions (their handles are read-only); `problem`
// says where one had no usable value (its default was used there).
json Views(const render::SceneSampler& sampler, const session::Session& session,
           const std::vector<double>& times) {
  json views = json::array();
  const auto& scene = session.scene();
  for (size_t i = 0; i < scene.views.size(); ++i) {
    const auto& e = scene.views[i];
    const render::ViewMotion motion = sampler.Motion(&e);
    json cameras = json::array();
    double fov_y = 0;
    std::string problem;
    for (double t : times) {
      const render::Camera c = render::MakeCamera(motion.At(t, &problem), 1, 1);
      fov_y = c.fov_y;
      cameras.push_back(CameraFrame(c));
    }
    json expressions = json::array();
    if (!e.position_expr.empty()) expressions.push_back("pos");
    if (!e.rotation_expr.empty()) expressions.push_back("rot");
    if (!e.scale_expr.empty()) expressions.push_back("scale");
    json view = {{"name", e.name.empty() ? "view " + std::to_string(i + 1) : e.name},
                 {"fov_y", fov_y},
                 {"moves", motion.moves()},
                 {"expressions", std::move(expressions)},
                 {"cameras", std::move(cameras)}};
    if (!motion.error().empty() || !problem.empty())
      view["problem"] = motion.error().empty() ? problem : motion.error();
    views.push_back(std::move(view));
  }
  return views;
}

// [x y z qx qy qz qw] of every body at time t, one list.
json PoseFrame(const render::SceneSampler& sampler, double t) {
  json frame = json::array();
  for (const auto& pose : sampler.Poses(t)) {
    const Eigen::Quaterniond q = pose.q.normalized();
    for (double v : {pose.p.x(), pose.p.y(), pose.p.z(), q.x(), q.y(), q.z(), q.w()})
      frame.push_back(Round(v));
  }
  return frame;
}

// The overlays a player draws at time t, one list each: every link's two
// ends [ax ay az bx by bz] (LinkSegments: links whose bodies or trajectory
// are unknown are left out for the whole run), and every scene force's
// point of application and world vector [bx by bz fx fy fz] (all zero
// where the force cannot be evaluated, so the count never changes).
struct OverlayFrame {
  json links = json::array(), arrows = json::array();
};
OverlayFrame Overlays(const render::SceneSampler& sampler, double t) {
  const std::vector<render::Pose> poses = sampler.Poses(t);
  OverlayFrame frame;
  for (const auto& s : sampler.LinkSegments(t, poses))
    for (double v : {s.a.x(), s.a.y(), s.a.z(), s.b.x(), s.b.y(), s.b.z()})
      frame.links.push_back(Round(v));
  // ForceVectors has the forces that can be evaluated, in scene order.
  const auto values = sampler.ForceValues(t);
  const auto vectors = sampler.ForceVectors(t, poses);
  size_t next = 0;
  for (const auto& value : values) {
    render::Segment s{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    if (value && next < vectors.size()) s = vectors[next++];
    const Eigen::Vector3d f = s.b - s.a;
    for (double v : {s.a.x(), s.a.y(), s.a.z(), f.x(), f.y(), f.z()})
      frame.arrows.push_back(Round(v));
  }
  return frame;
}

// Adds the overlays at `times` to a player's data: links and arrows (one
// list per frame) and the length the longest arrow is drawn at (as asgard
// render's: a fifth of the view's radius).
void AddOverlays(json& data, const render::SceneSampler& sampler, const std::vector<double>& times,
                 double radius) {
  json links = json::array(), arrows = json::array();
  for (double t : times) {
    OverlayFrame f = Overlays(sampler, t);
    links.push_back(std::move(f.links));
    arrows.push_back(std::move(f.arrows));
  }
  data["links"] = std::move(links);
  data["arrows"] = std::move(arrows);
  data["arrow_length"] = Round(radius / 5);
}

// [vx vy vz wx wy wz] of every body at time t (ω in world axes), one list:
// differences of the poses over a step of 1e-5 of the run (central inside,
// second order one-sided at the ends) — what a viewer needs to interpolate
// between frames with cubic Hermite polynomials.
json VelocityFrame(const render::SceneSampler& sampler, double t) {
  const double t0 = sampler.t0(), t1 = sampler.t1();
  const double h = std::max(1e-5 * (t1 - t0), 1e-7);
  // Samples at t + k·h for three k, and the weights of the derivative.
  double k[3] = {-1, 0, 1}, w[3] = {-0.5, 0, 0.5};
  if (t - h < t0) k[0] = 0, k[1] = 1, k[2] = 2, w[0] = -1.5, w[1] = 2, w[2] = -0.5;
  if (t + h > t1 && t - h >= t0) k[0] = -2, k[1] = -1, k[2] = 0, w[0] = 0.5, w[1] = -2, w[2] = 1.5;
  std::vector<std::vector<render::Pose>> at;
  for (double kk : k) at.push_back(sampler.Poses(std::clamp(t + kk * h, t0, t1)));
  const std::vector<render::Pose> now = sampler.Poses(t);
  json frame = json::array();
  for (size_t b = 0; b < now.size(); ++b) {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    Eigen::Vector4d dq = Eigen::Vector4d::Zero();
    const Eigen::Quaterniond q = now[b].q.normalized();
    for (int i = 0; i < 3; ++i) {
      v += w[i] / h * at[i][b].p;
      Eigen::Quaterniond qi = at[i][b].q.normalized();
      if (qi.coeffs().dot(q.coeffs()) < 0) qi.coeffs() *= -1;
      dq += w[i] / h * qi.coeffs();
    }
    // ω = 2 q̇ q*, in world axes.
    Eigen::Quaterniond qdot;
    qdot.coeffs() = dq;
    const Eigen::Vector3d omega = 2 * (qdot * q.conjugate()).vec();
    for (double x : {v.x(), v.y(), v.z(), omega.x(), omega.y(), omega.z()})
      frame.push_back(Round(x));
  }
  return frame;
}

// A camera for a square picture as a player takes it (a wider picture keeps
// the vertical field, a taller one the horizontal).
json CameraJson(const render::Camera& c) {
  return {{"eye", Vec(c.eye)},
          {"target", Vec(c.target)},
          {"up", Vec(c.up)},
          {"tan_half_fov", std::tan(c.fov_y / 2)}};
}

json Poses(const render::SceneSampler& sampler, const session::Session* session) {
  const std::vector<double> times = sampler.FrameTimes();
  json names = json::array();
  for (const auto& b : sampler.bodies()) names.push_back(b.name);
  json frames = json::array(), forces = json::array(), velocities = json::array(),
       torques = json::array();
  auto vectors = [](const std::vector<std::optional<Eigen::Vector3d>>& v) {
    json values = json::array();
    for (const auto& f : v) values.push_back(f ? Vec(*f) : json());
    return values;
  };
  for (double t : times) {
    frames.push_back(PoseFrame(sampler, t));
    velocities.push_back(VelocityFrame(sampler, t));
    forces.push_back(vectors(sampler.ForceValues(t)));
    const auto tv = sampler.TorqueValues(t);
    if (!tv.empty()) torques.push_back(vectors(tv));  // only a scene with torques
  }
  json rounded = json::array();
  for (double t : times) rounded.push_back(Round(t));
  // Each trajectory's value at the frame times: the curve a viewer draws when
  // it cannot read the knots itself (and against which its own is checked).
  json trajectories = json::array();
  if (session)
    for (const auto& tr : session->scene().trajectories) {
      const physics::TrajectoryCurve curve(tr.knots);
      json values = json::array();
      for (double t : times) values.push_back(Vec(curve.Value(t)));
      trajectories.push_back({{"name", tr.name}, {"values", std::move(values)}});
    }
  // The default view of asgard render, and its camera's eye distance (in
  // framing radii) and tan of half the field of view: what a viewer needs to
  // ask for a movie seen as it shows the scene.
  const render::ViewState framing = sampler.ElementView(nullptr);
  const render::Camera camera = render::MakeCamera(framing, 1, 1);
  json data = {{"ok", true},
               {"t0", sampler.t0()},
               {"t1", sampler.t1()},
               {"frame_rate", sampler.frame_rate()},
               {"times", std::move(rounded)},
               {"bodies", std::move(names)},
               {"poses", std::move(frames)},
               {"velocities", std::move(velocities)},
               {"forces", std::move(forces)},
               {"trajectories", std::move(trajectories)},
               {"framing",
                {{"center", Vec(framing.center)},
                 {"radius", Round(framing.radius)},
                 {"eye_distance", (camera.eye - camera.target).norm() / framing.radius},
                 {"tan_half_fov", std::tan(camera.fov_y / 2)}}},
               {"views", session ? Views(sampler, *session, times) : json::array()},
               {"camera", CameraJson(render::MakeCamera(*sampler.SceneView(), 1, 1))}};
  if (!torques.empty()) data["torques"] = std::move(torques);
  AddOverlays(data, sampler, times, framing.radius);
  return data;
}

json Refused(const std::string& why) { return {{"ok", false}, {"error", why}}; }

}  // namespace

std::optional<json> Dispatch(const std::string& method, const json& /*params*/,
                             const session::Session* session, const render::SceneSampler* sampler) {
  if (method == "scene_state")
    return session ? SceneState(*session) : Refused("no scene is loaded");
  if (method == "meshes")
    return sampler ? Meshes(*sampler) : Refused("the scene has not been simulated");
  if (method == "poses")
    return sampler ? Poses(*sampler, session) : Refused("the scene has not been simulated");
  return std::nullopt;
}

json PlayerData(const render::SceneSampler& sampler, const render::ViewState& view, double rate,
                const render::ViewMotion* motion) {
  json data = Meshes(sampler);
  const double t0 = sampler.t0(), t1 = std::max(sampler.t0(), sampler.t1());
  rate = std::isfinite(rate) && rate > 0 ? rate : sampler.frame_rate();
  const int count = static_cast<int>(
      std::clamp(std::floor((t1 - t0) * rate + 1e-9) + 1, 1.0, double{kMaxPlayerFrames}));
  const std::vector<double> times = render::SceneSampler::FrameTimes(t0, t1, count);
  json frames = json::array();
  for (double t : times) frames.push_back(PoseFrame(sampler, t));
  data["times"] = times;
  data["poses"] = std::move(frames);
  data["camera"] = CameraJson(render::MakeCamera(view, 1, 1));
  if (motion && motion->moves()) {
    json cameras = json::array();
    for (double t : times) cameras.push_back(CameraFrame(render::MakeCamera(motion->At(t), 1, 1)));
    data["cameras"] = std::move(cameras);
  }
  AddOverlays(data, sampler, times, view.radius);
  return data;
}

}  // namespace asgard::editor_rpc
