// asgard-core's editor methods (core/app/editor_rpc.h): what the browser's
// handles and language viewers read — word spans, element editability, the
// body centroids and the per-frame force values.
#include "core/app/editor_rpc.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/pipeline/pipeline.h"
#include "core/render/sampler.h"
#include "core/render/view.h"
#include "core/session/session.h"

namespace asgard::editor_rpc {
namespace {

using nlohmann::json;

const std::string kScene =
    "simulator -finish 1\n"
    "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n"
    "shape_set off -desc {-sub {-pos {2 0 0} -sphere 0.5}}\n"
    "body a -shape ball -init_pos {1 2 3} -mass 2\n"
    "body b -shape off -init_pos [list 0 0 0]\n"
    "force -body a -x 0 -y -1 -z 0 -gravitational 1\n"
    "force -body b -x {sin(t)} -y 0 -z 0\n";

const json* FindParam(const json& state, const std::string& element, const std::string& param) {
  for (const auto& p : state["parameters"])
    if (p["element"] == element && p["param"] == param) return &p;
  return nullptr;
}

TEST(EditorRpc, SceneStateLocatesEachWordAndSaysWhichElementsTakeEdits) {
  session::Session s(kScene);
  const json state = *Dispatch("scene_state", json::object(), &s, nullptr);
  const json* pos = FindParam(state, "a", "init_pos");
  ASSERT_NE(pos, nullptr);
  EXPECT_TRUE((*pos)["editable"].get<bool>());
  EXPECT_EQ((*pos)["kind"], "body");
  // "{1 2 3}" on line 4: columns of its first character and one past its end.
  const int column = static_cast<int>(std::string("body a -shape ball -init_pos ").size()) + 1;
  EXPECT_EQ((*pos)["line"], 4);
  EXPECT_EQ((*pos)["column"], column);
  EXPECT_EQ((*pos)["end_line"], 4);
  EXPECT_EQ((*pos)["end_column"], column + 7);
  const json* expr = FindParam(state, "b", "init_pos");
  ASSERT_NE(expr, nullptr);
  EXPECT_FALSE((*expr)["editable"].get<bool>());
  EXPECT_FALSE((*expr)["reason"].get<std::string>().empty());
  bool saw_b = false;
  for (const auto& e : state["elements"])
    if (e["element"] == "b") {
      saw_b = true;
      EXPECT_TRUE(e["editable"].get<bool>())
          << "a computed word does not make its command read-only";
    }
  EXPECT_TRUE(saw_b);
}

TEST(EditorRpc, MeshesGiveCentroidsAndPosesGiveEachForceAtEachFrame) {
  pipeline::Run run = pipeline::Simulate(kScene);
  ASSERT_TRUE(run.ok) << run.solver_error;
  render::SceneSampler sampler(run.scene, *run.equations, *run.simulation);
  const json meshes = *Dispatch("meshes", json::object(), nullptr, &sampler);
  ASSERT_EQ(meshes["bodies"].size(), 2u);
  // b's sphere sits at x = 2 of its shape: that is its centre of mass.
  EXPECT_NEAR(meshes["bodies"][1]["centroid"][0].get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(meshes["bodies"][0]["centroid"][0].get<double>(), 0.0, 1e-6);
  const json poses = *Dispatch("poses", json::object(), nullptr, &sampler);
  const auto& times = poses["times"];
  ASSERT_EQ(poses["forces"].size(), times.size());
  for (size_t k = 0; k < times.size(); ++k) {
    const json& f = poses["forces"][k];
    ASSERT_EQ(f.size(), 2u);
    // -gravitational 1: the vector times a's mass (2).
    EXPECT_NEAR(f[0][1].get<double>(), -2.0, 1e-6);
    // An expression of time, rounded to six decimals.
    EXPECT_NEAR(f[1][0].get<double>(), std::sin(times[k].get<double>()), 2e-6);
  }
}

TEST(EditorRpc, PosesCarryEachBodysVelocityAndAngularVelocityAtEachFrame) {
  // Thrown under gravity and spinning: v = (1, 2 − 10 t, 0), ω = (0, 0, 3)
  // (a ball: no torque, ω constant).
  const std::string text =
      "simulator -finish 1 -step 0.1\n"
      "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n"
      "body s -shape ball -init_dpos {1 2 0} -init_drot {0 0 3}\n"
      "force -body s -gravitational 1 -x 0 -y -10 -z 0\n";
  pipeline::Run run = pipeline::Simulate(text);
  ASSERT_TRUE(run.ok) << run.solver_error;
  render::SceneSampler sampler(run.scene, *run.equations, *run.simulation);
  const json poses = *Dispatch("poses", json::object(), nullptr, &sampler);
  const auto& times = poses["times"];
  ASSERT_EQ(poses["velocities"].size(), times.size());
  ASSERT_GT(times.size(), 5u);
  for (size_t k = 0; k < times.size(); ++k) {
    const double t = times[k].get<double>();
    const json& v = poses["velocities"][k];
    ASSERT_EQ(v.size(), 6u);
    EXPECT_NEAR(v[0].get<double>(), 1.0, 1e-4) << "t = " << t;
    EXPECT_NEAR(v[1].get<double>(), 2.0 - 10.0 * t, 1e-4) << "t = " << t;
    EXPECT_NEAR(v[2].get<double>(), 0.0, 1e-4);
    EXPECT_NEAR(v[3].get<double>(), 0.0, 1e-4);
    EXPECT_NEAR(v[4].get<double>(), 0.0, 1e-4);
    EXPECT_NEAR(v[5].get<double>(), 3.0, 1e-4) << "t = " << t;
  }
}

TEST(EditorRpc, PosesSampleEachTrajectoryAtEachFrame) {
  // Two knots: a straight line at constant speed, extrapolated linearly
  // beyond t = 0.5 (the curve the viewer draws for points it cannot read).
  const std::string text = kScene + "trajectory tr -points [list {0 1 0 0} {0.5 2 1 0}]\n";
  session::Session s(text);
  pipeline::Run run = pipeline::Simulate(text);
  ASSERT_TRUE(run.ok) << run.solver_error;
  render::SceneSampler sampler(run.scene, *run.equations, *run.simulation);
  const json poses = *Dispatch("poses", json::object(), &s, &sampler);
  ASSERT_EQ(poses["trajectories"].size(), 1u);
  const json& tr = poses["trajectories"][0];
  EXPECT_EQ(tr["name"], "tr");
  ASSERT_EQ(tr["values"].size(), poses["times"].size());
  for (size_t k = 0; k < poses["times"].size(); ++k) {
    const double t = poses["times"][k].get<double>();
    EXPECT_NEAR(tr["values"][k][0].get<double>(), 1 + 2 * t, 2e-6);
    EXPECT_NEAR(tr["values"][k][1].get<double>(), 2 * t, 2e-6);
    EXPECT_NEAR(tr["values"][k][2].get<double>(), 0.0, 1e-12);
  }
}

// The cameras of view elements as asgard render places them: a -follow
// view's centre is the body at every frame; the eye sits kEyeDistance
// framing radii / scale from it; the field of view fits the unit sphere
// seen from there (render/view.cc).  Light sources come with the meshes.
TEST(EditorRpc, ViewCamerasFollowTheirBodyAndLightsComeWithTheMeshes) {
  const std::string text = kScene +
                           "view chase -follow a -scale 2\n"
                           "lightsource -type point -pos {1 2 3} -color red -intensity 0.5\n";
  session::Session s(text);
  ASSERT_TRUE(s.Simulate());
  const pipeline::Run& run = *s.run();
  render::SceneSampler sampler(run.scene, *run.equations, *run.simulation);
  const json poses = *Dispatch("poses", json::object(), &s, &sampler);
  ASSERT_EQ(poses["views"].size(), 1u);
  const json& view = poses["views"][0];
  EXPECT_EQ(view["name"], "chase");
  EXPECT_TRUE(view["moves"].get<bool>());
  EXPECT_NEAR(view["fov_y"].get<double>(), 2 * std::atan(1.06 * std::tan(std::asin(0.25))), 1e-12);
  const double radius = poses["framing"]["radius"].get<double>();
  EXPECT_NEAR(poses["framing"]["eye_distance"].get<double>(), render::kEyeDistance, 1e-9);
  ASSERT_EQ(view["cameras"].size(), poses["times"].size());
  for (size_t k = 0; k < poses["times"].size(); ++k) {
    const json& cam = view["cameras"][k];
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(cam[1][c].get<double>(), poses["poses"][k][c].get<double>(), 2e-6)
          << "the centre is body a at frame " << k;
    double d = 0;
    for (int c = 0; c < 3; ++c) d += std::pow(cam[0][c].get<double>() - cam[1][c].get<double>(), 2);
    EXPECT_NEAR(std::sqrt(d), render::kEyeDistance * radius / 2, 1e-5);
  }
  // The renditions' camera (the scene's last view, as the document view's
  // WebGL player takes it): eye kEyeDistance radii / scale from the target,
  // the view's field.
  const json& camera = poses["camera"];
  double d = 0;
  for (int c = 0; c < 3; ++c)
    d += std::pow(camera["eye"][c].get<double>() - camera["target"][c].get<double>(), 2);
  EXPECT_NEAR(std::sqrt(d), render::kEyeDistance * radius / 2, 1e-5);
  EXPECT_NEAR(camera["tan_half_fov"].get<double>(), std::tan(view["fov_y"].get<double>() / 2),
              1e-12);
  const json meshes = *Dispatch("meshes", json::object(), &s, &sampler);
  ASSERT_EQ(meshes["lights"].size(), 1u);
  const json& light = meshes["lights"][0];
  EXPECT_FALSE(light["directional"].get<bool>());
  EXPECT_EQ(light["position"], json({1, 2, 3}));
  EXPECT_EQ(light["color"][0].get<double>(), 1.0);
  EXPECT_EQ(light["color"][1].get<double>(), 0.0);
  EXPECT_NEAR(light["intensity"].get<double>(), 0.5, 1e-12);
}

// Seed 4.1.7: views whose -pos, -rot and -scale are expressions of time and
// of a body's state, evaluated at every frame of the pose stream.  With -rot
// R and -center c the camera looks at c − Rᵀ·pos from kEyeDistance · radius /
// scale along Rᵀ·ẑ, with Rᵀ·ŷ up (render/view.h).
TEST(EditorRpc, ViewsWhoseOptionsAreExpressionsMoveTheirCameraEveryFrame) {
  const std::string text = kScene +
                           "view lift -center {0 0 0} -rot {0 0 {t}} -pos {0 0 {10 + t}} "
                           "-scale {1 + t}\n"
                           "view track -rot {0 0 0} -center {0 0 0} -pos {{-a.x} {-a.y} {-a.z}}\n"
                           "view still -rot {0 0 0} -pos {1 2 3}\n";
  session::Session s(text);
  ASSERT_TRUE(s.Simulate());
  const pipeline::Run& run = *s.run();
  render::SceneSampler sampler(run.scene, *run.equations, *run.simulation);
  const json poses = *Dispatch("poses", json::object(), &s, &sampler);
  ASSERT_EQ(poses["views"].size(), 3u);
  const json &lift = poses["views"][0], &track = poses["views"][1], &still = poses["views"][2];
  EXPECT_TRUE(lift["moves"].get<bool>());
  EXPECT_EQ(lift["expressions"], json({"pos", "rot", "scale"}));
  EXPECT_TRUE(track["moves"].get<bool>());
  EXPECT_EQ(track["expressions"], json({"pos"}));
  EXPECT_FALSE(still["moves"].get<bool>());
  EXPECT_TRUE(still["expressions"].empty());
  EXPECT_FALSE(lift.contains("problem"));
  const double radius = sampler.SceneBound().radius;
  // The frame times unrounded (the stream's are rounded to 1e-6, as every
  // value in it: hence the tolerance).
  const std::vector<double> times = sampler.FrameTimes();
  ASSERT_EQ(times.size(), poses["times"].size());
  ASSERT_GE(times.size(), 5u);
  const double tol = 1e-6;
  for (size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    const json& cam = lift["cameras"][k];
    // Target −Rᵀ(0 0 10+t) = (0 0 −10−t) (R turns about z); eye kEyeDistance ·
    // radius / (1 + t) above it; up Rᵀŷ = (sin t, cos t, 0).
    const double distance = render::kEyeDistance * radius / (1 + t);
    const double want_target[3] = {0, 0, -10 - t};
    const double want_eye[3] = {0, 0, -10 - t + distance};
    const double want_up[3] = {std::sin(t), std::cos(t), 0};
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(cam[1][c].get<double>(), want_target[c], tol) << "target at t = " << t;
      EXPECT_NEAR(cam[0][c].get<double>(), want_eye[c], tol) << "eye at t = " << t;
      EXPECT_NEAR(cam[2][c].get<double>(), want_up[c], tol) << "up at t = " << t;
    }
    // track looks at body a's sampled position: c − (−a) = a.  Body a
    // falls from (1 2 3) at 1 unit/s² (its gravitational force is −1 · mass
    // along y), so a.y = 2 − t²/2 within the solver's tolerance.
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(track["cameras"][k][1][c].get<double>(), poses["poses"][k][c].get<double>(), tol)
          << "track's target is a's sampled position at t = " << t;
    EXPECT_NEAR(track["cameras"][k][1][1].get<double>(), 2 - t * t / 2, 1e-4) << "t = " << t;
    // still: the same camera at every frame.
    EXPECT_EQ(still["cameras"][k], still["cameras"][0]);
  }
}

// The exported page's data carries the scene's view per frame when it moves
// (and not when it stands still).
TEST(EditorRpc, PlayerDataCarriesAMovingViewsCameraAtEachFrame) {
  session::Session s(kScene + "view lift -center {0 0 0} -rot {0 0 0} -pos {0 0 {10 + t}}\n");
  ASSERT_TRUE(s.Simulate());
  const pipeline::Run& run = *s.run();
  render::SceneSampler sampler(run.scene, *run.equations, *run.simulation);
  const render::ViewMotion motion = sampler.Motion(sampler.FindView());
  const json data = PlayerData(sampler, *sampler.SceneView(), 10, &motion);
  ASSERT_EQ(data["cameras"].size(), data["times"].size());
  ASSERT_EQ(data["times"].size(), 11u);
  for (size_t k = 0; k < data["times"].size(); ++k) {
    const double t = data["times"][k].get<double>();
    EXPECT_NEAR(data["cameras"][k][1][2].get<double>(), -10 - t, 1e-6) << "t = " << t;
  }
  const render::ViewMotion framing = sampler.Motion(nullptr);
  EXPECT_FALSE(PlayerData(sampler, *sampler.SceneView(), 10, &framing).contains("cameras"));
}

// An expression with no usable value at some frame (-scale <= 0) leaves the
// option at its default there and says where.
TEST(EditorRpc, AViewExpressionWithoutAUsableValueSaysWhen) {
  session::Session s(kScene + "view shrink -scale {1 - 2 * t}\n");
  ASSERT_TRUE(s.Simulate());
  const pipeline::Run& run = *s.run();
  render::SceneSampler sampler(run.scene, *run.equations, *run.simulation);
  const render::ViewMotion motion = sampler.Motion(&run.scene.views[0]);
  std::string problem;
  EXPECT_NEAR(motion.At(0.25, &problem).scale, 0.5, 1e-12);
  EXPECT_TRUE(problem.empty());
  EXPECT_EQ(motion.At(0.75, &problem).scale, 1.0) << "the default";
  EXPECT_NE(problem.find("view 'shrink': -scale is -0.5"), std::string::npos) << problem;
  EXPECT_NE(problem.find("t = 0.75"), std::string::npos) << problem;
  const json poses = *Dispatch("poses", json::object(), &s, &sampler);
  EXPECT_TRUE(poses["views"][0].contains("problem"));
}

// A changed light source needs no new motion, but the run a sampler draws
// takes it (an incremental simulation keeps the run).
TEST(EditorRpc, AnIncrementalSimulationKeepsTheRunsLightsAndViewsCurrent) {
  session::Session s(kScene + "lightsource -type point -pos {1 2 3} -color red\n");
  ASSERT_TRUE(s.Simulate());
  const pipeline::Run* before = s.run();
  s.UpdateText(kScene + "lightsource -type point -pos {1 2 3} -color blue\nview v -scale 3\n");
  ASSERT_TRUE(s.Simulate());
  ASSERT_EQ(s.run(), before) << "the same run, carried on";
  render::SceneSampler sampler(s.run()->scene, *s.run()->equations, *s.run()->simulation);
  const auto lights = sampler.SceneLights();
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_EQ(lights[0].color.b, 1.0);
  EXPECT_EQ(lights[0].color.r, 0.0);
  ASSERT_EQ(s.run()->scene.views.size(), 1u);
  EXPECT_EQ(s.run()->scene.views[0].name, "v");
}

TEST(EditorRpc, MotionMethodsRefuseBeforeASimulation) {
  const json r = *Dispatch("poses", json::object(), nullptr, nullptr);
  EXPECT_FALSE(r["ok"].get<bool>());
  EXPECT_FALSE(Dispatch("no_such_method", json::object(), nullptr, nullptr).has_value());
}

}  // namespace
}  // namespace asgard::editor_rpc
