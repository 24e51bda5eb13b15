// Tests of the half-tone renderer's picture: shading, supersampling, threads, dithering,
// files, stereo, and the papers' scenes (render/halftone.h, raster.h, shading.h, scenes.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "cells/build_cells.h"
#include "render/halftone.h"
#include "render/pixel_fill.h"
#include "render/raster.h"
#include "render/raster_srgb.h"
#include "app/paper_bench.h"
#include "render/scenes.h"
#include "render/scene_objects.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

Mesh mesh(std::vector<Vec3> vertices, std::vector<std::vector<int>> polygons) {
  PaperScene s;
  s.vertices = std::move(vertices);
  s.polygons = std::move(polygons);
  return mesh_of(s);
}

/// A square of side 2·h facing a camera at the origin looking along +y, at distance d.
Mesh facing_square(double d, double h) { return mesh({{-h, d, -h}, {h, d, -h}, {h, d, h}, {-h, d, h}}, {{0, 1, 2, 3}}); }

Camera camera_at_origin(int w, int h, double fov = 40) { return Camera::look_at({0, 0, 0}, {0, 1, 0}, fov, w, h); }

const PaperScene& scene_named(const std::string& name) {
  static const std::vector<PaperScene> scenes = paper_scenes();
  for (const PaperScene& s : scenes)
    if (s.name == name) return s;
  throw std::runtime_error("no scene " + name);
}

double mean_linear(const Image& im) {
  const Image g = grey_of(im);
  double sum = 0;
  for (uint8_t v : g.data) sum += srgb_decoder()(v);
  return sum / double(g.data.size());
}

fs::path temp_dir() {
  fs::path d = fs::temp_directory_path() / ("avenues-halftone-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

/// A picture whose grey level ramps from black to white, left to right.
Image ramp(int w, int h) {
  Image im;
  im.resize(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) im.row(y)[x] = uint8_t(255 * x / (w - 1));
  return im;
}

}  // namespace

// --- shading -----------------------------------------------------------------------------

TEST(Shading, SrgbEncodingRoundTripsEveryCode) {
  for (int c = 0; c < 256; ++c) EXPECT_EQ(srgb_encoder()(srgb_decoder()(uint8_t(c))), c);
}

TEST(Shading, BouknightFlatIntensityOfASquareFacingTheEye) {
  // I = BACK + (1 − BACK)·R·cos φ with cos φ = 1: encoded once, at the end.
  HalftoneOptions o;
  o.colour = false;
  o.shading.back = 0.1;
  MeshPaint paint;
  Material m;
  m.reflectance = 0.5;
  m.colour = {1, 1, 1};
  paint.materials = {m};
  const Image im = render_meshes({facing_square(5, 1)}, {paint}, camera_at_origin(64, 64), o);
  EXPECT_EQ(im.row(32)[32], srgb_encoder()(float(0.1 + 0.9 * 0.5)));
  EXPECT_EQ(im.row(0)[0], 0);  // background
}

TEST(Shading, WyliesDistanceLawDimsFarSurfaces) {
  HalftoneOptions o;
  o.colour = false;
  o.shading.model = ShadingModel::Smooth;
  o.shading.back = 0;
  o.shading.falloff_start = 2;
  MeshPaint paint;
  Material m;
  m.reflectance = 1;
  m.colour = {1, 1, 1};
  paint.materials = {m};
  // At 4 m the centre is (2/4)² = 1/4 as bright; at 1 m (nearer than the start) full.
  for (double d : {1.0, 4.0}) {
    const Image im = render_meshes({facing_square(d, d)}, {paint}, camera_at_origin(64, 64), o);
    const double want = d > 2 ? 0.25 : 1.0;
    EXPECT_NEAR(srgb_decoder()(im.row(32)[32]), want, 0.01) << d;
  }
}

TEST(Shading, SmoothLightFollowsThePlaneAndDarkensTowardsItsEdges) {
  // Lit at each sample from the plane: cos φ = Z / distance falls off from the centre.
  HalftoneOptions o;
  o.colour = false;
  o.shading.model = ShadingModel::Smooth;
  o.shading.falloff_start = 0;
  const Image im = render_meshes({facing_square(3, 3)}, camera_at_origin(101, 101, 60), o);
  EXPECT_GT(im.row(50)[50], im.row(50)[5]);
  EXPECT_EQ(im.row(50)[20], im.row(50)[80]);  // symmetric
}

TEST(Shading, GouraudOverACurvedMeshIsSmooth) {
  // The torus, smooth: neighbouring pixels seldom differ by more than a few codes (no
  // facets; only silhouettes), flat: at every facet edge.
  const PaperScene& s = scene_named("torus");
  HalftoneOptions o;
  o.colour = false;
  auto roughness = [&](ShadingModel model) {
    o.shading.model = model;
    o.shading.falloff_start = 0;
    const Image im = render_meshes({mesh_of(s)}, {s.paint}, s.camera, o);
    long jumps = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 1; x < im.width; ++x) {
        const int a = im.row(y)[x - 1], b = im.row(y)[x];
        if (a > 0 && b > 0 && std::abs(a - b) > 8) ++jumps;
      }
    return jumps;
  };
  EXPECT_LT(roughness(ShadingModel::Smooth) * 4, roughness(ShadingModel::Flat));
}

// --- the picture -------------------------------------------------------------------------

TEST(Halftone, SupersamplingAveragesCoverageInLinearLight) {
  // A white square on black whose edges run through pixel centres (41 pixels across,
  // centred on a 64-pixel picture): one sample per pixel sees each edge pixel in or out,
  // 4 and 16 samples see it half covered, and the picture's mean light is the area.
  HalftoneOptions o;
  o.colour = false;
  o.shading.back = 1;  // white whatever the angle
  const Camera cam = camera_at_origin(64, 64);
  const double half = 20.5 / 32 * std::tan(20 * 3.14159265358979323846 / 180);  // [m] at 1 m
  const double area = (41.0 / 64) * (41.0 / 64);
  for (int samples : {1, 4, 16}) {
    o.samples = samples;
    MeshPaint white;
    Material m;
    m.colour = {1, 1, 1};
    white.materials = {m};
    const Image im = render_meshes({facing_square(1, half)}, {white}, cam, o);
    EXPECT_NEAR(mean_linear(im), area, samples == 1 ? 0.04 : 0.004) << samples;
    const long partial = std::count_if(im.data.begin(), im.data.end(), [](uint8_t v) { return v > 0 && v < 255; });
    if (samples == 1) {
      EXPECT_EQ(partial, 0);
    } else {
      EXPECT_GE(partial, 4 * 40);  // the square's four edges are grey
    }
  }
  o.samples = 3;
  EXPECT_THROW(render_meshes({facing_square(1, half)}, cam, o), std::invalid_argument);
}

TEST(Halftone, RowsOfSamplesLikeTheRowAboveMakeItsPixelsAndNoOthers) {
  // The same white square: its edges run through the centres of pixels 11 and 52, so at 4
  // and 16 samples rows 12-51 are one row of samples over and over (the painter copies the
  // pixels of such a row from the row above), and rows 11 and 52 are half covered. Every
  // row must be what its own samples make: rows 12-51 alike, rows 11 and 52 alike and grey
  // across the square (a copy of the black row above would leave them black), the rows
  // above and below black.
  HalftoneOptions o;
  o.colour = false;
  o.shading.back = 1;
  o.threads = 1;
  const Camera cam = camera_at_origin(64, 64);
  const double half = 20.5 / 32 * std::tan(20 * 3.14159265358979323846 / 180);
  MeshPaint white;
  Material m;
  m.colour = {1, 1, 1};
  white.materials = {m};
  for (int samples : {4, 16}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    o.samples = samples;
    const Image im = render_meshes({facing_square(1, half)}, {white}, cam, o);
    ASSERT_EQ(im.width, 64);
    ASSERT_EQ(im.channels, 1);
    auto row = [&](int y) { return std::vector<uint8_t>(im.row(y), im.row(y) + 64); };
    const std::vector<uint8_t> inside = row(32), edge = row(11);
    for (int y = 12; y <= 51; ++y) EXPECT_EQ(row(y), inside) << "row " << y;
    EXPECT_EQ(row(52), edge);
    for (int y : {0, 10, 53, 63}) EXPECT_EQ(row(y), std::vector<uint8_t>(64, 0)) << "row " << y;
    EXPECT_EQ(inside[11], edge[32]);  // half covered across or down
    for (int x = 12; x <= 51; ++x) {
      EXPECT_GT(edge[size_t(x)], 0) << "column " << x;
      EXPECT_LT(edge[size_t(x)], inside[size_t(x)]) << "column " << x;
      EXPECT_EQ(inside[size_t(x)], inside[32]);
    }
    EXPECT_GT(edge[11], 0);
    EXPECT_LT(edge[11], edge[32]);  // a quarter covered
  }
}

TEST(Halftone, OneAndTwoThreadsMakeTheSamePicture) {
  const CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/office-corridor.toml"));
  const Viewpoint vp = default_viewpoint(c);
  const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 480, 270);
  const VisibleSet vs = find_visible(c, cam, c.locate(vp.eye).cell);
  for (int samples : {1, 4}) {
    HalftoneOptions o;
    o.samples = samples;
    o.shading.model = ShadingModel::Smooth;
    RenderStats s1, s2;
    o.threads = 1;
    const Image one = render_view(c, cam, vs, o, &s1);
    o.threads = 2;
    const Image two = render_view(c, cam, vs, o, &s2);
    EXPECT_EQ(one.data, two.data);
    EXPECT_EQ(s1.spans, s2.spans);
    EXPECT_EQ(s1.pixels, s2.pixels);
    EXPECT_EQ(s1.active_max, s2.active_max);
  }
  const PaperScene& s = scene_named("ripple-torus");
  HalftoneOptions o;
  o.cull_back_faces = false;
  RenderStats r1, r2;
  o.threads = 1;
  const Image one = render_meshes({mesh_of(s)}, {s.paint}, s.camera, o, &r1);
  o.threads = 2;
  const Image two = render_meshes({mesh_of(s)}, {s.paint}, s.camera, o, &r2);
  EXPECT_EQ(one.data, two.data);
  EXPECT_EQ(r1.implicit_lines, r2.implicit_lines);
  EXPECT_EQ(r1.depth_sorts, r2.depth_sorts);
}

TEST(Halftone, AViewIsCoveredAndCounted) {
  const CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml"));
  const Viewpoint vp = default_viewpoint(c);
  const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 320, 180);
  const VisibleSet vs = find_visible(c, cam, c.locate(vp.eye).cell);
  RenderStats stats;
  const Image im = render_view(c, cam, vs, {}, &stats);
  EXPECT_EQ(im.width, 320);
  EXPECT_EQ(im.height, 180);
  EXPECT_EQ(im.channels, 3);
  EXPECT_EQ(stats.pixels, 320 * 180);
  EXPECT_GE(stats.spans, 180);
  EXPECT_GT(stats.render_us, 0);
  bool has_render_us = false, has_spans = false;
  for (const auto& [key, value] : stats.fields()) {
    has_render_us |= key == "render_us";
    has_spans |= key == "spans" && value == double(stats.spans);
  }
  EXPECT_TRUE(has_render_us && has_spans);
}

// --- dithering ---------------------------------------------------------------------------

TEST(Halftone, ARunOfPixelsIsWrittenWhateverItsLengthAndAlignment) {
  // FillColour::fill writes 16-byte vectors on the 16-byte grid, and its first and last flush
  // with the run's ends: every length and every start within a cache line, and nothing
  // written outside the run.
  const std::array<uint8_t, 3> colour{7, 200, 33};
  std::vector<uint8_t> buffer(1024);
  long wrong = 0;
  for (int channels : {1, 3})
    for (size_t n = 0; n <= 200; ++n)
      for (size_t start = 0; start < 64; ++start) {
        std::fill(buffer.begin(), buffer.end(), uint8_t(0xab));
        uint8_t* run = buffer.data() + 64 + start;
        FillColour(colour).fill(run, n, channels);
        for (size_t i = 0; i < buffer.size(); ++i) {
          const ptrdiff_t at = buffer.data() + i - run;
          const bool inside = at >= 0 && at < ptrdiff_t(n) * channels;
          wrong += buffer[i] != (inside ? colour[size_t(at % channels)] : uint8_t(0xab));
        }
      }
  EXPECT_EQ(wrong, 0);
}

TEST(Halftone, ColoursKeptForFillingAreTheColoursAskedFor) {
  // FillColours keeps 64 colours by a hash: colours that share a slot take turns in it.
  FillColours kept;
  std::vector<uint8_t> run(3 * 40);
  long wrong = 0;
  for (int round = 0; round < 3; ++round)
    for (int k = 0; k < 300; ++k) {
      const std::array<uint8_t, 3> colour{uint8_t(k * 37), uint8_t(k * 11 + round), uint8_t(255 - k)};
      kept.of(colour).fill(run.data(), 40, 3);
      for (size_t i = 0; i < run.size(); ++i) wrong += run[i] != colour[i % 3];
    }
  EXPECT_EQ(wrong, 0);
}

TEST(Dither, KeepsTheMeanGreyLevel) {
  const Image grey = ramp(256, 64);
  const double want = mean_linear(grey);
  for (Dither d : {Dither::Bayer, Dither::FloydSteinberg}) {
    const Image b = dither(grey, d);
    EXPECT_TRUE(b.bilevel);
    for (uint8_t v : b.data) ASSERT_TRUE(v == 0 || v == 255);
    EXPECT_NEAR(mean_linear(b), want, 0.02 * want) << to_string(d);
  }
  // A rendered picture too: the torus, ordered and diffused.
  const PaperScene& s = scene_named("torus");
  HalftoneOptions o;
  o.colour = false;
  const Image plain = render_meshes({mesh_of(s)}, {s.paint}, s.camera, o);
  for (Dither d : {Dither::Bayer, Dither::FloydSteinberg}) {
    o.dither = d;
    const Image b = render_meshes({mesh_of(s)}, {s.paint}, s.camera, o);
    EXPECT_TRUE(b.bilevel);
    EXPECT_NEAR(mean_linear(b), mean_linear(plain), 0.03 * mean_linear(plain)) << to_string(d);
  }
}

TEST(Dither, ParsesItsNames) {
  Dither d;
  EXPECT_TRUE(parse_dither("bayer", d) && d == Dither::Bayer);
  EXPECT_TRUE(parse_dither("fs", d) && d == Dither::FloydSteinberg);
  EXPECT_TRUE(parse_dither("none", d) && d == Dither::None);
  EXPECT_FALSE(parse_dither("halftone", d));
  ShadingModel m;
  EXPECT_TRUE(parse_shading("smooth", m) && m == ShadingModel::Smooth);
  EXPECT_FALSE(parse_shading("phong", m));
}

// --- files -------------------------------------------------------------------------------

TEST(RasterFiles, PngAndNetpbmReadBackAsWritten) {
  const fs::path dir = temp_dir();
  const PaperScene& s = scene_named("cottage");
  const Image rgb = render_meshes({mesh_of(s)}, {s.paint}, s.camera, {});
  const Image grey = grey_of(rgb);
  const Image bilevel = dither(grey, Dither::FloydSteinberg);
  for (const Image* im : {&rgb, &grey, &bilevel}) {
    const std::string png = (dir / "p.png").string();
    write_image(*im, png);
    const Image back = read_image(png);  // through libpng
    EXPECT_EQ(back.width, im->width);
    EXPECT_EQ(back.channels, im->channels);
    EXPECT_EQ(back.bilevel, im->bilevel);
    EXPECT_EQ(back.data, im->data);
  }
  write_image(grey, (dir / "g.pgm").string());
  EXPECT_EQ(read_image((dir / "g.pgm").string()).data, grey.data);
  write_image(rgb, (dir / "c.ppm").string());
  EXPECT_EQ(read_image((dir / "c.ppm").string()).data, rgb.data);
  write_image(bilevel, (dir / "b.pbm").string());
  EXPECT_EQ(read_image((dir / "b.pbm").string()).data, bilevel.data);
  // An RGB picture to PGM is its luminance; a grey one to PBM is dithered on the way.
  write_image(rgb, (dir / "l.pgm").string());
  EXPECT_EQ(read_image((dir / "l.pgm").string()).data, grey.data);
  write_image(grey, (dir / "d.PBM").string());
  EXPECT_TRUE(read_image((dir / "d.PBM").string()).bilevel);
  fs::remove_all(dir);
}

TEST(RasterFiles, UnknownExtensionNamesTheFile) {
  Image im;
  im.resize(4, 4, 1);
  try {
    write_image(im, "/tmp/picture.tiff");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp/picture.tiff"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find(raster_extensions()), std::string::npos);
  }
  EXPECT_FALSE(fs::exists("/tmp/picture.tiff"));
  EXPECT_TRUE(is_raster_path("a/b.PNG"));
  EXPECT_FALSE(is_raster_path("a/b.svg"));
  EXPECT_THROW(read_image("/nonexistent/x.png"), std::runtime_error);
}

// --- stereo ------------------------------------------------------------------------------

TEST(RasterStereo, AnaglyphSendsTheLeftEyeRedAndTheRightEyeCyan) {
  Image white, black;
  white.resize(8, 8, 1);
  black.resize(8, 8, 1);
  std::fill(white.data.begin(), white.data.end(), 255);
  std::fill(black.data.begin(), black.data.end(), 0);
  const Image left = anaglyph(white, black), right = anaglyph(black, white);
  EXPECT_EQ(left.channels, 3);
  EXPECT_EQ(left.data[0], 255);  // Dubois: 0.437 + 0.449 + 0.164 > 1
  EXPECT_EQ(left.data[1], 0);
  EXPECT_EQ(left.data[2], 0);
  EXPECT_EQ(right.data[0], 0);
  EXPECT_GT(right.data[1], 250);
  EXPECT_GT(right.data[2], 250);
  Image small;
  small.resize(4, 8, 1);
  EXPECT_THROW(anaglyph(white, small), std::invalid_argument);
}

TEST(RasterStereo, SideBySideParallelAndCross) {
  Image a, b;
  a.resize(3, 2, 1);
  b.resize(3, 2, 3);
  std::fill(a.data.begin(), a.data.end(), 10);
  std::fill(b.data.begin(), b.data.end(), 200);
  const Image parallel = stereo_composite(a, b, StereoComposite::Parallel);
  const Image cross = stereo_composite(a, b, StereoComposite::Cross);
  EXPECT_EQ(parallel.width, 6);
  EXPECT_EQ(parallel.channels, 3);
  EXPECT_EQ(parallel.row(1)[0], 10);
  EXPECT_EQ(parallel.row(1)[3 * 3], 200);
  EXPECT_EQ(cross.row(1)[0], 200);
  StereoComposite l;
  EXPECT_TRUE(parse_stereo_composite("cross", l) && l == StereoComposite::Cross);
  EXPECT_FALSE(parse_stereo_composite("pair", l));
}

TEST(RasterStereo, AViewFromTwoEyes) {
  const CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml"));
  const Viewpoint vp = default_viewpoint(c);
  Camera left = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 160, 90), right = left;
  left.eye = left.eye - 0.0325 * left.right;  // 65 mm apart, converging 2 m ahead
  right.eye = right.eye + 0.0325 * right.right;
  left.shift_x = 0.0325 / 2;
  right.shift_x = -0.0325 / 2;
  HalftoneOptions o;
  RenderStats stats;
  const Image parallel = render_stereo_view(c, {}, left, right, StereoComposite::Parallel, o, &stats);
  const Image cross = render_stereo_view(c, {}, left, right, StereoComposite::Cross, o);
  EXPECT_EQ(parallel.width, 320);
  EXPECT_EQ(stats.pixels, 2 * 160 * 90);
  EXPECT_NE(std::vector<uint8_t>(parallel.row(45), parallel.row(45) + 3 * 160),
            std::vector<uint8_t>(parallel.row(45) + 3 * 160, parallel.row(45) + 3 * 320));  // two eyes, two views
  EXPECT_EQ(std::vector<uint8_t>(parallel.row(45), parallel.row(45) + 3 * 160),
            std::vector<uint8_t>(cross.row(45) + 3 * 160, cross.row(45) + 3 * 320));
  EXPECT_EQ(render_stereo_view(c, {}, left, right, StereoComposite::Anaglyph, o).width, 160);
  o.dither = Dither::Bayer;
  EXPECT_TRUE(render_stereo_view(c, {}, left, right, StereoComposite::Parallel, o).bilevel);
  EXPECT_THROW(render_stereo_view(c, {}, left, right, StereoComposite::Anaglyph, o), std::invalid_argument);
}

// --- the papers' scenes -----------------------------------------------------------------

TEST(PaperScenes, CountsAreThePapers) {
  for (const PaperScene& s : paper_scenes()) {
    long edges = 0;
    for (const auto& p : s.polygons) edges += long(p.size());
    if (s.paper_polygons) {
      EXPECT_EQ(long(s.polygons.size()), s.paper_polygons) << s.name;
    }
    if (s.paper_edges) {
      EXPECT_EQ(edges, s.paper_edges) << s.name;
    }
    EXPECT_EQ(s.camera.width, 512);
    EXPECT_EQ(s.camera.height, 512);
  }
  EXPECT_TRUE(mesh_of(scene_named("torus")).closed);
  EXPECT_TRUE(mesh_of(scene_named("crow-object")).closed);
  EXPECT_TRUE(mesh_of(scene_named("wylie-cube")).closed);
}

TEST(PaperScenes, BundledFilesAreTheGeneratorsAndLoadAsMeshes) {
  for (const PaperScene& s : paper_scenes()) {
    const fs::path file = fs::path(AVENUES_SOURCE_DIR) / "plans" / "scenes" / (s.name + ".off");
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_TRUE(text.str() == off_text(s)) << file << " is not what off_text() writes: regenerate it";
    const Mesh loaded = load_mesh(file.string()), made = mesh_of(s);
    ASSERT_EQ(loaded.vertices.size(), made.vertices.size()) << s.name;
    for (size_t i = 0; i < made.vertices.size(); ++i) EXPECT_TRUE(loaded.vertices[i] == made.vertices[i]) << s.name;
    EXPECT_EQ(loaded.triangles, made.triangles) << s.name;
    EXPECT_EQ(loaded.polygon_of, made.polygon_of) << s.name;
    EXPECT_EQ(loaded.closed, made.closed) << s.name;
  }
}

TEST(PaperScenes, TheTableRunsEveryScene) {
  const std::vector<PaperBenchRow> rows = bench_papers(2, 1);
  ASSERT_EQ(rows.size(), paper_scenes().size());
  for (const PaperBenchRow& r : rows) {
    EXPECT_GT(r.stats.spans, 0) << r.scene;
    EXPECT_GT(r.stats.scanlines, 0) << r.scene;
    EXPECT_LE(r.stats.scanlines, 512) << r.scene;
  }
  const std::string table = papers_table(rows);
  EXPECT_NE(table.find("ripple-torus"), std::string::npos);
  EXPECT_NE(table.find("77,776"), std::string::npos);  // Bouknight's depth sorts beside ours
}

// An eye 3 mm from a pier 6 mm wide between two doorways, looking straight at it, a crate
// beyond the wall seen through both doorways. The near plane (1 cm) once cut the pier
// away: the picture cut at its masks then showed nothing there, and the one resolved by
// depth (the hull search's, the walkthrough's: the crate's room is searched through the
// hull of its two pieces of view, which spans the pier) showed the crate through the
// pier. Now the near plane comes no farther than half the eye's way to its cell's nearest
// face, and both pictures show the pier.
TEST(Halftone, AnEyeMillimetresFromAPierSeesThePierNotWhatLiesBehindIt) {
  Plan p;
  p.name = "a pier before the eye";
  p.far_margin = 3;
  p.storeys.push_back({"ground", 0, 2.5, 0.3, {}});
  auto wall = [](const std::string& name, std::vector<Vec2> centre) {
    Wall w;
    w.name = name;
    w.centre = std::move(centre);
    w.thickness = 0.2;
    return w;
  };
  auto doorway = [](const std::string& name, double at, double width) {
    Opening o;
    o.name = name;
    o.kind = OpeningKind::Door;
    o.at = at, o.width = width, o.sill = 0, o.head = 2.1;
    return o;
  };
  Wall middle = wall("middle", {{4, 0}, {4, 4}});
  middle.openings = {doorway("south", 1.0, 0.997), doorway("north", 2.003, 0.997)};  // the pier: y 1.997–2.003
  p.walls = {wall("box", {{0, 0}, {8, 0}, {8, 4}, {0, 4}, {0, 0}}), middle};
  Room west, east;
  west.name = "west", west.label = Vec2{2, 2};
  east.name = "east", east.label = Vec2{6, 2};
  p.rooms = {west, east};
  Object crate;
  crate.name = "crate";
  crate.box = {2, 3, 2};
  crate.position = {6, 2, 0};
  p.objects = {crate};
  const CellComplex c = build_cells(p);
  const std::vector<PlacedObject> objects = place_objects(c);
  ASSERT_EQ(objects.size(), 1u);
  const Camera cam = Camera::look_at({3.897, 2, 1.2}, {5, 2, 1.2}, 120, 96, 64);
  const CellId eye_cell = c.locate(cam.eye).cell;
  ASSERT_NE(eye_cell, kNoCell);
  HalftoneOptions o;
  o.threads = 1;
  Image masked, by_depth;
  for (const bool hull : {false, true}) {
    TraverseParams params;
    params.merge_pieces = true;
    params.hull_pieces = hull;
    render_view(c, objects, cam, find_visible(c, cam, eye_cell, params), o, hull ? by_depth : masked);
  }
  ASSERT_EQ(masked.data.size(), by_depth.data.size());
  // The pier fills the middle half of the picture; the two agree but along its edges.
  int differ = 0;
  for (size_t i = 0; i < masked.data.size(); i += 3)
    differ += !std::equal(&masked.data[i], &masked.data[i] + 3, &by_depth.data[i]);
  EXPECT_LE(differ, 2 * 64) << "the pictures differ in " << differ << " pixels";
  // Straight ahead, the pier's shade in both, not the crate's.
  const size_t mid = (size_t(32) * 96 + 48) * 3;
  Image bare;
  const std::vector<PlacedObject> none;
  TraverseParams params;
  params.merge_pieces = params.hull_pieces = true;
  render_view(c, none, cam, find_visible(c, cam, eye_cell, params), o, bare);
  EXPECT_TRUE(std::equal(&by_depth.data[mid], &by_depth.data[mid] + 3, &bare.data[mid]));
  EXPECT_TRUE(std::equal(&masked.data[mid], &masked.data[mid] + 3, &bare.data[mid]));
}
