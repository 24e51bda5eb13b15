// Tests of the DXF plan reader (plans/formats/dxf_plan.cpp, wall_arrangement.cpp):
//
//   * each DXF in ../shared/outside/dxf opens as a walkable plan (rooms, door portals,
//     views that agree with ray casting) or is refused with a clear error naming the
//     layers and --layers; simple.dxf and two-rooms.dxf give one and two rooms and the
//     door their block shows;
//   * tiny drawings written here with dxflib, one per wall convention: double lines with
//     a door gap and its swing, closed polylines, a hatched wall too thick to tell by
//     width alone, a window in a gap, wall ends left open, partitions drawn on the door
//     layer with a door block holding its leaf, a window in an outer wall; and the layer
//     override, units and the refusal.
#include <gtest/gtest.h>
#include <unistd.h>

#include <dxflib/dl_dxf.h>

#include <filesystem>
#include <functional>
#include <numbers>
#include <set>
#include <string>

#include "plan_import_oracle.h"
#include "plans/formats/dxf_layer_names.h"
#include "plans/formats/dxf_plan.h"
#include "plans/mesh.h"
#include "plans/plan_writer.h"
#include "visibility/viewpoint.h"

namespace avenues {
namespace {

namespace fs = std::filesystem;
const fs::path kSamples = fs::path(AVENUES_OUTSIDE_DIR) / "dxf";

/// A drawing written with dxflib's own writer (R2000), into a scratch file.
class TinyDxf {
 public:
  explicit TinyDxf(int insunits = 6) : insunits_(insunits) {}
  /// The drawings it wrote go with it, and their folder once it is empty.
  ~TinyDxf() {
    std::error_code ec;
    for (const fs::path& p : written_) fs::remove(p, ec);
    if (!written_.empty()) fs::remove(written_.front().parent_path(), ec);  // only when empty
  }
  TinyDxf(const TinyDxf&) = delete;
  TinyDxf& operator=(const TinyDxf&) = delete;
  /// Where the drawing's own origin lies: what line, polyline, arc and text draw is moved there.
  void place_at(Vec2 origin) { o_ = origin; }
  void line(const std::string& layer, Vec2 a, Vec2 b) {
    a = a + o_, b = b + o_;
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeLine(dw, DL_LineData(a.x, a.y, 0, b.x, b.y, 0), attr(layer));
    });
  }
  /// `bulges`, per vertex: the tangent of a quarter of the arc to the next (none: straight).
  void polyline(const std::string& layer, std::vector<Vec2> pts, bool closed, std::vector<double> bulges = {}) {
    for (Vec2& p : pts) p = p + o_;
    bulges.resize(pts.size(), 0);
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writePolyline(dw, DL_PolylineData(int(pts.size()), 0, 0, closed ? 1 : 0), attr(layer));
      for (size_t i = 0; i < pts.size(); ++i) dxf.writeVertex(dw, DL_VertexData(pts[i].x, pts[i].y, 0, bulges[i]));
      dxf.writePolylineEnd(dw);
    });
  }
  void arc(const std::string& layer, Vec2 c, double r, double a0_deg, double a1_deg) {
    c = c + o_;
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeArc(dw, DL_ArcData(c.x, c.y, 0, r, a0_deg, a1_deg), attr(layer));
    });
  }
  /// An arc written as a program that mirrored it writes it: in its object coordinates
  /// with extrusion direction (0, 0, -1), where x runs the other way. The arc it draws is
  /// centred at c from a0 to a1 degrees, counter-clockwise, in the plan.
  void arc_mirrored(const std::string& layer, Vec2 c, double r, double a0_deg, double a1_deg) {
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, "ARC");
      dw.dxfString(8, layer);
      dw.dxfReal(10, -c.x), dw.dxfReal(20, c.y), dw.dxfReal(30, 0);
      dw.dxfReal(40, r);
      dw.dxfReal(210, 0), dw.dxfReal(220, 0), dw.dxfReal(230, -1);
      dw.dxfReal(50, 180 - a1_deg), dw.dxfReal(51, 180 - a0_deg);
    });
  }
  /// An MLINE through `pts` (open) of two elements `width` apart about its middle, as
  /// AutoCAD writes one: per vertex its segment's direction, the miter, and per element
  /// the offset along the miter followed by where the element starts and, past each cut,
  /// stops and starts again (`cuts`, per segment: distances along it).
  void mline(const std::string& layer, std::vector<Vec2> pts, double width, std::vector<std::vector<double>> cuts = {}) {
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, "MLINE");
      dw.dxfString(100, "AcDbEntity");
      dw.dxfString(8, layer);
      dw.dxfString(100, "AcDbMline");
      dw.dxfString(2, "STANDARD");
      dw.dxfReal(40, width), dw.dxfInt(70, 1), dw.dxfInt(71, 1);
      dw.dxfInt(72, int(pts.size())), dw.dxfInt(73, 2);
      dw.dxfReal(10, pts[0].x), dw.dxfReal(20, pts[0].y), dw.dxfReal(30, 0);
      for (size_t i = 0; i < pts.size(); ++i) {
        auto unit = [](Vec2 v) { return (1 / length(v)) * v; };
        const Vec2 in = i > 0 ? unit(pts[i] - pts[i - 1]) : unit(pts[1] - pts[0]);
        const Vec2 out = i + 1 < pts.size() ? unit(pts[i + 1] - pts[i]) : in;
        // The miter halves the turn; an element offset h from the middle meets it at h / sin.
        const Vec2 left_in{-in.y, in.x}, left_out{-out.y, out.x};
        const Vec2 miter = unit(left_in + left_out);
        const double along = 1 / dot(miter, left_out);
        dw.dxfReal(11, pts[i].x), dw.dxfReal(21, pts[i].y), dw.dxfReal(31, 0);
        dw.dxfReal(12, out.x), dw.dxfReal(22, out.y), dw.dxfReal(32, 0);
        dw.dxfReal(13, miter.x), dw.dxfReal(23, miter.y), dw.dxfReal(33, 0);
        for (double h : {width / 2, -width / 2}) {
          std::vector<double> params{h * along, 0};
          if (i < cuts.size()) params.insert(params.end(), cuts[i].begin(), cuts[i].end());
          dw.dxfInt(74, int(params.size()));
          for (double v : params) dw.dxfReal(41, v);
          dw.dxfInt(75, 0);
        }
      }
    });
  }
  /// An LWPOLYLINE drawn `width` wide (its constant width, code 43).
  void wide_polyline(const std::string& layer, std::vector<Vec2> pts, bool closed, double width) {
    for (Vec2& p : pts) p = p + o_;
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, "LWPOLYLINE");
      dw.dxfString(100, "AcDbEntity");
      dw.dxfString(8, layer);
      dw.dxfString(100, "AcDbPolyline");
      dw.dxfInt(90, int(pts.size()));
      dw.dxfInt(70, closed ? 1 : 0);
      dw.dxfReal(43, width);
      for (Vec2 p : pts) dw.dxfReal(10, p.x), dw.dxfReal(20, p.y);
    });
  }
  /// An LWPOLYLINE whose pieces have widths of their own (per vertex, its piece's start and
  /// end width, codes 40 and 41), as AutoCAD's PLINE writes it when the width is changed
  /// along the way.
  void polyline_of_widths(const std::string& layer, std::vector<Vec2> pts, bool closed, std::vector<double> widths) {
    for (Vec2& p : pts) p = p + o_;
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, "LWPOLYLINE"), dw.dxfString(100, "AcDbEntity"), dw.dxfString(8, layer);
      dw.dxfString(100, "AcDbPolyline"), dw.dxfInt(90, int(pts.size())), dw.dxfInt(70, closed ? 1 : 0);
      for (size_t i = 0; i < pts.size(); ++i)
        dw.dxfReal(10, pts[i].x), dw.dxfReal(20, pts[i].y), dw.dxfReal(40, widths[i]), dw.dxfReal(41, widths[i]);
    });
  }
  /// A filled SOLID quadrilateral, corners in DXF's order (1 2 4 3 around).
  void solid(const std::string& layer, Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeSolid(dw, DL_SolidData(a.x, a.y, 0, b.x, b.y, 0, d.x, d.y, 0, c.x, c.y, 0), attr(layer));
    });
  }
  /// A 3DFACE with corners a, b, c, d (d = c for a triangle).
  void face3d(const std::string& layer, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.write3dFace(dw, DL_3dFaceData(a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z), attr(layer));
    });
  }
  void text(const std::string& layer, Vec2 p, const std::string& t) {
    p = p + o_;
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeText(dw, DL_TextData(p.x, p.y, 0, p.x, p.y, 0, 0.2, 1, 0, 0, 0, t, "standard", 0), attr(layer));
    });
  }
  /// An entity of a type dxflib does not know (AutoCAD Architecture's AEC_WALL ...), with
  /// some of the binary proxy graphics such objects carry.
  void foreign(const std::string& type, const std::string& layer) {
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, type), dw.dxfString(100, "AcDbEntity"), dw.dxfString(8, layer);
      dw.dxfInt(92, 16), dw.dxfString(310, "0123456789ABCDEF0123456789ABCDEF");
    });
  }
  /// A line and a text in paper space (group 67), as a layout's sheet holds them.
  void on_paper(const std::string& layer, Vec2 a, Vec2 b, const std::string& t) {
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, "LINE"), dw.dxfString(100, "AcDbEntity"), dw.dxfInt(67, 1), dw.dxfString(8, layer);
      dw.dxfString(100, "AcDbLine");
      dw.dxfReal(10, a.x), dw.dxfReal(20, a.y), dw.dxfReal(30, 0), dw.dxfReal(11, b.x), dw.dxfReal(21, b.y), dw.dxfReal(31, 0);
      dw.dxfString(0, "TEXT"), dw.dxfString(100, "AcDbEntity"), dw.dxfInt(67, 1), dw.dxfString(8, layer);
      dw.dxfString(100, "AcDbText");
      dw.dxfReal(10, a.x), dw.dxfReal(20, a.y + 0.3), dw.dxfReal(30, 0), dw.dxfReal(40, 0.2), dw.dxfString(1, t);
    });
  }
  /// A solid hatch of rings (each a closed polygon).
  void hatch(const std::string& layer, std::vector<std::vector<Vec2>> rings) {
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      DL_HatchData h(int(rings.size()), true, 1, 0, "SOLID");
      dxf.writeHatch1(dw, h, attr(layer));
      for (const auto& r : rings) {
        DL_HatchLoopData loop(int(r.size()));
        dxf.writeHatchLoop1(dw, loop);
        for (size_t i = 0; i < r.size(); ++i) {
          const Vec2 a = r[i], b = r[(i + 1) % r.size()];
          dxf.writeHatchEdge(dw, DL_HatchEdgeData(a.x, a.y, b.x, b.y));
        }
        dxf.writeHatchLoop2(dw, loop);
      }
      dxf.writeHatch2(dw, h, attr(layer));
    });
  }
  /// A solid hatch of a disc, its boundary a polyline of two vertices bulged into half
  /// circles (how a round column's fill is saved).
  void hatch_disc(const std::string& layer, Vec2 c, double r) {
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, "HATCH"), dw.dxfString(100, "AcDbEntity"), dw.dxfString(8, layer), dw.dxfString(100, "AcDbHatch");
      dw.dxfReal(10, 0), dw.dxfReal(20, 0), dw.dxfReal(30, 0), dw.dxfReal(210, 0), dw.dxfReal(220, 0), dw.dxfReal(230, 1);
      dw.dxfString(2, "SOLID"), dw.dxfInt(70, 1), dw.dxfInt(71, 0), dw.dxfInt(91, 1);
      dw.dxfInt(92, 2), dw.dxfInt(72, 1), dw.dxfInt(73, 1), dw.dxfInt(93, 2);
      for (double side : {-1.0, 1.0}) dw.dxfReal(10, c.x + side * r), dw.dxfReal(20, c.y), dw.dxfReal(42, 1);
      dw.dxfInt(97, 0), dw.dxfInt(75, 0), dw.dxfInt(76, 1), dw.dxfInt(98, 0);
    });
  }
  /// A block "door" holding a swing, inserted at `at` turned by `deg`: its leaf stands
  /// open along +y from the hinge at the origin, its swing closes towards (width, 0).
  void door_block(const std::string& layer, Vec2 at, double deg, double width) {
    blocks_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeBlock(dw, DL_BlockData("DOOR-SINGLE", 0, 0, 0, 0));
      dxf.writeArc(dw, DL_ArcData(0, 0, 0, width, 0, 90), attr("0"));
      dxf.writeLine(dw, DL_LineData(0, 0, 0, 0, width, 0), attr("0"));
      dxf.writeEndBlock(dw, "DOOR-SINGLE");
    });
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeInsert(dw, DL_InsertData("DOOR-SINGLE", at.x, at.y, 0, 1, 1, 1, deg, 1, 1, 0, 0), attr(layer));
    });
  }
  /// A door block inserted mirrored as some programs write it: extrusion -Z, the
  /// insertion point's x negated. In the plan its hinge is at `at`, its leaf stands open
  /// along +x and its swing closes towards (at.x, at.y + width).
  void door_block_mirrored(const std::string& layer, Vec2 at, double width) {
    blocks_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeBlock(dw, DL_BlockData("DOOR-M", 0, 0, 0, 0));
      // Drawn to be mirrored: the leaf along -x, the swing from +y round to it.
      dxf.writeArc(dw, DL_ArcData(0, 0, 0, width, 90, 180), attr("0"));
      dxf.writeLine(dw, DL_LineData(0, 0, 0, -width, 0, 0), attr("0"));
      dxf.writeEndBlock(dw, "DOOR-M");
    });
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, "INSERT");
      dw.dxfString(8, layer);
      dw.dxfString(2, "DOOR-M");
      dw.dxfReal(10, -at.x), dw.dxfReal(20, at.y), dw.dxfReal(30, 0);
      dw.dxfReal(210, 0), dw.dxfReal(220, 0), dw.dxfReal(230, -1);
    });
  }
  /// A room tag: a block (its frame) inserted at `at` with attributes (tag, value) after
  /// it, each written at the insertion point, as AutoCAD writes a tag's ATTRIBs.
  void room_tag(const std::string& layer, Vec2 at, std::vector<std::pair<std::string, std::string>> attributes) {
    blocks_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeBlock(dw, DL_BlockData("ROOMTAG", 0, 0, 0, 0));
      for (auto [a, b] : {std::pair{Vec2{-0.5, -0.2}, Vec2{0.5, -0.2}}, {Vec2{0.5, -0.2}, Vec2{0.5, 0.2}},
                          {Vec2{0.5, 0.2}, Vec2{-0.5, 0.2}}, {Vec2{-0.5, 0.2}, Vec2{-0.5, -0.2}}})
        dxf.writeLine(dw, DL_LineData(a.x, a.y, 0, b.x, b.y, 0), attr("0"));
      dxf.writeEndBlock(dw, "ROOMTAG");
    });
    body_.push_back([=](DL_Dxf&, DL_WriterA& dw) {
      dw.dxfString(0, "INSERT");
      dw.dxfString(8, layer);
      dw.dxfInt(66, 1);
      dw.dxfString(2, "ROOMTAG");
      dw.dxfReal(10, at.x), dw.dxfReal(20, at.y), dw.dxfReal(30, 0);
      for (const auto& [tag, value] : attributes) {
        dw.dxfString(0, "ATTRIB");
        dw.dxfString(8, layer);
        dw.dxfReal(10, at.x), dw.dxfReal(20, at.y), dw.dxfReal(30, 0);
        dw.dxfReal(40, 0.2);
        dw.dxfString(1, value);
        dw.dxfString(2, tag);
        dw.dxfInt(70, 0);
      }
      dw.dxfString(0, "SEQEND");
      dw.dxfString(8, layer);
    });
  }
  /// A block of lines (on layer 0, taking the INSERT's layer) inserted at `at` turned by `deg`.
  void block_of_lines(const std::string& name, const std::string& layer, std::vector<std::pair<Vec2, Vec2>> lines,
                      Vec2 at, double deg) {
    blocks_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeBlock(dw, DL_BlockData(name, 0, 0, 0, 0));
      for (const auto& [a, b] : lines) dxf.writeLine(dw, DL_LineData(a.x, a.y, 0, b.x, b.y, 0), attr("0"));
      dxf.writeEndBlock(dw, name);
    });
    body_.push_back([=](DL_Dxf& dxf, DL_WriterA& dw) {
      dxf.writeInsert(dw, DL_InsertData(name, at.x, at.y, 0, 1, 1, 1, deg, 1, 1, 0, 0), attr(layer));
    });
  }
  std::string write(const std::string& name) const {
    const fs::path dir = fs::temp_directory_path() / ("avenues-dxf-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string path = (dir / name).string();
    written_.push_back(path);
    DL_Dxf dxf;
    DL_WriterA* dw = dxf.out(path.c_str(), DL_Codes::AC1015);
    EXPECT_NE(dw, nullptr);
    dxf.writeHeader(*dw);
    dw->dxfString(9, "$INSUNITS");
    dw->dxfInt(70, insunits_);
    dw->sectionEnd();
    dw->sectionBlocks();
    for (const auto& b : blocks_) b(dxf, *dw);
    dw->sectionEnd();
    dw->sectionEntities();
    for (const auto& e : body_) e(dxf, *dw);
    dw->sectionEnd();
    dw->dxfEOF();
    dw->close();
    delete dw;
    return path;
  }

 private:
  static DL_Attributes attr(const std::string& layer) { return DL_Attributes(layer, 256, -1, "BYLAYER", 1.0); }
  mutable std::vector<fs::path> written_;  ///< by write(), removed with the drawing
  int insunits_;
  Vec2 o_{0, 0};
  std::vector<std::function<void(DL_Dxf&, DL_WriterA&)>> blocks_, body_;
};

/// Doors (or windows) in the plan: the openings of one gap, on however many walls its
/// line and the faces in its gap were cut into, share its name.
int doors_in(const Plan& p, OpeningKind kind = OpeningKind::Door) {
  std::set<std::string> names;
  for (const Wall& w : p.walls)
    for (const Opening& o : w.openings)
      if (o.kind == kind) names.insert(o.name);
  return int(names.size());
}

/// Two rooms 3.9 x 3 m in walls 0.2 m thick drawn as pairs of lines; the partition at
/// x 4.1–4.3 has a 0.9 m gap (y 1.0–1.9) with a door.
void two_rooms_in_double_lines(TinyDxf& d, const std::string& walls) {
  d.polyline(walls, {{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, true);
  d.line(walls, {0.2, 0.2}, {8.2, 0.2});
  d.line(walls, {8.2, 0.2}, {8.2, 3.2});
  d.line(walls, {8.2, 3.2}, {0.2, 3.2});
  d.line(walls, {0.2, 3.2}, {0.2, 0.2});
  for (double x : {4.1, 4.3}) {
    d.line(walls, {x, 0.2}, {x, 1.0});
    d.line(walls, {x, 1.9}, {x, 3.2});
  }
  d.line(walls, {4.1, 1.0}, {4.3, 1.0});
  d.line(walls, {4.1, 1.9}, {4.3, 1.9});
  d.text("Text", {2, 1.5}, "Kitchen");
  d.text("Text", {6, 1.5}, "Hall");
}

/// The same two rooms, each inside a closed polyline of its own and the outer face one
/// more: no door between them.
void two_rooms_in_closed_polylines(TinyDxf& d, const std::string& walls) {
  d.polyline(walls, {{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, true);
  d.polyline(walls, {{0.2, 0.2}, {4.1, 0.2}, {4.1, 3.2}, {0.2, 3.2}}, true);
  d.polyline(walls, {{4.3, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {4.3, 3.2}}, true);
}

/// One room, 4.4 × 3.4 m outside, its walls 0.2 m thick on layer "Walls", with a gap for a
/// window in its south wall from x = 1.5 to 2.7 (the jambs drawn).
void room_with_a_gap_in_its_south_wall(TinyDxf& d) {
  d.polyline("Walls", {{1.5, 0}, {0, 0}, {0, 3.4}, {4.4, 3.4}, {4.4, 0}, {2.7, 0}}, false);
  d.polyline("Walls", {{1.5, 0.2}, {0.2, 0.2}, {0.2, 3.2}, {4.2, 3.2}, {4.2, 0.2}, {2.7, 0.2}}, false);
  d.line("Walls", {1.5, 0}, {1.5, 0.2});
  d.line("Walls", {2.7, 0}, {2.7, 0.2});
}

/// What the reader said of the drawing, its summary's lines one after another.
std::string summary_text(const DxfPlan& r) {
  std::string said;
  for (const std::string& line : r.summary) said += line + "\n";
  return said;
}

/// The PlanError's message reading `path` gives, or "" (and a failure) when it is read.
std::string refusal(const std::string& path) {
  try {
    read_dxf_plan(path);
  } catch (const PlanError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " was read";
  return "";
}

void expect_walkable(const Plan& plan, int rooms, int doors) {
  ASSERT_EQ(int(plan.rooms.size()), rooms);
  EXPECT_EQ(doors_in(plan), doors);
  const CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_GE(avenues::testing::door_portals(c), doors);
  EXPECT_GE(avenues::testing::check_views_from_rooms(plan, c), 4 * rooms);
}

TEST(DxfPlan, DoubleLinesWithADoorSwing) {
  TinyDxf d;
  two_rooms_in_double_lines(d, "A-WALL");
  d.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);  // hinge at the gap's corner, closed towards (4.1, 1.9)
  const DxfPlan r = read_dxf_plan(d.write("double-lines.dxf"));
  expect_walkable(r.plan, 2, 1);
  EXPECT_EQ(r.plan.rooms[0].name == "Kitchen" || r.plan.rooms[1].name == "Kitchen", true);
  EXPECT_EQ(r.plan.rooms[0].name == "Hall" || r.plan.rooms[1].name == "Hall", true);
  EXPECT_NE(r.summary[0].find("'A-WALL'"), std::string::npos) << r.summary[0];
}

TEST(DxfPlan, StoreysDrawnSideBySideAreSaidToBeReadSideBySide) {
  // Two storeys of one house drawn beside each other, each titled below it: read as two
  // buildings on one ground, and the reader says so.
  TinyDxf d;
  two_rooms_in_double_lines(d, "A-WALL");
  d.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);
  d.text("Text", {2, -1}, "GROUND FLOOR PLAN");
  d.place_at({12, 0});
  two_rooms_in_double_lines(d, "A-WALL");
  d.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);
  d.text("Text", {2, -1}, "FIRST FLOOR PLAN");
  const DxfPlan r = read_dxf_plan(d.write("side-by-side.dxf"));
  EXPECT_EQ(r.plan.rooms.size(), 4u);
  bool said = false;
  for (const std::string& w : r.plan.warnings) said |= w.find("name 2 storeys ('GROUND FLOOR PLAN', 'FIRST FLOOR PLAN')") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(DxfPlan, PaperSpaceIsNoPartOfThePlan) {
  // A layout's sheet in paper space, its coordinates overlapping the plan's: a frame line
  // across the kitchen on the wall layer and the sheet's title inside it. Neither is read.
  TinyDxf d;
  two_rooms_in_double_lines(d, "A-WALL");
  d.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);
  d.on_paper("A-WALL", {2.0, 0.1}, {2.0, 3.3}, "GROUND FLOOR PLAN");
  const DxfPlan r = read_dxf_plan(d.write("paper-space.dxf"));
  expect_walkable(r.plan, 2, 1);
  for (const Room& room : r.plan.rooms) EXPECT_TRUE(room.name == "Kitchen" || room.name == "Hall") << room.name;
  const std::string said = summary_text(r);
  EXPECT_NE(said.find("2 lines, texts, fills and inserts in paper space"), std::string::npos) << said;
}

TEST(DxfPlan, ADoorBlockInsertClosesItsGap) {
  TinyDxf d;
  two_rooms_in_double_lines(d, "Wand");
  d.door_block("Tuer", {4.1, 1.9}, 270, 0.9);  // the block's swing turned to run from (4.1, 1.0)
  const DxfPlan r = read_dxf_plan(d.write("door-block.dxf"));
  expect_walkable(r.plan, 2, 1);
}

TEST(DxfPlan, ClosedPolylinesAroundEachRoom) {
  TinyDxf d;
  two_rooms_in_closed_polylines(d, "Walls");
  const DxfPlan r = read_dxf_plan(d.write("polylines.dxf"));
  expect_walkable(r.plan, 2, 0);
  EXPECT_EQ(r.plan.rooms[0].name.rfind("space", 0), 0u);  // no text: named by number
}

TEST(DxfPlan, AHatchTellsAThickWall) {
  // A wall ring 0.6 m thick: wider than any wall by width alone, a wall by its hatch.
  TinyDxf plain, hatched;
  for (TinyDxf* d : {&plain, &hatched}) {
    d->polyline("A-WALL", {{0, 0}, {5.2, 0}, {5.2, 5.2}, {0, 5.2}}, true);
    d->polyline("A-WALL", {{0.6, 0.6}, {4.6, 0.6}, {4.6, 4.6}, {0.6, 4.6}}, true);
  }
  hatched.hatch("A-WALL", {{{0, 0}, {5.2, 0}, {5.2, 5.2}, {0, 5.2}}, {{0.6, 0.6}, {4.6, 0.6}, {4.6, 4.6}, {0.6, 4.6}}});
  EXPECT_EQ(read_dxf_plan(plain.write("ring.dxf")).plan.rooms.size(), 2u);
  const DxfPlan r = read_dxf_plan(hatched.write("hatched-ring.dxf"));
  expect_walkable(r.plan, 1, 0);
}

TEST(DxfPlan, SolidsTellAThickWallAsAHatchDoes) {
  TinyDxf d;
  d.polyline("A-WALL", {{0, 0}, {5.2, 0}, {5.2, 5.2}, {0, 5.2}}, true);
  d.polyline("A-WALL", {{0.6, 0.6}, {4.6, 0.6}, {4.6, 4.6}, {0.6, 4.6}}, true);
  d.solid("A-WALL", {0, 0}, {5.2, 0}, {4.6, 0.6}, {0.6, 0.6});
  d.solid("A-WALL", {5.2, 0}, {5.2, 5.2}, {4.6, 4.6}, {4.6, 0.6});
  d.solid("A-WALL", {5.2, 5.2}, {0, 5.2}, {0.6, 4.6}, {4.6, 4.6});
  d.solid("A-WALL", {0, 5.2}, {0, 0}, {0.6, 0.6}, {0.6, 4.6});
  expect_walkable(read_dxf_plan(d.write("solid-ring.dxf")).plan, 1, 0);
}

TEST(DxfPlan, MirroredArcsAndBlocksPlaceTheirDoors) {
  // A swing stored mirrored (extrusion -Z, x running the other way) lies in the gap all
  // the same, and so does a door block inserted mirrored: each places its door.
  TinyDxf arc, block;
  two_rooms_in_double_lines(arc, "Walls");
  arc.arc_mirrored("Doors", {4.3, 1.0}, 0.9, 0, 90);
  expect_walkable(read_dxf_plan(arc.write("mirrored-arc.dxf")).plan, 2, 1);
  two_rooms_in_double_lines(block, "Walls");
  block.door_block_mirrored("Doors", {4.3, 1.0}, 0.9);
  expect_walkable(read_dxf_plan(block.write("mirrored-block.dxf")).plan, 2, 1);
}

TEST(DxfPlan, WallsDrawnAsMultilinesWithACutForTheDoor) {
  // AutoCAD's MLINE, how many drawings draw walls: the outer ring and the partition are
  // multilines 0.2 m wide, the partition cut (MLEDIT) where its door is.
  TinyDxf d;
  d.mline("A-WALL", {{0.1, 0.1}, {8.3, 0.1}, {8.3, 3.3}, {0.1, 3.3}, {0.1, 0.1}}, 0.2);
  d.mline("A-WALL", {{4.2, 0.1}, {4.2, 3.3}}, 0.2, {{0.9, 1.8}});
  d.arc("A-DOOR", {4.3, 1.0}, 0.9, 0, 90);
  d.text("Text", {2, 1.5}, "Kitchen");
  d.text("Text", {6, 1.5}, "Hall");
  const DxfPlan r = read_dxf_plan(d.write("mline.dxf"));
  expect_walkable(r.plan, 2, 1);
}

TEST(DxfPlan, RoomTagsNameTheirRoomsByTheirNameAttribute) {
  // Rooms named by tag blocks (AIA's A-AREA-IDEN): the NAME attribute names the room, the
  // number and the area do not.
  TinyDxf d;
  two_rooms_in_closed_polylines(d, "A-WALL");
  d.room_tag("A-AREA-IDEN", {2, 1.5}, {{"NAME", "Kitchen"}, {"NUMBER", "101"}, {"AREA", "11.7 m2"}});
  d.room_tag("A-AREA-IDEN", {6, 1.5}, {{"ROOM_NAME", "Hall"}, {"ROOMNUM", "102"}});
  const DxfPlan r = read_dxf_plan(d.write("room-tags.dxf"));
  std::set<std::string> names;
  for (const Room& room : r.plan.rooms) names.insert(room.name);
  EXPECT_EQ(names, (std::set<std::string>{"Kitchen", "Hall"}));
}

TEST(DxfPlan, ADrawingInNationalGridCoordinatesOpensWhereItIs) {
  // Many offices draw a building where it stands in the national grid (metres, x about
  // 2,500 km). The two rooms there open as at the origin, and the default view stands in
  // a room: it stood 80 m off, outside the far box, when cell centroids were taken about
  // the origin.
  TinyDxf d;
  const Vec2 far{2'500'000, 5'600'000};
  d.place_at(far);
  two_rooms_in_double_lines(d, "Walls");
  d.arc("Doors", {4.3, 1.0}, 0.9, 0, 90);
  const DxfPlan r = read_dxf_plan(d.write("national-grid.dxf"));
  expect_walkable(r.plan, 2, 1);
  const CellComplex c = build_cells(r.plan);
  const Viewpoint v = default_viewpoint(c);
  EXPECT_EQ(c.locate(v.eye).what, Location::What::Cell);
  EXPECT_NEAR(v.eye.x - far.x, 2.15, 1.0);
}

TEST(DxfPlan, WallsDrawnAsWidePolylinesAreAsThickAsDrawn) {
  // Walls drawn with PLINE's width, 0.2 m, along their middles: the outer ring closed, the
  // partition in two pieces either side of the door. The rooms are as large as between
  // the bands' faces, and a thin (1 cm, a heavy pen) polyline on a wall layer is a line.
  TinyDxf d;
  d.wide_polyline("Walls", {{0.1, 0.1}, {8.3, 0.1}, {8.3, 3.3}, {0.1, 3.3}}, true, 0.2);
  d.wide_polyline("Walls", {{4.2, 0.1}, {4.2, 1.0}}, false, 0.2);
  d.wide_polyline("Walls", {{4.2, 1.9}, {4.2, 3.3}}, false, 0.2);
  d.arc("Doors", {4.3, 1.0}, 0.9, 0, 90);
  d.text("Text", {2, 1.5}, "Kitchen");
  d.text("Text", {6, 1.5}, "Hall");
  const DxfPlan r = read_dxf_plan(d.write("wide.dxf"));
  expect_walkable(r.plan, 2, 1);
  const CellComplex c = build_cells(r.plan);
  for (const RoomInfo& room : c.rooms) {
    if (room.named) {
      EXPECT_NEAR(room.area, 3.9 * 3.0, 0.2) << room.name;  // the door's gap goes to one of them
    }
  }
  bool said = false;
  for (const std::string& line : r.summary) said |= line.find("3 wide polylines on wall layers") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(DxfPlan, APolylineWhoseWidthChangesAlongTheWayIsAsThickAsDrawnPieceByPiece) {
  // A room drawn as one closed wide polyline: 0.3 m walls, but 0.1 m along the top. Each
  // run of one width is its band: the room's faces lie half a width inside each piece.
  TinyDxf d;
  d.polyline_of_widths("Walls", {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, true, {0.3, 0.3, 0.1, 0.3});
  d.text("Text", {2, 2}, "Room");
  const DxfPlan r = read_dxf_plan(d.write("widths.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 1u);
  double top = 0, bottom = 0;  // the lengths of wall along the room's top and bottom faces
  for (const Wall& w : r.plan.walls) {
    const Vec2 a = w.centre.front(), b = w.centre.back();
    if (std::fabs(a.y - 3.95) < 1e-3 && std::fabs(b.y - 3.95) < 1e-3) top += length(b - a);
    if (std::fabs(a.y - 0.15) < 1e-3 && std::fabs(b.y - 0.15) < 1e-3) bottom += length(b - a);
  }
  EXPECT_NEAR(top, 3.7, 0.01);
  EXPECT_NEAR(bottom, 3.7, 0.01);
  EXPECT_EQ(cells_are_valid(build_cells(r.plan)), "");
}

TEST(DxfPlan, AreasAndSizesUnderARoomsNameAreNoPartOfIt) {
  // Drawings write a room's area or size under its name, in the same MTEXT or a text of
  // its own: the name is the name. A room's number stays.
  TinyDxf d;
  two_rooms_in_closed_polylines(d, "Walls");
  d.text("Text", {2, 1.5}, "KITCHEN\\P12'-9\" x 9'-10\"");  // one MTEXT-style string, paragraphs apart
  d.text("Text", {2, 1.0}, "11.70 m\xc2\xb2");
  d.text("Text", {6, 1.5}, "Bedroom 2");
  d.text("Text", {6, 1.0}, "3,90 x 3,00");
  const DxfPlan r = read_dxf_plan(d.write("areas.dxf"));
  std::set<std::string> names;
  for (const Room& room : r.plan.rooms) names.insert(room.name);
  EXPECT_EQ(names, (std::set<std::string>{"KITCHEN", "Bedroom 2"}));
}

TEST(DxfPlan, WallsDrawnOnlyAsFillsAreWalls) {
  // Some exports draw walls as solid hatches alone, no line along them: the hatch's
  // outline is the walls' faces. Two rooms in one wall fill with two holes, and a door
  // gap left in the fill between them.
  TinyDxf d;
  d.hatch("A-WALL", {{{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}},
                     {{0.2, 0.2}, {4.1, 0.2}, {4.1, 1.0}, {4.3, 1.0}, {4.3, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {4.3, 3.2},
                      {4.3, 1.9}, {4.1, 1.9}, {4.1, 3.2}, {0.2, 3.2}}});
  d.arc("A-DOOR", {4.3, 1.0}, 0.9, 0, 90);
  d.text("Text", {2, 1.5}, "Kitchen");
  d.text("Text", {6, 1.5}, "Hall");
  const DxfPlan r = read_dxf_plan(d.write("fills.dxf"));
  expect_walkable(r.plan, 2, 1);
  bool said = false;
  for (const std::string& line : r.summary) said |= line.find("fills' outlines taken as the walls' faces") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(DxfPlan, ASwingOnLayerZeroIsADoorAndACornerShelfIsNot) {
  // Walls on their layer, the door's swing and leaf on layer 0, as a drawing with no door
  // layer has them; a quarter-round shelf of door radius in the hall's corner (its ends on
  // the two walls) is furniture.
  TinyDxf d;
  two_rooms_in_double_lines(d, "Walls");
  d.arc("0", {4.1, 1.0}, 0.9, 90, 180);
  d.line("0", {4.1, 1.0}, {3.2, 1.0});
  d.arc("0", {8.2, 3.2}, 0.6, 180, 270);
  const DxfPlan r = read_dxf_plan(d.write("swing-on-0.dxf"));
  const std::string said = summary_text(r);
  EXPECT_NE(said.find(": 1 swings,"), std::string::npos) << said;
  expect_walkable(r.plan, 2, 1);
}

TEST(DxfPlan, ADoorDrawnOverAWallNotCutForItOpensTheWall) {
  // A sketch: the partition's two faces drawn straight through, the door's swing (an arc,
  // or a door block) drawn on top with its hinge and closed end on the near face. The
  // partition is opened between them, and the door joins the rooms.
  TinyDxf arc, block;
  for (TinyDxf* d : {&arc, &block}) {
    d->polyline("A-WALL", {{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, true);
    d->polyline("A-WALL", {{0.2, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {0.2, 3.2}}, true);
    d->line("A-WALL", {4.1, 0.2}, {4.1, 3.2});
    d->line("A-WALL", {4.3, 0.2}, {4.3, 3.2});
    d->text("Text", {2, 1.5}, "Kitchen");
    d->text("Text", {6, 1.5}, "Hall");
  }
  arc.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);
  arc.line("A-DOOR", {4.1, 1.0}, {3.2, 1.0});
  block.door_block("Tuer", {4.1, 1.9}, 270, 0.9);
  for (TinyDxf* d : {&arc, &block}) {
    const DxfPlan r = read_dxf_plan(d->write(d == &arc ? "uncut-arc.dxf" : "uncut-block.dxf"));
    const std::string said = summary_text(r);
    EXPECT_NE(said.find("1 doors drawn over walls not cut for them"), std::string::npos) << said;
    expect_walkable(r.plan, 2, 1);
  }
}

TEST(DxfPlan, ASwingOnTheWallLayerIsADoorNotAQuarterDiscRoom) {
  // A drawing with its doors on the wall layer: the swing about the jamb at (4.1, 1.0),
  // once with its leaf drawn open and once without. A rounded corner of the same radius
  // (ends on two walls, its centre in the room) stays a wall.
  TinyDxf with_leaf, without;
  for (TinyDxf* d : {&with_leaf, &without}) {
    two_rooms_in_double_lines(*d, "Walls");
    d->arc("Walls", {4.1, 1.0}, 0.9, 90, 180);
    d->arc("Walls", {7.3, 2.3}, 0.9, 0, 90);
  }
  with_leaf.line("Walls", {4.1, 1.0}, {3.2, 1.0});
  for (TinyDxf* d : {&with_leaf, &without}) {
    const DxfPlan r = read_dxf_plan(d->write(d == &without ? "wall-swing.dxf" : "wall-swing-leaf.dxf"));
    const std::string said = summary_text(r);
    EXPECT_NE(said.find(": 1 swings,"), std::string::npos) << said;
    expect_walkable(r.plan, 2, 1);
  }
}

TEST(DxfPlan, ASwingDrawnAsShortStraightLinesIsASwing) {
  // The swing of DoubleLinesWithADoorSwing as a program that writes arcs as lines draws
  // it: twelve lines of 7.5 degrees, once as one polyline and once as separate LINEs,
  // with the leaf drawn from the hinge to the swing's open end. As lines on the door
  // layer they were frames: a curved wall across the gap, and no way between the rooms.
  const Vec2 hinge{4.1, 1.0};
  std::vector<Vec2> arc;
  for (int i = 0; i <= 12; ++i) {
    const double t = (90 + 7.5 * i) * std::numbers::pi / 180;
    arc.push_back(hinge + 0.9 * Vec2{std::cos(t), std::sin(t)});
  }
  TinyDxf as_polyline, as_lines;
  for (TinyDxf* d : {&as_polyline, &as_lines}) {
    two_rooms_in_double_lines(*d, "A-WALL");
    d->line("A-DOOR", hinge, arc.back());  // the leaf, open
  }
  as_polyline.polyline("A-DOOR", arc, false);
  for (size_t i = 0; i + 1 < arc.size(); ++i) as_lines.line("A-DOOR", arc[i], arc[i + 1]);
  for (TinyDxf* d : {&as_polyline, &as_lines}) {
    const DxfPlan r = read_dxf_plan(d->write(d == &as_lines ? "swing-lines.dxf" : "swing-polyline.dxf"));
    const std::string said = summary_text(r);
    EXPECT_NE(said.find("1 curves drawn as short straight lines on door layers taken as arcs"), std::string::npos) << said;
    expect_walkable(r.plan, 2, 1);
  }
}

TEST(DxfPlan, AColumnDrawnOnlyAsAFillBesideWallLinesIsAWall) {
  // Walls drawn as lines, and a column 0.3 m square in the kitchen drawn only as a SOLID
  // on the wall layer: its outline bounds the room. A hatch along the wall lines (the
  // usual poché) adds nothing.
  TinyDxf d;
  two_rooms_in_double_lines(d, "A-WALL");
  d.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);
  d.solid("A-WALL", {1.5, 1.5}, {1.8, 1.5}, {1.8, 1.8}, {1.5, 1.8});
  d.hatch("A-WALL", {{{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, {{0.2, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {0.2, 3.2}}});
  const DxfPlan r = read_dxf_plan(d.write("column.dxf"));
  expect_walkable(r.plan, 2, 1);
  const std::string said = summary_text(r);
  EXPECT_NE(said.find("1 fills on wall layers with no wall line along their outline"), std::string::npos) << said;
  double around = 0;  // walls along the column's four sides
  auto on_column = [](Vec2 p) {
    const bool x_in = p.x > 1.5 - 1e-3 && p.x < 1.8 + 1e-3, y_in = p.y > 1.5 - 1e-3 && p.y < 1.8 + 1e-3;
    const bool x_side = std::fabs(p.x - 1.5) < 1e-3 || std::fabs(p.x - 1.8) < 1e-3;
    const bool y_side = std::fabs(p.y - 1.5) < 1e-3 || std::fabs(p.y - 1.8) < 1e-3;
    return x_in && y_in && (x_side || y_side);
  };
  for (const Wall& w : r.plan.walls)
    if (on_column(w.centre.front()) && on_column(w.centre.back())) around += length(w.centre.back() - w.centre.front());
  EXPECT_NEAR(around, 1.2, 0.01);
}

TEST(DxfPlan, ARoundColumnFilledWithABulgedBoundaryStandsInItsRoom) {
  // A fill's boundary saved as a polyline with bulges (two half circles): the column is
  // round, 0.4 m across, not a two-point ring read as nothing.
  TinyDxf d;
  two_rooms_in_double_lines(d, "A-WALL");
  d.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);
  d.hatch_disc("A-WALL", {2.0, 2.4}, 0.2);
  const DxfPlan r = read_dxf_plan(d.write("round-column.dxf"));
  expect_walkable(r.plan, 2, 1);
  double around = 0;  // walls on the column's circle, as long as its circumference
  for (const Wall& w : r.plan.walls) {
    const Vec2 a = w.centre.front(), b = w.centre.back();
    if (std::fabs(length(a - Vec2{2.0, 2.4}) - 0.2) < 2e-3 && std::fabs(length(b - Vec2{2.0, 2.4}) - 0.2) < 2e-3)
      around += length(b - a);
  }
  EXPECT_NEAR(around, 2 * std::numbers::pi * 0.2, 0.02);
}

TEST(DxfPlan, AColumnOnAColumnLayerStandsInItsRoom) {
  // AIA's structural column layer: a 0.3 m square in the kitchen is solid, not floor.
  TinyDxf d;
  two_rooms_in_double_lines(d, "A-WALL");
  d.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);
  d.polyline("S-COLS", {{1.5, 1.5}, {1.8, 1.5}, {1.8, 1.8}, {1.5, 1.8}}, true);
  const DxfPlan r = read_dxf_plan(d.write("column-layer.dxf"));
  expect_walkable(r.plan, 2, 1);
  double around = 0;
  for (const Wall& w : r.plan.walls) {
    const Vec2 a = w.centre.front(), b = w.centre.back();
    const bool on = std::max({std::fabs(a.x - 1.65), std::fabs(a.y - 1.65), std::fabs(b.x - 1.65), std::fabs(b.y - 1.65)}) < 0.151;
    if (on) around += length(b - a);
  }
  EXPECT_NEAR(around, 1.2, 0.01);
  EXPECT_NE(r.summary[0].find("'S-COLS'"), std::string::npos) << r.summary[0];
}

TEST(DxfPlan, AWindowAcrossAGapBetweenTwoRooms) {
  TinyDxf d;
  two_rooms_in_double_lines(d, "Walls");
  d.line("Windows", {4.2, 1.0}, {4.2, 1.9});  // the glass, jamb to jamb
  const DxfPlan r = read_dxf_plan(d.write("window.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 2u);
  EXPECT_EQ(doors_in(r.plan, OpeningKind::Window), 1);
  for (const Wall& w : r.plan.walls)
    for (const Opening& o : w.openings) EXPECT_DOUBLE_EQ(o.sill, 0.9);
  EXPECT_EQ(cells_are_valid(build_cells(r.plan)), "");
}

TEST(DxfPlan, AWindowBlockOnLayerZeroIsAWindow) {
  // A window drawn as a block named for it, inserted on layer 0 (which says nothing): its
  // glass lines are a window's, as if on a window layer.
  TinyDxf d;
  two_rooms_in_double_lines(d, "Walls");
  d.block_of_lines("WINDOW-900", "0", {{{0, 0}, {0.9, 0}}, {{0, 0.05}, {0.9, 0.05}}}, {4.175, 1.0}, 90);
  const DxfPlan r = read_dxf_plan(d.write("window-block.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 2u);
  EXPECT_EQ(doors_in(r.plan, OpeningKind::Window), 1);
  EXPECT_EQ(cells_are_valid(build_cells(r.plan)), "");
  bool said = false;
  for (const std::string& line : r.summary) said |= line.find("windows from layers 'block WINDOW-900'") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(DxfPlan, WallEndsLeftOpenAreClosed) {
  // The partition's face lines stop at the door gap with no line across the wall's end,
  // and one of them stops 2 cm short of the outer wall: the ends are closed all the same.
  TinyDxf d;
  d.polyline("Walls", {{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, true);
  d.polyline("Walls", {{0.2, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {0.2, 3.2}}, true);
  d.line("Walls", {4.1, 0.22}, {4.1, 1.0});
  d.line("Walls", {4.3, 0.2}, {4.3, 1.0});
  d.line("Walls", {4.1, 1.9}, {4.1, 3.2});
  d.line("Walls", {4.3, 1.9}, {4.3, 3.2});
  d.arc("Doors", {4.1, 1.0}, 0.9, 90, 180);
  const DxfPlan r = read_dxf_plan(d.write("open-ends.dxf"));
  expect_walkable(r.plan, 2, 1);
}

TEST(DxfPlan, APartitionsCornerARoundingShortOfTheWallClosesItsRooms) {
  // The partition's upper piece is one polyline whose corners stop 0.06 mm below the
  // wall's face (0.1 mm once snapped to the reader's grid): no end is free there, and
  // the sliver between them joined the two rooms into one face.
  TinyDxf d;
  d.polyline("Walls", {{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, true);
  d.polyline("Walls", {{0.2, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {0.2, 3.2}}, true);
  d.polyline("Walls", {{4.1, 0.2}, {4.1, 1.0}, {4.3, 1.0}, {4.3, 0.2}}, false);
  d.polyline("Walls", {{4.1, 1.9}, {4.1, 3.19994}, {4.3, 3.19994}, {4.3, 1.9}}, false);
  d.line("Walls", {4.1, 1.9}, {4.3, 1.9});
  d.arc("Doors", {4.1, 1.0}, 0.9, 90, 180);
  const DxfPlan r = read_dxf_plan(d.write("corner-short.dxf"));
  for (const std::string& w : r.plan.warnings) ADD_FAILURE() << w;
  expect_walkable(r.plan, 2, 1);
}

TEST(DxfPlan, PartitionsOnTheDoorLayerWithADoorBlock) {
  // As in ground-floor-lhs.dxf: the outer walls on the wall layer, the partition drawn on
  // the door layer with its door, a block holding the swing and the open leaf.
  TinyDxf d;
  d.polyline("A-WALL", {{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, true);
  d.polyline("A-WALL", {{0.2, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {0.2, 3.2}}, true);
  d.polyline("A-DOOR", {{4.1, 0.2}, {4.1, 1.0}, {4.3, 1.0}, {4.3, 0.2}}, false);
  d.polyline("A-DOOR", {{4.1, 3.2}, {4.1, 1.9}, {4.3, 1.9}, {4.3, 3.2}}, false);
  d.door_block("A-DOOR", {4.1, 1.0}, 90, 0.9);  // hinge at (4.1, 1.0), leaf open towards -x
  d.text("Text", {2, 1.5}, "Office");
  d.text("Text", {6, 1.5}, "Store");
  const DxfPlan r = read_dxf_plan(d.write("door-layer-partition.dxf"));
  expect_walkable(r.plan, 2, 1);
}

TEST(DxfPlan, TheLeavesOfADoubleDoorMeetMidway) {
  // A 1.6 m gap (y 0.8–2.4) in the partition, two swings of 0.8 m closing at (4.1, 1.6),
  // far from any wall line: each closed end is at the other's.
  TinyDxf d;
  d.polyline("Walls", {{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, true);
  d.polyline("Walls", {{0.2, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {0.2, 3.2}}, true);
  d.polyline("Walls", {{4.1, 0.2}, {4.1, 0.8}, {4.3, 0.8}, {4.3, 0.2}}, false);
  d.polyline("Walls", {{4.1, 3.2}, {4.1, 2.4}, {4.3, 2.4}, {4.3, 3.2}}, false);
  d.arc("Doors", {4.1, 0.8}, 0.8, 90, 180);
  d.line("Doors", {4.1, 0.8}, {3.3, 0.8});
  d.arc("Doors", {4.1, 2.4}, 0.8, 180, 270);
  d.line("Doors", {4.1, 2.4}, {3.3, 2.4});
  const DxfPlan r = read_dxf_plan(d.write("double-door.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 2u);
  EXPECT_NE(r.summary.back().find(", 2 doors,"), std::string::npos) << r.summary.back();
  double open = 0;  // the door openings cover the whole gap, leaf by leaf
  for (const Wall& w : r.plan.walls)
    for (const Opening& o : w.openings) open += o.kind == OpeningKind::Door ? o.width : 0;
  EXPECT_NEAR(open, 1.6, 0.01);
  const CellComplex c = build_cells(r.plan);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_GE(avenues::testing::door_portals(c), 1);
  EXPECT_GE(avenues::testing::check_views_from_rooms(r.plan, c), 8);
}

TEST(DxfPlan, DoubleActingLeavesOnTheWallLayerAreADoorNotHalfDiscRooms) {
  // As ground-floor-lhs.dxf draws a double-acting pair, all on the wall layer: a 1.8 m gap
  // (y 0.8–2.6) in the partition, each leaf drawn open both ways across the wall at its
  // hinge (a 4 cm outline along the chord) and a half circle about the hinge, once as a
  // bulged polyline, once as an ARC. A half circle of the same size whose ends stand on
  // the outer wall (a niche) stays a wall.
  TinyDxf d;
  d.polyline("Walls", {{0, 0}, {8.4, 0}, {8.4, 3.4}, {0, 3.4}}, true);
  d.polyline("Walls", {{0.2, 0.2}, {8.2, 0.2}, {8.2, 3.2}, {0.2, 3.2}}, true);
  d.polyline("Walls", {{4.1, 0.2}, {4.1, 0.8}, {4.3, 0.8}, {4.3, 0.2}}, false);
  d.polyline("Walls", {{4.1, 3.2}, {4.1, 2.6}, {4.3, 2.6}, {4.3, 3.2}}, false);
  d.polyline("Walls", {{3.3, 0.8}, {5.1, 0.8}, {5.1, 0.84}, {3.3, 0.84}}, true);  // the lower leaf
  d.polyline("Walls", {{5.1, 0.8}, {3.3, 0.8}}, false, {1.0});                    // its half circle
  d.polyline("Walls", {{3.3, 2.6}, {5.1, 2.6}, {5.1, 2.56}, {3.3, 2.56}}, true);  // the upper leaf
  d.arc("Walls", {4.2, 2.6}, 0.9, 180, 360);
  d.arc("Walls", {7.0, 0.2}, 0.6, 0, 180);  // a niche standing on the wall's inner face
  const DxfPlan r = read_dxf_plan(d.write("double-acting.dxf"));
  EXPECT_NE(r.summary.back().find(", 2 doors,"), std::string::npos) << r.summary.back();
  double open = 0;  // the leaves shut across the whole gap
  for (const Wall& w : r.plan.walls)
    for (const Opening& o : w.openings) open += o.kind == OpeningKind::Door ? o.width : 0;
  EXPECT_NEAR(open, 1.8, 0.02);
  const std::string said = summary_text(r);
  EXPECT_NE(said.find(": 2 swings,"), std::string::npos) << said;
  EXPECT_EQ(r.plan.rooms.size(), 2u) << said;  // no half-disc rooms beside the gap
  const CellComplex c = build_cells(r.plan);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_GE(avenues::testing::door_portals(c), 1);
  EXPECT_GE(avenues::testing::check_views_from_rooms(r.plan, c), 8);
}

TEST(DxfPlan, ASlidingDoorClosesItsGapWithADoor) {
  // Two panels (thin outlines on the door layer) overlapping in the middle of the
  // partition's gap, no swing: the gap is closed by a door, not by the panels as walls.
  TinyDxf d;
  two_rooms_in_double_lines(d, "A-WALL");
  d.polyline("A-DOOR", {{4.15, 1.0}, {4.19, 1.0}, {4.19, 1.5}, {4.15, 1.5}}, true);
  d.polyline("A-DOOR", {{4.21, 1.4}, {4.25, 1.4}, {4.25, 1.9}, {4.21, 1.9}}, true);
  const DxfPlan r = read_dxf_plan(d.write("sliding.dxf"));
  expect_walkable(r.plan, 2, 1);
  double open = 0;
  for (const Wall& w : r.plan.walls)
    for (const Opening& o : w.openings) open += o.kind == OpeningKind::Door ? o.width : 0;
  EXPECT_NEAR(open, 0.9, 0.02);  // the whole gap, jamb to jamb
  EXPECT_TRUE(r.plan.warnings.empty()) << r.plan.warnings.front();
}

TEST(DxfPlan, APocketDoorDrawnOpenInItsWall) {
  // The two leaves slid into pockets in the wall either side of the gap, each overlapping
  // the gap by 5 cm, arrows between them: one door across the whole gap.
  TinyDxf d;
  two_rooms_in_double_lines(d, "Walls");
  d.polyline("Doors", {{4.18, 0.55}, {4.22, 0.55}, {4.22, 1.05}, {4.18, 1.05}}, true);
  d.polyline("Doors", {{4.18, 1.85}, {4.22, 1.85}, {4.22, 2.35}, {4.18, 2.35}}, true);
  d.line("Doors", {4.35, 1.1}, {4.35, 1.35});  // arrows beside the gap
  d.line("Doors", {4.35, 1.55}, {4.35, 1.8});
  const DxfPlan r = read_dxf_plan(d.write("pocket.dxf"));
  expect_walkable(r.plan, 2, 1);
  EXPECT_NE(r.summary[1].find("1 doors without a swing"), std::string::npos) << r.summary[1];
}

TEST(DxfPlan, ADoorBlockWithoutASwingByItsName) {
  // A block "Sliding Door 900" on a layer named for nothing, holding the two leaves as
  // lines along the gap (y 1.0-1.9 once turned by 90°): read as a door by its name.
  TinyDxf d;
  two_rooms_in_double_lines(d, "Wand");
  d.block_of_lines("Sliding Door 900", "Ausbau", {{{0, 0.02}, {0.5, 0.02}}, {{0.4, -0.02}, {0.9, -0.02}}}, {4.2, 1.0}, 90);
  const DxfPlan r = read_dxf_plan(d.write("sliding-block.dxf"));
  expect_walkable(r.plan, 2, 1);
}

TEST(DxfPlan, DoorSizedLinesInNoWallGapAreNamedNotPlaced) {
  // Closed partition; a wardrobe's sliding front on the door layer stands in the room,
  // in no wall gap: a warning naming where and the layer, and the rooms stay two.
  TinyDxf d;
  two_rooms_in_double_lines(d, "Walls");
  d.line("Walls", {4.1, 1.0}, {4.1, 1.9});
  d.line("Walls", {4.3, 1.0}, {4.3, 1.9});
  d.polyline("Doors", {{1.0, 2.0}, {2.2, 2.0}, {2.2, 2.04}, {1.0, 2.04}}, true);
  const DxfPlan r = read_dxf_plan(d.write("wardrobe.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 2u);
  EXPECT_EQ(doors_in(r.plan), 0);
  ASSERT_EQ(r.plan.warnings.size(), 1u);
  EXPECT_NE(r.plan.warnings[0].find("(1.60, 2.02) m, layer 'Doors', drawn without a swing"), std::string::npos)
      << r.plan.warnings[0];
}

TEST(DxfPlan, AWindowInAnOuterWall) {
  // A gap in the south wall (x 1.5–2.7) with the window's glass lines across it: the
  // room is closed by the window, which opens onto the outside.
  TinyDxf d;
  room_with_a_gap_in_its_south_wall(d);
  d.line("Ext Windows", {1.5, 0.08}, {2.7, 0.08});
  d.line("Ext Windows", {1.5, 0.12}, {2.7, 0.12});
  const DxfPlan r = read_dxf_plan(d.write("outer-window.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 1u);
  EXPECT_EQ(doors_in(r.plan, OpeningKind::Window), 1);
  const CellComplex c = build_cells(r.plan);
  EXPECT_EQ(cells_are_valid(c), "");
  // The window looks out: the outside is free space, the wall ring between is solid.
  EXPECT_GE(avenues::testing::portals_out(c, PortalKind::Window), 1);
  EXPECT_GT(avenues::testing::check_views_from_rooms(r.plan, c), 0);
}

TEST(DxfPlan, AWindowDrawnOnLayerZeroClosesItsGap) {
  // The window of AWindowInAnOuterWall drawn on layer 0, as anandkothartrdl-plan.dxf draws
  // its living room's: the glass, two frames at the jambs, a sill line outside the wall.
  // Furniture on layer 0 (a sofa 0.9 m deep against the wall, a bookcase spanning the
  // room's width) stays furniture. Before, the room was outside through the gap.
  TinyDxf d;
  room_with_a_gap_in_its_south_wall(d);
  d.line("0", {1.55, 0.08}, {2.65, 0.08});
  d.line("0", {1.55, 0.12}, {2.65, 0.12});
  d.polyline("0", {{1.5, 0.05}, {1.55, 0.05}, {1.55, 0.15}, {1.5, 0.15}}, true);
  d.polyline("0", {{2.65, 0.05}, {2.7, 0.05}, {2.7, 0.15}, {2.65, 0.15}}, true);
  d.line("0", {1.45, -0.1}, {2.75, -0.1});  // the sill, outside
  d.polyline("0", {{1.0, 3.2}, {3.0, 3.2}, {3.0, 2.3}, {1.0, 2.3}}, true);   // a sofa
  d.polyline("0", {{0.2, 1.6}, {4.2, 1.6}, {4.2, 1.9}, {0.2, 1.9}}, true);   // a bookcase, wall to wall
  d.text("Text", {1.0, 1.0}, "Living");
  const DxfPlan r = read_dxf_plan(d.write("window-on-0.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 1u);
  EXPECT_EQ(r.plan.rooms[0].name, "Living");
  EXPECT_EQ(doors_in(r.plan, OpeningKind::Window), 1);
  const std::string said = summary_text(r);
  EXPECT_NE(said.find("'0 (lines in wall gaps)'"), std::string::npos) << said;
  const CellComplex c = build_cells(r.plan);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_GE(avenues::testing::portals_out(c, PortalKind::Window), 1);
  EXPECT_GT(avenues::testing::check_views_from_rooms(r.plan, c), 0);
}

TEST(DxfPlan, AFrontDoorLeadsOutAndTheWallRingStaysSolid) {
  // A room in a 0.2 m wall ring, with a 0.9 m door gap in its south wall (x 1.5–2.4)
  // and the door's swing inside: the door opens onto the outside.
  TinyDxf d;
  d.polyline("Walls", {{1.5, 0}, {0, 0}, {0, 3.4}, {4.4, 3.4}, {4.4, 0}, {2.4, 0}}, false);
  d.polyline("Walls", {{1.5, 0.2}, {0.2, 0.2}, {0.2, 3.2}, {4.2, 3.2}, {4.2, 0.2}, {2.4, 0.2}}, false);
  d.line("Walls", {1.5, 0}, {1.5, 0.2});
  d.line("Walls", {2.4, 0}, {2.4, 0.2});
  d.line("Doors", {1.5, 0.2}, {1.5, 1.1});  // the leaf, open
  d.arc("Doors", {1.5, 0.2}, 0.9, 0, 90);
  const DxfPlan r = read_dxf_plan(d.write("front-door.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 1u);
  EXPECT_EQ(doors_in(r.plan), 1);
  EXPECT_TRUE(r.plan.unnamed_spaces_solid);
  EXPECT_FALSE(r.plan.outside_solid);
  const CellComplex c = build_cells(r.plan);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_EQ(avenues::testing::portals_out(c, PortalKind::Door), 1);
  // No free cell stands in the wall ring: the middle of its west side is solid.
  for (const Cell& cell : c.cells) {
    if (cell.kind == CellKind::Sky) continue;
    EXPECT_FALSE(cell.contains({0.1, 1.7, 1.2})) << "cell of kind " << int(cell.kind) << " in the wall";
  }
  EXPECT_GT(avenues::testing::check_views_from_rooms(r.plan, c), 0);
  // Saved and read back, the plan is the same building.
  const std::string toml = plan_as_toml(r.plan);
  EXPECT_NE(toml.find("unnamed_spaces_solid = true"), std::string::npos);
  const CellComplex back = build_cells(parse_plan(toml, "front-door.toml"));
  EXPECT_EQ(back.cells.size(), c.cells.size());
  EXPECT_EQ(back.portals.size(), c.portals.size());
}

TEST(DxfPlan, UnitsFromInsunitsOrTheOption) {
  TinyDxf d(4);  // millimetres
  d.polyline("Walls", {{0, 0}, {8400, 0}, {8400, 3400}, {0, 3400}}, true);
  d.polyline("Walls", {{200, 200}, {8200, 200}, {8200, 3200}, {200, 3200}}, true);
  const std::string path = d.write("mm.dxf");
  const DxfPlan r = read_dxf_plan(path);
  ASSERT_EQ(r.plan.rooms.size(), 1u);
  double hi = 0;
  for (const Wall& w : r.plan.walls)
    for (Vec2 p : w.centre) hi = std::max(hi, p.x);
  EXPECT_NEAR(hi, 8.4, 0.01);  // the outer face, between the wall and the outside
  DxfPlanOptions cm;
  cm.unit = "cm";
  const DxfPlan r2 = read_dxf_plan(path, cm);
  hi = 0;
  for (const Wall& w : r2.plan.walls)
    for (Vec2 p : w.centre) hi = std::max(hi, p.x);
  EXPECT_NEAR(hi, 84, 0.1);  // in cm the ring is 2 m thick: a room of its own, with the outside beyond
  EXPECT_EQ(r2.plan.rooms.size(), 2u);
  cm.unit = "furlong";
  EXPECT_THROW(read_dxf_plan(path, cm), PlanError);
}

TEST(DxfPlan, WithoutInsunitsTheDoorSwingsTellTheUnit) {
  // The same two rooms drawn in centimetres and in inches, no $INSUNITS: 840 or 331 units
  // across reads as metres by the extent alone (a 840 m house); the 90 cm (35.4 in)
  // swing says cm (in). Without a swing the extent still decides.
  auto hi_x = [](const Plan& p) {
    double hi = 0;
    for (const Wall& w : p.walls)
      for (Vec2 q : w.centre) hi = std::max(hi, q.x);
    return hi;
  };
  for (const auto& [unit, name] : {std::pair{0.01, "cm"}, std::pair{0.0254, "in"}}) {
    SCOPED_TRACE(name);
    TinyDxf d(0);
    const double k = 1 / unit;  // drawing units per metre
    d.polyline("Walls", {{0, 0}, {8.4 * k, 0}, {8.4 * k, 3.4 * k}, {0, 3.4 * k}}, true);
    d.polyline("Walls", {{0.2 * k, 0.2 * k}, {4.1 * k, 0.2 * k}, {4.1 * k, 3.2 * k}, {0.2 * k, 3.2 * k}}, true);
    d.polyline("Walls", {{4.3 * k, 0.2 * k}, {8.2 * k, 0.2 * k}, {8.2 * k, 3.2 * k}, {4.3 * k, 3.2 * k}}, true);
    d.arc("Doors", {4.3 * k, 1.0 * k}, 0.9 * k, 0, 90);
    const DxfPlan r = read_dxf_plan(d.write(std::string("no-units-") + name + ".dxf"));
    EXPECT_NEAR(hi_x(r.plan), 8.4, 0.01);
    bool said = false;
    for (const std::string& w : r.plan.warnings) said |= w.find(std::string("taken as ") + name + ", guessed from its door swings") != std::string::npos;
    EXPECT_TRUE(said);
  }
  TinyDxf d(0);
  d.polyline("Walls", {{0, 0}, {8400, 0}, {8400, 3400}, {0, 3400}}, true);
  d.polyline("Walls", {{200, 200}, {8200, 200}, {8200, 3200}, {200, 3200}}, true);
  EXPECT_NEAR(hi_x(read_dxf_plan(d.write("no-units-no-doors.dxf")).plan), 8.4, 0.01);  // mm by its extent
}

TEST(DxfPlan, ACurvedWallIsCutAsFinelyAsAPlansArcs) {
  // A round room 10 m across in a ring wall 0.2 m thick, each circle drawn as two arcs.
  TinyDxf d;  // metres
  for (double r : {5.0, 5.2}) {
    d.arc("Walls", {0, 0}, r, 0, 180);
    d.arc("Walls", {0, 0}, r, 180, 360);
  }
  const DxfPlan p = read_dxf_plan(d.write("round.dxf"));
  ASSERT_EQ(p.plan.rooms.size(), 1u);
  // Every piece of the inner face strays no further from its circle than a plan's arcs
  // do (Plan::arc_tolerance, 1 cm); 16 pieces per half turn would stray 2.4 cm.
  int inner = 0;
  for (const Wall& w : p.plan.walls) {
    const Vec2 a = w.centre.front(), b = w.centre.back();
    // (the drawing is snapped to 0.1 mm)
    if (std::fabs(length(a) - 5) > 1e-4 || std::fabs(length(b) - 5) > 1e-4) continue;
    ++inner;
    EXPECT_GE(length(0.5 * (a + b)), 5 - p.plan.arc_tolerance - 1e-4);
  }
  EXPECT_GE(inner, 50);
  EXPECT_EQ(cells_are_valid(build_cells(p.plan)), "");
}

TEST(DxfPlan, A3dModelIsToldFromAFloorPlanAndReadAsAMesh) {
  // A box 2 x 1 x 0.5 m drawn in millimetres as six 3DFACEs, z up (AutoCAD's axes).
  TinyDxf d(4);
  const double X = 2000, Y = 1000, Z = 500;
  d.face3d("Model", {0, 0, 0}, {0, Y, 0}, {X, Y, 0}, {X, 0, 0});
  d.face3d("Model", {0, 0, Z}, {X, 0, Z}, {X, Y, Z}, {0, Y, Z});
  d.face3d("Model", {0, 0, 0}, {X, 0, 0}, {X, 0, Z}, {0, 0, Z});
  d.face3d("Model", {0, Y, 0}, {0, Y, Z}, {X, Y, Z}, {X, Y, 0});
  d.face3d("Model", {0, 0, 0}, {0, 0, Z}, {0, Y, Z}, {0, Y, 0});
  d.face3d("Model", {X, 0, 0}, {X, Y, 0}, {X, Y, Z}, {X, 0, Z});
  const std::string path = d.write("box-3d.dxf");
  const DxfPlan r = read_dxf_plan(path);
  EXPECT_EQ(r.model_faces, 6);
  EXPECT_DOUBLE_EQ(r.metres_per_unit, 0.001);
  EXPECT_TRUE(r.plan.rooms.empty());
  // Assimp reads its faces; AutoCAD's z stays up, in the unit $INSUNITS said.
  const Mesh m = load_mesh(path, MeshAxes{std::nullopt, r.metres_per_unit});
  ASSERT_EQ(m.triangles.size(), 12u);
  Vec3 lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (Vec3 v : m.vertices) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  EXPECT_NEAR(hi.x - lo.x, 2, 1e-6);
  EXPECT_NEAR(hi.y - lo.y, 1, 1e-6);
  EXPECT_NEAR(hi.z - lo.z, 0.5, 1e-6);
  // Drawn Y-up (LightWave's DXF), --up y stands it on its y.
  const Mesh ym = load_mesh(path, MeshAxes{'y', r.metres_per_unit});
  lo = {1e9, 1e9, 1e9}, hi = {-1e9, -1e9, -1e9};
  for (Vec3 v : ym.vertices) lo.z = std::min(lo.z, v.z), hi.z = std::max(hi.z, v.z);
  EXPECT_NEAR(hi.z - lo.z, 1, 1e-6);
  // Naming its layer as walls asks for a floor plan: there is none.
  DxfPlanOptions o;
  o.layers = "walls=Model";
  EXPECT_THROW(read_dxf_plan(path, o), PlanError);
}

TEST(DxfPlan, LinesOnALayerNamedForNothingAreWallsAndLayersOverride) {
  // A layer whose name says nothing: its lines are taken as walls, as a CAD viewer would
  // show them, with a warning naming the layer and --layers.
  TinyDxf d;
  d.polyline("Lines", {{0, 0}, {4, 0}, {4, 3}, {0, 3}}, true);
  d.polyline("Lines", {{0.2, 0.2}, {3.8, 0.2}, {3.8, 2.8}, {0.2, 2.8}}, true);
  d.line("Dimensions", {0, -0.5}, {4, -0.5});
  d.line("A-FURN", {1, 1}, {2, 1});
  const std::string path = d.write("lines.dxf");
  const DxfPlan guessed = read_dxf_plan(path);
  EXPECT_EQ(guessed.plan.rooms.size(), 1u);
  bool warned = false;
  for (const std::string& w : guessed.plan.warnings)
    warned |= w.find("the lines of layer(s) 'Lines' are taken as walls") != std::string::npos &&
              w.find("--layers") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_EQ(guessed.summary[0], "walls from layers 'Lines'");
  DxfPlanOptions o;
  o.layers = "walls=lines";
  EXPECT_EQ(read_dxf_plan(path, o).plan.rooms.size(), 1u);
  o.layers = "walls=nosuch";
  EXPECT_THROW(read_dxf_plan(path, o), PlanError);
  o.layers = "floors=Lines";
  EXPECT_THROW(read_dxf_plan(path, o), PlanError);

  // Only dimensions, text and furniture: nothing to take as walls, an error listing the
  // layers and --layers.
  TinyDxf notes;
  notes.line("Dimensions", {0, -0.5}, {4, -0.5});
  notes.polyline("A-FURN", {{1, 1}, {2, 1}, {2, 2}}, true);
  const std::string what = refusal(notes.write("notes.dxf"));
  EXPECT_NE(what.find("'A-FURN'"), std::string::npos) << what;
  EXPECT_NE(what.find("--layers"), std::string::npos) << what;
}

TEST(DxfPlan, AutoCadArchitectureObjectsAreNamedWithTheWayToExportThem) {
  // Walls and doors as AutoCAD Architecture's objects, which no reader but AutoCAD's own
  // draws: not "no layer holds walls" (A-WALL does), but what they are and what to do.
  TinyDxf aec;
  for (int i = 0; i < 4; ++i) aec.foreign("AEC_WALL", "A-WALL");
  aec.foreign("AEC_DOOR", "A-DOOR");
  const std::string what = refusal(aec.write("aec.dxf"));
  EXPECT_NE(what.find("4 AEC_WALL"), std::string::npos) << what;
  EXPECT_NE(what.find("1 AEC_DOOR"), std::string::npos) << what;
  EXPECT_NE(what.find("-AECEXPORTTOAUTOCAD"), std::string::npos) << what;
  // Beside walls drawn as lines, they are skipped with a warning naming them.
  TinyDxf mixed;
  two_rooms_in_double_lines(mixed, "A-WALL");
  mixed.arc("A-DOOR", {4.1, 1.0}, 0.9, 90, 180);
  mixed.foreign("ACAD_PROXY_ENTITY", "A-FURN");
  const DxfPlan r = read_dxf_plan(mixed.write("proxy.dxf"));
  expect_walkable(r.plan, 2, 1);
  bool warned = false;
  for (const std::string& w : r.plan.warnings) warned |= w.find("1 ACAD_PROXY_ENTITY") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(DxfLayerNames, TheNamesDrawingsUseInManyLanguages) {
  const std::vector<std::pair<std::string, LayerRole>> names = {
      // AIA and its modifiers: tags, demolition, what is above, elevations are no walls.
      {"A-WALL", LayerRole::Walls}, {"A-WALL-EXTR", LayerRole::Walls}, {"A-WALL-PATT", LayerRole::Walls},
      {"A-DOOR", LayerRole::Doors}, {"A-GLAZ", LayerRole::Windows}, {"A-DOOR-GLAZ", LayerRole::Doors},
      {"A-DOOR-IDEN", LayerRole::None}, {"A-WALL-DEMO", LayerRole::None}, {"A-WALL-ABOV", LayerRole::None},
      {"A-GLAZ-ELEV", LayerRole::None}, {"A-WALL-NPLT", LayerRole::None}, {"A-ANNO-TEXT", LayerRole::None},
      // English and German, joined words included.
      {"Walls", LayerRole::Walls}, {"Interior Partitions", LayerRole::Walls}, {"Ext Windows", LayerRole::Windows},
      {"Aussenwand", LayerRole::Walls}, {"Innenwände", LayerRole::Walls}, {"INNENWÄNDE", LayerRole::Walls},
      {"Haustür", LayerRole::Doors}, {"TÜREN", LayerRole::Doors}, {"Dachfenster", LayerRole::Windows},
      {"Fenster und Türen", LayerRole::Doors}, {"Möbel", LayerRole::None}, {"Wand-Bemaßung", LayerRole::None},
      // DXF's \U+ escape of R2000 and older: INNENW\U+00C4NDE.
      {"INNENW\\U+00C4NDE", LayerRole::Walls},
      // French, Spanish, Italian, Portuguese, Dutch.
      {"MURS", LayerRole::Walls}, {"Murs porteurs", LayerRole::Walls}, {"Cloisons", LayerRole::Walls},
      {"PORTES", LayerRole::Doors}, {"FENÊTRES", LayerRole::Windows}, {"Porte-fenêtre", LayerRole::Doors},
      {"Menuiseries", LayerRole::Doors}, {"Cotation", LayerRole::None}, {"Supporte", LayerRole::None},
      {"MUROS", LayerRole::Walls}, {"Tabiques", LayerRole::Walls}, {"PUERTAS", LayerRole::Doors},
      {"VENTANAS", LayerRole::Windows}, {"Carpintería", LayerRole::Doors},
      {"Muri", LayerRole::Walls}, {"Tramezzi", LayerRole::Walls}, {"Porte", LayerRole::Doors}, {"Finestre", LayerRole::Windows},
      {"Infissi", LayerRole::Doors}, {"Arredo", LayerRole::None},
      {"Paredes", LayerRole::Walls}, {"Portas", LayerRole::Doors}, {"Janelas", LayerRole::Windows},
      {"Muren", LayerRole::Walls}, {"binnenwanden", LayerRole::Walls}, {"Deuren", LayerRole::Doors},
      {"Ramen", LayerRole::Windows}, {"Kozijnen", LayerRole::Doors}, {"Profondeur", LayerRole::None},
      // Nordic, Slavic, Turkish; Chinese and Japanese.
      {"Vägg", LayerRole::Walls}, {"Dörrar", LayerRole::Doors}, {"Fönster", LayerRole::Windows},
      {"Vinduer", LayerRole::Windows}, {"Ściany", LayerRole::Walls}, {"Drzwi", LayerRole::Doors}, {"Okna", LayerRole::Windows},
      {"СТЕНЫ", LayerRole::Walls}, {"Перегородки", LayerRole::Walls}, {"Двери", LayerRole::Doors}, {"Окна", LayerRole::Windows},
      {"Duvar", LayerRole::Walls}, {"Kapı", LayerRole::Doors}, {"Pencere", LayerRole::Windows},
      {"墙体", LayerRole::Walls}, {"门", LayerRole::Doors}, {"窗", LayerRole::Windows}, {"门窗", LayerRole::Doors},
      {"壁", LayerRole::Walls}, {"ドア", LayerRole::Doors}, {"窓", LayerRole::Windows}, {"家具", LayerRole::None},
      // A German office's layers (ROHBAU: the shell, AUSBAU: the fit-out); what walls are made of.
      {"ROHBAU - Darstellungen - Waende", LayerRole::Walls}, {"AUSBAU - Darstellungen - Trennwaende", LayerRole::Walls},
      {"AUSBAU - Darstellungen - Trockenbau", LayerRole::Walls}, {"AUSBAU - Darstellungen - Fassade", LayerRole::Walls},
      {"AUSBAU - Objekte - Tueren", LayerRole::Doors}, {"ROHBAU - Darstellungen - Decken", LayerRole::None},
      {"AUSBAU - Darstellungen - Fassade-Bemaßung", LayerRole::None}, {"A-Drywall", LayerRole::Walls},
      {"Masonry", LayerRole::Walls}, {"Maçonnerie", LayerRole::Walls}, {"Façade", LayerRole::Walls},
      // Columns are walls; their grid is not.
      {"S-COLS", LayerRole::Walls}, {"A-COLS", LayerRole::Walls}, {"Columns", LayerRole::Walls}, {"Stützen", LayerRole::Walls},
      {"Poteaux", LayerRole::Walls}, {"Pilares", LayerRole::Walls}, {"Colonne", LayerRole::Walls}, {"Колонны", LayerRole::Walls},
      {"柱", LayerRole::Walls}, {"S-GRID", LayerRole::None}, {"A-COLS-IDEN", LayerRole::None}, {"Colour", LayerRole::None},
      // Nothing said.
      {"0", LayerRole::None}, {"Defpoints", LayerRole::None}, {"A786g - Works of Art - sculpture-murals", LayerRole::None}, {"Furniture", LayerRole::None}};
  for (const auto& [name, role] : names) EXPECT_EQ(layer_role_by_name(name), role) << name;
  EXPECT_TRUE(names_a_door("PORTE_90"));
  EXPECT_TRUE(names_a_door("Tür 88.5"));
  EXPECT_TRUE(names_a_door("SLIDING-2P"));
  EXPECT_FALSE(names_a_door("SUPPORT"));
  EXPECT_FALSE(names_a_door("WINDOW-1200"));
  EXPECT_TRUE(names_a_window("WINDOW-1200"));
  EXPECT_TRUE(names_a_window("Fenster_2-flg"));
  EXPECT_FALSE(names_a_window("Porte-fenêtre"));  // a glazed door is a door
  for (const char* title : {"GROUND FLOOR PLAN", "First Floor", "1. Obergeschoss", "Grundriss EG", "Rez-de-chaussée",
                            "1er étage", "Planta baja", "Piano terra", "Begane grond", "Level 2", "Basement"})
    EXPECT_TRUE(names_a_storey(title)) << title;
  for (const char* title : {"FLOOR PLAN", "Kitchen", "Scale 1:100", "Floor finish: oak", "Legend"})
    EXPECT_FALSE(names_a_storey(title)) << title;
}

TEST(DxfPlan, AFrenchDrawingOpensByItsLayerNames) {
  // MURS, PORTES, FENETRES: the rooms, the door from its swing and the window.
  TinyDxf d;
  two_rooms_in_double_lines(d, "MURS");
  d.arc("PORTES", {4.3, 1.0}, 0.9, 0, 90);
  d.line("PORTES", {4.3, 1.0}, {5.2, 1.0});
  // A window in the outer wall of the first room: a 1.2 m gap, its glass across it.
  d.line("FENETRES", {1.4, 3.3}, {2.6, 3.3});
  const DxfPlan r = read_dxf_plan(d.write("francais.dxf"));
  EXPECT_EQ(r.plan.rooms.size(), 2u);
  EXPECT_EQ(doors_in(r.plan), 1);
  bool said = false;
  for (const std::string& s : r.summary) said |= s.find("walls from layers 'MURS'") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(DxfPlan, DoorTagsOnAnIdenLayerAreNoWalls) {
  // AIA's A-DOOR-IDEN holds door numbers in hexagons: drawn in the middle of a room they
  // would be a column there if the layer counted as a door layer (whose straight lines close
  // the walls), and its numbers are no room names.
  TinyDxf d;
  two_rooms_in_double_lines(d, "A-WALL");
  d.arc("A-DOOR", {4.3, 1.0}, 0.9, 0, 90);
  std::vector<Vec2> hex;
  for (int k = 0; k < 6; ++k) hex.push_back(Vec2{2, 2.4} + 0.25 * Vec2{std::cos(k * M_PI / 3), std::sin(k * M_PI / 3)});
  d.polyline("A-DOOR-IDEN", hex, true);
  d.text("A-DOOR-IDEN", {1.9, 2.35}, "101");
  const DxfPlan r = read_dxf_plan(d.write("tags.dxf"));
  ASSERT_EQ(r.plan.rooms.size(), 2u);
  const CellComplex c = build_cells(r.plan);
  EXPECT_EQ(cells_are_valid(c), "");
  double named_area = 0;
  for (const RoomInfo& room : c.rooms) {
    if (room.named) named_area += room.area;
    EXPECT_EQ(room.name.find("101"), std::string::npos) << "a door's number named a room: " << room.name;
  }
  EXPECT_NEAR(named_area, 2 * 3.9 * 3.0 + 0.2 * 0.9, 0.05);  // the two rooms and the door's gap
}

TEST(DxfPlan, NotADxfFile) {
  const fs::path p = fs::temp_directory_path() / ("avenues-not-" + std::to_string(::getpid()) + ".dxf");
  { std::ofstream(p) << "name = \"house\"\n"; }
  EXPECT_THROW(read_dxf_plan(p.string()), PlanError);
  fs::remove(p);
}

// ---------------------------------------------------------------------------------
// The drawings from outside.

TEST(DxfPlan, SimpleAndTwoRoomsOpenWithTheirDoor) {
  // Cut from ground-floor-lhs.dxf: columns and a wall on the structure layer, the
  // partitions on the door layer, one door block (swing drawn as splines, wall-end caps,
  // frames and the open leaf) in the first room's partition, leading out of the cut.
  for (auto [file, rooms] : {std::pair{"simple.dxf", 1}, std::pair{"two-rooms.dxf", 2}}) {
    SCOPED_TRACE(file);
    const DxfPlan r = read_dxf_plan((kSamples / file).string());
    ASSERT_EQ(int(r.plan.rooms.size()), rooms);
    EXPECT_EQ(doors_in(r.plan), 1);
    const CellComplex c = build_cells(r.plan);
    EXPECT_EQ(cells_are_valid(c), "");
    EXPECT_GE(avenues::testing::check_views_from_rooms(r.plan, c), 4 * rooms);
  }
}

// The default view of a drawing whose first room's largest cell has no door of its own
// (two-rooms.dxf: the room is parted into cells, its opening in another) looks along the
// room and out of it, not at the nearest wall: the old rule, the portal listed first, saw
// 3 cells and a wall; the heading that sees the most cells sees 13.
TEST(DxfPlan, TheDefaultViewOfARoomWithoutADoorInItsCellLooksAlongTheRoom) {
  const DxfPlan r = read_dxf_plan((kSamples / "two-rooms.dxf").string());
  const CellComplex c = build_cells(r.plan);
  const Viewpoint v = default_viewpoint(c);
  const Location at = c.locate(v.eye);
  ASSERT_EQ(at.what, Location::What::Cell);
  const Camera cam = Camera::look_at(v.eye, v.look, v.fov_deg, 64, 36);
  const size_t seen = find_visible(c, cam, at.cell, Kernel::Double).cells.size();
  EXPECT_GE(seen, 10u);
  for (int k = 0; k < 16; ++k)  // none of the sixteen headings sees more
    EXPECT_LE(find_visible(c, Camera::yaw_pitch(v.eye, k * 22.5, 0, v.fov_deg, 64, 36), at.cell, Kernel::Double).cells.size(),
              seen);
}

TEST(DxfPlan, FuzzFindingsAreReadOrRefusedNamingTheFile) {
  // tests/fuzz/regressions/dxf: inputs the DXF fuzz target once broke the reader with
  // (coordinates near 1e50 overflowed the wall-line-end grid's cell count).
  const fs::path dir = fs::path(AVENUES_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / "dxf";
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    SCOPED_TRACE(e.path().string());
    ++n;
    try {
      read_dxf_plan(e.path().string());
    } catch (const PlanError& err) {
      EXPECT_NE(std::string(err.what()).find(e.path().string()), std::string::npos) << err.what();
    }
  }
  EXPECT_GE(n, 1);
}

TEST(DxfPlan, OldStylePolylinesOnALayerNamedForNothingAreItsWalls) {
  // evil-spirit-house.dxf: 8 POLYLINE/VERTEX/SEQEND outlines on a layer named for nothing,
  // beside layers of dimensions and text. Its lines are taken as the walls, with a warning
  // naming the layer; named with --layers, the plan is the same (the vertices are entities
  // of their own, which dxflib ends with a section end each).
  const std::string file = (kSamples / "evil-spirit-house.dxf").string();
  const DxfPlan guessed = read_dxf_plan(file);
  bool warned = false;
  for (const std::string& w : guessed.plan.warnings) warned |= w.find("'s001-#def-active-grp' are taken as walls") != std::string::npos;
  EXPECT_TRUE(warned);
  DxfPlanOptions o;
  o.layers = "walls=s001-#def-active-grp";
  const DxfPlan r = read_dxf_plan(file, o);
  EXPECT_GE(r.plan.rooms.size(), 2u);
  EXPECT_EQ(guessed.plan.walls.size(), r.plan.walls.size());
  EXPECT_EQ(guessed.plan.rooms.size(), r.plan.rooms.size());
  const CellComplex c = build_cells(guessed.plan);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_GT(avenues::testing::check_views_from_rooms(guessed.plan, c), 0);
}

TEST(DxfPlan, EachOutsideDrawingOpensOrIsRefusedClearly) {
  int opened = 0, refused = 0;
  for (const auto& e : fs::directory_iterator(kSamples)) {
    if (e.path().extension() != ".dxf") continue;
    SCOPED_TRACE(e.path().filename().string());
    try {
      const DxfPlan r = read_dxf_plan(e.path().string());
      const CellComplex c = build_cells(r.plan);
      EXPECT_EQ(cells_are_valid(c), "");
      EXPECT_GE(r.plan.rooms.size(), 1u);
      // The house plan's swings and windows sit in its wall gaps; the office floor's door
      // blocks stand in partitions drawn on the door layer.
      const std::string name = e.path().filename().string();
      if (name == "anandkothartrdl-plan.dxf") {
        EXPECT_GE(avenues::testing::door_portals(c), 2);
        EXPECT_GE(doors_in(r.plan, OpeningKind::Window), 1);
        // The gym's pocket doors to the study, drawn without a swing.
        EXPECT_NE(r.summary[1].find("1 doors without a swing"), std::string::npos) << r.summary[1];
      }
      if (name == "ground-floor-lhs.dxf") {
        EXPECT_GE(doors_in(r.plan), 4);
      }
      EXPECT_GT(avenues::testing::check_views_from_rooms(r.plan, c), 0);
      std::printf("[ dxf      ] %s: %s\n", e.path().filename().c_str(), r.summary.back().c_str());
      ++opened;
    } catch (const PlanError& err) {
      EXPECT_NE(std::string(err.what()).find("--layers"), std::string::npos) << err.what();
      std::printf("[ dxf      ] %s: refused: %.120s\n", e.path().filename().c_str(), err.what());
      ++refused;
    }
  }
  EXPECT_EQ(opened + refused, 5);
  EXPECT_EQ(opened, 5);
}

}  // namespace
}  // namespace avenues
