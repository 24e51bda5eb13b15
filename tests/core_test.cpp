// Tests of core/: what every module shares (angles, number formatting, stage timers,
// geometry predicates, atomic files, invariant checks).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "core/angles.h"
#include "core/atomic_file.h"
#include "core/check.h"
#include "core/geometry.h"
#include "core/number_format.h"
#include "core/stage_timer.h"
#include "tests/test_files.h"

namespace avenues {
namespace {

TEST(Angles, ConversionsAreNamedForWhatTheyReturn) {
  EXPECT_DOUBLE_EQ(rad_from_deg(180), std::numbers::pi);
  EXPECT_DOUBLE_EQ(rad_from_deg(90), std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(deg_from_rad(std::numbers::pi / 4), 45);
  EXPECT_NEAR(deg_from_rad(rad_from_deg(37.5)), 37.5, 1e-12);
  static_assert(rad_from_deg(0) == 0);
}

TEST(NumberFormat, ShortForMessagesExactWhereAsked) {
  EXPECT_EQ(format_number(2.5), "2.5");
  EXPECT_EQ(format_number(1e300), "1e+300");
  EXPECT_EQ(format_number(0.1234567), "0.123457");
  EXPECT_EQ(format_number("%.3f", 2.0), "2.000");
}

TEST(StageTimer, AppendsItsStageEvenWhenUnwinding) {
  std::vector<StageTime> t;
  { ScopedStageTimer s(t, "one"); }
  try {
    ScopedStageTimer s(t, "two");
    throw std::runtime_error("x");
  } catch (const std::runtime_error&) {
  }
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].stage, "one");
  EXPECT_EQ(t[1].stage, "two");
  EXPECT_GE(t[0].seconds, 0);
}

TEST(Geometry, PointInConvexPolygonIsClosedAndOrientationFree) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Vec3 n{0, 0, 1};
  EXPECT_TRUE(in_convex_polygon(square, n, {0.5, 0.5, 0}, 1e-9));
  EXPECT_TRUE(in_convex_polygon(square, n, {1, 0.5, 0}, 1e-9));  // on an edge
  EXPECT_TRUE(in_convex_polygon(square, n, {0, 0, 0}, 1e-9));    // at a corner
  EXPECT_FALSE(in_convex_polygon(square, n, {1.01, 0.5, 0}, 1e-9));
  const std::vector<Vec3> clockwise(square.rbegin(), square.rend());
  EXPECT_TRUE(in_convex_polygon(clockwise, n, {0.5, 0.5, 0}, 1e-9));
  EXPECT_FALSE(in_convex_polygon(clockwise, n, {-0.5, 0.5, 0}, 1e-9));
}

TEST(Geometry, CutPolygonAndItsArea) {
  const std::vector<Vec3> square{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  EXPECT_DOUBLE_EQ(polygon_area(square), 4);
  const std::vector<Vec3> half = cut_polygon(square, [](Vec3 p) { return 1 - p.x; });  // x <= 1
  EXPECT_DOUBLE_EQ(polygon_area(half), 2);
  EXPECT_TRUE(cut_polygon(square, [](Vec3 p) { return -1 - p.x; }).empty());
  // Far from the origin the area keeps its digits (fanned from the first vertex).
  std::vector<Vec3> far = square;
  for (Vec3& p : far) p = p + Vec3{5.4e6, 5.4e6, 0};
  EXPECT_NEAR(polygon_area(far), 4, 1e-6);
}

TEST(Geometry, AreaAndCentroidKeepTheirMillimetresFarFromTheOrigin) {
  // A 3.9 x 3 m room in national grid coordinates (x 2,500 km, y 5,600 km): about the
  // origin each cross product is about 1.4e13 m² and its rounding about 2e-3 m², so the
  // area and the centroid came out metres wrong.
  const Vec2 far{2'500'000.1, 5'600'000.2};
  std::vector<Vec2> room{{0.2, 0.2}, {4.1, 0.2}, {4.1, 3.2}, {0.2, 3.2}};
  for (Vec2& q : room) q = q + far;
  EXPECT_NEAR(signed_area(room), 11.7, 1e-6);
  const Vec2 c = centroid(room) - far;
  EXPECT_NEAR(c.x, 2.15, 1e-6);
  EXPECT_NEAR(c.y, 1.7, 1e-6);
  EXPECT_EQ(centroid(std::vector<Vec2>{}).x, 0);
  EXPECT_EQ(signed_area(std::vector<Vec2>{}), 0);
}

TEST(Geometry, ABoxGrowsByEachPointAndPassesOverNaNCoordinates) {
  Box3 b;
  EXPECT_FALSE(b.contains({0, 0, 0}));  // empty
  b.add({1, -2, 3});
  b.add({-1, 5, std::nan("")});  // z unknown: only x and y count
  b.add({std::nan(""), std::nan(""), -4});
  EXPECT_EQ(b.lo.x, -1);
  EXPECT_EQ(b.lo.y, -2);
  EXPECT_EQ(b.lo.z, -4);
  EXPECT_EQ(b.hi.x, 1);
  EXPECT_EQ(b.hi.y, 5);
  EXPECT_EQ(b.hi.z, 3);
  Box3 none;
  none.add({std::nan(""), std::nan(""), std::nan("")});
  EXPECT_EQ(none.lo.x, HUGE_VAL);  // still empty
  EXPECT_EQ(none.hi.z, -HUGE_VAL);
}

TEST(AtomicFile, WritesWholeOrLeavesTheTargetAlone) {
  namespace fs = std::filesystem;
  const avenues::testing::TempDir scratch("avenues-core");  // the test's own, named for it
  const fs::path& dir = scratch.path();
  const std::string target = (dir / "out.txt").string();
  write_file_atomically(target, "first");
  write_file_atomically(target, "second");
  std::ifstream in(target);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "second");
  EXPECT_THROW(write_file_atomically((dir / "missing" / "x.txt").string(), "x"), std::runtime_error);
  EXPECT_THROW(write_file_atomically(dir.string(), "x"), std::runtime_error);  // a directory
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left behind
}

TEST(AtomicFile, SeveralFilesAreWrittenAllOrNoneAndNoneIsNamedTwice) {
  namespace fs = std::filesystem;
  const avenues::testing::TempDir scratch("avenues-core-several");
  const fs::path& dir = scratch.path();
  const std::string a = (dir / "a.txt").string(), b = (dir / "b.txt").string();
  const std::string a_again = (dir / "." / "sub" / ".." / "a.txt").string();
  fs::create_directory(dir / "sub");
  // One file by two names: the second is named, before anything is written.
  EXPECT_NO_THROW(check_named_once({a, b, "", ""}));  // empty names (no stats file asked for) are skipped
  try {
    check_named_once({a, b, a_again});
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(a_again), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("named twice"), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_files_atomically({{a, "1"}, {a_again, "2"}}), std::runtime_error);
  EXPECT_FALSE(fs::exists(a));
  // A file that cannot be made (its folder missing) leaves the others unwritten too.
  EXPECT_THROW(write_files_atomically({{a, "1"}, {(dir / "missing" / "c.txt").string(), "3"}}), std::runtime_error);
  EXPECT_FALSE(fs::exists(a));
  write_files_atomically({{a, "1"}, {b, "2"}});
  std::ifstream in_a(a), in_b(b);
  std::stringstream ta, tb;
  ta << in_a.rdbuf(), tb << in_b.rdbuf();
  EXPECT_EQ(ta.str(), "1");
  EXPECT_EQ(tb.str(), "2");
}

TEST(Check, AFailedCheckNamesWhatAndWhere) {
  try {
    AVENUES_CHECK(1 + 1 == 3, std::string("arithmetic holds"));
    FAIL() << "no throw";
  } catch (const InvariantError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("arithmetic holds"), std::string::npos) << what;
    EXPECT_NE(what.find("core_test.cpp:"), std::string::npos) << what;
  }
  AVENUES_CHECK(true, std::string("never built"));
  int evaluated = 0;
  AVENUES_DCHECK(++evaluated > 0, std::string("counts"));
  EXPECT_EQ(evaluated, kInvariantChecks ? 1 : 0);
}

}  // namespace
}  // namespace avenues
