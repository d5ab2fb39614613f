// asgard-core's editor methods (core/app/editor_rpc.h): what the browser's
// handles and language viewers read — word spans, element editability, the
// body centroids and the per-frame force values.
#include "core/app/editor_rpc.h"

#include <gtest/gtest.h>

#include "core/pipeline/pipeline.h"
#include "core/render/sampler.h"
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

TEST(EditorRpc, MotionMethodsRefuseBeforeASimulation) {
  const json r = *Dispatch("poses", json::object(), nullptr, nullptr);
  EXPECT_FALSE(r["ok"].get<bool>());
  EXPECT_FALSE(Dispatch("no_such_method", json::object(), nullptr, nullptr).has_value());
}

}  // namespace
}  // namespace asgard::editor_rpc
