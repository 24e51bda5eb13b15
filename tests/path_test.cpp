// Avenues — `avenues path`, run as a person (or a cluster job) would run it.
//
// The real executable, started by argv (tests/avenues_run.h: no shell sees the arguments),
// in a fresh temporary directory; the film is read back with libavformat; the MPI walks run
// under the real mpirun (Open MPI), on 2 and 3 ranks, and one rank is killed mid-walk.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include "tests/avenues_run.h"
#include "tests/test_files.h"

namespace fs = std::filesystem;
using avenues::testing::Outcome;
using avenues::testing::slurp;

namespace {

const std::string kHouse = std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml";

/// What libavformat finds in a film: its video stream's codec and size, and its frames.
struct FilmInfo {
  std::string codec;
  int width = 0, height = 0;
  long frames = 0;
};

FilmInfo probe_film(const fs::path& path) {
  FilmInfo info;
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) return info;
  if (avformat_find_stream_info(format, nullptr) >= 0) {
    const int video = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
    if (video >= 0) {
      const AVCodecParameters* p = format->streams[video]->codecpar;
      info.codec = avcodec_get_name(p->codec_id);
      info.width = p->width;
      info.height = p->height;
      AVPacket* packet = av_packet_alloc();
      while (av_read_frame(format, packet) >= 0) {
        info.frames += packet->stream_index == video;  // one coded picture a packet
        av_packet_unref(packet);
      }
      av_packet_free(&packet);
    }
  }
  avformat_close_input(&format);
  return info;
}

class Path : public avenues::testing::AvenuesRun {
 protected:
#ifdef AVENUES_MPIRUN
  /// `mpirun -np RANKS avenues ARGS`.
  static std::vector<std::string> mpirun(int ranks, const std::vector<std::string>& args) {
    std::vector<std::string> cmd = {AVENUES_MPIRUN, "--allow-run-as-root", "--oversubscribe", "-np", std::to_string(ranks)};
    const std::vector<std::string> command = avenues::testing::avenues_argv(args);
    cmd.insert(cmd.end(), command.begin(), command.end());
    return cmd;
  }
  Outcome run_mpi(int ranks, const std::vector<std::string>& args) { return run_argv(mpirun(ranks, args)); }
#endif

  /// The frames in `sub` (frame-NNNN.EXT), by name, with their bytes.
  std::map<std::string, std::string> frames(const std::string& sub) const {
    std::map<std::string, std::string> out;
    static const std::regex frame(R"(frame-[0-9]+\.(png|svg))");
    for (const auto& e : fs::directory_iterator(path(sub)))
      if (std::regex_match(e.path().filename().string(), frame)) out[e.path().filename().string()] = slurp(e.path());
    return out;
  }
  /// Every name in `sub`, hidden ones included.
  std::vector<std::string> names(const std::string& sub) const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(path(sub))) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
};

/// A short walk through Jones's house: its arguments before -o.
std::vector<std::string> walk_args(const std::string& out, const std::string& step = "0.5",
                                   const std::string& size = "161x91") {
  return {"path", kHouse, "--through", "L,K", "--step", step, "--size", size, "-o", out};
}

}  // namespace

TEST_F(Path, FilmHasEveryFrameAtAnEvenSize) {
  Outcome r = run(walk_args("walk"));
  ASSERT_EQ(r.status, 0) << r.err;
  const size_t n = frames("walk").size();
  ASSERT_GE(n, 5u);
  EXPECT_NE(r.out.find("walk.mp4"), std::string::npos) << r.out;
  // 161 x 91 scaled to the even size below for yuv420p; H.264 where libavcodec has libx264.
  const FilmInfo film = probe_film(path("walk/walk.mp4"));
  EXPECT_TRUE(film.codec == "h264" || film.codec == "mpeg4") << film.codec;
  EXPECT_EQ(film.width, 160);
  EXPECT_EQ(film.height, 90);
  EXPECT_EQ(film.frames, long(n));
  for (const std::string& name : names("walk")) EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
}

// Issue 21: on one thread (--threads 1, or an MPI rank's share of a machine with as many
// ranks as cores) the film is encoded between the frames, on that thread and with a
// one-thread encoder, not beside them: the film is as whole, and the frames the same bytes.
TEST_F(Path, OneThreadMakesTheFilmBetweenItsFrames) {
  std::vector<std::string> args = walk_args("one");
  args.insert(args.end(), {"--threads", "1"});
  const Outcome one = run(args);
  ASSERT_EQ(one.status, 0) << one.err;
  const Outcome all = run(walk_args("all"));
  ASSERT_EQ(all.status, 0) << all.err;
  const auto frames_one = frames("one");
  ASSERT_GE(frames_one.size(), 5u);
  EXPECT_EQ(frames_one, frames("all"));
  EXPECT_EQ(probe_film(path("one/walk.mp4")).frames, long(frames_one.size()));
  EXPECT_EQ(probe_film(path("all/walk.mp4")).frames, long(frames_one.size()));
  for (const std::string& name : names("one")) EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
}

// What reading the objects' meshes let pass is said by a walk as by a view: once.
TEST_F(Path, SaysWhatTheObjectsMeshesLetPass) {
  write("crate.obj", "mtllib crate.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 1\nusemtl Paint\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n");
  const std::string plan = write("room.toml",
                                 "name = 'crate room'\nunits = 'm'\n"
                                 "[[wall]]\nname = 'outside'\nthickness = 0.2\npath = [[0, 0], [5, 0], [5, 4], [0, 4], [0, 0]]\n"
                                 "[[room]]\nname = 'room'\nat = [1, 1]\n"
                                 "[[object]]\nname = 'crate'\nmesh = 'crate.obj'\nposition = [2.5, 2, 0]\n");
  const Outcome r = run({"path", plan, "--keys", write("keys.txt", "1 1 1.5 4 3 1\n1.2 1.1 1.5 4 3 1\n"), "--size",
                         "32x18", "-o", "walk"});
  ASSERT_EQ(r.status, 0) << r.err;
  size_t said = 0;
  for (size_t at = r.err.find("'crate.mtl' is not at hand"); at != std::string::npos;
       at = r.err.find("'crate.mtl' is not at hand", at + 1))
    ++said;
  EXPECT_EQ(said, 1u) << r.err;
}

// Issue 13, item 1: the film was made by a shell command with the output folder in quotes.
TEST_F(Path, NoShellSeesTheOutputName) {
  for (const std::string out : {"inj';touch PWNED;'", "it's", "sp ace $(touch PWNED2)"}) {
    Outcome r = run(walk_args(out, "1.0", "64x36"));
    ASSERT_EQ(r.status, 0) << out << "\n" << r.err;
    const size_t n = frames(out).size();
    EXPECT_GE(n, 2u) << out;
    EXPECT_EQ(probe_film(path(out) / "walk.mp4").frames, long(n)) << out;
  }
  EXPECT_FALSE(fs::exists(path("PWNED")));
  EXPECT_FALSE(fs::exists(path("PWNED2")));
  EXPECT_FALSE(fs::exists(fs::current_path() / "PWNED"));
}

// Issue 13, item 5: --step 1e-6 ran forever; --step 1e-9 with --keys overflowed an int.
TEST_F(Path, RefusesAStepThatIsNoLengthOrAWalkTooLong) {
  std::ofstream(path("keys.txt")) << "1.5 3 1.6  5 3 1.4\n3.0 2 1.6  5 1.6 1.4\n";
  for (const std::string step : {"1e-6", "1e-9", "0", "-0.5", "nan", "inf"}) {
    for (bool keys : {false, true}) {
      std::vector<std::string> args = {"path", kHouse, "--step", step, "-o", "none"};
      if (keys) args.insert(args.end(), {"--keys", "keys.txt"});
      else args.insert(args.end(), {"--through", "L,K"});
      Outcome r = run(args);
      EXPECT_EQ(r.status, 2) << step << (keys ? " --keys" : "");
      // What is no positive number the command line's check refuses; a positive step
      // under a millimetre, the walk's own.
      const bool positive = step == "1e-6" || step == "1e-9";
      EXPECT_NE(r.err.find(positive ? "--step must be a length of at least 0.001 m" : "--step: "), std::string::npos)
          << r.err;
      EXPECT_FALSE(fs::exists(path("none"))) << step;
    }
  }
  // A millimetre is a step, but that walk is longer than the limit asked for...
  Outcome r = run({"path", kHouse, "--through", "L,K,D", "--step", "0.001", "--max-frames", "1000", "-o", "none"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("more than --max-frames 1000"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("none")));
  // ... and so is a step of a metre through the keyframes above a limit of 2.
  Outcome keyed = run({"path", kHouse, "--keys", "keys.txt", "--step", "0.1", "--max-frames", "2", "-o", "none"});
  EXPECT_EQ(keyed.status, 2);
  EXPECT_NE(keyed.err.find("would have 20 frames"), std::string::npos) << keyed.err;  // 1 + ceil(1.80 / 0.1)
  EXPECT_EQ(run({"path", kHouse, "--keys", "keys.txt", "--max-frames", "1", "-o", "none"}).status, 2);
  EXPECT_FALSE(fs::exists(path("none")));
}

// Issue 13, items 9 and 11: a second walk into the same folder left the first one's frames,
// and its film had them all.
TEST_F(Path, AWalkOwnsItsOutput) {
  ASSERT_EQ(run(walk_args("walk", "0.25", "64x36")).status, 0);
  const size_t first = frames("walk").size();
  // What a killed walk leaves (a frame being written) and what is not the walk's.
  std::ofstream(path("walk/.frame-0003.png.tmp-a1B2c3")) << "half a frame";
  std::ofstream(path("walk/notes.txt")) << "mine";
  fs::create_directories(path("walk/frame-sketches"));
  Outcome r = run(walk_args("walk", "1.0", "64x36"));
  ASSERT_EQ(r.status, 0) << r.err;
  const size_t second = frames("walk").size();
  ASSERT_LT(second, first);
  EXPECT_EQ(probe_film(path("walk/walk.mp4")).frames, long(second));
  std::vector<std::string> expected = {"frame-sketches", "notes.txt", "walk.mp4"};
  for (size_t k = 1; k <= second; ++k) expected.push_back("frame-000" + std::to_string(k) + ".png");
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(names("walk"), expected);
  // Drawn frames replace the pictures, and there is no film of drawings.
  ASSERT_EQ(run({"path", kHouse, "--through", "L,K", "--step", "1.0", "--format", "svg", "-o", "walk"}).status, 0);
  for (const std::string& name : names("walk")) EXPECT_EQ(name.find(".png"), std::string::npos) << name;
  EXPECT_FALSE(fs::exists(path("walk/walk.mp4")));
}

// A frame that cannot be written stops the walk (exit 2): the frames before it are
// complete, and there is no film, not even its temporary file.
TEST_F(Path, AFailedFrameLeavesCompleteFramesAndNoFilm) {
  fs::create_directories(path("walk/frame-0004.png"));
  Outcome r = run(walk_args("walk", "0.3", "64x36"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot write walk/frame-0004.png: is a directory"), std::string::npos) << r.err;
  EXPECT_EQ(names("walk"), (std::vector<std::string>{"frame-0001.png", "frame-0002.png", "frame-0003.png", "frame-0004.png"}));
}

TEST_F(Path, ResumeRendersOnlyTheMissingFrames) {
  ASSERT_EQ(run(walk_args("walk", "0.5", "96x54")).status, 0);
  const auto whole = frames("walk");
  ASSERT_GE(whole.size(), 5u);
  fs::remove(path("walk/frame-0002.png"));
  fs::remove(path("walk/frame-0005.png"));
  fs::remove(path("walk/walk.mp4"));
  const auto kept = fs::last_write_time(path("walk/frame-0001.png"));
  Outcome r = run({"path", kHouse, "--through", "L,K", "--step", "0.5", "--size", "96x54", "-o", "walk", "--resume"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("resuming: " + std::to_string(whole.size() - 2) + " of " + std::to_string(whole.size())),
            std::string::npos)
      << r.out;
  EXPECT_EQ(frames("walk"), whole);
  EXPECT_EQ(fs::last_write_time(path("walk/frame-0001.png")), kept);
  EXPECT_EQ(probe_film(path("walk/walk.mp4")).frames, long(whole.size()));
}

TEST_F(Path, StereoFramesAndOptionsAreChecked) {
  Outcome r = run({"path", kHouse, "--through", "L,K", "--step", "1.0", "--size", "64x36", "--stereo", "parallel",
                       "-o", "pair"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(probe_film(path("pair/walk.mp4")).width, 128);  // the two eyes side by side
  for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
           {"--stereo", "pair"}, {"--samples", "3"}, {"--threads", "-1"}, {"--shading", "glossy"},
           {"--stereo", "cross", "--interocular", "nan"}}) {
    std::vector<std::string> args = {"path", kHouse, "--through", "L,K", "-o", "none"};
    args.insert(args.end(), bad.begin(), bad.end());
    Outcome b = run(args);
    EXPECT_EQ(b.status, 2) << bad[0];
    EXPECT_NE(b.err.find(bad[bad.size() - 2]), std::string::npos) << b.err;
    EXPECT_FALSE(fs::exists(path("none")));
  }
}

// --- under MPI: mpirun -np N avenues path ... (app/mpi_walk.h) ---------------------------

#ifdef AVENUES_MPIRUN

TEST_F(Path, MpiWalksAreByteIdenticalToOneProcess) {
  const std::vector<std::string> args = {"path", kHouse, "--through", "L,K,D", "--step", "0.4", "--size", "96x54"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = args;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ASSERT_EQ(run(with({"-o", "one"})).status, 0);
  const auto one = frames("one");
  ASSERT_GE(one.size(), 10u);
  for (int ranks : {2, 3}) {
    const std::string out = "ranks" + std::to_string(ranks);
    Outcome r = run_mpi(ranks, with({"-o", out}));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(frames(out), one) << ranks << " ranks";
    EXPECT_NE(r.out.find("on " + std::to_string(ranks) + " ranks"), std::string::npos) << r.out;
    EXPECT_EQ(probe_film(path(out) / "walk.mp4").frames, long(one.size()));
    // One progress bar, rank 0's, ending at every frame.
    EXPECT_NE(r.err.find("] " + std::to_string(one.size()) + "/" + std::to_string(one.size())), std::string::npos) << r.err;
  }
  // Stereo frames (an anaglyph) and drawings.
  ASSERT_EQ(run(with({"--stereo", "anaglyph", "-o", "s1"})).status, 0);
  ASSERT_EQ(run_mpi(2, with({"--stereo", "anaglyph", "-o", "s2"})).status, 0);
  EXPECT_EQ(frames("s2"), frames("s1"));
  ASSERT_EQ(run(with({"--format", "svg", "--stereo", "cross", "-o", "d1"})).status, 0);
  ASSERT_EQ(run_mpi(3, with({"--format", "svg", "--stereo", "cross", "-o", "d3"})).status, 0);
  EXPECT_EQ(frames("d3"), frames("d1"));
  EXPECT_FALSE(frames("d1").empty());
}

TEST_F(Path, MpiBadInputIsReportedOnceByRankZero) {
  Outcome r = run_mpi(2, {"path", kHouse, "--through", "L,Attic", "-o", "none"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no room 'Attic'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("no room 'Attic'"), r.err.rfind("no room 'Attic'")) << r.err;
  EXPECT_FALSE(fs::exists(path("none")));
}

// A rank whose frame cannot be written (here the frame's name is taken by a folder) stops
// the walk, named with its frame; --resume, the folder gone, finishes it.
TEST_F(Path, MpiRankThatFailsStopsTheWalkAndResumeFinishesIt) {
  const std::vector<std::string> args = {"path", kHouse, "--through", "L,K", "--step", "0.3", "--size", "64x36", "-o", "walk"};
  ASSERT_EQ(run({"path", kHouse, "--through", "L,K", "--step", "0.3", "--size", "64x36", "-o", "one"}).status, 0);
  fs::create_directories(path("walk/frame-0004.png"));
  Outcome r = run_mpi(2, args);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex("avenues: rank [01] failed at frame 4 \\(of [0-9]+\\): cannot write")))
      << r.err;
  EXPECT_NE(r.err.find("--resume"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("walk/walk.mp4")));
  fs::remove(path("walk/frame-0004.png"));
  std::vector<std::string> again = args;
  again.push_back("--resume");
  Outcome resumed = run_mpi(2, again);
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_EQ(frames("walk"), frames("one"));
  EXPECT_EQ(probe_film(path("walk/walk.mp4")).frames, long(frames("one").size()));
}

namespace {

/// The process of the MPI rank `rank` whose command line names `marker`, or -1.
pid_t rank_process(int rank, const std::string& marker) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string cmdline = slurp(e.path() / "cmdline"), env = slurp(e.path() / "environ");
    if (cmdline.find(marker) == std::string::npos || cmdline.find("mpirun") != std::string::npos) continue;
    if (env.find(std::string("OMPI_COMM_WORLD_RANK=") + std::to_string(rank) + '\0') != std::string::npos)
      return pid_t(std::stol(pid));
  }
  return -1;
}

}  // namespace

// A rank killed mid-walk (SIGKILL: it cannot report) stops the job; rank 0 says which
// frames were in progress, and --resume keeps the frames done and completes the film.
// (That the frames of an MPI walk are those of one process is shown above.)
TEST_F(Path, MpiRankKilledMidWalkAndResumeCompletesTheFilm) {
  const std::string out = "killed-" + std::to_string(::getpid());  // names this job's processes
  // Frames large enough that the walk lasts several seconds: under a loaded suite, finding
  // the ranks in /proc once took longer than a walk of 160 x 90 frames, which had ended
  // (all 235 frames written, the film being encoded) by the time its ranks were stopped.
  // At 960 x 540 the test takes about 7 s on its own.
  const std::vector<std::string> args = {"path",   kHouse,    "--through", "L,K,D", "--step", "0.05",
                                         "--size", "960x540", "--samples", "16",    "-o",     out};
  avenues::testing::Child job = start_argv(mpirun(2, args));
  ASSERT_GT(job.pid(), 0);
  // Both ranks are stopped as soon as they are found (long before their first frame), then
  // let run in slices of 2 ms until a few frames are written: a slice holds at most a few
  // frames, so the walk cannot end before rank 1 is killed however the machine's load
  // delays this test (polling a running walk once missed all 235 frames of it).
  pid_t ranks[2] = {-1, -1};
  for (int tries = 0; tries < 1200 && (ranks[0] < 0 || ranks[1] < 0); ++tries) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    for (int k = 0; k < 2; ++k)
      if (ranks[k] < 0) ranks[k] = rank_process(k, out);
  }
  ASSERT_GT(ranks[0], 0) << "rank 0 never showed up";
  ASSERT_GT(ranks[1], 0) << "rank 1 never showed up";
  auto signal_both = [&](int sig) { return ::kill(ranks[0], sig) == 0 && ::kill(ranks[1], sig) == 0; };
  ASSERT_TRUE(signal_both(SIGSTOP)) << "the walk ended before its ranks could be stopped";
  bool ready = false;
  for (int slice = 0; slice < 30000 && !ready; ++slice) {
    ASSERT_TRUE(signal_both(SIGCONT)) << "a rank ended before the walk's first frames";
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ASSERT_TRUE(signal_both(SIGSTOP)) << "a rank ended before the walk's first frames";
    ready = fs::exists(path(out)) && frames(out).size() >= 3;
  }
  ASSERT_TRUE(ready) << "no frames written";
  ASSERT_EQ(::kill(ranks[1], SIGKILL), 0);
  ASSERT_EQ(::kill(ranks[0], SIGCONT), 0);  // rank 0 reports the frames in progress as the job stops
  Outcome r = finish(job);
  const size_t done = frames(out).size();
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("rank 1"), std::string::npos) << r.err;  // mpirun names the rank that died
  EXPECT_TRUE(std::regex_search(r.err, std::regex("in progress: frame [0-9]+ on rank [01]"))) << r.err;  // rank 0
  EXPECT_NE(r.err.find("--resume"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path(out) / "walk.mp4"));

  std::vector<std::string> again = args;
  again.push_back("--resume");
  Outcome resumed = run_mpi(2, again);
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(resumed.out, m, std::regex("resuming: ([0-9]+) of ([0-9]+) frames"))) << resumed.out;
  const size_t kept = std::stoul(m[1]), total = std::stoul(m[2]);
  EXPECT_GE(kept, done);  // every complete frame kept (and those finished as the job stopped)
  ASSERT_LT(kept, total) << "the walk ended before rank 1 was killed";
  EXPECT_EQ(frames(out).size(), total);
  EXPECT_EQ(probe_film(path(out) / "walk.mp4").frames, long(total));
  for (const std::string& name : names(out)) EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
}

#endif
