// The asgard-core protocol's editing methods: load, simulate, edit, update,
// undo — the same session the CLI and the tests use, behind the pipe.
#include <gtest/gtest.h>

#include "medium-plugin/slave.h"

namespace asgard::medium {
namespace {

const std::string kCore = std::string(ASGARD_BINARY_DIR) + "/core/app/asgard-core";
const std::string kScene =
    "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n"
    "body a -shape ball -init_pos {0 0 0} -init_dpos {1 0 0}  ;# mover\n"
    "body b -shape ball -init_pos {0 5 0}\n"
    "foreach i {1 2} { body c$i -shape ball -init_pos \"$i 9 0\" }\n"
    "simulator -finish 2\n";

TEST(Protocol, EditsBecomeTextPatchesAndResimulationIsIncremental) {
  SlaveProcess slave(kCore, 20.0);
  ASSERT_TRUE(slave.running()) << slave.error();
  auto r = slave.Call("load", {{"text", kScene}});
  ASSERT_EQ(r.status, CallStatus::kOk);
  r = slave.Call("simulate", nlohmann::json::object());
  ASSERT_EQ(r.status, CallStatus::kOk);
  EXPECT_FALSE(r.result["incremental"].get<bool>());

  r = slave.Call("edit", {{"element", "b"}, {"param", "init_pos"}, {"values", {0, 6, 0}}});
  ASSERT_EQ(r.status, CallStatus::kOk);
  ASSERT_EQ(r.result["edits"].size(), 1u);
  EXPECT_EQ(r.result["edits"][0]["text"], "6");
  EXPECT_EQ(r.result["edits"][0]["line"], 3);
  EXPECT_EQ(r.result["units"], "bytes");
  std::string expected = kScene;
  expected.replace(expected.find("{0 5 0}") + 3, 1, "6");
  EXPECT_EQ(r.result["text"], expected);

  r = slave.Call("simulate", nlohmann::json::object());
  ASSERT_EQ(r.status, CallStatus::kOk);
  EXPECT_TRUE(r.result["incremental"].get<bool>());
  EXPECT_GT(r.result["components_reset"].get<int>(), 0);

  // Read-only parameters are refused with the reason, and nothing changes.
  r = slave.Call("edit", {{"element", "c1"}, {"param", "init_pos"}, {"values", {0, 0, 0}}});
  EXPECT_EQ(r.status, CallStatus::kRemoteError);
  EXPECT_NE(r.message.find("made in a loop"), std::string::npos) << r.message;
  r = slave.Call("edit", {{"element", "b"}, {"param", "init_pos"}, {"values", "x"}});
  EXPECT_EQ(r.status, CallStatus::kRemoteError);

  // An update from a language view reports what changed; undo restores.
  std::string typed = expected;
  typed.replace(typed.find("-init_dpos {1 0 0}"), 18, "-init_dpos {2 0 0}");
  r = slave.Call("update", {{"text", typed}});
  ASSERT_EQ(r.status, CallStatus::kOk);
  r = slave.Call("undo", nlohmann::json::object());
  ASSERT_EQ(r.status, CallStatus::kOk);
  EXPECT_EQ(r.result["text"], expected);
  r = slave.Call("undo", nlohmann::json::object());
  EXPECT_EQ(r.result["text"], kScene);
}

}  // namespace
}  // namespace asgard::medium
