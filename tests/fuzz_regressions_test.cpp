// Every input a fuzzer once crashed or exhausted a parser with (tests/fuzz/regressions/),
// run through the real build's parser: each must now be refused cleanly, with an error
// naming the file, or read. The fuzz targets themselves run in ctest (fuzz.*, built
// with clang and sanitizers by tests/fuzz/CMakeLists.txt).
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "plans/formats/ifc_building.h"
#include "plans/formats/sweet_home.h"
#include "plans/mesh.h"
#include "tests/test_files.h"

namespace fs = std::filesystem;

namespace {
std::vector<fs::path> regressions(const std::string& target) {
  std::vector<fs::path> out;
  const fs::path dir = fs::path(AVENUES_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / target;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path());
  return out;
}

/// Every regression input of `target` is read by `read`, or refused with a PlanError
/// naming the file.
template <class Read>
void read_or_refused(const std::string& target, Read&& read) {
  const auto files = regressions(target);
  ASSERT_GE(files.size(), 1u);
  for (const fs::path& f : files) {
    try {
      read(f.string());
    } catch (const avenues::PlanError& e) {
      EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos) << e.what();
    }
  }
}
}  // namespace

// Each of these once ran OpenMesh out of memory. Each is now refused naming the file, or,
// where only some of its elements are unusable (the mesh readers drop what they cannot use,
// as OBJ's and STL's tools do), read with a warning naming the file and what was dropped.
TEST(FuzzRegressions, MeshesThatRanOpenMeshOutOfMemoryAreRefusedOrReadNamingTheFile) {
  const auto files = regressions("mesh");
  ASSERT_GE(files.size(), 4u);
  for (const fs::path& f : files) {
    std::vector<std::string> warnings;
    try {
      const avenues::Mesh m = avenues::load_mesh(f.string(), {}, &warnings);
      EXPECT_FALSE(m.triangles.empty()) << f;
      ASSERT_FALSE(warnings.empty()) << f << " was read whole, but it is malformed";
      EXPECT_NE(warnings[0].find(f.string()), std::string::npos) << warnings[0];
      EXPECT_NE(warnings[0].find("dropped"), std::string::npos) << warnings[0];
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos) << e.what();
    }
  }
}

// OpenMesh's ASCII PLY reader reads each number with the stream's >>, a face's vertex count
// into a variable it does not set first: once a value is not read whole (ply-vertex-not-a-
// number.ply: a stray byte in a coordinate), the stream fails and the count is whatever an
// earlier call left on the stack. fuzz.mesh ran out of memory (billions of vertex handles)
// when that file followed others (nan-vertex.obj), not alone. A count read whole can be as
// bad: "-3" reads as 4294967293 (ply-negative-face-size.ply). In one process, after
// whatever came before, each is refused naming the value, and a good PLY still reads.
TEST(FuzzRegressions, PlyValuesOpenMeshCannotReadAreRefusedWhateverWasReadBefore) {
  const fs::path dir = fs::path(AVENUES_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / "mesh";
  const std::string not_a_number = (dir / "ply-vertex-not-a-number.ply").string();
  const std::string negative = (dir / "ply-negative-face-size.ply").string();
  const std::string good = (fs::path(AVENUES_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "mesh" / "site-coordinates-double.ply").string();
  auto refusal = [](const std::string& path) -> std::string {
    try {
      (void)avenues::load_mesh(path);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "read";
  };
  for (int round = 0; round < 3; ++round) {
    std::vector<std::string> warnings;
    try {
      (void)avenues::load_mesh((dir / "nan-vertex.obj").string(), {}, &warnings);
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(refusal(not_a_number),
              "cannot read mesh " + not_a_number + ": vertex 2 (of 3): '51?\?\?\?' is not a number in a float's range");
    EXPECT_EQ(refusal(negative), "cannot read mesh " + negative +
                                     ": face 1 (of 1): '-3' is not a vertex count or index (a whole number from 0 to 4294967295)");
    const avenues::Mesh m = avenues::load_mesh(good);
    EXPECT_EQ(m.vertices.size(), 3u);
    EXPECT_EQ(m.triangles.size(), 1u);
  }
}

TEST(FuzzRegressions, WellFormedOffFilesStillRead) {
  // The checks in front of OpenMesh must not refuse what every OFF writer writes:
  // comments, blank lines, colours after a face.
  const avenues::testing::TempDir scratch("avenues-fuzz-regression");  // the test's own, named for it
  const fs::path p = scratch.path() / "ok.off";
  {
    std::FILE* f = std::fopen(p.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("OFF\n# a square\n4 2 0\n\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 255 0 0\n3 0 2 3\n", f);
    std::fclose(f);
  }
  const avenues::Mesh m = avenues::load_mesh(p.string());
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 2u);
}

TEST(FuzzRegressions, IfcInputsAreReadOrRefusedNamingTheFile) {
  read_or_refused("ifc", [](const std::string& f) { (void)avenues::read_ifc_building(f); });
}

// Homes that once hung the Sweet Home reader (a cut-out's SVG path with numbers after a
// closepath looped in place): each is now read, or refused naming the file, in no time.
TEST(FuzzRegressions, HomesThatHungTheReaderAreReadOrRefusedNamingTheFile) {
  read_or_refused("home", [](const std::string& f) { (void)avenues::read_sweet_home(f); });
}
