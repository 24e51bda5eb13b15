// Avenues — hostile but realistic input (issue 13): no crash, no hang, no shell, no silent
// wrong answer. Each test is one of the cases found, run through the real executable
// (AVENUES_BINARY, by its argument vector: no shell sees the arguments; tests/avenues_run.h)
// or, where the command line cannot reach the case deterministically, through the library
// function that handles it (a signal arriving while a temporary file exists, GMP running
// out of memory).
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include <gmp.h>
#include <zip.h>
#include <gtest/gtest.h>

#include "cells/gmp_memory.h"
#include "core/atomic_file.h"
#include "core/subprocess.h"
#include "plans/formats/file_format.h"
#include "plans/mesh.h"
#include "plans/formats/sweet_home.h"
#include "tests/avenues_run.h"
#include "tests/test_files.h"

namespace fs = std::filesystem;
using avenues::testing::Outcome;
using avenues::testing::slurp;

namespace {

const std::string kSource = AVENUES_SOURCE_DIR;
const std::string kPlan = kSource + "/plans/jones-house.toml";

class Hostile : public avenues::testing::AvenuesRun {};

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

/// Share of zero bytes in a binary PGM's pixels (black), -1 when it is not one.
double black_share(const std::string& pgm) {
  int w = 0, h = 0, maxval = 0, used = 0;
  if (std::sscanf(pgm.c_str(), "P5 %d %d %d%n", &w, &h, &maxval, &used) != 3 || w <= 0 || h <= 0) return -1;
  const std::string px = pgm.substr(size_t(used) + 1);
  if (px.size() < size_t(w) * size_t(h)) return -1;
  size_t black = 0;
  for (size_t i = 0; i < size_t(w) * size_t(h); ++i) black += px[i] == 0;
  return double(black) / double(size_t(w) * size_t(h));
}

}  // namespace

// Item 1: another program is run by its argument vector; quotes and semicolons reach it
// as they are, and nothing runs them as commands.
TEST_F(Hostile, ProgramsRunByArgvNeverThroughAShell) {
  const avenues::ProgramResult r =
      avenues::run_program({"printf", "%s|", "it's", "x';touch PWNED;'", "$(touch PWNED2)"}, dir().string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "it's|x';touch PWNED;'|$(touch PWNED2)|");
  EXPECT_FALSE(fs::exists(path("PWNED")));
  EXPECT_FALSE(fs::exists(path("PWNED2")));
  EXPECT_EQ(avenues::run_program({"sh", "-c", "exit 3"}).status, 3);
  try {
    avenues::run_program({"avenues-no-such-program"});
    ADD_FAILURE() << "a missing program must throw";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(), "avenues-no-such-program")) << e.what();
  }
}

// Item 2: an output path naming a device, a FIFO or /dev/null is refused, exit 2, and
// stays what it was; a regular file is still replaced.
TEST_F(Hostile, OutputsOnlyReplaceRegularFiles) {
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0644), 0);
  Outcome r = run({"cells", kPlan, "--svg", "fifo"});
  EXPECT_EQ(r.status, 2) << r.output();
  EXPECT_TRUE(has(r.output(), "fifo") && has(r.output(), "FIFO")) << r.output();
  EXPECT_TRUE(fs::is_fifo(path("fifo")));
  r = run({"view", kPlan, "--size", "32x18", "-o", "/dev/null"});
  EXPECT_EQ(r.status, 2) << r.output();
  EXPECT_TRUE(has(r.output(), "/dev/null") && has(r.output(), "character device")) << r.output();
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  if (::mknod(path("null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {  // needs CAP_MKNOD
    r = run({"cells", kPlan, "--save", "null"});
    EXPECT_EQ(r.status, 2) << r.output();
    EXPECT_TRUE(fs::is_character_file(path("null")));
  }
  EXPECT_THROW(avenues::check_output_path("/dev/null"), std::runtime_error);
  EXPECT_NO_THROW(avenues::check_output_path(path("nothing-there.svg").string()));
  write("old.svg", "old");
  r = run({"cells", kPlan, "--svg", "old.svg"});
  EXPECT_EQ(r.status, 0) << r.output();
  EXPECT_TRUE(has(slurp(path("old.svg")), "<svg"));
  for (const std::string& f : files()) EXPECT_FALSE(has(f, ".tmp-")) << f;
}

// Item 4: GMP's memory running out is std::bad_alloc, not abort() (in a child process whose
// address space is limited, so that the allocation fails for certain).
/// In a child process: GMP asked for 2 GiB in 1 GiB of address space. Exits 0 when that
/// threw std::bad_alloc.
[[noreturn]] void exhaust_gmp() {
  avenues::use_throwing_gmp_allocator();
  rlimit limit{};
  limit.rlim_cur = limit.rlim_max = rlim_t(1) << 30;
  ::setrlimit(RLIMIT_AS, &limit);
  mpz_t z;
  mpz_init(z);
  int status = 1;
  try {
    mpz_realloc2(z, uint64_t(1) << 34);  // 2^34 bits: 2 GiB of limbs
  } catch (const std::bad_alloc&) {
    status = 0;
  }
  mpz_clear(z);
  std::_Exit(status);
}

TEST(HostileMemory, GmpExhaustionThrowsBadAlloc) {
  EXPECT_EXIT(exhaust_gmp(), ::testing::ExitedWithCode(0), "");
}

// Item 4 through the executable: a generated office decomposed under a tight address-space
// limit ends with "out of memory while decomposing FILE", exit 2 (not SIGABRT in GMP, not a
// message without the file). The limit is what avenues needs to start at all (found by
// halving, since it differs between builds) and a few MiB more, far less than the
// decomposition needs.
TEST_F(Hostile, OutOfMemoryWhileDecomposingNamesThePlan) {
  Outcome r = run({"generate", "office", "--rooms", "20x20", "-o", "office.toml"});
  ASSERT_EQ(r.status, 0) << r.output();
  // A fixed script: the limit [KiB], the binary and its arguments are its arguments.
  auto within = [&](long kib, std::vector<std::string> args) {
    const std::vector<std::string> command = avenues::testing::avenues_argv(args);
    std::vector<std::string> argv = {"sh", "-c", "ulimit -v \"$1\" && shift && exec \"$0\" \"$@\"", command[0],
                                     std::to_string(kib)};
    argv.insert(argv.end(), command.begin() + 1, command.end());
    return run_argv(argv);
  };
  long lo = 1000, hi = 4'000'000;  // [KiB] too little to start; enough
  // Starting and reporting an error (which loads the unwinder) is what must fit.
  auto starts = [&](long kib) {
    const Outcome q = within(kib, {"cells", "no-such-plan.toml"});
    return q.status == 2 && has(q.output(), "no-such-plan.toml: no such file");
  };
  ASSERT_TRUE(starts(hi));
  while (hi - lo > 500) {
    const long mid = (lo + hi) / 2;
    (starts(mid) ? hi : lo) = mid;
  }
  r = within(hi + 4000, {"cells", "office.toml"});
  EXPECT_EQ(r.status, 2) << "limit " << hi + 4000 << " KiB\n" << r.output();
  EXPECT_TRUE(has(r.output(), "out of memory while decomposing office.toml")) << r.output();
}

// Item 6: every numeric option is checked for finiteness and range where the command line
// is parsed, and the message names the option.
TEST_F(Hostile, NumericOptionsAreCheckedAndNamed) {
  const std::vector<std::vector<std::string>> bad = {
      {"view", kPlan, "--fov", "0"},          {"view", kPlan, "--fov", "-5"},
      {"view", kPlan, "--fov", "nan"},        {"view", kPlan, "--fov", "180"},
      {"view", kPlan, "--yaw", "inf"},        {"view", kPlan, "--pitch", "nan"},
      {"view", kPlan, "--pitch", "1000"},     {"view", kPlan, "--size", "0x10"},
      {"view", kPlan, "--kernel", "quad"},    {"view", kPlan, "--samples", "3"},
      {"view", kPlan, "--falloff", "nan"},    {"view", kPlan, "--interocular", "-1"},
      {"walk", kPlan, "--fov", "nan"},        {"walk", kPlan, "--samples", "2"},
      {"walk", kPlan, "--kernel", "x"},       {"walk", kPlan, "--size", "10"},
      {"path", kPlan, "--fov", "0"},          {"path", kPlan, "--step", "nan"},
      {"path", kPlan, "--step", "-1"},        {"path", kPlan, "--kernel", "x"},
      {"bench", "walk", "--frames", "0"},     {"bench", "papers", "--repeats", "-2"},
      {"view", kPlan, "--search", "fast"},    {"walk", kPlan, "--search", "tree"},
      {"path", kPlan, "--search", "x"},       {"bench", "walk", "--search", "both"},
      {"walk", kPlan, "--detail", "-1"},      {"path", kPlan, "--detail", "nan"},
  };
  for (const std::vector<std::string>& args : bad) {
    const Outcome r = run(args);
    const std::string& option = args[args.size() - 2];
    EXPECT_EQ(r.status, 2) << args[0] << " " << option << " " << args.back() << "\n" << r.output();
    EXPECT_TRUE(has(r.output(), option)) << option << " " << args.back() << ": the message names the option\n" << r.output();
  }
  EXPECT_TRUE(files().empty());
}

// Item 7: an empty output name is a mistake, not "write nothing".
TEST_F(Hostile, EmptyOutputNamesAreRefused) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"view", kPlan, "-o", ""}, {"cells", kPlan, "--svg", ""}, {"cells", kPlan, "--save", ""},
           {"export", kPlan, "-o", ""}, {"view", kPlan, "--stats-json", ""}}) {
    const Outcome r = run(args);
    EXPECT_EQ(r.status, 2) << args[2] << "\n" << r.output();
    EXPECT_TRUE(has(r.output(), args[2])) << r.output();
  }
}

// Item 8: an eye exactly on a wall of no thickness sees the room it looks into, as an eye a
// micrometre into that room does (it gave an all-black picture).
TEST_F(Hostile, EyeOnASheetWallSeesTheRoomItLooksInto) {
  for (const std::vector<std::string>& pose :
       std::vector<std::vector<std::string>>{{"5,2.5,1.6", "9,2.5,1.6"}, {"5,2.5,1.6", "1,2.5,1.6"}}) {
    const Outcome r =
        run({"view", kPlan, "--eye", pose[0], "--look", pose[1], "--size", "64x36", "-o", "a.pgm"});
    ASSERT_EQ(r.status, 0) << r.output();
    EXPECT_LT(black_share(slurp(path("a.pgm"))), 0.05) << pose[0] << " looking at " << pose[1];
  }
  // At the T-junction (5, 3) of two sheets the eye stands in both rooms beside the sheet it
  // looks along, and the picture is their two views composed (it was half black).
  for (const std::vector<std::string>& pose : std::vector<std::vector<std::string>>{
           {"5,3,1.6", "9,2.5,1.6"}, {"5,3,1.6", "9,3.5,1.6"}, {"5,3,1.6", "9,3,1.6"}}) {
    const Outcome r =
        run({"view", kPlan, "--eye", pose[0], "--look", pose[1], "--size", "64x36", "-o", "a.pgm"});
    ASSERT_EQ(r.status, 0) << r.output();
    EXPECT_LT(black_share(slurp(path("a.pgm"))), 0.05) << pose[0] << " looking at " << pose[1];
  }
}

// Item 10: SIGTERM or SIGINT while a temporary output file exists removes it; the process
// still dies of the signal.
TEST(HostileSignals, PendingTemporaryFilesAreRemovedOnSigtermAndSigint) {
  const fs::path dir = fs::temp_directory_path() / ("avenues-signal-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (int sig : {SIGTERM, SIGINT}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      avenues::PendingTempFile one((dir / "a.svg").string());
      avenues::PendingTempFile two((dir / "b.cells").string());
      if (::write(one.fd(), "partial", 7) != 7) std::_Exit(3);
      ::raise(sig);
      std::_Exit(4);  // not reached: the signal ends the process
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
    EXPECT_TRUE(fs::is_empty(dir)) << "a temporary file was left on signal " << sig;
  }
  fs::remove_all(dir);
}

// Item 12: a file is told by its content where its extension is unknown or misleading.
TEST(HostileFormats, FilesAreToldByTheirContent) {
  using avenues::FileFormat;
  using avenues::detect_format;
  const std::string stl_header(80, ' ');
  const std::string one_triangle = stl_header + std::string("\x01\0\0\0", 4) + std::string(50, '\0');
  const struct {
    const char* name;
    std::string head;
    FileFormat want;
  } cases[] = {
      {"plan.toml", "\x89PNG\r\n\x1a\n....", FileFormat::Png},
      {"plan.dxf", "  0\nSECTION\n  2\nHEADER\n", FileFormat::Dxf},
      {"plan", "999\nmade by hand\n0\nSECTION\n", FileFormat::Dxf},
      {"house.ifc", "ISO-10303-21;\nHEADER;\n", FileFormat::Ifc},
      {"house.toml", "\xEF\xBB\xBFISO-10303-21;\n", FileFormat::Ifc},
      {"home.zip", std::string("PK\x03\x04", 4) + "....", FileFormat::SweetHome},
      {"doom.dat", "IWAD\x02\0\0\0", FileFormat::DoomWad},
      {"mod.bin", "PWAD\x02\0\0\0", FileFormat::DoomWad},
      {"saved.bin", std::string("AVCELLS\0", 8) + "\4\0\0\0", FileFormat::Cells},
      {"mesh.txt", "OFF\n3 1 0\n", FileFormat::Off},
      {"mesh.dat", "ply\nformat ascii 1.0\n", FileFormat::Ply},
      {"mesh", one_triangle, FileFormat::Stl},
      {"mesh.asc", "solid x\n facet normal 0 0 1\n", FileFormat::Stl},
      {"mesh.txt", "# a mesh\nv 0 0 0\nv 1 0 0\n", FileFormat::Obj},
      {"Home", "<?xml version='1.0'?>\n<home version='6400'>", FileFormat::SweetHome},
      {"plan.txt", "name = \"x\"\n[[storey]]\n", FileFormat::Toml},
      {"table.off", "", FileFormat::Off},
      {"random.bin", std::string("\x01\x02\x00\xff", 4), FileFormat::Unknown},
      {"program.toml", std::string("\x7f" "ELF\x02\x01\x01\0", 8), FileFormat::Unknown},
  };
  for (const auto& c : cases)
    EXPECT_EQ(detect_format(c.name, c.head, c.head.size()), c.want)
        << c.name << ": detected as " << avenues::format_name(detect_format(c.name, c.head, c.head.size()));
}

// Item 12 through the executable: formats Avenues cannot read say so, exit 2 (and a DXF or
// IFC file with nothing in it says what it lacks); a plan or a saved complex under another
// name is read by its content.
TEST_F(Hostile, PlansOfOtherFormatsSaySoAndMisnamedPlansAreRead) {
  write("plan.dxf", "  0\nSECTION\n  2\nENTITIES\n  0\nENDSEC\n  0\nEOF\n");
  write("model.ifc", "ISO-10303-21;\nHEADER;\nENDSEC;\nEND-ISO-10303-21;\n");
  write("plan.png", "\x89PNG\r\n\x1a\n\0\0\0\rIHDR");
  write("really-a-png.toml", "\x89PNG\r\n\x1a\n\0\0\0\rIHDR");
  write("noise.bin", std::string("\x01\x02\x00\xff\xfe", 5));
  const struct {
    const char* file;
    const char* says;
  } cannot[] = {// DXF and IFC are read now: an empty drawing and an empty model are clear errors.
                {"plan.dxf", "plan.dxf: no layer holds walls"},
                {"model.ifc", "model.ifc:1: not a well-formed STEP file: it has no DATA section"},
                {"plan.png", "plan.png is a PNG image, which Avenues cannot read yet"},
                {"really-a-png.toml", "really-a-png.toml is a PNG image"},
                {"noise.bin", "noise.bin is not a plan Avenues can read"}};
  for (const auto& c : cannot) {
    const Outcome r = run({"cells", c.file});
    EXPECT_EQ(r.status, 2) << c.file << "\n" << r.output();
    EXPECT_TRUE(has(r.output(), c.says)) << r.output();
  }
  fs::copy_file(kPlan, path("jones.plan"));
  Outcome r = run({"cells", "jones.plan", "--save", "saved.bin"});
  ASSERT_EQ(r.status, 0) << r.output();
  r = run({"cells", "saved.bin", "--json"});
  EXPECT_EQ(r.status, 0) << r.output();
  EXPECT_TRUE(has(r.output(), "\"cells\"")) << r.output();
}

// Items 13 and 14: a broken mesh names the file and what is wrong with it. OFF and PLY refuse
// a bad vertex or face, naming the line; an STL cut short is refused. An OBJ or STL drops
// the elements it cannot use, as their own tools do (next test); one left with no face is
// refused, naming the line or triangle that cost it its last.
TEST_F(Hostile, BrokenMeshesNameTheFileAndTheFault) {
  std::string noise;
  for (int i = 0; i < 3000; ++i) noise += char((i * 7919 + 13) % 256);
  write("noise.off", noise);
  write("big.ply",
        "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n");
  write("points.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "end_header\n0 0 0\n1 0 0\n0 1 0\n");
  write("huge.off", "OFF\n4 1 0\n0 0 0\n1e300 0 0\n0 1 0\n0 0 1\n3 0 1 2\n");
  write("bad-index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  std::string stl(80, ' ');
  stl += std::string("\x10\0\0\0", 4);  // 16 triangles announced
  stl += std::string(50, '\0');          // one given
  write("short.stl", stl);
  std::string nan_stl(80, ' ');
  nan_stl += std::string("\x01\0\0\0", 4);
  std::string tri(50, '\0');
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(tri.data() + 12, &nan, 4);
  write("nan.stl", nan_stl + tri);
  fs::create_directories(path("dir.off"));
  const struct {
    const char* file;
    std::vector<const char*> says;
  } cases[] = {
      {"noise.off", {"noise.off"}},
      {"big.ply", {"big.ply", "4000000000", "vertex"}},
      {"points.ply", {"points.ply", "3 points and no faces", "point cloud"}},
      {"huge.off", {"huge.off", "line 4", "1e300"}},
      {"bad-index.obj", {"bad-index.obj", "line 4", "'7'"}},
      {"nan.obj", {"nan.obj", "line 2", "nan"}},
      {"short.stl", {"short.stl", "16 triangles"}},
      {"nan.stl", {"nan.stl", "triangle 1"}},
      {"dir.off", {"dir.off", "directory"}},
  };
  for (const auto& c : cases) {
    const Outcome r = run({"cells", c.file});
    EXPECT_EQ(r.status, 2) << c.file << "\n" << r.output();
    for (const char* s : c.says) EXPECT_TRUE(has(r.output(), s)) << c.file << ": no '" << s << "' in\n" << r.output();
    EXPECT_FALSE(has(r.output(), "out of memory")) << r.output();
  }
}

// A mesh's unusable elements cost themselves, not the file: an STL's triangle with a vertex
// that is no coordinate (binary or ASCII), an OBJ's vertex and the faces using it. Each is
// said in one warning naming the triangle or line; the rest is read.
TEST_F(Hostile, AMeshsUnusableElementsCostThemselvesNotTheFile) {
  auto triangle = [](std::array<float, 9> v) {
    std::string t(50, '\0');
    std::memcpy(t.data() + 12, v.data(), 36);
    return t;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::string binary(80, ' ');
  binary += std::string("\x03\0\0\0", 4);
  binary += triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}) + triangle({0, 0, 0, nan, 0, 0, 0, 1, 0}) +
            triangle({0, 0, 0, 0, 1, 0, 0, 0, 1});
  write("two-of-three.stl", binary);
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  std::string ascii = "solid s\n" + facet + facet + "endsolid s\n";
  ascii.replace(ascii.find("vertex 1 0 0", ascii.find("vertex 1 0 0") + 1), 12, "vertex 1e40 0 0");
  write("one-of-two.stl", ascii);
  write("holed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 inf\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 5\n");
  write("holed.off", "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1e300\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 2 4\n3 0 1 9\n");
  // A binary PLY with a NaN vertex: no check reads its numbers before OpenMesh does.
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  for (const std::array<float, 3>& v : {std::array<float, 3>{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, nan}})
    ply.append(reinterpret_cast<const char*>(v.data()), 12);
  for (const std::array<int32_t, 3>& f : {std::array<int32_t, 3>{0, 1, 2}, {0, 1, 3}}) {
    ply += '\x03';
    ply.append(reinterpret_cast<const char*>(f.data()), 12);
  }
  write("holed.ply", ply);
  const struct {
    const char* file;
    size_t triangles;
    const char* says;
  } cases[] = {
      {"two-of-three.stl", 2, "triangle 2 has a vertex that is not a coordinate"},
      {"one-of-two.stl", 1, "facet 2, line 12: '1e40' is not a coordinate"},
      {"holed.obj", 2, "line 4: 'inf' is not a coordinate"},
      {"holed.off", 2, "line 6: '1e300' is not a coordinate"},
      {"holed.ply", 1, "vertex 3 is not a finite number"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    std::vector<std::string> warnings;
    const avenues::Mesh m = avenues::load_mesh(path(c.file).string(), {}, &warnings);
    EXPECT_EQ(m.triangles.size(), c.triangles);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(has(warnings[0], c.says)) << warnings[0];
    EXPECT_TRUE(has(warnings[0], c.file)) << warnings[0];
    for (const avenues::Vec3& v : m.vertices) EXPECT_TRUE(std::isfinite(v.x) && std::abs(v.x) <= 1) << v.x;
    const Outcome r = run({"cells", c.file});
    EXPECT_EQ(r.status, 0) << r.output();
    EXPECT_TRUE(has(r.err, c.says)) << r.err;
  }
}

// Item 13: an object's mesh that is a directory, a FIFO or /dev/zero is named as what it is;
// keyframes that are a directory likewise.
TEST_F(Hostile, MeshAndKeyPathsThatAreNotFiles) {
  fs::create_directories(path("meshes/dir.off"));
  ASSERT_EQ(::mkfifo(path("meshes/fifo.off").c_str(), 0644), 0);
  const std::string plan_text = slurp(kSource + "/plans/furnished-room.toml");
  ASSERT_TRUE(has(plan_text, "mesh = \"meshes/table.off\""));
  for (const std::string& mesh : {std::string("meshes/dir.off"), std::string("meshes/fifo.off"), std::string("/dev/zero")}) {
    std::string text = plan_text;
    const std::string line = "mesh = \"meshes/table.off\"";
    text.replace(text.find(line), line.size(), "mesh = \"" + mesh + "\"");
    write("room.toml", text);
    const Outcome r = run({"view", "room.toml", "--size", "32x18", "-o", "a.png"});
    EXPECT_EQ(r.status, 2) << mesh << "\n" << r.output();
    EXPECT_TRUE(has(r.output(), mesh)) << r.output();
    EXPECT_TRUE(has(r.output(), mesh == "meshes/dir.off" ? "directory" : "not a regular file")) << r.output();
    EXPECT_FALSE(fs::exists(path("a.png")));
  }
  fs::create_directories(path("keys"));
  const Outcome r = run({"path", kPlan, "--keys", "keys", "-o", "frames"});
  EXPECT_EQ(r.status, 2) << r.output();
  EXPECT_TRUE(has(r.output(), "keys: not a regular file")) << r.output();
}

// Item 17: a saved complex names its objects' meshes relative to itself, so it loads from
// any folder; a version-3 file (meshes relative to where it was saved from) still loads.
TEST_F(Hostile, SavedCellsFindTheirMeshesFromAnywhere) {
  fs::create_directories(path("house/meshes"));
  fs::copy_file(kSource + "/plans/furnished-room.toml", path("house/room.toml"));
  fs::copy_file(kSource + "/plans/meshes/table.off", path("house/meshes/table.off"));
  fs::create_directories(path("out"));
  Outcome r = run({"cells", "house/room.toml", "--save", "out/room.cells"});
  ASSERT_EQ(r.status, 0) << r.output();
  avenues::testing::RunOptions in_out;
  in_out.cwd = path("out");
  r = run({"view", "room.cells", "--size", "32x18", "-o", "a.png"}, in_out);
  EXPECT_EQ(r.status, 0) << r.output();
  EXPECT_TRUE(fs::exists(path("out/a.png")));
  // Saved beside where it runs, then marked version 3: the old meaning of the same path.
  r = run({"cells", "house/room.toml", "--save", "old.cells"});
  ASSERT_EQ(r.status, 0) << r.output();
  std::string bytes = slurp(path("old.cells"));
  ASSERT_GT(bytes.size(), 12u);
  bytes[8] = 3;
  write("old.cells", bytes);
  r = run({"view", "old.cells", "--size", "32x18", "-o", "b.png"});
  EXPECT_EQ(r.status, 0) << r.output();
  EXPECT_TRUE(fs::exists(path("b.png")));
}

// Item 16: a small archive whose Home.xml inflates past the limit (512 MiB) is refused with
// the entry named, exit 2, before it is parsed; nothing is written.
TEST_F(Hostile, AnArchiveEntryInflatingPastTheLimitIsRefused) {
  const std::string huge(size_t(513) << 20, ' ');  // 513 MiB of spaces: deflates to about half a megabyte
  int err = 0;
  zip_t* za = zip_open(path("bomb.sh3d").c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  ASSERT_NE(za, nullptr) << "libzip error " << err;
  const zip_int64_t idx = zip_file_add(za, "Home.xml", zip_source_buffer(za, huge.data(), huge.size(), 0), 0);
  ASSERT_GE(idx, 0) << zip_strerror(za);
  ASSERT_EQ(zip_set_file_compression(za, zip_uint64_t(idx), ZIP_CM_DEFLATE, 1), 0);
  ASSERT_EQ(zip_close(za), 0);
  ASSERT_LT(fs::file_size(path("bomb.sh3d")), uintmax_t(4) << 20);
  const Outcome r = run({"cells", "bomb.sh3d", "--svg", "bomb.svg"});
  EXPECT_EQ(r.status, 2) << r.output();
  EXPECT_TRUE(has(r.output(), "bomb.sh3d")) << r.output();
  EXPECT_TRUE(has(r.output(), "'Home.xml'")) << r.output();
  EXPECT_TRUE(has(r.output(), "512 MiB")) << r.output();
  EXPECT_FALSE(fs::exists(path("bomb.svg")));
}

// Item 16, the reader's limit itself: an entry inflating past HomeLimits::max_entry_bytes
// (the fuzz target's 1 MiB, and its seed of 2 KB inflating to 2 MiB) is refused naming the
// entry and the limit.
TEST(HostileArchive, TheEntryLimitIsTheReadersOwn) {
  const std::string seed = kSource + "/tests/fuzz/corpus/home/inflates-past-the-limit.sh3d";
  ASSERT_LT(fs::file_size(seed), uintmax_t(8192));
  avenues::HomeLimits limits;
  limits.max_entry_bytes = size_t(1) << 20;
  try {
    avenues::read_sweet_home(seed, avenues::HomeEntry::Preferred, limits);
    ADD_FAILURE() << "an entry inflating to 2 MiB was read under a 1 MiB limit";
  } catch (const avenues::PlanError& e) {
    EXPECT_TRUE(has(e.what(), "inflates-past-the-limit.sh3d")) << e.what();
    EXPECT_TRUE(has(e.what(), "entry 'Home.xml' of the archive inflates to more than 1 MiB")) << e.what();
  }
}
