// Avenues — DXF floor plans (see dxf_plan.h).
#include "plans/formats/dxf_plan.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include "core/angles.h"
#include "core/number_format.h"
#include "plans/formats/arcs_in_lines.h"
#include "plans/formats/dxf_layer_names.h"
#include "plans/formats/segment_grid.h"
#include "plans/formats/swingless_doors.h"
#include "plans/formats/uncut_walls.h"
#include "plans/formats/wall_swings.h"
#include "plans/formats/wall_arrangement.h"
#include "plans/formats/wall_line_ends.h"

namespace avenues {
namespace {

constexpr double kPi = std::numbers::pi;

/// A door's swing, drawn as an arc: a leaf 0.4 to 1.6 m wide, opening 60 to 120 degrees
/// (a quarter turn, drawn loosely; not a bi-fold's small arcs, not a revolving door).
bool door_swing_radius(double r_m) { return r_m >= 0.4 && r_m <= 1.6; }
bool door_swing_sweep(double deg) { return deg >= 60 && deg <= 120; }

/// A circular arc: centre, its two ends (counter-clockwise from p0 to p1), its sweep.
struct ArcPiece {
  Vec2 c, p0, p1;
  double r = 0, sweep_deg = 0;
  std::string layer;
};
struct SegPiece {
  Vec2 a, b;
  std::string layer;
  bool curved = false;  ///< a piece of an arc, circle, ellipse or spline (a swing, never a door frame)
  bool door_block = false;  ///< inside a block whose name says door (its panels, whatever their layer)
  std::string window_block;  ///< the name of the block whose name says window that it is in, if any
};
struct TextPiece {
  Vec2 p;
  std::string text, layer;
};
struct HatchPiece {
  std::vector<std::vector<Vec2>> rings;
  std::string layer;
};
struct InsertPiece {
  std::string block, layer;
  Vec2 at, scale{1, 1};
  double angle_deg = 0;
  int cols = 1, rows = 1;
  double col_sp = 0, row_sp = 0;
};
/// A polyline drawn with a constant width (LWPOLYLINE's 43, POLYLINE's 40 = 41): a wall
/// drawn as a wide line, on a wall layer, is the band it covers.
struct Band {
  std::vector<Vec2> pts;  ///< along its middle, arcs cut into pieces
  bool closed = false;
  double width = 0;
  std::string layer;
};
/// Entities of model space or of one block, in drawing units.
struct Group {
  Vec2 base;
  std::vector<SegPiece> segs;
  std::vector<ArcPiece> arcs;
  std::vector<TextPiece> texts;
  std::vector<HatchPiece> hatches;
  std::vector<InsertPiece> inserts;
  std::vector<std::pair<std::vector<Vec2>, std::string>> closed;  ///< closed polylines (room outlines)
  std::vector<std::pair<std::vector<Vec2>, std::string>> curves;  ///< splines as points (swings drawn as splines)
  std::vector<Band> bands;
};

/// Metres per drawing unit from $INSUNITS (0 when unitless or unknown).
double metres_of_insunits(int u) {
  switch (u) {
    case 1: return 0.0254;
    case 2: return 0.3048;
    case 4: return 0.001;
    case 5: return 0.01;
    case 6: return 1;
    case 14: return 0.1;
    default: return 0;
  }
}

/// The lengths a drawing may be in, by their --unit names.
struct LengthUnit {
  const char* name;
  double metres;
};
constexpr LengthUnit kLengthUnits[] = {{"mm", 0.001}, {"cm", 0.01}, {"m", 1}, {"in", 0.0254}, {"ft", 0.3048}};

/// Metres per unit of --unit's name ("m", "cm", "mm", "in", "ft", any case); 0 when unknown.
double metres_of_unit_name(const std::string& name) {
  std::string u = name;
  for (char& ch : u) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  for (const LengthUnit& l : kLengthUnits)
    if (u == l.name) return l.metres;
  return 0;
}

/// Points along an arc from angle a0 to a1 (radians, counter-clockwise), ends exact: 16
/// pieces per half turn at least, more where a piece would stray further than `sagitta`
/// (drawing units; 0: no bound) from the arc, as Plan::arc_tolerance asks of a plan's.
std::vector<Vec2> arc_points(Vec2 c, double r, double a0, double a1, double sagitta = 0) {
  while (a1 <= a0) a1 += 2 * kPi;
  double step = kPi / 16;
  if (sagitta > 0 && r > sagitta) step = std::min(step, 2 * std::acos(1 - sagitta / r));
  const int n = std::clamp(int(std::ceil((a1 - a0) / step)), 2, 1024);
  std::vector<Vec2> out;
  for (int i = 0; i <= n; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    out.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return out;
}

/// The arc of a polyline's bulged piece from a to b (a bulge is tan(θ/4) of the arc's angle
/// θ, positive counter-clockwise): its centre, radius and angles, counter-clockwise from a0
/// to a1 (from b to a when the bulge is negative). a != b, bulge != 0.
struct BulgeArc {
  Vec2 c;
  double r, a0, a1;
};
BulgeArc bulge_arc(Vec2 a, Vec2 b, double bulge) {
  const double theta = 4 * std::atan(bulge), chord = length(b - a);
  const double r = chord / (2 * std::sin(std::fabs(theta) / 2));
  const Vec2 m = 0.5 * (a + b), u = (1 / chord) * (b - a), left{-u.y, u.x};
  const double h = r * std::cos(theta / 2);  // centre to chord, signed with the bulge
  const Vec2 c = m + (bulge > 0 ? h : -h) * left;
  const double aa = std::atan2(a.y - c.y, a.x - c.x), ab = std::atan2(b.y - c.y, b.x - c.x);
  return bulge > 0 ? BulgeArc{c, r, aa, ab} : BulgeArc{c, r, ab, aa};
}

/// The points of a polyline's bulged piece from a to b, a and b included; the chord when it
/// has no bulge.
std::vector<Vec2> bulge_points(Vec2 a, Vec2 b, double bulge, double sagitta = 0) {
  if (std::fabs(bulge) < 1e-9 || !(length(b - a) > 0) || !std::isfinite(bulge)) return {a, b};
  const BulgeArc k = bulge_arc(a, b, bulge);
  std::vector<Vec2> pts = arc_points(k.c, k.r, k.a0, k.a1, sagitta);
  if (bulge < 0) std::reverse(pts.begin(), pts.end());
  pts.front() = a, pts.back() = b;
  return pts;
}

std::string lower(std::string s) {
  for (char& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

/// MTEXT's formatting codes out: \P paragraph, {\fArial;...}, \A1; etc.
std::string plain_text(const std::string& t) {
  std::string out;
  for (size_t i = 0; i < t.size(); ++i) {
    const char ch = t[i];
    if (ch == '{' || ch == '}') continue;
    if (ch == '\\' && i + 1 < t.size()) {
      const char code = t[i + 1];
      if (code == 'P' || code == 'X' || code == '~') { out += ' '; ++i; continue; }
      if (code == '\\' || code == '{' || code == '}') { out += code; ++i; continue; }
      if (std::strchr("fFHhWwQqTtAaCcpS", code)) {  // codes with an argument up to ';'
        const size_t semi = t.find(';', i);
        if (semi == std::string::npos) break;
        i = semi;
        continue;
      }
      ++i;  // \L \l \O \o \K \k: underline etc.
      continue;
    }
    out += ch;
  }
  // %%c %%d %%p: diameter, degree, plus-minus; drop them.
  for (size_t k; (k = out.find("%%")) != std::string::npos;) out.erase(k, 3);
  const size_t b = out.find_first_not_of(" \t"), e = out.find_last_not_of(" \t");
  return b == std::string::npos ? "" : out.substr(b, e - b + 1);
}

/// Whether a line of text is a measurement, not a name: an area or size written under a
/// room's name ("25.3 m²", "12'-0\" x 14'-6\"", "3,20 x 4,10 m", "150 sq ft"). Its
/// words are all numbers, units and "x"; a bare number ("101", a room's number) is none.
bool is_measurement(const std::string& line) {
  std::string t;
  for (char c : line) t += (c == '\'' || c == '"' || c == '(' || c == ')' || c == '=' || c == ':') ? ' ' : c;
  std::istringstream words(t);
  bool digits = false, unit_or_mark = line.find_first_of("'\"") != std::string::npos;
  int n = 0;
  for (std::string w; words >> w; ++n) {
    std::string f;
    for (char c : w) f += char(std::tolower(static_cast<unsigned char>(c)));
    if (f == "x" || f == "\xc3\x97") { unit_or_mark = true; continue; }  // x, ×
    for (const char* u : {"m\xc2\xb2", "m2", "m^2", "sq.ft.", "sqft", "sq", "ft", "ft2", "sf", "mq", "qm", "m", "cm", "mm", "in"})
      if (f == u) { unit_or_mark = true, f.clear(); break; }
    if (f.empty()) continue;
    // A number, perhaps with its unit joined on ("25.3m²", "4,10m", "-6").
    size_t k = 0;
    while (k < f.size() && (std::isdigit(static_cast<unsigned char>(f[k])) || f[k] == '.' || f[k] == ',' || f[k] == '-' || f[k] == '/' || f[k] == '+'))
      digits |= std::isdigit(static_cast<unsigned char>(f[k])) != 0, ++k;
    if (k == 0) return false;
    const std::string rest = f.substr(k);
    if (rest.empty()) {
      if (f.find_first_of(".,") != std::string::npos) unit_or_mark = true;
      continue;
    }
    bool unit = false;
    for (const char* u : {"m\xc2\xb2", "m2", "m", "cm", "mm", "ft", "sf", "sqft", "mq", "qm", "in"}) unit |= rest == u;
    if (!unit) return false;
    unit_or_mark = true;
  }
  return n > 0 && digits && unit_or_mark;
}

/// A text's words as a room's name: MTEXT's paragraphs that are not measurements.
std::string label_text(const std::string& raw) {
  std::string out;
  size_t from = 0;
  while (from <= raw.size()) {
    size_t to = raw.find("\\P", from);
    if (to == std::string::npos) to = raw.size();
    const std::string line = plain_text(raw.substr(from, to - from));
    if (!line.empty() && !is_measurement(line)) out += (out.empty() ? "" : " ") + line;
    from = to + 2;
  }
  return out;
}

/// De Boor evaluation of a non-rational B-spline at `samples` points.
std::vector<Vec2> spline_points(int degree, const std::vector<double>& knots, const std::vector<Vec2>& ctrl) {
  const int n = int(ctrl.size());
  if (degree < 1 || n <= degree || int(knots.size()) != n + degree + 1) return ctrl;
  const double t0 = knots[size_t(degree)], t1 = knots[size_t(n)];
  if (!(t1 > t0)) return ctrl;
  const int samples = std::clamp(n * 8, 8, 400);
  std::vector<Vec2> out;
  for (int s = 0; s <= samples; ++s) {
    const double t = s == samples ? t1 : t0 + (t1 - t0) * s / samples;
    int k = degree;
    while (k < n - 1 && knots[size_t(k + 1)] <= t) ++k;
    std::vector<Vec2> d(ctrl.begin() + (k - degree), ctrl.begin() + k + 1);
    for (int r = 1; r <= degree; ++r)
      for (int j = degree; j >= r; --j) {
        const int i = k - degree + j;
        const double den = knots[size_t(i + degree - r + 1)] - knots[size_t(i)];
        const double a = den > 0 ? (t - knots[size_t(i)]) / den : 0;
        d[size_t(j)] = (1 - a) * d[size_t(j - 1)] + a * d[size_t(j)];
      }
    out.push_back(d[size_t(degree)]);
  }
  return out;
}

/// An entity's object coordinate system, as a map of its 2D points (and elevation) into
/// the plan: AutoCAD's arbitrary axis algorithm for its extrusion direction. Identity for
/// +Z; a mirror in x for -Z (what mirroring an arc, circle, polyline, text, hatch or block
/// in some programs writes); a projection onto the plan for any other direction.
struct Ocs {
  Vec3 ax{1, 0, 0}, ay{0, 1, 0}, n{0, 0, 1};
  bool flat = true;  ///< normal ±Z: a similarity of the plan (mirrored for -Z)
  bool mirrored = false;
  Vec2 operator()(Vec2 p, double z = 0) const {
    const Vec3 w = p.x * ax + p.y * ay + z * n;
    return {w.x, w.y};
  }
  static Ocs of(const double* d) {
    Ocs o;
    Vec3 n{d[0], d[1], d[2]};
    const double len = length(n);
    if (!(len > 0) || !std::isfinite(len)) return o;
    n = (1 / len) * n;
    if (std::fabs(n.x) < 1e-9 && std::fabs(n.y) < 1e-9) {
      if (n.z < 0) o.ax = {-1, 0, 0}, o.n = {0, 0, -1}, o.mirrored = true;
      return o;
    }
    const Vec3 ax = std::fabs(n.x) < 1.0 / 64 && std::fabs(n.y) < 1.0 / 64 ? cross(Vec3{0, 1, 0}, n) : cross(Vec3{0, 0, 1}, n);
    o.ax = (1 / length(ax)) * ax;
    o.ay = cross(n, o.ax);
    o.n = n;
    o.flat = false;
    return o;
  }
};

/// An MLINE (AutoCAD's multiline, how walls were drawn with MLINE): its vertices, and per
/// vertex and element the line's parameters (code 41: the offset along the miter, then
/// where the element starts and stops along the segment; cuts for openings).
struct MLine {
  std::string layer;
  bool closed = false;
  bool paper = false;  ///< in paper space (group 67)
  struct Vertex { Vec2 p, dir, miter; std::vector<std::vector<double>> params; };
  std::vector<Vertex> vertices;
  int next_coord = 0;  ///< the 2x code expected next (21, 22, 23), or 0
};

/// dxflib's callbacks, collecting model space and blocks into Groups.
class Collector : public DL_CreationAdapter {
 public:
  Group model;
  Group paper;  ///< paper space's entities (a layout's title block, notes): read and left out
  std::map<std::string, Group> blocks;
  int insunits = 0;
  double sagitta = 0;  ///< [drawing units] an arc's pieces' furthest from it; 0 while no unit is known
  int faces_3d = 0;  ///< 3DFACEs and polygon or polyface mesh POLYLINEs: a 3D model's
  std::map<std::string, int> layer_entities;
  std::vector<std::string> skipped;
  std::map<std::string, int> foreign_objects;  ///< AEC_WALL, ACAD_PROXY_ENTITY ...: by type, how many

  /// What foreign_objects means for the plan, or "" when there are none.
  std::string foreign_note() const {
    if (foreign_objects.empty()) return {};
    std::string list;
    for (const auto& [type, n] : foreign_objects) list += (list.empty() ? "" : ", ") + std::to_string(n) + " " + type;
    return "the drawing holds objects that only AutoCAD Architecture (or another of AutoCAD's verticals) can draw (" +
           list + "); save it with its Export to AutoCAD (-AECEXPORTTOAUTOCAD), which turns them into lines, and open that";
  }

  void setVariableInt(const std::string& key, int value, int) override {
    if (key != "$INSUNITS") return;
    insunits = value;
    // The header comes before the entities: arcs are cut as finely as a plan's would be.
    if (const double m = metres_of_insunits(value); m > 0 && sagitta == 0) sagitta = Plan{}.arc_tolerance / m;
  }
  void addLayer(const DL_LayerData& d) override { layer_entities.emplace(d.name, 0); }
  void addBlock(const DL_BlockData& d) override {
    flush();
    cur_ = &blocks[d.name];
    cur_->base = {d.bpx, d.bpy};
    in_block_ = true;
  }
  void endBlock() override { in_block_ = false, flush(), cur_ = &model; }
  // No flush at endSection: dxflib calls it after every entity, and an old-style
  // POLYLINE's vertices are entities of their own that follow it (up to its SEQEND).
  void endSequence() override { flush(); }

  // LINE, SPLINE, ELLIPSE, MTEXT and MLINE are in world coordinates; ARC, CIRCLE,
  // LWPOLYLINE and 2D POLYLINE, TEXT, INSERT, HATCH, SOLID and TRACE in their own (Ocs).
  void addLine(const DL_LineData& d) override { flush(), map_ = {}, seg({d.x1, d.y1}, {d.x2, d.y2}); }
  void addArc(const DL_ArcData& d) override {
    flush();
    map_ = ocs(), z_ = d.cz;
    arc({d.cx, d.cy}, d.radius, rad_from_deg(d.angle1), rad_from_deg(d.angle2));
  }
  void addCircle(const DL_CircleData& d) override {
    flush();
    map_ = ocs(), z_ = d.cz;
    const std::vector<Vec2> pts = arc_points({d.cx, d.cy}, d.radius, 0, 2 * kPi, sagitta);
    for (size_t i = 0; i + 1 < pts.size(); ++i) seg(pts[i], pts[i + 1], true);
  }
  void addEllipse(const DL_EllipseData& d) override {
    flush();
    map_ = {};
    // The minor axis is the extrusion direction x the major axis, times the ratio.
    const Ocs o = ocs();
    const Vec3 minor = d.ratio * cross(o.n, Vec3{d.mx, d.my, d.mz});
    const Vec2 c{d.cx, d.cy}, m{d.mx, d.my}, n{minor.x, minor.y};
    double a1 = d.angle2;
    while (a1 <= d.angle1) a1 += 2 * kPi;
    const int steps = std::clamp(int((a1 - d.angle1) / (kPi / 16)) + 1, 2, 64);
    Vec2 prev = c + std::cos(d.angle1) * m + std::sin(d.angle1) * n;
    for (int i = 1; i <= steps; ++i) {
      const double t = d.angle1 + (a1 - d.angle1) * i / steps;
      const Vec2 p = c + std::cos(t) * m + std::sin(t) * n;
      seg(prev, p, true);
      prev = p;
    }
  }
  void addPolyline(const DL_PolylineData& d) override {
    flush();
    map_ = (d.flags & 8) ? Ocs{} : ocs();  // a 3D polyline's are world's
    z_ = d.elevation;
    pending_layer_ = getAttributes().getLayer();
    in_poly_ = (d.flags & (16 | 64)) == 0;  // not a polygon or polyface mesh
    if (!in_poly_) {
      skipped.push_back("a 3D mesh POLYLINE on layer '" + layer() + "'");
      ++faces_3d;
    }
    poly_closed_ = (d.flags & 1) != 0;
    poly_width_ = ended_width_;
    poly_.clear();
    piece_widths_.clear();
    lw_widths_ = ended_vertex_widths_;  // an LWPOLYLINE's, per vertex (an old POLYLINE's come with each VERTEX)
  }
  void addVertex(const DL_VertexData& d) override {
    if (!in_poly_) return;
    // The width of the piece from this vertex on: its own start and end widths when it has
    // them and they agree, else the polyline's constant one; -1 when it tapers.
    std::pair<double, double> w{-1, -1};
    if (poly_.size() < lw_widths_.size()) w = lw_widths_[poly_.size()];
    else if (!ended_vertex_widths_.empty()) w = ended_vertex_widths_.front();
    if (w.first < 0) w.first = poly_width_;
    if (w.second < 0) w.second = poly_width_;
    piece_widths_.push_back(w.first == w.second ? w.first : -1);
    poly_.push_back({{d.x, d.y}, d.bulge});
  }
  void add3dFace(const DL_3dFaceData&) override {
    flush();
    ++faces_3d;
  }
  // A SOLID or TRACE (a filled quadrilateral, its corners in the order 1 2 4 3) tells a
  // wall's face as a hatch does.
  void addSolid(const DL_SolidData& d) override { filled_quad(d); }
  void addTrace(const DL_TraceData& d) override { filled_quad(d); }
  void processCodeValuePair(unsigned int code, const std::string& value) override {
    // dxflib hands over an entity when the next one's 0 arrives, after this call: the
    // width of the polyline just ended waits in ended_width_.
    if (code == 2 && entity_ == "SECTION") section_ = value;
    if (code == 0) {
      ended_width_ = width_start_ > 0 && width_start_ == width_end_ ? width_start_ : 0;
      ended_vertex_widths_ = std::move(vertex_widths_);
      vertex_widths_.clear();
      entity_ = value, width_start_ = width_end_ = 0;
      // Objects of AutoCAD's verticals (Architecture's AEC_WALL, AEC_DOOR ...; proxies),
      // which only those programs can draw: counted, to say so.
      if ((section_ == "ENTITIES" || section_ == "BLOCKS") && (value.rfind("AEC", 0) == 0 || value == "ACAD_PROXY_ENTITY"))
        ++foreign_objects[value];
      if (mline_) {
        emit_mline(*mline_);
        mline_.reset();
      }
      if (value == "MLINE") mline_.emplace();
      return;
    }
    if (mline_ && code == 8) {
      mline_->layer = value;
      return;
    }
    if (mline_ && code == 67) {
      mline_->paper = value.find_first_not_of(" 0") != std::string::npos;
      return;
    }
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (end == value.c_str() || !std::isfinite(v)) return;
    // Widths per vertex (its piece's start and end): an LWPOLYLINE's after each vertex's
    // 10, an old-style POLYLINE's on each VERTEX.
    if ((entity_ == "LWPOLYLINE" && code == 10) || (entity_ == "VERTEX" && vertex_widths_.empty())) {
      if (vertex_widths_.size() < 1000000) vertex_widths_.push_back({-1, -1});
    }
    if (((entity_ == "LWPOLYLINE" && !vertex_widths_.empty()) || entity_ == "VERTEX") && (code == 40 || code == 41) && v >= 0) {
      if (vertex_widths_.empty()) vertex_widths_.push_back({-1, -1});
      (code == 40 ? vertex_widths_.back().first : vertex_widths_.back().second) = v;
      return;
    }
    if ((entity_ == "LWPOLYLINE" && code == 43) || (entity_ == "POLYLINE" && (code == 40 || code == 41))) {
      if (v > 0) {
        if (code != 41) width_start_ = v;
        if (code != 40) width_end_ = v;
      }
      return;
    }
    if (!mline_) return;
    MLine& ml = *mline_;
    if (code == 71 && std::fabs(v) < 1e9) ml.closed = (int(v) & 2) != 0;
    if (code == 11 && ml.vertices.size() < 100000) {
      ml.vertices.push_back({{v, 0}, {1, 0}, {0, 1}, {}});
      ml.next_coord = 21;
      return;
    }
    if (ml.vertices.empty()) return;
    MLine::Vertex& vx = ml.vertices.back();
    if (code == 21 && ml.next_coord == 21) vx.p.y = v, ml.next_coord = 0;
    else if (code == 12) vx.dir.x = v, ml.next_coord = 22;
    else if (code == 22 && ml.next_coord == 22) vx.dir.y = v, ml.next_coord = 0;
    else if (code == 13) vx.miter.x = v, ml.next_coord = 23;
    else if (code == 23 && ml.next_coord == 23) vx.miter.y = v, ml.next_coord = 0;
    else if (code == 74 && vx.params.size() < 16) vx.params.emplace_back();
    else if (code == 41 && !vx.params.empty() && vx.params.back().size() < 34) vx.params.back().push_back(v);
  }
  void addSpline(const DL_SplineData& d) override {
    flush();
    pending_layer_ = getAttributes().getLayer();
    in_spline_ = true;
    spline_degree_ = int(d.degree);
    ctrl_.clear(), knots_.clear(), fit_.clear();
  }
  void addControlPoint(const DL_ControlPointData& d) override { ctrl_.push_back({d.x, d.y}); }
  void addKnot(const DL_KnotData& d) override { knots_.push_back(d.k); }
  void addFitPoint(const DL_FitPointData& d) override { fit_.push_back({d.x, d.y}); }
  void addInsert(const DL_InsertData& d) override {
    flush();
    map_ = {};
    // Mirrored by its extrusion (-Z): x -> -x after the placement, that is the insertion
    // point's x, the x scale and the angle negated.
    const Ocs o = ocs();
    const bool mirror = o.flat && o.mirrored;
    cur_->inserts.push_back({d.name, layer(), o({d.ipx, d.ipy}, d.ipz), {mirror ? -d.sx : d.sx, d.sy},
                             mirror ? -d.angle : d.angle, std::max(d.cols, 1), std::max(d.rows, 1), d.colSp, d.rowSp});
    count();
  }
  void addText(const DL_TextData& d) override {
    flush();
    map_ = {};
    cur_->texts.push_back({text_at(d, ocs()), label_text(d.text), layer()});
    count();
  }
  // A block's attribute whose tag says name (a room tag's NAME, as AIA's A-AREA-IDEN tags
  // carry it; ROOM, RAUM, NOM, TITLE, LABEL, SPACE ...) names a room as a text does; its
  // number, area, finish or height do not.
  void addAttribute(const DL_AttributeData& d) override {
    flush();
    map_ = {};
    const std::string tag = fold_layer_name(d.tag), text = label_text(d.text);
    bool names = false;
    for (const char* w : {"name", "nom", "room", "raum", "title", "titel", "label", "bezeich", "desc", "use", "nutzung",
                          "function", "funktion", "designation", "zimmer", "stanza", "piece", "pièce", "local", "space",
                          "espace", "ambiente", "ruimte"})
      names |= tag.find(w) != std::string::npos;
    for (const char* w : {"num", "area", "fläche", "flaeche", "surf", "height", "finish"})
      names &= tag.find(w) == std::string::npos;
    if (!names || std::none_of(text.begin(), text.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || (c & 0x80); }))
      return;
    cur_->texts.push_back({text_at(d, ocs()), text, layer()});
    count();
  }
  void addMText(const DL_MTextData& d) override {
    flush();
    map_ = {};
    cur_->texts.push_back({{d.ipx, d.ipy}, label_text(mtext_ + d.text), layer()});
    mtext_.clear();
    count();
  }
  void addMTextChunk(const std::string& text) override { mtext_ += text; }
  void addHatch(const DL_HatchData&) override {
    flush();
    map_ = {};
    hatch_map_ = ocs();
    cur_->hatches.push_back({{}, layer()});
    count();
  }
  void addHatchLoop(const DL_HatchLoopData&) override {
    if (!cur_->hatches.empty()) cur_->hatches.back().rings.emplace_back();
  }
  void addHatchEdge(const DL_HatchEdgeData& e) override {
    if (cur_->hatches.empty() || cur_->hatches.back().rings.empty()) return;
    std::vector<Vec2>& ring = cur_->hatches.back().rings.back();
    const size_t first = ring.size();
    if (e.type == 0) {  // a polyline boundary, its pieces bulged (arcs) where a vertex says so
      std::vector<std::pair<Vec2, double>> v;
      for (const std::vector<double>& x : e.vertices)
        if (x.size() >= 2) v.push_back({{x[0], x[1]}, x.size() >= 3 ? x[2] : 0.0});
      for (size_t i = 0; i < v.size(); ++i) {
        ring.push_back(v[i].first);
        if (v[i].second == 0 || v.size() < 2) continue;
        const std::vector<Vec2> arc = bulge_points(v[i].first, v[(i + 1) % v.size()].first, v[i].second, sagitta);
        ring.insert(ring.end(), arc.begin() + 1, arc.end() - 1);
      }
    } else if (e.type == 1) {
      if (ring.empty()) ring.push_back({e.x1, e.y1});
      ring.push_back({e.x2, e.y2});
    } else if (e.type == 2) {
      double a0 = e.angle1, a1 = e.angle2;
      if (!e.ccw) a0 = -e.angle2, a1 = -e.angle1;
      std::vector<Vec2> pts = arc_points({e.cx, e.cy}, e.radius, a0, a1, sagitta);
      if (!e.ccw) {
        for (Vec2& p : pts) p.y = 2 * e.cy - p.y;  // mirrored back: clockwise arcs
      }
      ring.insert(ring.end(), pts.begin(), pts.end());
    }
    for (size_t i = first; i < ring.size(); ++i) ring[i] = hatch_map_(ring[i]);
  }

  /// Ends the wide polyline's band under way, if any.
  void end_band() {
    if (!band_) return;
    if (band_->closed && band_->pts.size() > 1 && length(band_->pts.back() - band_->pts.front()) == 0) band_->pts.pop_back();
    if (band_->pts.size() >= 2) cur_->bands.push_back(std::move(*band_));
    band_.reset();
  }

  /// Ends a polyline or spline under way.
  void flush() {
    if (in_poly_ && poly_.size() >= 2) {
      // Widths: one for the whole polyline (a closed band), or per piece (AutoCAD's PLINE
      // with its width changed along the way): each run of pieces of one width its band.
      const size_t n = poly_.size(), segs = poly_closed_ ? n : n - 1;
      piece_widths_.resize(n, poly_width_);
      const bool one_width =
          std::all_of(piece_widths_.begin(), piece_widths_.begin() + std::ptrdiff_t(segs), [&](double w) { return w == piece_widths_[0]; });
      if (one_width && piece_widths_[0] > 0) band_.emplace(Band{{}, poly_closed_, piece_widths_[0], layer()});
      std::vector<Vec2> ring;
      for (size_t i = 0; i < segs; ++i) {
        const Vec2 a = poly_[i].first, b = poly_[(i + 1) % n].first;
        const double bulge = poly_[i].second;
        if (!one_width && (i == 0 || piece_widths_[i] != piece_widths_[i - 1])) {
          end_band();
          if (piece_widths_[i] > 0) band_.emplace(Band{{}, false, piece_widths_[i], layer()});
        }
        ring.push_back(a);
        if (std::fabs(bulge) < 1e-9 || length(b - a) == 0) {
          seg(a, b);
          continue;
        }
        const BulgeArc k = bulge_arc(a, b, bulge);
        arc(k.c, k.r, k.a0, k.a1);
      }
      for (Vec2& p : ring) p = map_(p, z_);
      if (poly_closed_ && n >= 3) cur_->closed.push_back({ring, layer()});
      end_band();
      count();
    }
    if (in_spline_) {
      map_ = {};
      const std::vector<Vec2> pts =
          !ctrl_.empty() ? spline_points(spline_degree_, knots_, ctrl_) : fit_;
      for (size_t i = 0; i + 1 < pts.size(); ++i) seg(pts[i], pts[i + 1], true);
      if (pts.size() >= 2) cur_->curves.push_back({pts, layer()});
      count();
    }
    in_poly_ = in_spline_ = false;
    poly_.clear();
    // What follows is the entity being read (flush runs as each begins): in model space,
    // or in a layout's paper space (group 67: title blocks, viewports' frames, notes in
    // paper coordinates that would land among the rooms), which is no part of the plan.
    if (!in_block_) cur_ = getAttributes().isInPaperSpace() ? &paper : &model;
  }

 private:
  /// The layer of the entity being read: a polyline or spline under way keeps its own
  /// (it is flushed when a later entity begins).
  std::string layer() { return in_poly_ || in_spline_ ? pending_layer_ : getAttributes().getLayer(); }
  void count() { ++layer_entities[layer()]; }
  /// The object coordinates of the entity being read, by its extrusion direction.
  Ocs ocs() { return Ocs::of(getExtrusion()->getDirection()); }
  /// Where a text (or an attribute) stands: justified text by its alignment point.
  static Vec2 text_at(const DL_TextData& d, const Ocs& o) {
    const bool aligned = d.hJustification != 0 || d.vJustification != 0;
    return aligned ? o({d.apx, d.apy}, d.apz) : o({d.ipx, d.ipy}, d.ipz);
  }
  /// A line of the entity being read, from its own coordinates (map_).
  void seg(Vec2 a, Vec2 b, bool curved = false) {
    if (band_) {  // a wide polyline's middle, its pieces in order
      if (band_->pts.empty()) band_->pts.push_back(map_(a, z_));
      band_->pts.push_back(map_(b, z_));
      return;
    }
    cur_->segs.push_back({map_(a, z_), map_(b, z_), layer(), curved, false, {}});
    if (!in_poly_ && !in_spline_) count();
  }
  void arc(Vec2 c, double r, double a0, double a1) {
    const std::vector<Vec2> pts = arc_points(c, r, a0, a1, sagitta);
    for (size_t i = 0; i + 1 < pts.size(); ++i) seg(pts[i], pts[i + 1], true);
    if (!map_.flat) return;  // seen edge-on or slanted: an ellipse in the plan, no door swing
    double sweep = a1 - a0;
    while (sweep <= 0) sweep += 2 * kPi;
    ArcPiece piece{map_(c, z_), map_(pts.front(), z_), map_(pts.back(), z_), r, deg_from_rad(sweep), layer()};
    if (map_.mirrored) std::swap(piece.p0, piece.p1);  // counter-clockwise from p0 to p1 again
    cur_->arcs.push_back(piece);
  }
  void filled_quad(const DL_TraceData& d) {
    flush();
    map_ = {};
    const Ocs o = ocs();
    std::vector<Vec2> ring;
    for (int k : {0, 1, 3, 2}) ring.push_back(o({d.x[k], d.y[k]}, d.z[k]));
    cur_->hatches.push_back({{ring}, layer()});
    count();
  }
  /// An MLINE's elements as lines, their cuts left open.
  void emit_mline(const MLine& ml) {
    flush();
    if (!in_block_) cur_ = ml.paper ? &paper : &model;
    const size_t n = ml.vertices.size();
    if (n < 2) return;
    const size_t segs = ml.closed ? n : n - 1;
    for (size_t i = 0; i < segs; ++i) {
      const MLine::Vertex &v = ml.vertices[i], &w = ml.vertices[(i + 1) % n];
      const double dl = length(v.dir);
      if (!(dl > 0)) continue;
      const Vec2 d = (1 / dl) * v.dir;
      for (size_t k = 0; k < v.params.size() && k < w.params.size(); ++k) {
        const std::vector<double>& pv = v.params[k];
        const Vec2 start = v.p + (pv.empty() ? 0.0 : pv[0]) * v.miter;
        const Vec2 stop = w.p + (w.params[k].empty() ? 0.0 : w.params[k][0]) * w.miter;
        const double t_end = dot(stop - start, d);
        // After the offset: where the element starts, then where it stops and starts
        // again past each cut; an odd count runs on to the next vertex's miter.
        std::vector<double> at(pv.size() > 1 ? pv.begin() + 1 : pv.end(), pv.end());
        if (at.empty()) at.push_back(0);
        if (at.size() % 2 == 1) at.push_back(t_end);
        for (size_t j = 0; j + 1 < at.size(); j += 2) {
          const double t0 = std::max(at[j], 0.0), t1 = std::min(at[j + 1], t_end);
          if (t1 > t0) cur_->segs.push_back({start + t0 * d, start + t1 * d, ml.layer, false, false, {}});
        }
      }
    }
    ++layer_entities[ml.layer];
  }

  Group* cur_ = &model;
  bool in_block_ = false;  ///< between a BLOCK and its ENDBLK
  Ocs map_, hatch_map_;  ///< the coordinates of the entity being read (of its edges, for a hatch)
  double z_ = 0;         ///< its elevation in them
  std::optional<MLine> mline_;
  std::string entity_;                ///< the type of the entity whose pairs are being read
  std::string section_;               ///< the section being read (HEADER, BLOCKS, ENTITIES ...)
  double width_start_ = 0, width_end_ = 0, ended_width_ = 0, poly_width_ = 0;
  /// Per vertex, its piece's start and end width (-1: not given): being read, of the entity
  /// just ended, and of the LWPOLYLINE under way.
  std::vector<std::pair<double, double>> vertex_widths_, ended_vertex_widths_, lw_widths_;
  std::vector<double> piece_widths_;  ///< per vertex of the polyline under way: its piece's width, -1 tapering
  std::optional<Band> band_;          ///< a wide polyline being flushed
  bool in_poly_ = false, poly_closed_ = false, in_spline_ = false;
  std::vector<std::pair<Vec2, double>> poly_;
  int spline_degree_ = 3;
  std::vector<Vec2> ctrl_, fit_;
  std::vector<double> knots_;
  std::string mtext_;
  std::string pending_layer_;
};

/// A 2D placement: p ↦ at + R(angle)·(scale ∘ (p − base)).
struct Placement {
  Vec2 at, scale{1, 1}, base;
  double c = 1, s = 0;
  Vec2 operator()(Vec2 p) const {
    const Vec2 q{scale.x * (p.x - base.x), scale.y * (p.y - base.y)};
    return {at.x + c * q.x - s * q.y, at.y + s * q.x + c * q.y};
  }
};

/// Everything of model space with the blocks expanded, in drawing units. An entity
/// inside a block takes the INSERT's layer when it is on layer 0; `door_block` marks
/// what came from a block whose name says door.
struct Flat {
  std::vector<SegPiece> segs;
  std::vector<std::pair<ArcPiece, bool>> arcs;  ///< arc, from a door block
  std::vector<TextPiece> texts;
  std::vector<HatchPiece> hatches;
  std::vector<std::pair<std::vector<Vec2>, std::string>> closed;
  /// Spline curves, a chain of pieces per door block placed (`chain` numbers it; -1 in model space).
  struct Curve { std::vector<Vec2> pts; std::string layer; bool door_block; int chain; };
  std::vector<Curve> curves;
  std::vector<Band> bands;
  int placements = 0;
  std::vector<std::string> missing_blocks;
};

/// The outline of a wide polyline, half-width h either side of its middle: mitred where it
/// turns (bevelled where it turns back sharper than 135 degrees), capped square at the ends
/// of an open one.
std::vector<std::pair<Vec2, Vec2>> band_outline(std::vector<Vec2> pts, bool closed, double h) {
  std::vector<Vec2> p;
  for (Vec2 q : pts)
    if (p.empty() || length(q - p.back()) > 0) p.push_back(q);
  if (closed && p.size() > 1 && length(p.back() - p.front()) == 0) p.pop_back();
  std::vector<std::pair<Vec2, Vec2>> out;
  const size_t n = p.size();
  if (n < 2 || !(h > 0)) return out;
  const bool ring = closed && n >= 3;
  const size_t segs = ring ? n : n - 1;
  auto left_of = [&](size_t i) {  // unit left normal of segment i
    const Vec2 d = p[(i + 1) % n] - p[i];
    return (1 / length(d)) * Vec2{-d.y, d.x};
  };
  for (const double side : {1.0, -1.0}) {
    std::vector<Vec2> edge;
    for (size_t i = 0; i < n; ++i) {
      const bool has_in = ring || i > 0, has_out = ring || i + 1 < n;
      if (!has_in) { edge.push_back(p[i] + side * h * left_of(i)); continue; }
      const Vec2 n_in = left_of((i + segs - 1) % segs);
      if (!has_out) { edge.push_back(p[i] + side * h * n_in); continue; }
      const Vec2 n_out = left_of(i % segs);
      const double c = 1 + dot(n_in, n_out);
      if (c < 0.3) {
        edge.push_back(p[i] + side * h * n_in), edge.push_back(p[i] + side * h * n_out);
      } else {
        edge.push_back(p[i] + (side * h / c) * (n_in + n_out));
      }
    }
    for (size_t i = 0; i + 1 < edge.size(); ++i) out.push_back({edge[i], edge[i + 1]});
    if (ring) out.push_back({edge.back(), edge.front()});
  }
  if (!ring) {  // the caps
    out.push_back({p[0] + h * left_of(0), p[0] - h * left_of(0)});
    out.push_back({p[n - 1] + h * left_of(n - 2), p[n - 1] - h * left_of(n - 2)});
  }
  return out;
}

/// `door_block`: inside a block whose name says door (door, Tür, porte, sliding, pocket,
/// bi-fold ...); `window_block`: the name of the block whose name says window it is in.
void flatten(const Collector& col, const Group& g, const std::vector<Placement>& chain, const std::string& layer_0,
             bool door_block, int depth, Flat& out, int chain_of_insert = -1, const std::string& window_block = {}) {
  auto place = [&](Vec2 p) {
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) p = (*it)(p);
    return p;
  };
  auto lay = [&](const std::string& l) { return l == "0" && !layer_0.empty() ? layer_0 : l; };
  bool mirrored = false;
  for (const Placement& pl : chain) mirrored ^= (pl.scale.x * pl.scale.y < 0);
  double scale = 1;
  for (const Placement& pl : chain) scale *= std::fabs(pl.scale.x);
  for (const SegPiece& s : g.segs) out.segs.push_back({place(s.a), place(s.b), lay(s.layer), s.curved, door_block, window_block});
  for (const ArcPiece& a : g.arcs) {
    ArcPiece b{place(a.c), place(a.p0), place(a.p1), a.r * scale, a.sweep_deg, lay(a.layer)};
    if (mirrored) std::swap(b.p0, b.p1);
    out.arcs.push_back({b, door_block});
  }
  for (const TextPiece& t : g.texts) out.texts.push_back({place(t.p), t.text, lay(t.layer)});
  for (const HatchPiece& h : g.hatches) {
    HatchPiece k{{}, lay(h.layer)};
    for (const auto& r : h.rings) {
      k.rings.emplace_back();
      for (Vec2 p : r) k.rings.back().push_back(place(p));
    }
    out.hatches.push_back(k);
  }
  for (const auto& [ring, l] : g.closed) {
    std::vector<Vec2> r;
    for (Vec2 p : ring) r.push_back(place(p));
    out.closed.push_back({r, lay(l)});
  }
  const int chain_no = chain_of_insert;
  for (const auto& [pts, l] : g.curves) {
    std::vector<Vec2> r;
    for (Vec2 p : pts) r.push_back(place(p));
    out.curves.push_back({r, lay(l), door_block, chain_no});
  }
  for (const Band& b : g.bands) {
    Band k{{}, b.closed, b.width * scale, lay(b.layer)};
    for (Vec2 p : b.pts) k.pts.push_back(place(p));
    out.bands.push_back(std::move(k));
  }
  if (depth >= 8) return;
  for (const InsertPiece& ins : g.inserts) {
    auto it = col.blocks.find(ins.block);
    if (it == col.blocks.end()) {
      out.missing_blocks.push_back(ins.block);
      continue;
    }
    const double a = rad_from_deg(ins.angle_deg);
    const int copies = std::min(ins.cols * ins.rows, 1000);
    for (int k = 0; k < copies; ++k) {
      const double dx = (k % ins.cols) * ins.col_sp, dy = (k / ins.cols) * ins.row_sp;
      Placement pl;
      pl.at = ins.at + Vec2{std::cos(a) * dx - std::sin(a) * dy, std::sin(a) * dx + std::cos(a) * dy};
      pl.scale = {ins.scale.x == 0 ? 1 : ins.scale.x, ins.scale.y == 0 ? 1 : ins.scale.y};
      pl.base = it->second.base;
      pl.c = std::cos(a), pl.s = std::sin(a);
      std::vector<Placement> next = chain;
      next.push_back(pl);
      const bool door = door_block || names_a_door(ins.block);
      flatten(col, it->second, next, lay(ins.layer), door, depth + 1, out, out.placements++,
              door ? std::string() : names_a_window(ins.block) ? ins.block : window_block);
    }
  }
}

/// Door swings drawn as short straight lines (arcs_in_lines.h) on a door layer or in a door
/// block: each is an arc, its lines curved pieces as an ARC's are (no frame, no wall: as
/// straight lines they closed the door's gap with a curved wall, and the rooms either side
/// had no way between them). Returns how many were found.
int swings_drawn_as_lines(Flat& flat, const std::map<std::string, LayerRole>& role) {
  std::vector<size_t> seg_of;
  std::vector<std::pair<Vec2, Vec2>> lines;
  for (size_t i = 0; i < flat.segs.size(); ++i) {
    const SegPiece& s = flat.segs[i];
    if (s.curved || !(length(s.b - s.a) > 0) || (role.at(s.layer) != LayerRole::Doors && !s.door_block)) continue;
    seg_of.push_back(i);
    lines.push_back({s.a, s.b});
  }
  const std::vector<ArcOfLines> arcs = arcs_in_lines(lines);
  for (const ArcOfLines& a : arcs) {
    const SegPiece& first = flat.segs[seg_of[a.lines.front()]];
    flat.arcs.push_back({ArcPiece{a.centre, a.from, a.to, a.r, a.sweep_deg, first.layer}, first.door_block});
    for (size_t k : a.lines) flat.segs[seg_of[k]].curved = true;
  }
  return int(arcs.size());
}

}  // namespace

bool looks_like_dxf(const std::string& head) {
  std::istringstream in(head);
  auto trim = [](std::string s) {
    s.erase(0, s.find_first_not_of(" \t\r"));
    s.erase(s.find_last_not_of(" \t\r") + 1);
    return s;
  };
  for (std::string code, value; std::getline(in, code) && std::getline(in, value);) {
    if (trim(code) == "999") continue;  // comments may come first
    return trim(code) == "0" && trim(value) == "SECTION";
  }
  return false;
}

DxfPlan read_dxf_plan(const std::string& path, const DxfPlanOptions& opt) {
  const SourceLoc file{path, 0, 0, ""};
  if (!(opt.storey_height > 0)) throw PlanError(file, "--storey-height must be positive");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw PlanError(file, "cannot open the file");
    std::string head(1024, '\0');
    head.resize(size_t(probe.read(head.data(), std::streamsize(head.size())).gcount()));
    if (head.rfind("AutoCAD Binary DXF", 0) == 0) throw PlanError(file, "a binary DXF: save it as ASCII DXF");
    if (!looks_like_dxf(head)) throw PlanError(file, "not a DXF drawing (it does not start with '0 SECTION')");
  }
  Collector col;
  // --unit first: it decides how finely arcs are cut (a bad one is refused below).
  if (const double m = metres_of_unit_name(opt.unit); m > 0) col.sagitta = Plan{}.arc_tolerance / m;
  DL_Dxf dxf;
  if (!dxf.in(path, &col)) throw PlanError(file, "dxflib cannot read the file");
  col.flush();

  DxfPlan out;
  Plan& plan = out.plan;
  plan.name = std::filesystem::path(path).stem().string();
  plan.source = path;
  plan.lenient = true;
  plan.unnamed_spaces_solid = true;  // the wall faces; the outside is free
  for (const std::string& s : col.skipped) plan.warnings.push_back(s + ": skipped");
  if (!col.foreign_note().empty()) plan.warnings.push_back(col.foreign_note() + "; they are skipped");

  // Which layer is what: --layers first, then the usual names.
  std::map<std::string, LayerRole> given;
  if (!opt.layers.empty()) {
    std::istringstream spec(opt.layers);
    for (std::string part; std::getline(spec, part, ';');) {
      if (part.empty()) continue;
      const size_t eq = part.find('=');
      const std::string key = lower(part.substr(0, eq));
      LayerRole r = key == "walls" ? LayerRole::Walls : key == "doors" ? LayerRole::Doors : key == "windows" ? LayerRole::Windows : LayerRole::None;
      if (eq == std::string::npos || r == LayerRole::None)
        throw PlanError({path, 0, 0, "--layers"}, "'" + part + "': expected walls=NAME,..., doors=... or windows=...");
      std::istringstream names(part.substr(eq + 1));
      for (std::string nm; std::getline(names, nm, ',');)
        if (!nm.empty()) given[fold_layer_name(nm)] = r;
    }
  }
  Flat flat;
  flatten(col, col.model, {}, "", false, 0, flat);
  std::set<std::string> layers;
  for (const auto& [l, n] : col.layer_entities) layers.insert(l);
  for (const SegPiece& s : flat.segs) layers.insert(s.layer);
  for (const Band& b : flat.bands) layers.insert(b.layer);
  std::map<std::string, LayerRole> role;
  for (const std::string& l : layers) {
    auto it = given.find(fold_layer_name(l));
    role[l] = it != given.end() ? it->second : (given.empty() ? layer_role_by_name(l) : LayerRole::None);
  }
  // With --layers, a role it does not name still goes by the usual names.
  if (!given.empty()) {
    std::set<LayerRole> named;
    for (const auto& [l, r] : given) named.insert(r);
    for (const std::string& l : layers)
      if (role[l] == LayerRole::None && !given.count(fold_layer_name(l)) && !named.count(layer_role_by_name(l))) role[l] = layer_role_by_name(l);
  }
  // A window block's lines on a layer that says nothing (layer 0, a generic one) are
  // window lines: they go on a layer of their own, named after the block, for the summary.
  for (SegPiece& s : flat.segs)
    if (!s.window_block.empty() && role[s.layer] == LayerRole::None) {
      s.layer = "block " + s.window_block;
      role[s.layer] = LayerRole::Windows;
    }
  const int swings_as_lines = swings_drawn_as_lines(flat, role);
  std::vector<std::string> taken[4];
  for (const auto& [l, r] : role)
    if (r != LayerRole::None) taken[int(r)].push_back(l);
  for (const auto& named : given) {  // (clang before 16 cannot capture a structured binding)
    const std::string& nm = named.first;
    if (std::none_of(layers.begin(), layers.end(), [&](const std::string& l) { return fold_layer_name(l) == nm; }))
      throw PlanError({path, 0, 0, "--layers"}, "the drawing has no layer '" + nm + "'");
  }

  std::set<std::string> wall_layers_used;
  for (const SegPiece& s : flat.segs)
    if (role[s.layer] == LayerRole::Walls) wall_layers_used.insert(s.layer);
  for (const Band& b : flat.bands)
    if (role[b.layer] == LayerRole::Walls) wall_layers_used.insert(b.layer);
  // Walls drawn only as fills (hatches, SOLIDs) on a wall layer, not a line beside them:
  // the fills' outlines are the wall lines (and the fills still tell the wall faces).
  bool walls_from_fills = false;
  if (wall_layers_used.empty()) {
    for (const HatchPiece& h : flat.hatches) {
      if (role[h.layer] != LayerRole::Walls) continue;
      for (const auto& r : h.rings)
        for (size_t i = 0; r.size() >= 3 && i < r.size(); ++i)
          if (length(r[(i + 1) % r.size()] - r[i]) > 0) {
            flat.segs.push_back({r[i], r[(i + 1) % r.size()], h.layer, false, false, {}});
            wall_layers_used.insert(h.layer);
          }
    }
    walls_from_fills = !wall_layers_used.empty();
  }
  // No wall lines but 3D faces: a 3D model (SketchUp's, LightWave's), read as a mesh.
  if (wall_layers_used.empty() && given.empty() && col.faces_3d > 0) {
    out.model_faces = col.faces_3d;
    out.metres_per_unit = metres_of_insunits(col.insunits);
    return out;
  }
  // No layer named for walls and none given: as a CAD viewer shows a drawing whatever its
  // layers, the lines of every layer whose name does not say it holds something else
  // (dimensions, text, furniture ...) are the walls, and a warning names them and --layers.
  if (wall_layers_used.empty() && given.empty()) {
    for (const SegPiece& s : flat.segs)
      if (role[s.layer] == LayerRole::None && !names_no_building(s.layer)) wall_layers_used.insert(s.layer);
    for (const Band& b : flat.bands)
      if (role[b.layer] == LayerRole::None && !names_no_building(b.layer)) wall_layers_used.insert(b.layer);
    std::string list;
    for (const std::string& l : wall_layers_used) {
      role[l] = LayerRole::Walls;
      taken[int(LayerRole::Walls)].push_back(l);
      list += (list.empty() ? "'" : ", '") + l + "'";
    }
    if (!list.empty())
      plan.warnings.push_back("no layer holds walls by its name: the lines of layer(s) " + list +
                              " are taken as walls (name the wall layers with --layers "
                              "'walls=NAME,NAME;doors=NAME;windows=NAME')");
  }
  if (wall_layers_used.empty()) {
    std::string list;
    for (const std::string& l : layers) {
      auto it = col.layer_entities.find(l);
      list += "\n  '" + l + "'";
      if (it != col.layer_entities.end() && it->second > 0) list += " (" + std::to_string(it->second) + " entities)";
    }
    if (!col.foreign_note().empty()) throw PlanError(file, "no wall lines: " + col.foreign_note());
    throw PlanError(file, "no layer holds walls by its name (A-WALL, Walls, partitions, ... Existing Structure, "
                          "Wand, Murs, Muros, Muri, Paredes, Muren, Стены, 墙): its layers are" + list +
                          "\nname the wall layers with --layers 'walls=NAME,NAME;doors=NAME;windows=NAME'");
  }

  // Units.
  double unit = 0;
  std::string unit_said;
  if (!opt.unit.empty()) {
    unit = metres_of_unit_name(opt.unit);
    if (unit == 0) throw PlanError({path, 0, 0, "--unit"}, "unknown unit '" + opt.unit + "' (use m, cm, mm, in or ft)");
    unit_said = opt.unit + " (--unit)";
  } else if ((unit = metres_of_insunits(col.insunits)) > 0) {
    unit_said = format_number(unit) + " m per unit ($INSUNITS " + std::to_string(col.insunits) + ")";
  } else {
    double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
    auto grow = [&](Vec2 p) { lo_x = std::min(lo_x, p.x), hi_x = std::max(hi_x, p.x), lo_y = std::min(lo_y, p.y), hi_y = std::max(hi_y, p.y); };
    for (const SegPiece& s : flat.segs)
      if (role[s.layer] == LayerRole::Walls) grow(s.a), grow(s.b);
    for (const Band& b : flat.bands)
      if (role[b.layer] == LayerRole::Walls)
        for (Vec2 p : b.pts) grow(p);
    const double across = std::max(hi_x - lo_x, hi_y - lo_y);
    // A door's swing is 0.55-1.3 m in any building: its radius in drawing units tells the
    // unit where mm, cm, m, inches and feet give disjoint ranges (a plan in cm, as many
    // European offices draw, is 800-2,000 units across, which its extent alone reads as mm).
    std::vector<double> radii;
    for (const auto& [a, in_door_block] : flat.arcs)
      if ((role[a.layer] == LayerRole::Doors || in_door_block) && door_swing_sweep(a.sweep_deg) && a.r > 0) radii.push_back(a.r);
    const LengthUnit* by_doors = nullptr;
    if (!radii.empty()) {
      std::nth_element(radii.begin(), radii.begin() + long(radii.size() / 2), radii.end());
      const double r = radii[radii.size() / 2];
      for (const LengthUnit& l : kLengthUnits)
        if (r * l.metres >= 0.55 && r * l.metres <= 1.3 && across * l.metres >= 2 && across * l.metres <= 2000) by_doors = &l;
      if (by_doors)
        unit = by_doors->metres, unit_said = std::string(by_doors->name) + ", guessed from its door swings' radius of " +
                                             format_number(r) + " units (no $INSUNITS; say --unit)";
    }
    if (!by_doors) {
      unit = across > 1000 ? 0.001 : 1;
      unit_said = std::string(unit == 1 ? "m" : "mm") + ", guessed from the walls' extent of " + format_number(across) +
                  " units (no $INSUNITS; say --unit)";
    }
    plan.warnings.push_back("the drawing states no unit: taken as " + unit_said);
  }
  auto m = [&](Vec2 p) { return unit * p; };
  // A door's swing: an arc of a leaf's radius and a quarter turn, loosely, on a door layer
  // or in a door block.
  auto is_swing = [&](const ArcPiece& a, bool in_door_block) {
    return (role[a.layer] == LayerRole::Doors || in_door_block) && door_swing_radius(a.r * unit) && door_swing_sweep(a.sweep_deg);
  };
  // Wide polylines: on a wall layer and 5 cm wide or more, the wall's faces (the band's
  // outline); elsewhere, or thinner (a heavy pen), the line along their middle.
  int bands_as_walls = 0;
  for (const Band& b : flat.bands) {
    if (role[b.layer] == LayerRole::Walls && b.width * unit >= 0.05) {
      for (const auto& [a, c] : band_outline(b.pts, b.closed, b.width / 2)) flat.segs.push_back({a, c, b.layer, false, false, {}});
      ++bands_as_walls;
    } else {
      for (size_t i = 0; i + 1 < b.pts.size(); ++i) flat.segs.push_back({b.pts[i], b.pts[i + 1], b.layer, false, false, {}});
      if (b.closed) flat.segs.push_back({b.pts.back(), b.pts.front(), b.layer, false, false, {}});
    }
  }
  // Fills standing for walls beside walls drawn as lines (columns drawn as SOLID squares, a
  // core hatched without an outline): where no wall line runs along most of a wall-layer
  // fill's outline, its edges that no line runs along are wall lines.
  int fills_as_walls = 0;
  if (!walls_from_fills) {
    std::vector<std::pair<Vec2, Vec2>> lines;
    for (const SegPiece& s : flat.segs)
      if (role[s.layer] == LayerRole::Walls) lines.push_back({m(s.a), m(s.b)});
    SegmentGrid grid(lines, 0.5);
    constexpr double kAlong = 0.01;  // [m]
    auto near_a_line = [&](Vec2 p) {
      bool near = false;
      grid.near(p, kAlong, [&](size_t j) { near = near || distance_to_segment(p, lines[j].first, lines[j].second) < kAlong; });
      return near;
    };
    for (const HatchPiece& h : flat.hatches) {
      if (role[h.layer] != LayerRole::Walls) continue;
      for (const auto& r : h.rings) {
        if (r.size() < 3) continue;
        double perimeter = 0, along = 0;
        std::vector<std::pair<Vec2, Vec2>> bare;
        for (size_t i = 0; i < r.size(); ++i) {
          const Vec2 a = r[i], b = r[(i + 1) % r.size()];
          const double len = length(m(b) - m(a));
          if (!(len > 0)) continue;
          perimeter += len;
          if (near_a_line(m(a)) && near_a_line(m(0.5 * (a + b))) && near_a_line(m(b))) along += len;
          else bare.push_back({a, b});
        }
        if (!(along < 0.5 * perimeter)) continue;
        for (const auto& [a, b] : bare) flat.segs.push_back({a, b, h.layer, false, false, {}});
        ++fills_as_walls;
      }
    }
  }
  if (walls_from_fills) out.summary.push_back("the wall layers hold fills and no lines: the fills' outlines taken as the walls' faces");
  if (swings_as_lines > 0)
    out.summary.push_back(std::to_string(swings_as_lines) + " curves drawn as short straight lines on door layers taken as arcs (swings)");
  if (fills_as_walls > 0)
    out.summary.push_back(std::to_string(fills_as_walls) +
                          " fills on wall layers with no wall line along their outline (columns, cores): their outlines taken as walls");
  if (bands_as_walls > 0)
    out.summary.push_back(std::to_string(bands_as_walls) + " wide polylines on wall layers taken as walls as wide as they are drawn");
  out.drawing.reserve(flat.segs.size());
  for (const SegPiece& s : flat.segs) out.drawing.push_back({m(s.a), m(s.b)});

  // Windows drawn on layer 0 (anandkothartrdl-plan.dxf draws its living room's glazing so,
  // and the room was read as outside through the gap): lines on layer 0 that lie in a wall
  // gap from end to end, thin across it (at most 0.6 m) and 0.3–6 m long, found as doors
  // without a swing are (swingless_doors.h), are window lines. Furniture on layer 0 is
  // thicker across, or stands in a room, not in a gap in a wall.
  {
    std::vector<std::pair<Vec2, Vec2>> loose, wall_lines;
    std::vector<size_t> seg_of;
    for (size_t i = 0; i < flat.segs.size(); ++i) {
      const SegPiece& s = flat.segs[i];
      if (s.curved) continue;
      if (s.layer == "0" && !s.door_block && s.window_block.empty()) loose.push_back({m(s.a), m(s.b)}), seg_of.push_back(i);
      else if (role[s.layer] == LayerRole::Walls || role[s.layer] == LayerRole::Windows) wall_lines.push_back({m(s.a), m(s.b)});
    }
    if (!loose.empty()) {
      SwinglessDoorParams prm;
      prm.min_width = 0.3, prm.max_width = 6.0;
      prm.max_across = 0.6, prm.join_across = 0.05;  // thick across (sills inside and out), not joined across
      const std::string layer = "0 (lines in wall gaps)";
      std::vector<SwinglessDoor> found = find_swingless_doors(loose, std::vector<bool>(loose.size(), false), wall_lines, {}, prm);
      // One window per gap: of the pieces found in one gap (the glass with its frames, a sill
      // line inside, another outside), the one of most lines, then the longest, is the window.
      std::erase_if(found, [](const SwinglessDoor& w) { return !w.placed; });
      std::sort(found.begin(), found.end(), [](const SwinglessDoor& a, const SwinglessDoor& b) {
        return a.lines.size() != b.lines.size() ? a.lines.size() > b.lines.size() : length(a.b - a.a) > length(b.b - b.a);
      });
      std::vector<const SwinglessDoor*> kept;
      for (const SwinglessDoor& w : found) {
        const Vec2 u = (1 / std::max(1e-9, length(w.b - w.a))) * (w.b - w.a), n{-u.y, u.x};
        const bool same_gap = std::any_of(kept.begin(), kept.end(), [&](const SwinglessDoor* k) {
          const double lo = std::min(dot(k->a - w.a, u), dot(k->b - w.a, u)), hi = std::max(dot(k->a - w.a, u), dot(k->b - w.a, u));
          return std::fabs(dot(k->where - w.where, n)) < prm.max_across && hi > 0 && lo < length(w.b - w.a);
        });
        if (same_gap) continue;
        kept.push_back(&w);
        for (int i : w.lines) flat.segs[seg_of[size_t(i)]].layer = layer;
        role[layer] = LayerRole::Windows;
      }
      if (!kept.empty()) taken[int(LayerRole::Windows)].push_back(layer);
    }
  }

  WallArrangementInput arr_in;
  // Door and window gaps, windows first: each cluster of window-layer lines (glass,
  // frames, mullions, sills touching one another) is one window.
  struct Gap { Vec2 a, b; bool door; Vec2 where; };
  std::vector<Gap> gaps;
  std::vector<SegPiece> win;
  for (const SegPiece& s : flat.segs)
    if (role[s.layer] == LayerRole::Windows) win.push_back({m(s.a), m(s.b), s.layer, s.curved, false, {}});
  std::vector<int> window_of(win.size(), -1);  // per window line: its gap, or -1 (too small to be a window)
  {
    std::vector<int> parent(win.size());
    for (size_t i = 0; i < win.size(); ++i) parent[i] = int(i);
    std::function<int(int)> root = [&](int i) { return parent[size_t(i)] == i ? i : parent[size_t(i)] = root(parent[size_t(i)]); };
    // Lines touch when an end of one lies within 2 cm of the other (the lines near each
    // end from a grid: a curtain wall's thousands of lines are not compared pairwise).
    std::vector<std::pair<Vec2, Vec2>> lines;
    for (const SegPiece& w : win) lines.push_back({w.a, w.b});
    SegmentGrid grid(lines, 0.5);
    for (size_t i = 0; i < win.size(); ++i)
      for (const Vec2 e : {win[i].a, win[i].b})
        grid.near(e, 0.02, [&](size_t j) {
          if (j != i && distance_to_segment(e, win[j].a, win[j].b) < 0.02) parent[size_t(root(int(i)))] = root(int(j));
        });
    std::map<int, int> longest;
    for (size_t i = 0; i < win.size(); ++i) {
      const int r = root(int(i));
      auto it = longest.find(r);
      if (it == longest.end() || length(win[i].b - win[i].a) > length(win[size_t(it->second)].b - win[size_t(it->second)].a))
        longest[r] = int(i);
    }
    std::map<int, int> gap_of_root;
    for (const auto& [r, i] : longest) {
      const SegPiece& w = win[size_t(i)];
      if (length(w.b - w.a) < 0.3) continue;
      gap_of_root[r] = int(gaps.size());
      gaps.push_back({w.a, w.b, false, 0.5 * (w.a + w.b)});
    }
    for (size_t i = 0; i < win.size(); ++i)
      if (auto it = gap_of_root.find(root(int(i))); it != gap_of_root.end()) window_of[i] = it->second;
  }

  // Wall lines: everything on the wall layers, the straight lines of the door layers
  // (door frames and jambs, the caps of the wall's ends in a door block, partitions drawn
  // with their doors, as in ground-floor-lhs.dxf; a door's swing is never a wall), and
  // the window lines, each carrying its window: the room closes at the window's lines,
  // and its face there is the window.
  struct WallLine { Vec2 a, b; int closes = -1; };
  // Swings drawn where the walls are (wall_swings.h): double-acting doors' half circles on
  // a wall or door layer, layer 0 or in a door block; swings on a wall layer or layer 0.
  std::vector<bool> panel(flat.segs.size(), false);  // door leaves and panels: no wall lines
  struct Swing { Vec2 hinge, closed; std::string layer; };
  std::vector<Swing> swings_among_walls;
  {
    std::vector<size_t> seg_of;
    std::vector<WallSwingLine> lines;
    for (size_t i = 0; i < flat.segs.size(); ++i) {
      const SegPiece& s = flat.segs[i];
      if (role[s.layer] == LayerRole::Walls || ((role[s.layer] == LayerRole::Doors || s.door_block) && !s.curved))
        seg_of.push_back(i), lines.push_back({m(s.a), m(s.b), s.curved});
    }
    std::vector<WallSwingArc> arcs;
    std::vector<const ArcPiece*> arc_of;
    for (const auto& [a, in_door_block] : flat.arcs) {
      const LayerRole lr = role[a.layer];
      const bool on_0 = a.layer == "0" && !in_door_block;  // a layer that says nothing
      WallSwingArc w{m(a.c), m(a.p0), m(a.p1), a.r * unit, a.sweep_deg, false, false};
      w.both_ways = a.sweep_deg >= 150 && a.sweep_deg <= 210 && (lr == LayerRole::Walls || lr == LayerRole::Doors || in_door_block || on_0);
      w.one_way = door_swing_sweep(a.sweep_deg) && (lr == LayerRole::Walls || on_0) && !in_door_block;
      if (!door_swing_radius(w.r) || (!w.both_ways && !w.one_way)) continue;
      arcs.push_back(w), arc_of.push_back(&a);
    }
    const WallSwings found = find_wall_swings(lines, arcs);
    for (size_t k = 0; k < lines.size(); ++k)
      if (found.no_wall[k]) panel[seg_of[k]] = true;
    for (const WallSwing& w : found.swings) swings_among_walls.push_back({w.hinge, w.shut, arc_of[w.arc]->layer});
  }
  // Doors drawn without a swing (sliding, pocket, bi-fold, leaves as lines): their panels
  // are no wall lines, and each closes its gap from end to end (swingless_doors.h).
  std::vector<SwinglessDoor> swingless;
  {
    std::vector<std::pair<Vec2, Vec2>> door_lines, wall_lines;
    std::vector<bool> door_line_is_wall;
    std::vector<size_t> seg_of;
    for (size_t i = 0; i < flat.segs.size(); ++i) {
      const SegPiece& s = flat.segs[i];
      if (s.curved || panel[i]) continue;
      const LayerRole r = role[s.layer];
      if (r == LayerRole::Doors || s.door_block) {
        door_lines.push_back({m(s.a), m(s.b)});
        door_line_is_wall.push_back(r == LayerRole::Doors || r == LayerRole::Walls);
        seg_of.push_back(i);
      } else if (r == LayerRole::Walls || r == LayerRole::Windows) {
        wall_lines.push_back({m(s.a), m(s.b)});
      }
    }
    std::vector<Vec2> swing_points;
    for (const auto& [a, in_door_block] : flat.arcs)  // swings (as below), not a bi-fold's small arcs
      if (is_swing(a, in_door_block))
        for (Vec2 p : {a.c, a.p0, a.p1}) swing_points.push_back(m(p));
    for (const Flat::Curve& cv : flat.curves)
      if ((role[cv.layer] == LayerRole::Doors || cv.door_block) && !cv.pts.empty())
        for (Vec2 p : {cv.pts.front(), cv.pts.back()}) swing_points.push_back(m(p));
    for (const Swing& sw : swings_among_walls)
      for (Vec2 p : {sw.hinge, sw.closed}) swing_points.push_back(p);
    swingless = find_swingless_doors(door_lines, door_line_is_wall, wall_lines, swing_points);
    for (SwinglessDoor& d : swingless) {
      for (int& i : d.lines) i = int(seg_of[size_t(i)]);  // now indices into flat.segs
      if (d.placed)
        for (int i : d.lines) panel[size_t(i)] = true;
    }
  }
  std::vector<WallLine> walls;
  auto segments_of = [](const std::vector<WallLine>& v) {
    std::vector<std::pair<Vec2, Vec2>> segs;
    segs.reserve(v.size());
    for (const WallLine& w : v) segs.push_back({w.a, w.b});
    return segs;
  };
  for (size_t i = 0; i < flat.segs.size(); ++i) {
    const SegPiece& s = flat.segs[i];
    if (!panel[i] && (role[s.layer] == LayerRole::Walls || (role[s.layer] == LayerRole::Doors && !s.curved)))
      walls.push_back({m(s.a), m(s.b)});
  }
  // Doors drawn over walls not cut for them (uncut_walls.h): the walls opened under them.
  {
    std::vector<SwingArc> swings;
    for (const auto& [a, in_door_block] : flat.arcs)
      if (is_swing(a, in_door_block))
        swings.push_back({m(a.c), m(a.p0), m(a.p1)});
    const OpenedWalls opened = open_walls_under_swings(segments_of(walls), swings);
    if (opened.doors > 0) {
      walls.clear();
      for (const auto& [a, b] : opened.lines) walls.push_back({a, b});
      out.summary.push_back(std::to_string(opened.doors) + " doors drawn over walls not cut for them: the walls opened there");
    }
  }
  for (size_t i = 0; i < win.size(); ++i) walls.push_back({win[i].a, win[i].b, window_of[i]});
  // The gaps a drawing leaves at its wall lines' ends: partitions stopping short, walls'
  // ends left open across their thickness.
  WallLineEnds ends;
  {
    ends = close_wall_line_ends(segments_of(walls));
    for (const auto& [a, b] : ends.added) walls.push_back({a, b});
  }
  for (const HatchPiece& h : flat.hatches)
    if (role[h.layer] == LayerRole::Walls) {
      std::vector<std::vector<Vec2>> rings;
      for (const auto& r : h.rings)
        if (r.size() >= 3) {
          rings.emplace_back();
          for (Vec2 p : r) rings.back().push_back(m(p));
        }
      if (!rings.empty()) arr_in.hatches.push_back(rings);
    }

  // The distance from p to the nearest wall line: from the lines binned near p when one
  // lies within 2 m (exact: any line that near is binned in a cell the query covers), else
  // from all of them.
  SegmentGrid wall_grid(segments_of(walls), 0.5);
  auto near_walls = [&](Vec2 p) {
    constexpr double kReach = 2;
    double best = 1e300;
    wall_grid.near(p, kReach, [&](size_t i) { best = std::min(best, distance_to_segment(p, walls[i].a, walls[i].b)); });
    if (best <= kReach) return best;
    for (const WallLine& s : walls) best = std::min(best, distance_to_segment(p, s.a, s.b));
    return best;
  };
  // Of a swing's two ends the closed one (where the leaf shuts) is the one the leaf is not
  // drawn to: the leaf, a line or thin outline from the hinge, passes through the middle
  // of hinge -> open end. When that does not tell, the end nearer the walls.
  auto closed_end = [&](Vec2 c, Vec2 e0, Vec2 e1) {
    const bool leaf0 = near_walls(0.5 * (c + e0)) < 0.03, leaf1 = near_walls(0.5 * (c + e1)) < 0.03;
    if (leaf0 != leaf1) return leaf0 ? e1 : e0;
    return near_walls(e0) <= near_walls(e1) ? e0 : e1;
  };
  // Door swings close their gaps: hinge to the arc's closed end.
  const size_t window_gaps = gaps.size();
  int swings = int(swings_among_walls.size());
  std::vector<Swing> found = swings_among_walls;
  for (const auto& [a0, in_door_block] : flat.arcs) {
    if (!is_swing(a0, in_door_block)) continue;
    ++swings;
    const Vec2 c = m(a0.c), e0 = m(a0.p0), e1 = m(a0.p1);
    found.push_back({c, closed_end(c, e0, e1), a0.layer});
  }
  // Swings drawn as splines (one or several pieces end to end): a quarter circle from P
  // to Q has its hinge C where CP ⟂ CQ and |CP| = |CQ|, on the side the curve bulges from.
  {
    std::vector<const Flat::Curve*> door_curves;
    for (const Flat::Curve& cv : flat.curves)
      if (role[cv.layer] == LayerRole::Doors || cv.door_block) door_curves.push_back(&cv);
    std::vector<bool> used(door_curves.size(), false);
    for (size_t i = 0; i < door_curves.size(); ++i) {
      if (used[i]) continue;
      used[i] = true;
      std::vector<Vec2> pts = door_curves[i]->pts;
      for (bool grew = true; grew;) {
        grew = false;
        for (size_t j = 0; j < door_curves.size(); ++j) {
          if (used[j] || door_curves[j]->chain != door_curves[i]->chain) continue;
          const std::vector<Vec2>& q = door_curves[j]->pts;
          const double tol = 0.002 / unit;
          if (length(q.front() - pts.back()) < tol) pts.insert(pts.end(), q.begin() + 1, q.end());
          else if (length(q.back() - pts.back()) < tol) pts.insert(pts.end(), q.rbegin() + 1, q.rend());
          else if (length(q.back() - pts.front()) < tol) pts.insert(pts.begin(), q.begin(), q.end() - 1);
          else if (length(q.front() - pts.front()) < tol) pts.insert(pts.begin(), q.rbegin(), q.rend() - 1);
          else continue;
          used[j] = grew = true;
        }
      }
      const Vec2 p = m(pts.front()), q = m(pts.back()), mid = m(pts[pts.size() / 2]);
      const double chord = length(q - p), r = chord / std::sqrt(2.0);
      if (!door_swing_radius(r)) continue;
      const Vec2 half = 0.5 * (p + q), n = 0.5 * Vec2{-(q.y - p.y), q.x - p.x};  // half the chord, across it
      for (const Vec2 c : {half + n, half - n}) {
        if (std::fabs(length(mid - c) - r) > 0.08 * r) continue;
        ++swings;
        found.push_back({c, closed_end(c, p, q), door_curves[i]->layer});
        break;
      }
    }
  }
  // A swing is placed when its hinge is at a wall and its closed end at a wall too, or
  // at the closed end of another swing (the two leaves of a double door meet midway).
  // (Points binned in 10 cm cells: a plan of thousands of doors compares each with its
  // neighbours only.)
  auto bin_of = [](Vec2 p) { return std::pair<int64_t, int64_t>(int64_t(std::floor(p.x / 0.1)), int64_t(std::floor(p.y / 0.1))); };
  auto for_near = [&](const std::map<std::pair<int64_t, int64_t>, std::vector<size_t>>& bins, Vec2 p, auto&& f) {
    const auto [bx, by] = bin_of(p);
    for (int64_t x = bx - 1; x <= bx + 1; ++x)
      for (int64_t y = by - 1; y <= by + 1; ++y)
        if (auto it = bins.find({x, y}); it != bins.end())
          for (size_t k : it->second) f(k);
  };
  std::map<std::pair<int64_t, int64_t>, std::vector<size_t>> closed_at, door_gap_at;  // swings by closed end, gaps by hinge
  for (size_t j = 0; j < found.size(); ++j) closed_at[bin_of(found[j].closed)].push_back(j);
  for (size_t i = 0; i < found.size(); ++i) {
    const Swing& sw = found[i];
    bool twice = false, meets = false;
    for_near(door_gap_at, sw.hinge, [&](size_t g) {
      twice = twice || (length(gaps[g].a - sw.hinge) < 0.02 && length(gaps[g].b - sw.closed) < 0.02);
    });
    for_near(closed_at, sw.closed, [&](size_t j) {
      meets = meets || (j != i && length(found[j].closed - sw.closed) < 0.05 && length(found[j].hinge - sw.hinge) > 0.3);
    });
    if (twice) continue;
    if (near_walls(sw.hinge) > 0.15 || (near_walls(sw.closed) > 0.15 && !meets)) {
      plan.warnings.push_back("the door swing at (" + format_number("%.2f", sw.hinge.x) + ", " +
                              format_number("%.2f", sw.hinge.y) + ") m, layer '" + sw.layer +
                              "', is in no wall gap: not placed");
      continue;
    }
    door_gap_at[bin_of(sw.hinge)].push_back(gaps.size());
    gaps.push_back({sw.hinge, sw.closed, true, sw.hinge});
  }
  int swingless_placed = 0;
  for (const SwinglessDoor& d : swingless) {
    const std::string& layer = flat.segs[size_t(d.lines.front())].layer;
    if (!d.placed) {
      plan.warnings.push_back("the door-sized lines at (" + format_number("%.2f", d.where.x) + ", " +
                              format_number("%.2f", d.where.y) + ") m, layer '" + layer +
                              "', drawn without a swing, lie in no wall gap: not placed");
      continue;
    }
    ++swingless_placed;
    gaps.push_back({d.a, d.b, true, d.where});
  }
  // The lines across the door gaps, into the jambs. They run along the walls' faces,
  // where a jamb's corner may lie a rounding beside them: such ends are joined to them.
  std::vector<WallLine> across;
  for (size_t g = window_gaps; g < gaps.size(); ++g) {
    const Vec2 d = gaps[g].b - gaps[g].a;
    const double len = length(d);
    if (len < 1e-3) continue;
    const Vec2 u = (0.03 / len) * d;  // into the jambs
    across.push_back({gaps[g].a - u, gaps[g].b + u, int(g)});
  }
  {
    std::vector<std::pair<Vec2, Vec2>> lines = segments_of(walls);
    for (const WallLine& s : across) lines.push_back({s.a, s.b});
    const auto joins = join_wall_line_ends(lines, walls.size());
    ends.joined += int(joins.size());
    for (const auto& [a, b] : joins) walls.push_back({a, b});
  }
  // Snap to 0.1 mm, and reach 1 mm past each end that no other line ends at, so that
  // lines drawn to meet do meet. Ends drawn at one point stay there: carried on, two
  // lines drawn end to end in one direction would lie side by side a rounding apart.
  auto snap = [](Vec2 p) { return Vec2{std::round(p.x * 1e4) / 1e4, std::round(p.y * 1e4) / 1e4}; };
  {
    std::map<std::pair<double, double>, int> ends_at;
    for (const WallLine& s : walls)
      if (length(s.b - s.a) >= 1e-4)
        for (Vec2 p : {snap(s.a), snap(s.b)}) ++ends_at[{p.x, p.y}];
    auto shared = [&](Vec2 p) { return ends_at[{p.x, p.y}] > 1; };
    for (const WallLine& s : walls) {
      const double len = length(s.b - s.a);
      if (len < 1e-4) continue;
      const Vec2 u = (kWallLineCarriedOn / len) * (s.b - s.a), a = snap(s.a), b = snap(s.b);
      arr_in.segments.push_back({shared(a) ? a : snap(s.a - u), shared(b) ? b : snap(s.b + u), s.closes});
    }
  }
  for (const WallLine& s : across) arr_in.segments.push_back({snap(s.a), snap(s.b), s.closes});

  // Room names: texts, and closed polylines on "Room - NAME" layers.
  std::vector<std::string> probe_name;
  for (const TextPiece& t : flat.texts)
    if (!t.text.empty() && role[t.layer] == LayerRole::None && !names_openings(t.layer)) {
      arr_in.probes.push_back(m(t.p));
      probe_name.push_back(t.text);
    }
  for (const auto& [ring, l] : flat.closed) {
    const std::string n = lower(l);
    if (n.rfind("room - ", 0) != 0 && n.rfind("room-", 0) != 0 && n.rfind("raum - ", 0) != 0) continue;
    std::vector<Vec2> r;
    for (Vec2 p : ring) r.push_back(m(p));
    arr_in.probes.push_back(centroid(r));
    probe_name.push_back(l.substr(l.find_first_of("-") + 1 + (l[l.find_first_of("-") + 1] == ' ')));
  }

  const WallArrangement arr = arrange_walls(arr_in);
  if (arr.spaces.empty())
    throw PlanError(file, "the lines on the wall layers " + [&] {
      std::string l;
      for (const std::string& x : taken[int(LayerRole::Walls)]) l += (l.empty() ? "'" : ", '") + x + "'";
      return l;
    }() + " enclose no space (" + std::to_string(arr.faces) + " closed faces, all narrow enough to be walls): "
          "every room must be closed by wall lines, door swings or window lines; name other wall layers with "
          "--layers 'walls=NAME,NAME;doors=NAME;windows=NAME'" + (col.foreign_note().empty() ? "" : "; " + col.foreign_note()));

  Storey storey;
  storey.name = "ground";
  storey.height = opt.storey_height;
  storey.where = file;
  plan.storeys.push_back(storey);
  std::vector<std::vector<std::string>> names(arr.spaces.size());
  for (size_t p = 0; p < arr.probe_space.size(); ++p) {
    const int sp = arr.probe_space[p];
    if (sp >= 0) {
      if (std::find(names[size_t(sp)].begin(), names[size_t(sp)].end(), probe_name[p]) == names[size_t(sp)].end())
        names[size_t(sp)].push_back(probe_name[p]);
    }
  }
  std::map<std::string, int> used;
  int named_rooms = 0;
  for (size_t i = 0; i < arr.spaces.size(); ++i) {
    Room r;
    for (size_t k = 0; k < names[i].size() && k < 3; ++k) r.name += (k ? " / " : "") + names[i][k];
    if (r.name.empty()) r.name = "space " + std::to_string(i + 1);
    else ++named_rooms;
    if (int n = ++used[r.name]; n > 1) r.name += " (" + std::to_string(n) + ")";
    r.label = arr.spaces[i].inside;
    r.where = {path, 0, 0, "room '" + r.name + "'"};
    plan.rooms.push_back(r);
  }
  std::vector<int> placed(gaps.size(), 0), faces_room(gaps.size(), 0);
  // The opening of gap `gi` along a line `width` long from its start: a door from the
  // floor, a window from its sill (0.9 m), both to 2.1 m, within the storey.
  auto gap_opening = [&](int gi, double width) {
    const bool door = gaps[size_t(gi)].door;
    Opening o;
    o.kind = door ? OpeningKind::Door : OpeningKind::Window;
    o.name = (door ? "door " : "window ") + std::to_string(gi + 1);
    o.at = 0;
    o.width = width;
    o.sill = door ? 0 : std::min(0.9, opt.storey_height / 3);
    o.head = std::min(2.1, opt.storey_height);
    o.where = {path, 0, 0, o.name};
    return o;
  };
  int doors = 0, windows = 0;
  for (const Sheet& s : arr.sheets) {
    Wall w;
    w.name = "wall " + std::to_string(plan.walls.size() + 1);
    w.thickness = 0;
    w.centre = {s.a, s.b};
    w.from_arc = {false};
    w.where = {path, 0, 0, "wall '" + w.name + "'"};
    // On a closing line: between two spaces any piece is the opening; onto a wall face
    // or the outside (a door out of the building, a window in an outer wall) a piece wide
    // enough to be one, not a sliver beside a door frame.
    if (s.closes >= 0) faces_room[size_t(s.closes)] = 1;  // a sheet: a room on one side at least
    if (s.closes >= 0 && (s.between_spaces || s.beside_gap_face || length(s.b - s.a) >= 0.25)) {
      const Gap& g = gaps[size_t(s.closes)];
      const Opening o = gap_opening(s.closes, length(s.b - s.a));
      if (o.width > 0.01) {
        if (!placed[size_t(s.closes)]) (g.door ? doors : windows) += 1;
        placed[size_t(s.closes)] = 1;
        w.openings.push_back(o);
      }
    }
    plan.walls.push_back(w);
  }
  // The faces lying in a gap (a window's glass between its lines): free from sill to
  // head, as a wall of their own shape with the opening across all of it.
  for (const GapFace& f : arr.gap_faces) {
    const Gap& g = gaps[size_t(f.closes)];
    Wall w;
    w.name = "wall " + std::to_string(plan.walls.size() + 1) + " (in " + (g.door ? "door " : "window ") +
             std::to_string(f.closes + 1) + ")";
    size_t longest = 0;
    for (size_t k = 0; k < f.poly.size(); ++k)
      if (length(f.poly[(k + 1) % f.poly.size()] - f.poly[k]) >
          length(f.poly[(longest + 1) % f.poly.size()] - f.poly[longest]))
        longest = k;
    const Vec2 a = f.poly[longest], b = f.poly[(longest + 1) % f.poly.size()];
    double width = 0;
    for (Vec2 p : f.poly) width = std::max(width, std::fabs(cross(b - a, p - a)) / length(b - a));
    w.centre = {a, b};
    w.from_arc = {false};
    w.thickness = width;
    w.footprint = f.poly;
    w.where = {path, 0, 0, "wall '" + w.name + "'"};
    w.openings.push_back(gap_opening(f.closes, length(b - a)));
    plan.walls.push_back(w);
  }
  for (size_t g = 0; g < gaps.size(); ++g)
    if (!placed[g])
      plan.warnings.push_back(std::string(gaps[g].door ? "the door" : "the window") + " at (" +
                              format_number("%.2f", gaps[g].where.x) + ", " + format_number("%.2f", gaps[g].where.y) +
                              ") m " +
                              (faces_room[g] ? "has a closed room on one side only, and less than 0.25 m of its line faces it"
                                             : "has no closed room on either side (the walls around it leave a gap "
                                               "elsewhere, or it is in no wall gap)") +
                              ": not placed");
  int outside_texts = 0;
  for (int sp : arr.probe_space) outside_texts += sp == -2;
  // Storeys drawn side by side: titles outside every room naming two or more storeys.
  std::vector<std::string> storey_titles;
  for (size_t p = 0; p < arr.probe_space.size(); ++p)
    if (arr.probe_space[p] == -2 && names_a_storey(probe_name[p]) &&
        std::find(storey_titles.begin(), storey_titles.end(), probe_name[p]) == storey_titles.end())
      storey_titles.push_back(probe_name[p]);
  if (storey_titles.size() >= 2) {
    std::string list;
    for (const std::string& t : storey_titles) list += (list.empty() ? "'" : ", '") + t + "'";
    plan.warnings.push_back("the drawing's titles name " + std::to_string(storey_titles.size()) + " storeys (" + list +
                            "): storeys drawn side by side are read as one storey, beside each other (Avenues does not "
                            "stack them); to walk one storey alone, save it as a drawing of its own");
  }
  if (outside_texts > 0)
    plan.warnings.push_back(std::to_string(outside_texts) +
                            " texts lie outside every closed room (the walls around them may not close)");
  for (const std::string& b : flat.missing_blocks) plan.warnings.push_back("INSERT of an undefined block '" + b + "'");

  auto joined = [](const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "'" : ", '") + x + "'";
    return s.empty() ? std::string("none") : s;
  };
  if (const size_t n = col.paper.segs.size() + col.paper.texts.size() + col.paper.hatches.size() + col.paper.inserts.size(); n > 0)
    out.summary.push_back(std::to_string(n) + " lines, texts, fills and inserts in paper space (a layout's sheet, not the plan) left out");
  out.summary.push_back("walls from layers " + joined(taken[int(LayerRole::Walls)]));
  out.summary.push_back("doors from layers " + joined(taken[int(LayerRole::Doors)]) + " and door blocks: " +
                        std::to_string(swings) + " swings, " +
                        std::to_string(swingless_placed) + " doors without a swing (sliding, pocket, folding)");
  out.summary.push_back("windows from layers " + joined(taken[int(LayerRole::Windows)]));
  out.summary.push_back("unit " + unit_said);
  out.summary.push_back(std::to_string(ends.joined) + " short lines joining wall line ends to a line they stop within 2 mm of; " +
                        std::to_string(ends.free_ends) + " ends touching no line: " +
                        std::to_string(ends.extended) + " carried on to the line they stop short of, " +
                        std::to_string(ends.capped) + " pairs joined across a wall's end");
  out.summary.push_back(std::to_string(arr.faces) + " faces in the walls' arrangement, " + std::to_string(arr.wall_faces) +
                        " of them wall (" + std::to_string(arr.hatched_faces) + " by hatching), " +
                        std::to_string(arr.gap_faces.size()) + " in door and window gaps (open)");
  out.summary.push_back(std::to_string(plan.walls.size()) + " walls, " + std::to_string(doors) + " doors, " +
                        std::to_string(windows) + " windows, " + std::to_string(plan.rooms.size()) + " rooms (" +
                        std::to_string(named_rooms) + " named from text)");
  return out;
}

}  // namespace avenues
