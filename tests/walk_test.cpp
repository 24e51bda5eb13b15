// Avenues — the walkthrough window (`avenues walk`), run for real under a virtual X server.
//
// Each test starts its own Xvfb (on a display number Xvfb picks itself, -displayfd), runs the
// real `avenues` binary in it (by argv: tests/avenues_run.h) with a key-event script (or
// real X key events sent by xdotool), and checks what the window showed — its screenshots,
// read back from the framebuffer by the viewer — against the offline renders `avenues view`
// writes for the same eye. Without Xvfb installed, the window tests skip with a message.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "cells/build_cells.h"
#include "core/thread_arena.h"
#include "plans/formats/dxf_plan.h"
#include "plans/formats/ifc_building.h"
#include "render/raster.h"
#include "tests/avenues_run.h"
#include "tests/test_files.h"
#include "tests/test_meshes.h"

namespace fs = std::filesystem;
using nlohmann::json;

using avenues::testing::Child;
using avenues::testing::Outcome;
using avenues::testing::slurp;

namespace {

std::string plan(const std::string& name) { return std::string(AVENUES_SOURCE_DIR) + "/plans/" + name; }

bool on_path(const std::string& program) {
  return avenues::testing::run_argv({"sh", "-c", "command -v \"$0\"", program}).status == 0;
}

/// The words of `text` (split at white space): view options a screenshot states, for a command line.
std::vector<std::string> split_words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

/// An Xvfb of its own, 1280×720×24, stopped (and killed with the test process) at the end.
class VirtualDisplay {
 public:
  VirtualDisplay() {
    if (!on_path("Xvfb")) {
      why_ = "Xvfb is not installed (apt-get install xvfb)";
      return;
    }
    int fds[2];
    if (pipe(fds) != 0) {
      why_ = "pipe failed";
      return;
    }
    pid_ = fork();
    if (pid_ == 0) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the test
      close(fds[0]);
      const int devnull = open("/dev/null", O_RDWR);
      dup2(devnull, 0), dup2(devnull, 1), dup2(devnull, 2);
      const std::string fd = std::to_string(fds[1]);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x720x24", "-nolisten", "tcp", "-noreset",
             static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    // Xvfb writes its display number once it is ready.
    std::string number;
    pollfd p{fds[0], POLLIN, 0};
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < deadline) {
      if (poll(&p, 1, 200) <= 0) continue;
      char c = 0;
      if (read(fds[0], &c, 1) != 1) break;
      if (c == '\n') break;
      number += c;
    }
    close(fds[0]);
    if (number.empty()) {
      why_ = "Xvfb did not start";
      stop();
      return;
    }
    display_ = ":" + number;
  }
  ~VirtualDisplay() { stop(); }
  bool ok() const { return !display_.empty(); }
  const std::string& why() const { return why_; }
  const std::string& display() const { return display_; }

 private:
  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    int status = 0;
    for (int i = 0; i < 50 && waitpid(pid_, &status, WNOHANG) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (waitpid(pid_, &status, WNOHANG) == 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, &status, 0);
    }
    pid_ = -1;
  }
  pid_t pid_ = -1;
  std::string display_, why_;
};

class WalkWindow : public avenues::testing::AvenuesRun {
 protected:
  WalkWindow() { run_options_.timeout_s = 120; }  // no walk hangs the suite

  /// Starts the virtual display, on which `avenues` then runs; false (the test skips) when
  /// Xvfb is missing.
  bool start_display() {
    x_ = std::make_unique<VirtualDisplay>();
    if (x_->ok()) run_options_.set_env = {"DISPLAY=" + x_->display()};
    return x_->ok();
  }

  json read_json(const std::string& name) const { return json::parse(slurp(path(name))); }

  /// Samples (of the RGB pictures) that differ by more than one level; -1 for different sizes.
  static long differing(const avenues::Image& a, const avenues::Image& b) {
    const avenues::Image x = avenues::rgb_of(a), y = avenues::rgb_of(b);
    if (x.width != y.width || x.height != y.height) return -1;
    long n = 0;
    for (size_t i = 0; i < x.data.size(); ++i) n += std::abs(int(x.data[i]) - int(y.data[i])) > 1;
    return n;
  }

  /// `avenues view PLAN <the screenshot's pose> [extra] -o NAME.png`, read back.
  avenues::Image offline(const std::string& plan_file, const json& shot, const std::string& name,
                         const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = split_words(shot["view_options"].get<std::string>());
    args.insert(args.begin(), {"view", plan_file});
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), {"-o", name});
    const Outcome r = run(args);
    EXPECT_EQ(r.status, 0) << r.err;
    return avenues::read_image(path(name).string());
  }

  /// Walks PLAN forward for `frames` frames from `eye` looking at `look` (through a door):
  /// the screenshot before is in room `from`, the one after in room `to`.
  void walk_through_door(const std::string& plan_file, const std::string& eye, const std::string& look,
                         const std::string& from, const std::string& to, int frames) {
    const std::string f = std::to_string(frames), g = std::to_string(frames + 1);
    write("door.txt", "0 screenshot before.png\n0 down W\n" + f + " up W\n" + g + " screenshot after.png\n" + g + " quit\n");
    const Outcome r = run({"walk", plan_file, "--eye", eye, "--look", look, "--size", "320x180", "--no-hud", "--script",
                           "door.txt", "--stats-json", "s.json"});
    ASSERT_EQ(r.status, 0) << r.err;
    const json s = read_json("s.json");
    ASSERT_EQ(s["screenshots"].size(), 2u);
    EXPECT_EQ(s["screenshots"][0]["room"], from);
    EXPECT_EQ(s["screenshots"][1]["room"], to) << "walked from '" << from << "' through the door";
  }

  std::unique_ptr<VirtualDisplay> x_;
};

#define NEED_DISPLAY()                                               \
  do {                                                               \
    if (!start_display()) GTEST_SKIP() << x_->why();                 \
  } while (0)

}  // namespace

// The heart of it: a real window, scripted keys and mouse move the eye, and the window's own
// framebuffer, read back, is the offline render of the same eye.
TEST_F(WalkWindow, ScriptedWalkShowsTheOfflineRenderOfTheSameEye) {
  NEED_DISPLAY();
  write("walk.txt",
        "# walk in, turn, look about, run a little\n"
        "0  down W\n40 up W\n41 down RIGHT\n60 up RIGHT\n61 look 30 12\n"
        "62 down LEFT_SHIFT\n62 down W\n75 up W\n75 up LEFT_SHIFT\n"
        "80 screenshot shot.png\n80 quit\n");
  const Outcome r = run({"walk", plan("jones-house.toml"), "--size", "640x360", "--no-hud", "--script", "walk.txt",
                         "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json s = read_json("s.json");
  ASSERT_EQ(s["screenshots"].size(), 1u);
  const json shot = s["screenshots"][0];
  EXPECT_EQ(s["frames"], 81);
  // The eye moved away from where the walk starts (the plan's viewpoint).
  const Outcome v = run({"view", plan("jones-house.toml"), "--stats-json", "start.json"});
  ASSERT_EQ(v.status, 0) << v.err;
  const json start = read_json("start.json");
  const double dx = shot["eye"][0].get<double>() - start["eye"][0].get<double>();
  const double dy = shot["eye"][1].get<double>() - start["eye"][1].get<double>();
  EXPECT_GT(std::hypot(dx, dy), 0.5) << shot.dump();
  EXPECT_NE(shot["yaw"].get<double>(), 0);
  const avenues::Image window = avenues::read_image(path("shot.png").string());
  EXPECT_EQ(window.width, 640);
  EXPECT_EQ(window.height, 360);
  const avenues::Image picture = offline(plan("jones-house.toml"), shot, "offline.png");
  EXPECT_EQ(differing(window, picture), 0) << "the window and `avenues view " << shot["view_options"] << "` differ";
}

// The frame budget (app/frame_budget.h): with a budget no frame can keep, walking drops the
// samples, then the resolution (the window shows each rendered pixel as a block), then the
// objects beyond 16 and 8 m, and the status line says so; once the eye stops, the view is rendered again at full detail —
// the offline render of the same eye.
TEST_F(WalkWindow, OverItsFrameBudgetTheWalkDropsDetailAndRestoresItWhenTheEyeStops) {
  NEED_DISPLAY();
  write("budget.txt", "0 down W\n12 screenshot moving.png\n13 up W\n20 screenshot still.png\n20 quit\n");
  const Outcome r = run({"walk", plan("two-storey-house.toml"), "--size", "640x360", "--no-hud", "--samples", "4",
                         "--frame-budget", "0.001", "--script", "budget.txt", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json s = read_json("s.json");
  ASSERT_EQ(s["screenshots"].size(), 2u);
  const json moving = s["screenshots"][0], still = s["screenshots"][1];
  // Over budget every frame: 4 samples, 1, half resolution, a quarter, then no objects
  // beyond 16 m, then 8 m.
  EXPECT_EQ(moving["detail"]["samples"], 1);
  EXPECT_EQ(moving["detail"]["scale"], 4);
  EXPECT_EQ(moving["detail"]["objects_within_m"], 8);
  bool says = false;
  for (const json& line : moving["status"])
    says |= line.get<std::string>().find("frame budget") != std::string::npos &&
            line.get<std::string>().find("no objects beyond 8 m") != std::string::npos;
  EXPECT_TRUE(says) << moving["status"].dump();
  EXPECT_FALSE(still["detail"].contains("objects_within_m"));
  EXPECT_GE(s["reduced_frames"].get<long>(), 10);
  EXPECT_GE(s["refined_frames"].get<long>(), 1);
  // The moving picture is made of 4 × 4 blocks.
  const avenues::Image shot = avenues::rgb_of(avenues::read_image(path("moving.png").string()));
  long off_block = 0;
  for (int y = 0; y < shot.height; ++y)
    for (int x = 0; x < shot.width; ++x)
      for (int k = 0; k < 3; ++k)
        off_block += shot.row(y)[3 * x + k] != shot.row(y - y % 4)[3 * (x - x % 4) + k];
  EXPECT_EQ(off_block, 0);
  // Still: full detail, the offline render of the same eye with the same samples.
  EXPECT_EQ(still["detail"]["samples"], 4);
  EXPECT_EQ(still["detail"]["scale"], 1);
  const avenues::Image window = avenues::read_image(path("still.png").string());
  const avenues::Image picture = offline(plan("two-storey-house.toml"), still, "offline.png", {"--samples", "4"});
  EXPECT_EQ(differing(window, picture), 0) << "the still window and `avenues view " << still["view_options"] << "` differ";
}

// A long search (an open grid of 48 × 48 boxes seen over its walls: thousands of cells)
// runs on both threads, the window in strips (visibility/strips.h), and the window still
// shows the offline render of the same eye, which searches the whole window at once.
TEST_F(WalkWindow, ALongSearchRunsInStripsOnEveryThreadAndShowsTheSamePicture) {
  NEED_DISPLAY();
  const avenues::Mesh boxes = avenues::testing::open_boxes(48);
  std::ostringstream obj;
  obj.precision(17);
  for (const avenues::Vec3& v : boxes.vertices) obj << "v " << v.x << " " << v.y << " " << v.z << "\n";
  for (const auto& t : boxes.triangles) obj << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  const std::string file = write("boxes.obj", obj.str());
  write("look.txt", "0 down W\n3 up W\n10 screenshot still.png\n10 quit\n");
  const Outcome r = run({"walk", file, "--eye", "-1,-0.3,1.6", "--look", "30,30,1.2", "--size", "320x180", "--no-hud",
                         "--script", "look.txt", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json s = read_json("s.json");
  ASSERT_EQ(s["screenshots"].size(), 1u);
  const json still = s["screenshots"][0];
  // Thousands of cells whole; the half-tone's search skips those seen between its samples.
  EXPECT_GT(still["visible_cells"].get<long>(), 1000) << still.dump();
  if (avenues::arena_for(0).max_concurrency() >= 2) {  // the threads the walk's pictures may take
    EXPECT_GE(still["search_threads"].get<int>(), 2) << still.dump();
  }
  bool says = false;
  for (const json& line : still["status"]) says |= line.get<std::string>().find("threads)") != std::string::npos;
  EXPECT_EQ(says, still["search_threads"].get<int>() > 1) << still["status"].dump();
  const avenues::Image window = avenues::read_image(path("still.png").string());
  const avenues::Image picture = offline(file, still, "offline.png");
  EXPECT_EQ(differing(window, picture), 0) << "the window and `avenues view " << still["view_options"] << "` differ";
}

// An IFC building walked for real: from one of the duplex's named spaces through a door
// (the model's IfcDoor, cut into its wall) into another.
TEST_F(WalkWindow, DuplexWalkGoesThroughADoorFromOneSpaceIntoAnother) {
  const std::string model = avenues::testing::outside_path("ifc/duplex.ifc");
  NEED_DISPLAY();
  const avenues::Plan p = avenues::read_ifc_building(model);
  const avenues::CellComplex c = avenues::build_cells(p);
  // A door with a different named room a metre either side of it, on the lowest storey
  // that has one.
  std::string from, to, eye, look;
  int doors = 0, located = 0;
  for (const avenues::Wall& w : p.walls) {
    const avenues::Storey& st = p.storeys[size_t(w.storey)];
    const avenues::Vec2 d = (1 / avenues::length(w.centre[1] - w.centre[0])) * (w.centre[1] - w.centre[0]);
    const avenues::Vec2 n{-d.y, d.x};
    for (const avenues::Opening& o : w.openings) {
      if (o.kind != avenues::OpeningKind::Door || o.width < 0.7 || o.sill > 0 || !from.empty()) continue;
      ++doors;
      const avenues::Vec2 m = w.centre[0] + (o.at + o.width / 2) * d;
      const double z = st.elevation + 1.6;
      const avenues::Vec2 a = m - (1.0 + w.thickness / 2) * n, b = m + (1.0 + w.thickness / 2) * n;
      const avenues::Location la = c.locate({a.x, a.y, z}), lb = c.locate({b.x, b.y, z});
      if (la.what != avenues::Location::What::Cell || lb.what != avenues::Location::What::Cell) continue;
      ++located;
      const int ra = c.cells[size_t(la.cell)].room, rb = c.cells[size_t(lb.cell)].room;
      if (ra < 0 || rb < 0 || ra == rb || !c.rooms[size_t(ra)].named || !c.rooms[size_t(rb)].named) continue;
      from = c.rooms[size_t(ra)].name, to = c.rooms[size_t(rb)].name;
      eye = std::to_string(a.x) + "," + std::to_string(a.y) + "," + std::to_string(z);
      look = std::to_string(b.x) + "," + std::to_string(b.y) + "," + std::to_string(z);
    }
  }
  ASSERT_FALSE(from.empty()) << "no door between two named spaces: " << doors << " doors, " << located
                              << " with free space on both sides";
  walk_through_door(model, eye, look, from, to, 90);
}

// A DXF drawing walked for real: in the house plan, from one room through a door its
// swing closed (a sheet of no thickness with the door cut in it) into the next.
TEST_F(WalkWindow, DxfHousePlanWalkGoesThroughADoorFromOneRoomIntoAnother) {
  const std::string drawing = avenues::testing::outside_path("dxf/anandkothartrdl-plan.dxf");
  NEED_DISPLAY();
  const avenues::DxfPlan d = avenues::read_dxf_plan(drawing);
  const avenues::CellComplex c = avenues::build_cells(d.plan);
  // The widest door with a different room 0.8 m either side of its middle.
  std::string from, to, eye, look;
  double widest = 0;
  for (const avenues::Wall& w : d.plan.walls) {
    const avenues::Vec2 a0 = w.centre[0], a1 = w.centre[1];
    const avenues::Vec2 u = (1 / avenues::length(a1 - a0)) * (a1 - a0), n{-u.y, u.x};
    for (const avenues::Opening& o : w.openings) {
      if (o.kind != avenues::OpeningKind::Door || o.width < 0.6 || o.width <= widest) continue;
      const avenues::Vec2 m = a0 + (o.at + o.width / 2) * u, a = m - 0.8 * n, b = m + 0.8 * n;
      const avenues::Location la = c.locate({a.x, a.y, 1.6}), lb = c.locate({b.x, b.y, 1.6});
      if (la.what != avenues::Location::What::Cell || lb.what != avenues::Location::What::Cell) continue;
      const int ra = c.cells[size_t(la.cell)].room, rb = c.cells[size_t(lb.cell)].room;
      if (ra < 0 || rb < 0 || ra == rb) continue;
      widest = o.width;
      from = c.rooms[size_t(ra)].name, to = c.rooms[size_t(rb)].name;
      eye = std::to_string(a.x) + "," + std::to_string(a.y) + ",1.6";
      look = std::to_string(b.x) + "," + std::to_string(b.y) + ",1.6";
    }
  }
  ASSERT_FALSE(from.empty()) << "no door between two rooms in " << drawing;
  walk_through_door(drawing, eye, look, from, to, 60);
}

TEST_F(WalkWindow, StereoSideBySideAndAnaglyphMatchTheOfflineStereoPictures) {
  NEED_DISPLAY();
  write("stereo.txt",
        "0 down W\n20 up W\n21 tap B\n22 screenshot sbs.png\n23 tap B\n24 screenshot anaglyph.png\n25 quit\n");
  const Outcome r = run({"walk", plan("two-storey-house.toml"), "--size", "640x360", "--no-hud", "--script",
                         "stereo.txt", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json s = read_json("s.json");
  ASSERT_EQ(s["screenshots"].size(), 2u);
  const json sbs = s["screenshots"][0], ana = s["screenshots"][1];
  EXPECT_EQ(sbs["stereo"], "side-by-side");
  EXPECT_EQ(ana["stereo"], "anaglyph");
  // Side by side: each eye gets half the window.
  std::string half = sbs["view_options"].get<std::string>();
  half.replace(half.find("--size 640x360"), 14, "--size 320x360");
  std::vector<std::string> args = split_words(half);
  args.insert(args.begin(), {"view", plan("two-storey-house.toml")});
  args.insert(args.end(), {"--stereo", "parallel", "-o", "sbs-offline.png"});
  const Outcome v = run(args);
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_EQ(differing(avenues::read_image(path("sbs.png").string()), avenues::read_image(path("sbs-offline.png").string())), 0);
  const avenues::Image a = offline(plan("two-storey-house.toml"), ana, "anaglyph-offline.png", {"--stereo", "anaglyph"});
  EXPECT_EQ(differing(avenues::read_image(path("anaglyph.png").string()), a), 0);
}

TEST_F(WalkWindow, ResizedWindowRendersAtItsNewSize) {
  NEED_DISPLAY();
  write("resize.txt", "0 resize 500 300\n2 down LEFT\n12 up LEFT\n13 screenshot small.png\n13 quit\n");
  const Outcome r = run({"walk", plan("office-corridor.toml"), "--size", "640x360", "--no-hud", "--script",
                         "resize.txt", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json shot = read_json("s.json")["screenshots"][0];
  const avenues::Image window = avenues::read_image(path("small.png").string());
  EXPECT_EQ(window.width, 500);
  EXPECT_EQ(window.height, 300);
  EXPECT_EQ(differing(window, offline(plan("office-corridor.toml"), shot, "offline.png")), 0);
}

TEST_F(WalkWindow, ProgressiveDisplayBuildsTheViewCellByCell) {
  NEED_DISPLAY();
  write("progressive.txt", "0 screenshot first.png\n1 screenshot second.png\n200 screenshot done.png\n200 quit\n");
  const Outcome r = run({"walk", plan("jones-house.toml"), "--size", "480x270", "--no-hud", "--progressive",
                         "--script", "progressive.txt", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json s = read_json("s.json");
  ASSERT_GE(s["last"]["avenues"].get<int>(), 3);
  const avenues::Image full = offline(plan("jones-house.toml"), s["screenshots"][2], "offline.png");
  const avenues::Image first = avenues::read_image(path("first.png").string());
  const avenues::Image second = avenues::read_image(path("second.png").string());
  // The first frame shows the eye's cell alone, the next one more, the last the whole view.
  EXPECT_GT(differing(first, full), 0);
  EXPECT_GT(differing(first, second), 0);
  EXPECT_GT(differing(second, full), 0);
  EXPECT_EQ(differing(avenues::read_image(path("done.png").string()), full), 0);
}

TEST_F(WalkWindow, HiddenLineModeShowsInkOnPaper) {
  NEED_DISPLAY();
  write("lines.txt", "0 tap L\n1 screenshot lines.png\n2 tap L\n3 screenshot halftone.png\n3 quit\n");
  const Outcome r = run({"walk", plan("jones-house.toml"), "--size", "640x360", "--no-hud", "--script", "lines.txt",
                         "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const avenues::Image lines = avenues::grey_of(avenues::read_image(path("lines.png").string()));
  long ink = 0, paper = 0;
  for (uint8_t v : lines.data) ink += v < 128, paper += v > 250;
  const double n = double(lines.data.size());
  EXPECT_GT(ink / n, 0.002) << "no lines drawn";
  EXPECT_LT(ink / n, 0.2);
  EXPECT_GT(paper / n, 0.7);
  EXPECT_EQ(read_json("s.json")["screenshots"][0]["style"], "lines");
  EXPECT_EQ(differing(avenues::read_image(path("halftone.png").string()),
                      offline(plan("jones-house.toml"), read_json("s.json")["screenshots"][1], "offline.png")),
            0);
}

TEST_F(WalkWindow, StatusLineAndHelpDrawOverThePictureOnly) {
  NEED_DISPLAY();
  write("hud.txt", "0 screenshot hud.png\n1 tap H\n2 screenshot help.png\n2 quit\n");
  const Outcome r = run({"walk", plan("jones-house.toml"), "--size", "640x360", "--script", "hud.txt", "--stats-json",
                         "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const avenues::Image bare = offline(plan("jones-house.toml"), read_json("s.json")["screenshots"][0], "offline.png");
  const avenues::Image hud = avenues::read_image(path("hud.png").string());
  const avenues::Image help = avenues::read_image(path("help.png").string());
  ASSERT_EQ(hud.width, bare.width);
  // The status line covers the top-left corner and nothing of the bottom half.
  long top_left = 0, bottom = 0, help_centre = 0;
  for (int y = 0; y < hud.height; ++y)
    for (int x = 0; x < hud.width; ++x)
      for (int k = 0; k < 3; ++k) {
        const size_t i = (size_t(y) * size_t(hud.width) + size_t(x)) * 3 + size_t(k);
        const bool differs = hud.data[i] != bare.data[i];
        if (y < 40 && x < 200) top_left += differs;
        if (y > hud.height / 2) bottom += differs;
        if (std::abs(y - hud.height / 2) < 20 && std::abs(x - hud.width / 2) < 100) help_centre += help.data[i] != hud.data[i];
      }
  EXPECT_GT(top_left, 1000);
  EXPECT_EQ(bottom, 0);
  EXPECT_GT(help_centre, 1000) << "the help did not show";
}

// Jones's sense switches latch: on, they move the eye along the world's axes at 1 m/s and
// change the picture's scale by 1.25 a second, every frame, until switched off. Here z+
// climbs the stairwell, x+ walks off it onto the landing, scale+ zooms in.
TEST_F(WalkWindow, SenseSwitchesLatchAndMoveTheEyeUpTheStairwell) {
  NEED_DISPLAY();
  write("switches.txt",
        "0 tap 5\n240 tap 5\n241 tap 1\n301 tap 1\n302 tap 7\n362 tap 7\n363 pose\n363 quit\n");
  const Outcome r = run({"walk", plan("two-storey-house.toml"), "--eye", "0.9,2.2,1.6", "--look", "0.9,5,1.6", "--fov",
                         "60", "--size", "320x180", "--script", "switches.txt", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json last = read_json("s.json")["last"];
  EXPECT_EQ(last["room"], "landing");
  EXPECT_EQ(last["storey"], "upper");
  EXPECT_NEAR(last["eye"][0].get<double>(), 1.9, 1e-9);
  EXPECT_NEAR(last["eye"][1].get<double>(), 2.2, 1e-9);
  EXPECT_NEAR(last["eye"][2].get<double>(), 2.9 + 1.6, 1e-9);
  const double want_fov = 2 * std::atan(std::tan(30 * M_PI / 180) / 1.25) * 180 / M_PI;
  EXPECT_NEAR(last["fov"].get<double>(), want_fov, 1e-6);
  EXPECT_NE(r.out.find("pose: --eye "), std::string::npos) << r.out;
}

// An IFC building walked as its users walk it (issue 17): in the duplex, from beside Bathroom 1
// (Revit's spaces make it one room with the living floor) east through a door onto the
// stair, up it to Level 2 (PgUp), along the hallway and west through a door into another
// room, Bathroom 2. The walk speed is 1.4 m/s, the turn 90°/s, frames 1/60 s.
TEST_F(WalkWindow, WalksTheDuplexThroughADoorUpItsStairAndThroughAnotherDoor) {
  NEED_DISPLAY();
  const std::string duplex = avenues::testing::outside_path("ifc/duplex.ifc");
  if (!fs::exists(duplex)) GTEST_SKIP() << "no " << duplex;
  write("duplex.txt",
        "0 down W\n105 up W\n106 pose\n"              // east 2.45 m, through the door, onto the stair
        "106 down PAGE_UP\n286 up PAGE_UP\n"           // up the stair to Level 2
        "287 down LEFT\n347 up LEFT\n348 down W\n403 up W\n"   // north 1.28 m along the hallway
        "404 down LEFT\n464 up LEFT\n465 down W\n565 up W\n"   // west 2.33 m, through the door
        "566 quit\n");
  const Outcome r = run({"walk", duplex, "--eye", "5.3,-9.67,1.62", "--look", "8,-9.67,1.62", "--size", "320x180",
                         "--script", "duplex.txt", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  // On the stair, still on Level 1: the door let the walk through.
  EXPECT_NE(r.out.find("pose: --eye 7.75"), std::string::npos) << r.out;
  const json last = read_json("s.json")["last"];
  EXPECT_EQ(last["room"], "Bathroom 2");
  EXPECT_EQ(last["storey"], "Level 2");
  EXPECT_EQ(last["mode"], "walk");
  EXPECT_NEAR(last["eye"][0].get<double>(), 7.75 - 1.4 * 100 / 60, 1e-6);
  EXPECT_NEAR(last["eye"][1].get<double>(), -9.67 + 1.4 * 55 / 60, 1e-6);
  EXPECT_NEAR(last["eye"][2].get<double>(), 3.12 + 1.6, 1e-3);
}

// The gamepad, through the same path as GLFW's gamepad state (a scripted pad stands in for a
// real one): the left stick walks, the right stick turns, a button is a command.
TEST_F(WalkWindow, AGamepadsSticksWalkTurnAndItsButtonsCommand) {
  NEED_DISPLAY();
  write("pad.txt",
        "0 pad LEFT_Y -1\n60 pad LEFT_Y 0\n"          // stick forward for one second (60 frames of 1/60 s)
        "61 pad RIGHT_X -1\n91 pad RIGHT_X 0\n"       // stick left for half a second
        "92 pad A 1\n93 pad A 0\n"                    // A: fly mode
        "94 pad RIGHT_TRIGGER 1\n124 pad RIGHT_TRIGGER -1\n"  // climb for half a second
        "125 pose\n125 quit\n");
  const Outcome r = run({"walk", plan("jones-house.toml"), "--eye", "2,1.5,1.6", "--look", "2,5,1.6", "--fov", "60",
                         "--size", "320x180", "--script", "pad.txt", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json last = read_json("s.json")["last"];
  // Forward at the walking speed (1.4 m/s) for the 60 frames the stick was held.
  EXPECT_NEAR(last["eye"][0].get<double>(), 2.0, 1e-9);
  EXPECT_NEAR(last["eye"][1].get<double>(), 1.5 + 1.4, 1e-6);
  // Turned left (anticlockwise) at 90°/s for 30 frames; A flipped walking to flying, and the
  // right trigger then climbed at 1.2 m/s for 30 frames.
  EXPECT_NEAR(last["yaw"].get<double>(), 90 + 45, 1e-6);
  EXPECT_EQ(last["mode"], "fly");
  EXPECT_NEAR(last["eye"][2].get<double>(), 1.6 + 0.6, 1e-6);
  write("bad.txt", "0 pad LEFT_Z 1\n");
  const Outcome named = run({"walk", plan("jones-house.toml"), "--script", "bad.txt"});
  EXPECT_EQ(named.status, 2);
  EXPECT_NE(named.err.find("bad.txt:1"), std::string::npos) << named.err;
  EXPECT_NE(named.err.find("LEFT_Z"), std::string::npos) << named.err;
}

TEST_F(WalkWindow, ExportsAndKeyframesFromTheWindow) {
  NEED_DISPLAY();
  write("export.txt",
        "5 screenshot shot.png\n5 tap F2\n6 tap F3\n7 tap F4\n8 tap K\n"
        "9 down W\n60 up W\n61 tap K\n62 down RIGHT\n80 up RIGHT\n81 tap K\n82 quit\n");
  const Outcome r = run({"walk", plan("jones-house.toml"), "--size", "480x270", "--script", "export.txt",
                         "--stats-json", "s.json", "--out-dir", "out", "--record", "keys.txt"});
  ASSERT_EQ(r.status, 0) << r.err;
  // F2: the picture as shown, without the status line: the offline render of that eye.
  ASSERT_TRUE(fs::exists(path("out/jones-house-0001.png"))) << r.out;
  EXPECT_EQ(differing(avenues::read_image(path("out/jones-house-0001.png").string()),
                      offline(plan("jones-house.toml"), read_json("s.json")["screenshots"][0], "offline.png")),
            0);
  // F3: the hidden-line drawing; F4: a stereo pair as a picture and as two drawings.
  pugi::xml_document svg;
  ASSERT_TRUE(svg.load_file(path("out/jones-house-0002.svg").c_str())) << r.out;
  EXPECT_TRUE(svg.child("svg")) << "not an SVG drawing";
  const avenues::Image pair = avenues::read_image(path("out/jones-house-0003-stereo.png").string());
  EXPECT_EQ(pair.width, 2 * 480);
  EXPECT_TRUE(fs::exists(path("out/jones-house-0004-stereo-left.svg")));
  EXPECT_TRUE(fs::exists(path("out/jones-house-0004-stereo-right.svg")));
  EXPECT_NE(r.out.find("wrote out/jones-house-0001.png"), std::string::npos) << r.out;
  // K: three keyframes, which `avenues path --keys` follows.
  std::istringstream keys(slurp(path("keys.txt")));
  int frames = 0;
  for (std::string line; std::getline(keys, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    double v[6];
    for (double& x : v) ASSERT_TRUE(words >> x) << line;
    ++frames;
  }
  EXPECT_EQ(frames, 3);
  const Outcome p = run({"path", plan("jones-house.toml"), "--keys", "keys.txt", "-o", "frames", "--format", "svg",
                         "--size", "160x90", "--step", "0.5"});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_TRUE(fs::exists(path("frames/frame-0001.svg")));
}

// A thousand frames of random input (keys held and let go, switches, mode and style toggles,
// mouse looks, resizes) from a fixed seed: no crash, the eye always somewhere, and memory
// flat from frame 100 to frame 1000.
TEST_F(WalkWindow, ThousandFramesOfRandomInputWithoutACrashOrALeak) {
  NEED_DISPLAY();
  for (const char* name : {"jones-house.toml", "two-storey-house.toml"}) {
    avenues::testing::RunOptions longer = run_options_;
    longer.timeout_s = 300;
    const Outcome r = run({"walk", plan(name), "--size", "640x360", "--random-input", "1971", "--frames", "1000",
                           "--stats-json", "s.json"},
                          longer);
    ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    const json s = read_json("s.json");
    EXPECT_EQ(s["frames"], 1000);
    EXPECT_FALSE(s["last"]["room"].get<std::string>().empty());
    const long at100 = s["rss_kb"]["frame_100"], last = s["rss_kb"]["last"];
    ASSERT_GT(at100, 0);
    // Pictures and textures follow the window's size (random resizes up to 1160 × 680), so
    // allow for a few frames' worth of buffers; a leak of a frame's picture per frame would
    // be gigabytes.
    EXPECT_LT(last - at100, 24 * 1024) << name << ": resident memory grew from " << at100 << " kB to " << last << " kB";
  }
}

// Real X key events (xdotool, through the X server like a keyboard's): the main job opens the
// window when there is a display, W walks, Escape quits; nothing is written offline.
TEST_F(WalkWindow, MainJobOpensTheWindowAndRealKeysWalk) {
  NEED_DISPLAY();
  if (!on_path("xdotool")) GTEST_SKIP() << "xdotool is not installed (apt-get install xdotool)";
  // xdotool on the same display, each call stopped after 20 s.
  avenues::testing::RunOptions briefly = run_options_;
  briefly.timeout_s = 20;
  auto xdotool = [&](std::vector<std::string> args) {
    args.insert(args.begin(), "xdotool");
    return run_argv(args, briefly).status;
  };
  // The window, once it is on the screen, gets the focus; then W is held and Escape pressed.
  auto walk_and_quit = [&](Child& child, const std::vector<std::string>& more) {
    bool focused = false;
    for (int i = 0; i < 100 && !focused && running(child); ++i) {
      focused = xdotool({"search", "--onlyvisible", "--name", "^Avenues - jones-house$", "windowfocus", "--sync"}) == 0;
      if (!focused) std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    EXPECT_TRUE(focused) << "no window appeared";
    std::vector<std::string> keys = {"keydown", "w", "sleep", "0.6", "keyup", "w", "sleep", "0.3"};
    keys.insert(keys.end(), more.begin(), more.end());
    keys.insert(keys.end(), {"key", "Escape"});
    EXPECT_EQ(xdotool(keys), 0);
    bool exited = false;
    for (int i = 0; i < 200 && !exited; ++i) {
      exited = !running(child);
      if (!exited) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    EXPECT_TRUE(exited) << "Escape did not close the window";
    if (!exited) ::kill(child.pid(), SIGTERM);  // timeout(1) passes it on
    return finish(child);
  };
  Child main_job = start({plan("jones-house.toml"), "--out-dir", "out"});
  const Outcome main_outcome = walk_and_quit(main_job, {});
  EXPECT_NE(main_outcome.out.find("opening the walkthrough window"), std::string::npos)
      << main_outcome.out << main_outcome.err;
  EXPECT_FALSE(fs::exists(path("out/jones-house-plan.svg"))) << "the offline job ran as well";
  // The same with a walk that reports where it ended: real key events moved the eye, and a
  // drag with the left button held turned it (0.15 degrees a pixel, to the right).
  Child walk = start({"walk", plan("jones-house.toml"), "--stats-json", "s.json"});
  const Outcome walked =
      walk_and_quit(walk, {"mousemove", "600", "300", "sleep", "0.2", "mousedown", "1", "sleep", "0.2",
                           "mousemove_relative", "200", "0", "sleep", "0.3", "mouseup", "1", "sleep", "0.2"});
  ASSERT_TRUE(fs::exists(path("s.json"))) << walked.err;
  const Outcome v = run({"view", plan("jones-house.toml"), "--stats-json", "start.json"});
  ASSERT_EQ(v.status, 0);
  const json s = read_json("s.json"), s0 = read_json("start.json");
  const double moved = std::hypot(s["last"]["eye"][0].get<double>() - s0["eye"][0].get<double>(),
                                  s["last"]["eye"][1].get<double>() - s0["eye"][1].get<double>());
  EXPECT_GT(moved, 0.2) << "holding W for 0.6 s did not walk";
  const double yaw0 = std::atan2(s0["look"][1].get<double>() - s0["eye"][1].get<double>(),
                                 s0["look"][0].get<double>() - s0["eye"][0].get<double>()) * 180 / M_PI;
  EXPECT_NEAR(s["last"]["yaw"].get<double>(), yaw0 - 200 * 0.15, 1.0) << "the drag did not turn the eye";
}

// Without a display the main job keeps to its offline work; a bad script names its line.
TEST_F(WalkWindow, WithoutADisplayWalkSaysSoAndBadScriptsNameTheLine) {
  Outcome r = run({"walk", plan("jones-house.toml"), "--frames", "3"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot open the walkthrough window: no display"), std::string::npos) << r.err;
  write("bad.txt", "0 down W\n\n5 press Q\n");
  r = run({"walk", plan("jones-house.toml"), "--script", "bad.txt"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bad.txt:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("unknown event 'press'"), std::string::npos) << r.err;
  write("bad-key.txt", "7 down NOPE\n");
  r = run({"walk", plan("jones-house.toml"), "--script", "bad-key.txt"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bad-key.txt:1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("unknown key 'NOPE'"), std::string::npos) << r.err;
  r = run({plan("jones-house.toml"), "--out-dir", "out"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("out/jones-house-plan.svg")));
  EXPECT_EQ(r.out.find("opening the walkthrough window"), std::string::npos);
}
