// Tests of the walkthrough's parts without a window: the walking state (app/walk_state.h),
// the exports and keyframes (app/walk_exports.h) and the frame statistics (app/walk_stats.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/plan_source.h"
#include "app/walk_exports.h"
#include "app/walk_state.h"
#include "app/walk_stats.h"
#include "tests/test_files.h"

namespace avenues::app {
namespace {

namespace fs = std::filesystem;

LoadedPlan jones_house() { return load_plan_source(std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml"); }

TEST(WalkState, StartsAtThePlansViewAndWalksAlongTheHeading) {
  const LoadedPlan plan = jones_house();  // [view]: eye (1.5, 3, 1.6) looking east, fov 60
  WalkOptions opt;
  WalkState s(plan, opt);
  EXPECT_NEAR(s.eye().x, 1.5, 1e-9);
  EXPECT_NEAR(s.eye().y, 3.0, 1e-9);
  EXPECT_NEAR(s.yaw(), 0, 1e-9);
  EXPECT_LT(s.pitch(), 0);  // it looks down a little, at (5, 3, 1.4)
  EXPECT_DOUBLE_EQ(s.fov(), 60);
  EXPECT_EQ(s.mode(), MoveMode::Walk);
  EXPECT_NE(s.place().find("room 'L'"), std::string::npos) << s.place();
  // A metre forward in walk mode: along the heading, at the same height.
  Motion m;
  m.forward = 1;
  EXPECT_TRUE(s.step(m, 0.1));
  EXPECT_NEAR(s.eye().x, 2.5, 1e-9);
  EXPECT_NEAR(s.eye().y, 3.0, 1e-9);
  EXPECT_NEAR(s.eye().z, 1.6, 1e-9);
  // A quarter turn left, then a metre forward: north.
  Motion turn;
  turn.turn = 90;
  EXPECT_TRUE(s.step(turn, 0.1));
  EXPECT_NEAR(s.yaw(), 90, 1e-9);
  EXPECT_TRUE(s.step(m, 0.1));
  EXPECT_NEAR(s.eye().x, 2.5, 1e-9);
  EXPECT_NEAR(s.eye().y, 4.0, 1e-9);
  // Nothing asked, nothing changes.
  EXPECT_FALSE(s.step(Motion{}, 0.1));
  // Zoom stays within its limits; the pitch within ±89°.
  Motion zoom;
  zoom.zoom = 1e6;
  s.step(zoom, 0.1);
  EXPECT_DOUBLE_EQ(s.fov(), WalkState::kMinFov);
  zoom.zoom = 1e-6;
  s.step(zoom, 0.1);
  EXPECT_DOUBLE_EQ(s.fov(), WalkState::kMaxFov);
  Motion up;
  up.pitch = 500;
  s.step(up, 0.1);
  EXPECT_DOUBLE_EQ(s.pitch(), 89);
  s.level();
  EXPECT_DOUBLE_EQ(s.pitch(), 0);
  s.toggle_mode();
  EXPECT_EQ(s.mode(), MoveMode::Fly);
  // The pose as `avenues view` options, exactly.
  EXPECT_EQ(s.pose_text(64, 36).rfind("--eye 2.5,4,1.6", 0), 0u) << s.pose_text(64, 36);
  EXPECT_NE(s.pose_text(64, 36).find("--size 64x36"), std::string::npos);
  EXPECT_EQ(s.pose_json()["mode"], "fly");
  EXPECT_EQ(s.pose_json()["room"], "L");
}

TEST(WalkState, AnEyeOutsideFreeSpaceIsRefusedNamingIt) {
  const LoadedPlan plan = jones_house();
  WalkOptions opt;
  opt.eye = "1.5,3,-0.5";  // below the ground, outside the far box
  opt.look = "5,3,-0.5";
  try {
    WalkState s(plan, opt);
    ADD_FAILURE() << "an eye in the ground was taken";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("the eye (1.5, 3, -0.5) is outside the far box"), std::string::npos) << e.what();
  }
}

TEST(WalkExports, NumbersPastWhatIsThereAndAppendsKeyframes) {
  const LoadedPlan plan = jones_house();
  avenues::testing::TempDir dir("avenues-walk-exports");
  WalkOptions opt;
  opt.out_dir = (dir.path() / "out").string();
  WalkExports ex(plan, opt);
  Image img;
  img.resize(4, 3, 3);
  EXPECT_EQ(ex.picture(img), "wrote " + opt.out_dir + "/jones-house-0001.png (the picture as shown)");
  std::ofstream(dir.path() / "out" / "jones-house-0002.png") << "someone else's";
  EXPECT_EQ(ex.picture(img), "wrote " + opt.out_dir + "/jones-house-0003.png (the picture as shown)");
  EXPECT_EQ(avenues::testing::slurp(dir.path() / "out" / "jones-house-0002.png"), "someone else's");
  EXPECT_EQ(ex.keyframe_file(), opt.out_dir + "/jones-house-keys.txt");
  ex.keyframe({1.5, 3, 1.6}, {2.5, 3, 1.6});
  const std::string said = ex.keyframe({2.5, 3, 1.6}, {2.5, 4, 1.6});
  EXPECT_NE(said.find("keyframe 2 appended"), std::string::npos) << said;
  EXPECT_EQ(ex.keyframes(), 2);
  const std::string keys = avenues::testing::slurp(ex.keyframe_file());
  EXPECT_EQ(keys.rfind("# avenues walk keyframes (jones-house)", 0), 0u) << keys;
  // Two lines of six numbers, exact to the last bit (17 digits), after the comment.
  std::istringstream in(keys.substr(keys.find('\n') + 1));
  const double want[12] = {1.5, 3, 1.6, 2.5, 3, 1.6, 2.5, 3, 1.6, 2.5, 4, 1.6};
  for (double w : want) {
    double got = 0;
    ASSERT_TRUE(in >> got) << keys;
    EXPECT_EQ(got, w);
  }
  // The view through `avenues view -o`'s code: a drawing beside the pictures.
  ViewOptions vo;
  const ViewSetup v = set_up_view(plan, vo);
  EXPECT_EQ(ex.view(v, ".svg", ""), "wrote " + opt.out_dir + "/jones-house-0004.svg");
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "jones-house-0004.svg"));
}

TEST(WalkStats, PercentilesAndTheReportAsJson) {
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);
  const Percentiles p = percentiles(v);
  EXPECT_DOUBLE_EQ(p.median, 50);
  EXPECT_DOUBLE_EQ(p.p95, 95);
  EXPECT_DOUBLE_EQ(p.p99, 99);
  EXPECT_DOUBLE_EQ(p.max, 100);
  EXPECT_DOUBLE_EQ(p.mean, 50.5);
  EXPECT_DOUBLE_EQ(percentiles({}).median, 0);
  WalkReport r;
  r.work_ms = v;
  r.render_ms = {2, 4};
  r.reduced_frames = 3;
  for (long f = 0; f < 100; ++f) r.sample_process(f);
  r.finish();
  EXPECT_GT(r.rss_kb_100, 0);
  EXPECT_GE(r.cpu_s_last, r.cpu_s_10);
  const nlohmann::json j = r.to_json("plan.toml");
  EXPECT_EQ(j["plan"], "plan.toml");
  EXPECT_EQ(j["frames"], 100);
  EXPECT_EQ(j["rendered_frames"], 2);
  EXPECT_EQ(j["reduced_frames"], 3);
  EXPECT_DOUBLE_EQ(j["work_ms"]["median"].get<double>(), 50);
  EXPECT_TRUE(j.contains("cpu_ms_per_frame"));
}

}  // namespace
}  // namespace avenues::app
