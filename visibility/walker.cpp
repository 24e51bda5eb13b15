// Avenues — the walking eye (see walker.h).
#include "visibility/walker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "plans/mesh.h"
#include "visibility/stereo.h"

namespace avenues {

namespace {

constexpr double kTol = 1e-9;         // [m] a point this close to a portal's plane and edges is on it
constexpr int kMaxCellsPerCast = 4096;  // a segment crossing more cells is taken as blocked
constexpr double kKneeMargin = 0.02;  // [m] the knee stands this much above the highest step

Vec3 unit(Vec3 v) {
  const double l = length(v);
  return l > 0 ? (1.0 / l) * v : Vec3{};
}

/// Where segment a + t·d, t in [t0, t1], first meets a triangle of `cell`'s detail
/// (CellComplex::detail_boxes): its t (HUGE_VAL for none) and the triangle's normal turned
/// along d (as a face's outward normal: out of the free space the segment leaves). A
/// segment starting on a triangle's plane (within kTol) is leaving it, and passes.
double detail_hit(const CellComplex& c, CellId cell, Vec3 a, Vec3 d, double t0, double t1, Vec3& normal) {
  double best = HUGE_VAL;
  if (size_t(cell) + 1 >= c.detail_start.size()) return best;
  Box3 span;
  span.add(a + t0 * d), span.add(a + std::min(t1, 1.0) * d);
  for (int32_t i = c.detail_start[size_t(cell)]; i < c.detail_start[size_t(cell) + 1]; ++i) {
    const CellComplex::DetailBox& db = c.detail_boxes[size_t(i)];
    if (!db.box.meets(span)) continue;
    const Mesh& m = *c.objects[size_t(db.object)].model;
    for (const auto& k : m.triangles) {
      const Triangle3 tri{m.vertices[size_t(k[0])], m.vertices[size_t(k[1])], m.vertices[size_t(k[2])]};
      double t, u, v;
      if (!line_plane_hit(tri, a, d, &t, &u, &v)) continue;
      // Edges and corners count, as for a detail solid (ClosedSurface::entry).
      if (!(t >= t0 && t <= t1 && t < best && u >= 0 && v >= 0 && u + v <= 1)) continue;
      const Vec3 n = cross(tri[1] - tri[0], tri[2] - tri[0]);
      const double ln = length(n), rate = dot(n, d) / ln;
      if (!(std::fabs(t * rate) > kTol)) continue;  // the start on its plane: leaving it
      best = t;
      normal = (rate > 0 ? 1.0 : -1.0) * ((1 / ln) * n);
    }
  }
  return best;
}

}  // namespace

const char* to_string(MoveMode m) { return m == MoveMode::Walk ? "walk" : "fly"; }

SegmentCast cast_segment(const CellComplex& complex, CellId from, Vec3 a, Vec3 b) {
  SegmentCast r;
  r.cell = from;
  if (from < 0 || from >= CellId(complex.cells.size())) {
    r.t = 0;
    r.blocked = true;
    return r;
  }
  const Vec3 d = b - a;
  const double scale = 1 + std::fabs(a.x) + std::fabs(a.y) + std::fabs(a.z);
  // A detail solid (a curved object the cells run through) stops the segment where it
  // first enters one.
  SurfaceEntry solid;
  if (!complex.detail_solids.empty()) {
    Box3 span;
    span.add(a), span.add(b);
    for (const ClosedSurface& s : complex.detail_solids) {
      if (!s.box().meets(span)) continue;
      const SurfaceEntry e = s.entry(a, b);
      if (e.hit && e.t < solid.t) solid = e;
    }
  }
  double t = 0;
  CellId cell = from;
  for (int steps = 0; steps < kMaxCellsPerCast; ++steps) {
    const Cell& here = complex.cells[size_t(cell)];
    // Where the segment leaves this convex cell: the first face it crosses outwards.
    double t_exit = HUGE_VAL;
    size_t exit_face = 0;
    for (size_t f = 0; f < here.faces.size(); ++f) {
      const double rate = dot(here.faces[f].plane.n, d);
      if (!(rate > 0)) continue;
      const double te = -here.faces[f].plane.eval(a) / rate;
      if (te < t_exit) t_exit = te, exit_face = f;
    }
    if (solid.hit && !(t_exit < solid.t)) {
      r.t = std::max(t, solid.t);
      r.blocked = true;
      r.cell = cell;
      r.normal = -1.0 * solid.normal;  // as a face's: out of the free space it bounds
      return r;
    }
    // A large soup's detail in this cell (a wall or slab that cuts no space) stops it too.
    if (!complex.detail_boxes.empty()) {
      Vec3 normal;
      const double hit = detail_hit(complex, cell, a, d, t, std::min(t_exit, 1.0), normal);
      if (hit < HUGE_VAL) {
        r.t = hit;
        r.blocked = true;
        r.cell = cell;
        r.normal = normal;
        return r;
      }
    }
    if (!(t_exit < 1)) {
      r.t = 1;
      r.cell = cell;
      return r;
    }
    t = std::max(t, t_exit);  // rounding never takes the walk backwards
    const Vec3 q = a + t * d;
    // The portal at q in a face the segment leaves by (at an edge, q lies on several).
    CellId next = kNoCell;
    bool stair = false;
    for (const Face& f : here.faces) {
      if (!(dot(f.plane.n, d) > 0) || std::fabs(f.plane.eval(q)) > kTol * scale) continue;
      for (PortalId pi : f.portals) {
        const Portal& p = complex.portals[size_t(pi)];
        if (in_convex_polygon(p.poly, p.plane.n, q, kTol)) {
          next = p.other(cell);
          stair = p.kind == PortalKind::Stairwell;
          break;
        }
      }
      if (next != kNoCell) break;
    }
    if (next == kNoCell) {
      r.t = t;
      r.blocked = true;
      r.cell = cell;
      r.normal = here.faces[exit_face].plane.n;
      return r;
    }
    r.stairwell |= stair;
    cell = next;
  }
  r.t = t;
  r.blocked = true;
  r.cell = cell;
  return r;
}

Walker::Walker(const CellComplex& complex, Vec3 eye, const WalkerOptions& options)
    : c_(complex), options_(options), eye_(eye) {
  if (!(options.eye_height > options.step_height && options.step_height >= 0 && options.clearance >= 0 &&
        options.fall_speed > 0))
    throw std::runtime_error("walker: the eye height must exceed the step height, and speeds be positive");
  const Location at = complex.locate(eye);
  if (at.what != Location::What::Cell)
    throw std::runtime_error(at.what == Location::What::Solid ? "the eye is inside " + at.solid
                                                              : std::string("the eye is outside the far box"));
  cell_ = at.cell;
  if (complex.storeys.empty()) {
    // The lowest corner of an opaque piece that is not the far box's.
    const Box3& far = complex.far_box;
    const double tol = 1e-9 * (1 + std::max({std::fabs(far.lo.x), std::fabs(far.hi.x), std::fabs(far.lo.y),
                                              std::fabs(far.hi.y), std::fabs(far.lo.z), std::fabs(far.hi.z)}));
    auto on = [tol](double v, double bound) { return std::fabs(v - bound) <= tol; };
    double lowest = HUGE_VAL;
    for (const Cell& cell : complex.cells)
      for (const Face& face : cell.faces)
        for (const OpaquePoly& piece : face.opaque) {
          if (piece.poly.empty()) continue;
          bool far_face[6] = {true, true, true, true, true, true};
          double low = HUGE_VAL;
          for (Vec3 p : piece.poly) {
            far_face[0] &= on(p.x, far.lo.x), far_face[1] &= on(p.x, far.hi.x), far_face[2] &= on(p.y, far.lo.y);
            far_face[3] &= on(p.y, far.hi.y), far_face[4] &= on(p.z, far.lo.z), far_face[5] &= on(p.z, far.hi.z);
            low = std::min(low, p.z);
          }
          if (std::none_of(far_face, far_face + 6, [](bool b) { return b; })) lowest = std::min(lowest, low);
        }
    // Detail stands on the ground too: a curved solid (a duck alone is all detail), a
    // large soup's small polygons.
    for (const ClosedSurface& s : complex.detail_solids) lowest = std::min(lowest, s.box().lo.z);
    for (const Object& o : complex.objects)
      if (o.cell >= 0 && o.model)
        for (Vec3 v : o.model->vertices) lowest = std::min(lowest, v.z);
    if (lowest < HUGE_VAL) ground_ = lowest;
  }
}

SegmentCast Walker::cast_from(Vec3 p, CellId hint, Vec3 q) const {
  const Cell& h = c_.cells[size_t(hint)];
  CellId start = hint;
  if (!h.contains(p)) {
    const Location at = c_.locate(p, hint);
    if (at.what != Location::What::Cell) {
      SegmentCast r;
      r.t = 0;
      r.blocked = true;
      r.cell = kNoCell;
      return r;
    }
    start = at.cell;
  }
  return cast_segment(c_, start, p, q);
}

double Walker::side_room(Vec3 p, CellId cell) const {
  const double r = options_.clearance;
  if (!(r > 0)) return 0;
  double room = r;
  for (const Vec3 axis : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}}) {
    const SegmentCast s = cast_from(p, cell, p + r * axis);
    if (s.blocked) room = std::min(room, s.t * r);
  }
  return room;
}

bool Walker::commit(Vec3 p, CellId c) {
  const Location at = c_.locate(p, c >= 0 ? c : cell_);
  if (at.what != Location::What::Cell) return false;
  eye_ = p;
  cell_ = at.cell;
  return true;
}

bool Walker::try_move(Vec3 d, Vec3* blocked_normal) {
  return mode_ == MoveMode::Walk ? try_walk(d, blocked_normal) : try_fly(d, blocked_normal);
}

bool Walker::try_fly(Vec3 d, Vec3* blocked_normal) {
  const Vec3 ahead = d + options_.clearance * unit(d);
  const SegmentCast e = cast_segment(c_, cell_, eye_, eye_ + ahead);
  if (e.blocked) {
    if (blocked_normal) *blocked_normal = e.normal;
    return false;
  }
  const SegmentCast to = cast_segment(c_, cell_, eye_, eye_ + d);
  const Vec3 p = eye_ + d;
  if (to.blocked || side_room(p, to.cell) < std::min(options_.clearance, side_room(eye_, cell_)) - kTol) return false;
  return commit(p, to.cell);
}

bool Walker::try_walk(Vec3 d, Vec3* blocked_normal) {
  d.z = 0;
  if (!(length(d) > 0)) return true;
  const Vec3 ahead = d + options_.clearance * unit(d);
  // The eye: through the portals, a clearance short of any wall.
  const SegmentCast e = cast_segment(c_, cell_, eye_, eye_ + ahead);
  if (e.blocked) {
    if (blocked_normal) *blocked_normal = e.normal;
    return false;
  }
  // The knee, just above the highest step: a window's sill or a low wall stops it.
  const Vec3 knee = eye_ - Vec3{0, 0, options_.eye_height - options_.step_height - kKneeMargin};
  const Location knee_at = c_.locate(knee, cell_);
  if (knee_at.what == Location::What::Cell) {
    const SegmentCast k = cast_segment(c_, knee_at.cell, knee, knee + ahead);
    if (k.blocked) {
      if (blocked_normal) *blocked_normal = k.normal;
      return false;
    }
  }
  const SegmentCast to = cast_segment(c_, cell_, eye_, eye_ + d);
  if (to.blocked) return false;
  Vec3 p = eye_ + d;
  CellId cell = to.cell;
  if (side_room(p, cell) < std::min(options_.clearance, side_room(eye_, cell_)) - kTol) return false;
  // A floor up to a step higher: step up onto it (with the head clear).
  bool stairwell = false;
  const double floor = face_under(p, cell, &stairwell);
  const double feet = eye_.z - options_.eye_height;
  if (!stairwell && floor > feet + kTol) {
    if (floor > feet + options_.step_height + kTol) return false;
    const double target = floor + options_.eye_height;
    if (target > p.z) {
      const SegmentCast up = cast_segment(c_, cell, p, {p.x, p.y, target + options_.clearance});
      if (up.blocked) return false;
      const SegmentCast rise = cast_segment(c_, cell, p, {p.x, p.y, target});
      p.z = target;
      cell = rise.cell;
    }
  }
  return commit(p, cell);
}

double Walker::face_under(Vec3 p, CellId cell, bool* stairwell) const {
  const double depth = p.z - c_.far_box.lo.z + 1;
  const SegmentCast down = cast_segment(c_, cell, p, p - Vec3{0, 0, depth});
  if (stairwell) *stairwell = down.stairwell;
  return p.z - down.t * depth;
}

double Walker::floor_below() const {
  const double face = face_under(eye_, cell_);
  return eye_.z >= ground_ && ground_ > face ? ground_ : face;
}

bool Walker::on_stair() const {
  const double span = c_.far_box.hi.z - c_.far_box.lo.z + 1;
  if (cast_segment(c_, cell_, eye_, eye_ - Vec3{0, 0, span}).stairwell) return true;
  return cast_segment(c_, cell_, eye_, eye_ + Vec3{0, 0, span}).stairwell;
}

bool Walker::try_climb(double dz) {
  if (dz == 0 || !on_stair()) return false;
  const double span = c_.far_box.hi.z - c_.far_box.lo.z + 1;
  double z = eye_.z + dz;
  if (dz > 0) {
    // Up the stair: never into the ceiling; and once no stairwell is left above, no higher
    // than eye height above the floor the stair arrives at (the top of the hole below).
    const SegmentCast up = cast_segment(c_, cell_, eye_, eye_ + Vec3{0, 0, span});
    z = std::min(z, eye_.z + up.t * span - options_.clearance);
    if (!up.stairwell) {
      const SegmentCast down = cast_segment(c_, cell_, eye_, eye_ - Vec3{0, 0, span});
      // The first stairwell portal below (the landing's floor hole), else the floor.
      double landing = eye_.z - down.t * span;
      const Cell& here = c_.cells[size_t(cell_)];
      if (down.stairwell) landing = here.z0;  // the eye's cell stands on the hole's top
      z = std::min(z, landing + options_.eye_height);
    }
    if (!(z > eye_.z)) return false;
  } else {
    z = std::max(z, floor_below() + options_.eye_height);
    if (!(z < eye_.z)) return false;
  }
  const SegmentCast to = cast_segment(c_, cell_, eye_, {eye_.x, eye_.y, z});
  if (to.blocked) return false;
  return commit({eye_.x, eye_.y, z}, to.cell);
}

void Walker::settle(double dt) {
  if (on_stair()) return;  // a stair holds the eye at its height
  const double floor = floor_below();
  const double target = floor + options_.eye_height;
  if (eye_.z > target) {
    const double z = std::max(target, eye_.z - options_.fall_speed * std::max(dt, 0.0));
    const SegmentCast to = cast_segment(c_, cell_, eye_, {eye_.x, eye_.y, z});
    if (!to.blocked) commit({eye_.x, eye_.y, z}, to.cell);
  } else if (eye_.z < target) {
    // Below eye height (after flying low): rise, a step at once, else at the fall speed.
    double z = target - eye_.z <= options_.step_height ? target : eye_.z + options_.fall_speed * std::max(dt, 0.0);
    z = std::min(z, target);
    const SegmentCast up = cast_segment(c_, cell_, eye_, {eye_.x, eye_.y, z + options_.clearance});
    if (up.blocked) z = std::min(z, eye_.z + up.t * (z + options_.clearance - eye_.z) - options_.clearance);
    if (!(z > eye_.z)) return;
    const SegmentCast to = cast_segment(c_, cell_, eye_, {eye_.x, eye_.y, z});
    if (!to.blocked) commit({eye_.x, eye_.y, z}, to.cell);
  }
}

double Walker::move(Vec3 delta, double dt) {
  const Vec3 start = eye_;
  Vec3 h = delta;
  if (mode_ == MoveMode::Walk) h.z = 0;
  if (length(h) > 0) {
    Vec3 n;
    if (!try_move(h, &n)) {
      // Slide: the move less its part into the wall it met, else each axis on its own.
      if (mode_ == MoveMode::Walk) n.z = 0;
      n = unit(n);
      bool slid = false;
      if (length(n) > 0) {
        const Vec3 along = h - dot(h, n) * n;
        if (length(along) > 1e-6 * length(h)) slid = try_move(along, nullptr);
      }
      if (!slid) {
        if (h.x != 0) try_move({h.x, 0, 0}, nullptr);
        if (h.y != 0) try_move({0, h.y, 0}, nullptr);
        if (mode_ == MoveMode::Fly && h.z != 0) try_move({0, 0, h.z}, nullptr);
      }
    }
  }
  if (mode_ == MoveMode::Walk) {
    if (delta.z != 0) try_climb(delta.z);
    settle(dt);
  }
  return length(eye_ - start);
}

}  // namespace avenues
