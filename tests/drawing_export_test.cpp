// Tests of the drawings' exports (render/drawing.h, render/stereo_drawing.h): every format
// is read back by an independent reader — SVG by pugixml, PDF by pdfinfo, EPS by its DSC
// header, DXF by dxflib's own reader, HPGL by a small parser here — and agrees with the
// drawing and the stats write_drawing() reported.
#include <gtest/gtest.h>

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>
#include <pugixml.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "cells/build_cells.h"
#include "render/drawing.h"
#include "render/overlay_drawing.h"
#include "render/stereo_drawing.h"
#include "render/view_lines.h"
#include "tests/avenues_run.h"
#include "tests/drawing_readers.h"
#include "tests/test_files.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

using avenues::testing::slurp;
using avenues::testing::DxfCounter;
using avenues::testing::parse_hpgl;
using avenues::testing::Plot;

namespace {

class DrawingExport : public avenues::testing::AvenuesRun {};

/// The furnished room from its viewpoint: both layers, both weights.
const Drawing& room_drawing() {
  static const Drawing d = [] {
    const CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/furnished-room.toml"));
    const Viewpoint vp = default_viewpoint(c);
    const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 1280, 720);
    return draw_view(c, prepare_line_scene(c), cam, find_visible(c, cam, c.locate(cam.eye).cell));
  }();
  return d;
}

/// n random strokes on a 1000 × 600 px page.
Drawing random_drawing(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0, 1000), y(0, 600), d(-20, 20);
  Drawing dr;
  dr.width = 1000;
  dr.height = 600;
  for (int i = 0; i < n; ++i) {
    const Vec2 a{x(rng), y(rng)};
    dr.strokes.push_back({a, a + Vec2{d(rng), d(rng)}, i % 3 ? Weight::Crease : Weight::Outline,
                          i % 5 ? Layer::Architecture : Layer::Furniture});
  }
  return dr;
}

}  // namespace

// The avenue overlay outlines every mask and draws the whole tree of a view of a few
// avenues; of a view of very many (here the furnished room's avenues repeated, as a finely
// cut scene's view gives 600,000), it outlines the shallowest kOverlayMasks and the first
// kOverlayTreeRows of the tree, and says so: the file stays one a browser opens.
TEST_F(DrawingExport, TheAvenueOverlayOfAVastViewShowsWhatAPersonCanRead) {
  const CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/furnished-room.toml"));
  const Viewpoint vp = default_viewpoint(c);
  const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 640, 360);
  const VisibleSet few = find_visible(c, cam, c.locate(cam.eye).cell);
  ASSERT_GE(few.avenues.size(), 2u);
  auto count = [](const pugi::xml_document& doc, const char* group, const char* element) {
    return doc.select_nodes((std::string("//*[@id='") + group + "']/*[local-name()='" + element + "']").c_str()).size();
  };
  auto title = [](const pugi::xml_document& doc, const char* group) {
    return std::string(doc.select_node((std::string("//*[@id='") + group + "']/*[local-name()='text']").c_str())
                           .node()
                           .child_value());
  };
  pugi::xml_document small;
  ASSERT_TRUE(small.load_string(overlay_svg(c, cam, few).c_str()));
  EXPECT_EQ(count(small, "picture-plane", "polygon"), few.avenues.size());
  EXPECT_EQ(count(small, "avenue-tree", "circle"), few.avenues.size());
  EXPECT_EQ(title(small, "picture-plane").find("shallowest"), std::string::npos) << title(small, "picture-plane");

  VisibleSet vast = few;  // copies of the avenues below the root, each a level deeper
  const size_t n = few.avenues.size();
  while (vast.avenues.size() < 2 * kOverlayMasks + 7) {
    const size_t from = vast.avenues.size() - (n - 1);
    for (size_t i = 1; i < n; ++i) {
      Avenue a = vast.avenues[from + i - 1];
      a.depth += 1;
      a.parent = int(from + i - 1);
      vast.avenues.push_back(a);
    }
  }
  const std::string svg = overlay_svg(c, cam, vast);
  pugi::xml_document big;
  ASSERT_TRUE(big.load_string(svg.c_str()));
  EXPECT_EQ(count(big, "picture-plane", "polygon"), kOverlayMasks);
  EXPECT_EQ(count(big, "avenue-tree", "circle"), kOverlayTreeRows);
  EXPECT_NE(title(big, "picture-plane").find(std::to_string(kOverlayMasks) + " of " + std::to_string(vast.avenues.size())),
            std::string::npos)
      << title(big, "picture-plane");
  EXPECT_NE(title(big, "avenue-tree").find("the first " + std::to_string(kOverlayTreeRows) + " of"), std::string::npos)
      << title(big, "avenue-tree");
  // The shallowest are outlined: the root's mask among them, and none deeper than one left out.
  std::vector<bool> outlined(vast.avenues.size(), false);
  for (const pugi::xpath_node& t : big.select_nodes("//*[@id='picture-plane']/*[local-name()='polygon']/*[local-name()='title']"))
    outlined.at(std::stoul(std::string(t.node().child_value()).substr(std::string("avenue ").size()))) = true;
  EXPECT_TRUE(outlined[0]);
  int deepest_outlined = 0, shallowest_left = 1 << 30;
  for (size_t i = 0; i < outlined.size(); ++i)
    (outlined[i] ? deepest_outlined : shallowest_left) =
        outlined[i] ? std::max(deepest_outlined, vast.avenues[i].depth) : std::min(shallowest_left, vast.avenues[i].depth);
  EXPECT_LE(deepest_outlined, shallowest_left);
}

TEST_F(DrawingExport, SvgReadsBackWithAGroupPerLayerAndWidthsInMillimetres) {
  const Drawing& d = room_drawing();
  const DrawingStats st = write_drawing(d, path("view.svg"));
  EXPECT_EQ(st.lines, d.strokes.size());
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(path("view.svg").c_str())) << "not well-formed XML";
  const pugi::xml_node svg = doc.child("svg");
  EXPECT_STREQ(svg.attribute("width").value(), "297.0000mm");
  // 1280 × 720 px on 277 mm between 10 mm margins: 155.8125 mm, plus the margins.
  EXPECT_STREQ(svg.attribute("height").value(), "175.8125mm");
  EXPECT_EQ(doc.select_nodes("//line").size(), d.strokes.size());
  for (const char* layer : {"architecture", "furniture"}) {
    const pugi::xpath_node g = doc.select_node((std::string("/svg/g[@id='") + layer + "']").c_str());
    ASSERT_TRUE(g) << layer;
    EXPECT_STREQ(g.node().select_node("g[@class='outline']").node().attribute("stroke-width").value(), "0.5000");
    EXPECT_STREQ(g.node().select_node("g[@class='crease']").node().attribute("stroke-width").value(), "0.2500");
    EXPECT_GT(g.node().select_nodes(".//line").size(), 0u) << layer;
  }
  EXPECT_EQ(files(), std::set<std::string>{"view.svg"});
}

TEST_F(DrawingExport, PdfIsReadByPdfinfoAtThePageSize) {
  const Drawing& d = room_drawing();
  EXPECT_EQ(write_drawing(d, path("view.pdf")).lines, d.strokes.size());
  const avenues::testing::Outcome info = run_argv({"pdfinfo", path("view.pdf")});
  const std::string out = info.output();
  EXPECT_EQ(info.status, 0) << out;
  int pages = 0;
  const size_t pages_at = out.find("Pages:");
  ASSERT_NE(pages_at, std::string::npos) << out;
  EXPECT_EQ(std::sscanf(out.c_str() + pages_at, "Pages: %d", &pages), 1);
  EXPECT_EQ(pages, 1);
  // 297 mm × 175.8125 mm in points.
  double w = 0, h = 0;
  const size_t at = out.find("Page size:");
  ASSERT_NE(at, std::string::npos) << out;
  ASSERT_EQ(std::sscanf(out.c_str() + at, "Page size: %lf x %lf pts", &w, &h), 2) << out;
  EXPECT_NEAR(w, 297 * 72 / 25.4, 0.01);
  EXPECT_NEAR(h, 175.8125 * 72 / 25.4, 0.01);
}

TEST_F(DrawingExport, EpsIsEncapsulatedPostScriptByCairo) {
  const Drawing& d = room_drawing();
  write_drawing(d, path("view.eps"));
  const std::string eps = slurp(path("view.eps"));
  EXPECT_EQ(eps.rfind("%!PS-Adobe-3.0 EPSF-3.0", 0), 0u) << eps.substr(0, 40);
  EXPECT_NE(eps.find("%%Creator: cairo"), std::string::npos);
  // The bounding box Cairo measured lies on the 842 × 499 pt page.
  int x0 = -1, y0 = -1, x1 = -1, y1 = -1;
  const size_t at = eps.find("%%BoundingBox:");
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(std::sscanf(eps.c_str() + at, "%%%%BoundingBox: %d %d %d %d", &x0, &y0, &x1, &y1), 4);
  EXPECT_TRUE(0 <= x0 && x0 < x1 && x1 <= 842 && 0 <= y0 && y0 < y1 && y1 <= 499) << eps.substr(at, 40);
  EXPECT_NE(eps.find("%%EOF"), std::string::npos);
}

TEST_F(DrawingExport, DxfReadsBackInDxflibWithNamedLayersLineweightsAndYUp) {
  const Drawing& d = room_drawing();
  EXPECT_EQ(write_drawing(d, path("view.dxf")).lines, d.strokes.size());
  DxfCounter counter;
  DL_Dxf dxf;
  ASSERT_TRUE(dxf.in(path("view.dxf"), &counter));
  EXPECT_EQ(counter.lines + counter.polyline_vertices / 2, int(d.strokes.size()));
  EXPECT_EQ(counter.layers_used, (std::set<std::string>{"architecture", "furniture"}));
  EXPECT_TRUE(counter.layers_declared.count("architecture") && counter.layers_declared.count("furniture"));
  EXPECT_EQ(counter.weights, (std::set<int>{25, 50}));  // standard lineweights, 1/100 mm
  // y up in millimetres: raster (x, y) → (10 + x·s, 175.8125 − 10 − y·s), s = 277/1280 mm/px.
  const double s = 277.0 / 1280;
  const Stroke& first = d.strokes.front();
  EXPECT_NEAR(counter.line_data.front().x1, 10 + first.a.x * s, 1e-6);
  EXPECT_NEAR(counter.line_data.front().y1, 165.8125 - first.a.y * s, 1e-6);
  EXPECT_EQ(files(), std::set<std::string>{"view.dxf"});
}

TEST_F(DrawingExport, HpglDrawsEveryStrokeOncePenByPenWithTheReportedTravel) {
  for (const Drawing& d : {room_drawing(), random_drawing(2000, 7)}) {
    const DrawingStats st = write_drawing(d, path("view.hpgl"));
    const std::string text = slurp(path("view.hpgl"));
    EXPECT_EQ(text.rfind("IN;", 0), 0u);
    const Plot plot = parse_hpgl(text);
    EXPECT_EQ(plot.segments, int(d.strokes.size()));
    EXPECT_EQ(size_t(plot.segments), st.lines);
    EXPECT_NEAR(plot.travel / 40, st.penup_mm_after, 1e-9);
    EXPECT_LE(st.penup_mm_after, st.penup_mm_before);
    EXPECT_EQ(plot.pens, (std::set<int>{0, 1, 2}));  // outline, crease, and put away
  }
  // Many scattered strokes: nearest-end-first cuts the travel several times over.
  const DrawingStats st = write_drawing(random_drawing(2000, 8), path("many.plt"));
  EXPECT_LT(st.penup_mm_after * 3, st.penup_mm_before);
}

TEST_F(DrawingExport, AnUnknownExtensionIsRefusedNamingTheFileAndTheFormats) {
  try {
    write_drawing(room_drawing(), path("view.png"));
    ADD_FAILURE() << "a .png drawing must be refused";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("view.png"), std::string::npos) << what;
    for (const char* ext : {".svg", ".pdf", ".eps", ".dxf", ".hpgl", ".plt"})
      EXPECT_NE(what.find(ext), std::string::npos) << what;
  }
  EXPECT_EQ(drawing_extensions(), ".svg, .pdf, .eps, .dxf, .hpgl, .plt");
  EXPECT_TRUE(files().empty());
  EXPECT_EQ(write_drawing(room_drawing(), path("UPPER.SVG")).lines, room_drawing().strokes.size());
}

TEST_F(DrawingExport, StereoPairsGoSideBySideOrIntoTwoFiles) {
  const Drawing& l = room_drawing();
  Drawing r = l;
  r.strokes.pop_back();
  const Drawing both = side_by_side(l, r);
  EXPECT_EQ(both.width, 2 * l.width);
  EXPECT_EQ(both.height, l.height);
  ASSERT_EQ(both.strokes.size(), l.strokes.size() + r.strokes.size());
  EXPECT_LT(length(both.strokes[l.strokes.size()].a - (r.strokes[0].a + Vec2{double(l.width), 0})), 1e-12);
  EXPECT_EQ(write_stereo_drawing(l, r, StereoLayout::Parallel, path("parallel.svg")).lines, both.strokes.size());
  EXPECT_EQ(write_stereo_drawing(l, r, StereoLayout::Cross, path("cross.svg")).lines, both.strokes.size());
  EXPECT_EQ(write_stereo_drawing(l, r, StereoLayout::Pair, path("pair.svg")).lines, both.strokes.size());
  EXPECT_EQ(files(), (std::set<std::string>{"parallel.svg", "cross.svg", "pair-left.svg", "pair-right.svg"}));
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(path("pair-right.svg").c_str()));
  EXPECT_EQ(doc.select_nodes("//line").size(), r.strokes.size());
  EXPECT_EQ(stereo_pair_paths("out/a.b.pdf")[1], "out/a.b-right.pdf");
}
