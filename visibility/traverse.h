// Avenues — the traversal, generic over its number type T (internal to visibility/).
//
// Jones 1971: "On arriving at a node ... there will be a representation of the current
// mask ... the first opening of the cell is examined ... A new mask is formed from the
// intersection of the current mask and the boundary of the opening projected on to the
// picture plane. If the intersection is empty then this opening is not visible ...
// Otherwise ... the algorithm now descends a level." Like Godot's portal tracer we skip
// portals seen from behind first; unlike it there is no depth cap — a cell already on the
// current avenue is never entered again (a straight ray cannot revisit a convex cell),
// which bounds the search even where rounding errs.
//
// Avenues that add nothing (TraverseParams::prune_covered): an avenue into a cell whose
// mask lies inside the mask of an avenue already found into that cell shows nothing the
// other does not, and neither does anything beyond it (every ray through it passes the
// same portals beyond the cell as the other's rays do), so it is not followed. The test is
// convex in convex, exact in the exact kernels and conservative in float and double
// (Mask::inside); an exactly equal mask (Mask::same_as) counts as inside in every kernel.
// The union of masks per cell, and so every drawing made from them, is unchanged. In exact
// arithmetic in a complex whose cells do not overlap, two avenues into one cell see
// disjoint sets of rays (a ray's chain of cells is unique), so what this prunes are the
// near-duplicates rounding and degenerate portals (stacked, or met edge-on) make. Measured
// (docs/PERFORMANCE.md, issue 18) on 3,400 random views of 17 plans, homes and Doom maps, it
// pruned nothing and cost time (the bookkeeping per avenue), so it is off by default.
//
// What multiplies avenues is not covering but parting: an outside sliced into many cells
// parts one cell's view into many disjoint pieces, one per chain of portals, and each
// goes on alone. The merged search (TraverseParams::merge_pieces, below) lets the pieces
// that reach a cell wait for one another, joins those whose union is convex
// (Mask::absorb), and only then goes on: the same rays per cell, fewer avenues.
//
// The projection is a parameter of the camera. Perspective: rays from the eye, and the
// plane of a portal edge passes through the eye. Parallel: every ray runs along forward
// from a point of the picture plane, so the avenues are prisms, not cones; the plane of a
// portal edge contains the direction, and a mask is the portals projected orthographically.
// A parallel search starts on a cut plane (run_cut): each cell the plane crosses is seen
// through its own cross-section, convex as the cell is, and the search goes on from there.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <boost/container/small_vector.hpp>

#include "visibility/mask.h"
#include "visibility/visible_set.h"

namespace avenues::detail {

template <class T>
double to_double_of(const T& x);

template <class T>
struct Vec3T {
  T x, y, z;
};
template <class T>
Vec3T<T> sub(const Vec3T<T>& a, const Vec3T<T>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T>
Vec3T<T> crossT(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
T dotT(const Vec3T<T>& a, const Vec3T<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// How the pieces of view that reach one cell are joined before the search goes on from it:
/// not at all (Jones), where their union is convex (merged: exact), or into their convex
/// hull (hull: conservative, for pictures that resolve depth).
enum class Join : uint8_t { None, Convex, Hull };

template <class T>
class Traversal {
 public:
  /// `strip` (perspective): the search through that part of the window only.
  Traversal(const CellComplex& c, const Camera& cam, bool prune_covered, VisibleSet& out, Join join = Join::None,
            const TraverseParams::Strip* strip = nullptr)
      : c_(c), out_(out), prune_(prune_covered && join == Join::None), merge_(join != Join::None),
        hull_(join == Join::Hull) {
    eye_ = in(cam.eye);
    right_ = in(cam.right);
    up_ = in(cam.up);
    forward_ = in(cam.forward);
    const double hw = cam.half_width(), hh = cam.half_height();
    eye_d_ = cam.eye;
    cam_ = cam;
    parallel_ = cam.is_parallel();
    double x0 = cam.shift_x - hw, x1 = cam.shift_x + hw;
    if (strip && !parallel_) x0 = std::max(x0, strip->x0), x1 = std::min(x1, strip->x1);
    window_ = Mask<T>::window(T(x0), T(x1), T(cam.shift_y - hh), T(cam.shift_y + hh));
    // Cells on the current avenue. Every visit clears its mark on the way out, so the
    // buffer is all zero between traversals: keep it per thread, and never clear a
    // 100,000-cell array for a view that sees five cells.
    thread_local std::vector<uint8_t> on_path;
    if (on_path.size() < c.cells.size()) on_path.assign(c.cells.size(), 0);
    on_path_ = on_path.data();
    // Per cell: the last avenue found into it (-1: none), chained back through reached_
    // (the same per-thread, all-clear-between-traversals rule as on_path).
    thread_local std::vector<int32_t> last_into;
    if (last_into.size() < c.cells.size()) last_into.assign(c.cells.size(), -1);
    last_into_ = last_into.data();
    if (c.portal_table.fits(c)) {
      table_ = &c.portal_table;
    } else {  // a complex never indexed (one a test made by hand): laid out for this search
      own_table_ = lay_out_portals(c);
      table_ = &own_table_;
    }
  }

  /// Pieces of view that hold no sample's centre of a half-tone of the camera's size, with
  /// `per_side` samples a side a pixel, are not followed (TraverseParams::samples_per_side).
  void only_through_samples(const Camera& cam, int per_side) {
    if (per_side <= 0) return;
    const ImageToRaster r = cam.image_to_raster();
    sample_.per_side = per_side;
    sample_.left = r.left, sample_.top = r.top;
    sample_.across = r.width * per_side / r.across, sample_.down = r.height * per_side / r.down;
  }

  /// The search from the eye in cell `start`. An eye on the boundary of its cell (within
  /// kOnBoundary: on a sheet wall, in a doorway's plane, at a T-junction of sheets, on an
  /// edge several cells share) stands in every cell that holds it, and each ray leaves it
  /// into the cell its direction points into: every such cell is a root, its mask the
  /// window clipped to the directions that enter it (the cone of the cell's faces through
  /// the eye, a half-plane each on the picture plane). The roots' masks tile the window, so
  /// the picture is their views composed; `start` goes first. Where no root keeps a mask
  /// (looking exactly along a face), `start` is searched through the whole window.
  void run(CellId start) {
    ClearMarks clear{*this};
    if (!on_boundary(start)) {
      root(start, window_);
      drain();
      return;
    }
    std::vector<CellId> roots{start};
    for (CellId id : c_.cells_holding(eye_d_, kOnBoundary))
      if (id != start) roots.push_back(id);
    bool any = false;
    for (CellId id : roots) {
      Mask<T> m = window_;
      bool alive = true;
      for (const Face& f : c_.cells[size_t(id)].faces) {
        const double n = length(f.plane.n);
        if (!(std::fabs(f.plane.eval(eye_d_)) <= kOnBoundary * n)) continue;
        alive = m.clip(trace(in(-1.0 * f.plane.n), eye_));  // directions d with n·d <= 0: into the cell
        if (!alive) break;
      }
      if (!alive || !(m.area2() > T(0))) continue;
      root(id, m);
      any = true;
    }
    if (!any) root(start, window_);
    drain();
  }

  /// A parallel search from a cut plane (its normal not perpendicular to forward): every
  /// cell the closed plane meets is a root, its mask the window clipped to the cell's
  /// cross-section projected on the picture plane. A point (x, y) of the picture starts its
  /// ray at o + t·f on the cut, o = eye + x·r + y·u, t = −(n_c·o + d_c)/(n_c·f); it lies in
  /// face (n, d) when n·o + d + t·(n·f) <= 0, i.e., times k = n_c·f > 0, when
  /// k·(n·o + d) − (n·f)·(n_c·o + d_c) <= 0: a half-plane of degree 2 in the input planes.
  void run_cut(Plane cut) {
    ClearMarks clear{*this};
    if (dot(cut.n, cam_.forward) < 0) cut = {-1.0 * cut.n, -cut.d};
    const Vec3T<T> nc = in(cut.n);
    const T dc = T(cut.d), k = dotT(nc, forward_);
    const T cr = dotT(nc, right_), cu = dotT(nc, up_), ce = dotT(nc, eye_) + dc;
    const double hw = cam_.half_width(), hh = cam_.half_height();
    for (CellId id = 0; id < CellId(c_.cells.size()); ++id) {
      const Cell& cl = c_.cells[size_t(id)];
      // In double, with a margin: does the box meet the plane, and the window?
      const Box3 b = cl.bounds();
      double lo = HUGE_VAL, hi = -HUGE_VAL, x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y, corner & 4 ? b.hi.z : b.lo.z};
        const double e = cut.eval(p), x = dot(p - eye_d_, cam_.right), y = dot(p - eye_d_, cam_.up);
        lo = std::min(lo, e), hi = std::max(hi, e);
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
      const double margin = 1e-6 * (1 + length(b.hi - b.lo) + std::fabs(cut.d));
      if (lo > margin || hi < -margin) continue;
      if (x1 < cam_.shift_x - hw - margin || x0 > cam_.shift_x + hw + margin || y1 < cam_.shift_y - hh - margin ||
          y0 > cam_.shift_y + hh + margin)
        continue;
      Mask<T> m = window_;
      bool alive = true;
      for (size_t f = 0; f < cl.faces.size() && alive; ++f) {
        const Vec3T<T> n = in(cl.faces[f].plane.n);
        const T d = T(cl.faces[f].plane.d), a = dotT(n, forward_);
        alive = m.clip({a * cr - k * dotT(n, right_), a * cu - k * dotT(n, up_), a * ce - k * (dotT(n, eye_) + d)});
      }
      if (!alive || !(m.area2() > T(0))) continue;
      out_.cut_cells.push_back(id);
      root(id, m);
    }
    drain();
  }

 private:
  /// The marks are cleared even when the traversal throws (an exact kernel out of memory,
  /// say): a visit's own clearing is skipped by the unwinding, so clear every cell any
  /// avenue reached. Harmless when they are clear already.
  struct ClearMarks {
    Traversal& t;
    ~ClearMarks() {
      for (const Avenue& a : t.out_.avenues) {
        t.on_path_[size_t(a.cell)] = 0;
        t.last_into_[size_t(a.cell)] = -1;
      }
      for (CellId id : t.touched_) {
        t.state_[size_t(id)] = kIdle;
        t.pieces_[size_t(id)].clear();
        t.waiters_[size_t(id)].clear();
        if (t.hull_) t.reach_[size_t(id)].clear(), t.rounds_[size_t(id)] = 0;
      }
    }
  };

  static Vec3T<T> in(Vec3 v) { return {T(v.x), T(v.y), T(v.z)}; }

  /// Whether two neighbouring corners of a portal are only a rounding apart: two exact
  /// corners (a soup's, say) that rounded to doubles a few units in the last place apart.
  /// The edge between them has no direction of its own: it may even turn the rounded
  /// polygon inward, and the plane through it and the eye would then cut away rays the
  /// portal passes. Such an edge bounds nothing; skipping it widens the rays let through
  /// by a rounding at most (as cone_planes skips coinciding mask vertices).
  static bool rounded_apart(Vec3 a, Vec3 b) {
    const double scale = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z), std::fabs(b.x), std::fabs(b.y),
                                   std::fabs(b.z)});
    const double d = std::max({std::fabs(b.x - a.x), std::fabs(b.y - a.y), std::fabs(b.z - a.z)});
    return d <= 64 * std::numeric_limits<double>::epsilon() * scale;
  }

  /// Whether the eye lies on a face of cell `id` (within kOnBoundary).
  bool on_boundary(CellId id) const {
    for (const Face& f : c_.cells[size_t(id)].faces)
      if (std::fabs(f.plane.eval(eye_d_)) <= kOnBoundary * length(f.plane.n)) return true;
    return false;
  }

  /// Picture-plane half-plane of the world plane with normal n through point p, which
  /// contains the rays' source: perspective, the plane passes through the eye, and it keeps
  /// directions d = x·right + y·up + forward with n·d >= 0; parallel, it contains forward,
  /// and it keeps the rays from o = eye + x·right + y·up with n·(o − p) >= 0.
  HalfPlane<T> trace(const Vec3T<T>& n, const Vec3T<T>& p) const {
    if (parallel_) return {dotT(n, right_), dotT(n, up_), dotT(n, sub(eye_, p))};
    return {dotT(n, right_), dotT(n, up_), dotT(n, forward_)};
  }

  using Corners = typename Mask<T>::Corners;
  using Seen = CellComplex::PortalTable::Seen;

  /// Corner k of the portal seen as s.
  const Vec3& corner(const Seen& s, size_t k) const { return table_->corners[size_t(s.corner0) + k]; }

  /// How a portal faces the eye: its normal N (into p.cell[1], exact in T) and the eye's
  /// side of its plane, s = N·(eye − corner) (parallel: N·(−forward)).
  struct Facing {
    Vec3T<T> N;
    T s;
  };

  void visit(CellId cell, const Mask<T>& mask, int parent, PortalId via, int depth) {
    Corners corners;  // its own: the search recurses from here
    mask.corners(corners);
    const int self = emit(cell, corners, parent, via, depth);
    std::vector<Vec2> mask_here = out_.avenues[size_t(self)].mask;  // a copy: the avenues move as the search adds more
    out_.max_depth = std::max(out_.max_depth, depth);
    on_path_[size_t(cell)] = 1;
    if (prune_) {
      reached_.push_back({mask, box_of(mask_here), last_into_[size_t(cell)]});
      last_into_[size_t(cell)] = self;
    }
    for_each_portal_seen(cell, mask_here, via,
                         [&](const Seen& s, const Facing& fc) { consider(mask, corners, self, depth, s, fc); });
    on_path_[size_t(cell)] = 0;
  }

  /// The mask's vertices in double, as an Avenue keeps them.
  static std::vector<Vec2> doubles_of(const Corners& c) {
    std::vector<Vec2> v;
    v.reserve(c.at.size());
    for (const Point2T<T>& p : c.at) v.push_back({to_double_of(p.x), to_double_of(p.y)});
    return v;
  }
  static std::vector<Vec2> doubles_of(const Mask<T>& m) {
    thread_local Corners c;
    m.corners(c);
    return doubles_of(c);
  }

  /// Appends the avenue (cell, the mask of these corners, ...) to the visible set; returns its index.
  int emit(CellId cell, const Corners& mask, int parent, PortalId via, int depth) {
    Avenue a;
    a.cell = cell;
    a.parent = parent;
    a.portal = via;
    a.depth = depth;
    a.mask = doubles_of(mask);
    out_.avenues.push_back(std::move(a));
    return int(out_.avenues.size()) - 1;
  }

  /// Calls f(portal, its Facing) for each portal of `cell` but `via` (the one the mask came
  /// through) that rays through `mask` (its vertices in double) may pass: each face's
  /// portals, on a long side face (a corridor's wall of doors) only those within the
  /// stretch of wall the mask can see (portals are sorted along side faces), none seen from
  /// behind (facing(), the cheaper test: about half of a cell's portals end there), and
  /// none that the mask's cone surely misses. `mask` must outlive the calls: where f may
  /// append avenues (which moves the visible set's masks), the caller's own copy.
  template <class F>
  void for_each_portal_seen(CellId cell, const std::vector<Vec2>& mask, PortalId via, F&& f) {
    const CellComplex::PortalTable& t = *table_;
    Cone cone;  // made when the first portal not seen edge-on wants it (a plan's cells may have none)
    bool cone_made = false;
    Facing fc;
    auto consider = [&](const Seen& p) {
      if (p.portal == via || !facing(p, fc)) return;
      if (!seen_edge_on(p)) {
        if (!cone_made) cone = cone_planes(mask), cone_made = true;
        if (surely_outside(cone, p)) return;
      }
      f(p, fc);
    };
    const int32_t first_face = t.cell_faces[size_t(cell)], end_face = t.cell_faces[size_t(cell) + 1];
    for (int32_t face = first_face; face < end_face; ++face) {
      // The hull search in floating point: a face's portals into one cell as their hull
      // (PortalTable::hulls), where it has them. What passes the hull holds all that passes
      // each, and the pieces would have been joined into their hull in that cell anyway.
      if (hull_ && std::is_floating_point_v<T> && t.face_hulls[size_t(face)] < t.face_hulls[size_t(face) + 1]) {
        for (int32_t i = t.face_hulls[size_t(face)]; i < t.face_hulls[size_t(face) + 1]; ++i) consider(t.hulls[size_t(i)]);
        continue;
      }
      const Seen* ps = t.seen.data() + t.face_seen[size_t(face)];
      size_t lo = 0, hi = size_t(t.face_seen[size_t(face) + 1] - t.face_seen[size_t(face)]);
      if (hi > kLinearScan) {
        const Cell& cl = c_.cells[size_t(cell)];
        const size_t k = size_t(face - first_face);
        if (cl.prism && k < cl.footprint.size()) side_range(cl, k, ps, hi, mask, lo, hi);
      }
      for (size_t i = lo; i < hi; ++i) consider(ps[i]);
    }
  }

  /// Whether parallel rays see portal p edge-on, in double (a door in a plan): such a
  /// portal lies along the side of a mask's prism, where no plane of it culls the portal;
  /// facing() refuses it exactly.
  bool seen_edge_on(const Seen& p) const {
    return parallel_ && std::fabs(dot(p.plane.n, cam_.forward)) <= 1e-12 * length(p.plane.n);
  }

  /// The mask's cone (perspective) or prism (parallel) as inward planes n·(v − eye) + d >= 0
  /// (world space, double): through the eye, d = 0; along forward, through a mask vertex.
  /// (Inline up to 8 planes: a mask's cone is made for every avenue, and nearly every mask
  /// has no more sides.)
  using Cone = boost::container::small_vector<Plane, 8>;
  Cone cone_planes(const std::vector<Vec2>& mask) const {
    Cone n;
    if (mask.size() < 3) return n;
    auto dir = [&](Vec2 m) { return m.x * cam_.right + m.y * cam_.up + (parallel_ ? Vec3{0, 0, 0} : cam_.forward); };
    Vec2 c{0, 0};
    for (Vec2 m : mask) c = c + (1.0 / double(mask.size())) * m;
    const Vec3 inside = dir(c);
    // The centroid lies left of every side of a convex counter-clockwise mask, and then
    // every plane turned by it supports the mask. Where it does not (see below), each plane
    // is checked against every vertex.
    bool careful = false;
    for (size_t i = 0; i < mask.size() && !careful; ++i) {
      const Vec2 a = mask[i], b = mask[(i + 1) % mask.size()];
      careful = cross(b - a, c - a) < -1e-12 * (1 + std::fabs(a.x) + std::fabs(a.y) + std::fabs(b.x) + std::fabs(b.y));
    }
    for (size_t i = 0; i < mask.size(); ++i) {
      const Vec3 a = dir(mask[i]), b = dir(mask[(i + 1) % mask.size()]);
      Plane plane;
      if (parallel_) {
        Vec3 p = cross(b - a, cam_.forward);
        const double l = length(p);
        if (!(l > 1e-9 * (1 + length(a) + length(b)))) continue;  // as below: too short to give a plane
        p = (1.0 / l) * p;
        if (dot(p, inside - a) < 0) p = -1.0 * p;
        plane = {p, -dot(p, a)};
      } else {
        Vec3 p = cross(a, b);
        const double l = length(p);
        // Two mask vertices that (nearly) coincide give no plane: a normal from a cross
        // product this short is all rounding, and could cull what the mask sees. Skipping
        // a plane only makes the cull more conservative.
        if (!(l > 1e-9 * length(a) * length(b))) continue;
        p = (1.0 / l) * p;
        plane = {dot(p, inside) < 0 ? -1.0 * p : p, 0};
      }
      // Nor does a plane with a vertex of the mask clearly outside it. A mask in floating
      // point can keep, beside an edge, a half-plane nearly parallel to it that bounds
      // nothing; its vertex with the edge lies far off (random plan 8836: (-5.7, -1.6) in a
      // window ±0.51 wide), the centroid above follows it out of the mask, and a plane
      // turned by that centroid culled a portal the mask sees.
      bool supports = true;
      for (size_t j = 0; careful && j < mask.size() && supports; ++j) {
        const Vec3 v = dir(mask[j]);
        supports = plane.eval(v) >= -1e-9 * (parallel_ ? 1 + length(v - a) : length(v));
      }
      if (supports) n.push_back(plane);
    }
    return n;
  }

  /// A cheap, conservative cull before the kernel's exact work: true when every vertex of
  /// the portal lies clearly outside one plane of the mask's cone (by more than a margin far
  /// above double rounding), so no ray through the mask can pass the portal.
  bool surely_outside(const Cone& cone, const Seen& p) const {
    for (const Plane& n : cone) {
      bool all_out = true;
      for (size_t k = 0; k < p.corners; ++k) {
        const Vec3 d = corner(p, k) - eye_d_;
        if (n.eval(d) >= -1e-9 * (1 + std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z) + std::fabs(n.d))) {
          all_out = false;
          break;
        }
      }
      if (all_out) return true;
    }
    return false;
  }

  /// Portals on a side face beyond which a mask is never worth a look-up.
  static constexpr size_t kLinearScan = 8;

  /// The index range [lo, hi) of side face k's portals (its n portals seen, ps) that the
  /// mask can see: the stretch of the face's line hit by rays through the mask
  /// (conservatively, in double, with a margin; rays parallel to the face reach out to
  /// infinity).
  void side_range(const Cell& cl, size_t k, const Seen* ps, size_t n_ps, const std::vector<Vec2>& mask, size_t& lo,
                  size_t& hi) const {
    const size_t n = cl.footprint.size();
    const Vec2 a = cl.footprint[k], b = cl.footprint[(k + 1) % n];
    const Vec2 u = (1.0 / length(b - a)) * (b - a);
    const Vec3 nrm = cl.faces[k].plane.n;
    if (parallel_) return side_range_parallel(cl, k, ps, n_ps, a, u, mask, lo, hi);
    // Signed distance from the eye to the face's plane: positive when the eye is on the
    // cell's side (its own cell), negative beyond it (a cell seen through portals). A ray d
    // meets the plane ahead when h / (n·d) > 0.
    const double h = -cl.faces[k].plane.eval(eye_d_);
    if (h == 0 || !std::isfinite(h)) return;  // the eye in the face's plane: keep them all
    const double sigma = h > 0 ? 1 : -1;
    const double se = dot(Vec2{eye_d_.x, eye_d_.y} - a, u);
    double smin = HUGE_VAL, smax = -HUGE_VAL;
    auto dir = [&](Vec2 m) { return m.x * cam_.right + m.y * cam_.up + cam_.forward; };
    auto reach_infinity = [&](Vec3 d) {  // a ray parallel to the face: unbounded along its direction
      double du = d.x * u.x + d.y * u.y;
      if (du >= 0) smax = HUGE_VAL;
      if (du <= 0) smin = -HUGE_VAL;
    };
    for (size_t i = 0; i < mask.size(); ++i) {
      const Vec3 p = dir(mask[i]), q = dir(mask[(i + 1) % mask.size()]);
      const double np = sigma * dot(nrm, p), nq = sigma * dot(nrm, q);
      if (np > 0) {
        const double s = se + sigma * h * (p.x * u.x + p.y * u.y) / np;
        smin = std::min(smin, s), smax = std::max(smax, s);
      } else if (np == 0) {
        reach_infinity(p);
      }
      if ((np > 0 && nq < 0) || (np < 0 && nq > 0)) reach_infinity(p + (np / (np - nq)) * (q - p));
    }
    if (smin > smax) {  // no ray through the mask meets this face
      lo = hi = 0;
      return;
    }
    portal_range(cl, k, ps, n_ps, a, u, smin - 1e-6 * (1 + std::fabs(se) + length(b - a)),
                 smax + 1e-6 * (1 + std::fabs(se) + length(b - a)), lo, hi);
  }

  /// The same for parallel rays: a ray from o along f meets the face's plane at an affine
  /// function of the mask point, so the mask's vertices bound the stretch (hits behind the
  /// ray's start only widen it); a face parallel to the rays keeps them all.
  void side_range_parallel(const Cell& cl, size_t k, const Seen* ps, size_t n_ps, Vec2 a, Vec2 u,
                           const std::vector<Vec2>& mask, size_t& lo, size_t& hi) const {
    const Plane& pl = cl.faces[k].plane;
    const double nf = dot(pl.n, cam_.forward);
    if (!(std::fabs(nf) > 1e-9)) return;
    double smin = HUGE_VAL, smax = -HUGE_VAL;
    for (Vec2 m : mask) {
      const Vec3 o = eye_d_ + m.x * cam_.right + m.y * cam_.up;
      const Vec3 hit = o + (-pl.eval(o) / nf) * cam_.forward;
      const double s = dot(Vec2{hit.x, hit.y} - a, u);
      smin = std::min(smin, s), smax = std::max(smax, s);
    }
    if (!std::isfinite(smin) || !std::isfinite(smax)) return;
    const double margin = 1e-6 * (1 + std::fabs(smin) + std::fabs(smax));
    portal_range(cl, k, ps, n_ps, a, u, smin - margin, smax + margin, lo, hi);
  }

  /// The index range [lo, hi) of side face k's portals that meet the stretch [smin, smax]
  /// of the face's line (coordinate along u from footprint vertex a).
  void portal_range(const Cell& cl, size_t k, const Seen* ps, size_t n_ps, Vec2 a, Vec2 u, double smin, double smax,
                    size_t& lo, size_t& hi) const {
    auto extent = [&](const Seen& p, bool hi_end) {
      double s = hi_end ? -HUGE_VAL : HUGE_VAL;
      for (size_t i = 0; i < p.corners; ++i) {
        const Vec3& v = corner(p, i);
        double t = dot(Vec2{v.x, v.y} - a, u);
        s = hi_end ? std::max(s, t) : std::min(s, t);
      }
      return s;
    };
    // Sorted by start; where they do not overlap (the rule), sorted by end too. Stacked
    // portals (Face::portals_overlap) are scanned from the first, the cone culls the rest.
    const Seen* end = ps + n_ps;
    lo = cl.faces[k].portals_overlap
             ? 0
             : size_t(std::partition_point(ps, end, [&](const Seen& p) { return extent(p, true) < smin; }) - ps);
    hi = size_t(std::partition_point(ps + lo, end, [&](const Seen& p) { return extent(p, false) <= smax; }) - ps);
  }

  void consider(const Mask<T>& mask, const Corners& corners, int self, int depth, const Seen& s, const Facing& fc) {
    const CellId other = s.other;
    if (on_path_[size_t(other)]) return;
    Mask<T> m;
    if (!through(s, fc, mask, corners, m)) return;
    if (prune_ && covered(other, m)) {
      ++out_.avenues_pruned;
      return;
    }
    visit(other, m, self, s.portal, depth + 1);
  }

  /// The first half of through(), without the mask: false when no ray from the eye in the
  /// cell p is seen from can cross portal p (seen from behind, or edge-on by parallel rays).
  bool facing(const Seen& p, Facing& fc) {
    ++out_.portals_tested;
    // Which side of the portal's plane is the eye on? Exactly, from input vertices: the
    // corners spanning the most area (not simply the first three, which may hold two
    // corners a rounding apart: see rounded_apart), found when the table was laid out.
    const size_t k1 = p.spread;
    const Vec3T<T> v0 = in(corner(p, 0)), v1 = in(corner(p, k1)), v2 = in(corner(p, k1 + 1));
    fc.N = crossT(sub(v1, v0), sub(v2, v0));  // points into p.cell[1]
    // Parallel: the eye is at infinity behind the picture, s = N·(−f).
    fc.s = parallel_ ? -dotT(fc.N, forward_) : dotT(fc.N, sub(eye_, v0));
    if (fc.s == T(0)) return !parallel_;  // parallel rays never cross a portal seen edge-on
    return (fc.s < T(0)) == p.first;  // else seen from behind
  }

  /// Sets m to mask `from` (of an avenue in the cell p is seen from; `from_corners`, its
  /// corners) narrowed to the rays that also pass portal p, once facing() said it may be
  /// crossed: false when none of area do (the eye in the portal's plane but outside it, or
  /// clipped away). In floating point a needle the clips leave with a corner strayed
  /// outside `from` is settled (Mask::settle_within).
  bool through(const Seen& p, const Facing& fc, const Mask<T>& from, const Corners& from_corners, Mask<T>& m) {
    m = from;
    const Corners* now = &from_corners;  // m's corners while no clip has changed it
    const size_t n = p.corners;
    const Vec3T<T>& N = fc.N;
    const T& s = fc.s;
    const bool from_first = p.first;
    if (s == T(0)) {
      // The eye stands in the portal's plane: through it, if it stands in the portal,
      // lies the whole half-space on the far side; otherwise it is seen edge-on.
      if (!eye_in_polygon(p, N)) return false;
      const Vec3T<T> toward = from_first ? N : Vec3T<T>{-N.x, -N.y, -N.z};
      if (!m.clip(trace(toward, eye_), &now)) return false;
    } else {
      // Rays through the portal: inside every plane through the eye and an edge.
      // With the eye behind N (s < 0) the edge normals (a-e)×(b-e) point inwards; for
      // parallel rays their limit as the eye recedes along −f, f×(b−a).
      for (size_t k = 0; k < n; ++k) {
        if (rounded_apart(corner(p, k), corner(p, (k + 1) % n))) continue;
        const Vec3T<T> a = in(corner(p, k)), b = in(corner(p, (k + 1) % n));
        Vec3T<T> e = parallel_ ? crossT(forward_, sub(b, a)) : crossT(sub(a, eye_), sub(b, eye_));
        if (s > T(0)) e = {-e.x, -e.y, -e.z};
        if (!m.clip(trace(e, a), &now)) return false;
      }
    }
    thread_local Corners clipped;
    if (!now) m.corners(clipped), now = &clipped;
    if (!(Mask<T>::area2(*now) > T(0))) return false;
    if (sample_.per_side > 0 && !sample_.held(*now)) {
      ++out_.between_samples;
      return false;
    }
    bool settled = false;
    const bool kept = m.settle_within(from, from_corners, *now, &settled);
    out_.masks_settled += settled;
    return kept;
  }

  // ---- The merged search (TraverseParams::merge_pieces) ----
  //
  // Two avenues into one cell see disjoint rays; where they were parted only by the edge
  // between two portals (the artificial portals of a sliced outside, say) their masks meet
  // along a whole edge, and if their union is convex it is one avenue: its rays pass the
  // same portals beyond the cell. So the pieces that reach a cell wait until no cell that
  // could still send one more is pending, are merged (Mask::absorb), and only then go on.
  // The order is a heuristic (a cell waits on a pending neighbour in front of it; a cycle
  // of waits is broken by taking the earliest pending cell); correctness does not depend
  // on it: every piece is followed, merged or not, so the union of masks per cell — every
  // ray's cell and what it meets — is the same as Jones's search finds.

  struct Piece {
    Mask<T> mask;
    int parent = -1;
    PortalId via = -1;
    int depth = 0;
    std::array<double, 4> box{};  ///< box_of the mask, grown (made when the cell has two or more pieces)
  };
  static constexpr uint8_t kIdle = 0, kPending = 1;

  /// A root avenue: followed at once (Jones), or the first piece of its cell (merged).
  void root(CellId cell, const Mask<T>& mask) {
    if (!merge_) {
      visit(cell, mask, -1, -1, 0);
      return;
    }
    if (!merged_ready_) prepare_merged();
    add_piece(cell, mask, -1, -1, 0);
  }

  void prepare_merged() {
    thread_local std::vector<std::vector<Piece>> pieces;
    thread_local std::vector<std::vector<CellId>> waiters;
    thread_local std::vector<uint8_t> state;
    if (pieces.size() < c_.cells.size()) pieces.resize(c_.cells.size());
    if (waiters.size() < c_.cells.size()) waiters.resize(c_.cells.size());
    if (state.size() < c_.cells.size()) state.assign(c_.cells.size(), kIdle);
    pieces_ = pieces.data(), waiters_ = waiters.data(), state_ = state.data();
    if (hull_) {
      thread_local std::vector<std::vector<Mask<T>>> reach;
      thread_local std::vector<uint8_t> rounds;
      if (reach.size() < c_.cells.size()) reach.resize(c_.cells.size());
      if (rounds.size() < c_.cells.size()) rounds.assign(c_.cells.size(), 0);
      reach_ = reach.data(), rounds_ = rounds.data();
    }
    merged_ready_ = true;
  }

  void add_piece(CellId cell, Mask<T> mask, int parent, PortalId via, int depth) {
    pieces_[size_t(cell)].push_back({std::move(mask), parent, via, depth, {}});
    if (state_[size_t(cell)] == kPending) return;
    state_[size_t(cell)] = kPending;
    touched_.push_back(cell);
    queued_.push_back(cell);
    ready_.push_back(cell);
  }

  /// A pending cell in front of `cell` (the eye on its side of a portal between them,
  /// clearly), which may yet send it a piece; kNoCell when there is none.
  CellId blocker(CellId cell) const {
    const CellComplex::PortalTable& t = *table_;
    const size_t begin = size_t(t.face_seen[size_t(t.cell_faces[size_t(cell)])]);
    const size_t end = size_t(t.face_seen[size_t(t.cell_faces[size_t(cell) + 1])]);
    for (size_t i = begin; i < end; ++i) {  // in the order of Cell::portals
      if (t.listed[i] < 0) break;  // the cell's last neighbour passed
      const Seen& p = t.seen[size_t(t.listed[i])];
      const CellId other = p.other;
      if (other == cell || state_[size_t(other)] != kPending) continue;
      const double e = p.plane.eval(eye_d_), tol = 1e-9 * (1 + length(eye_d_));
      // p.plane's normal points into cell[1]: the eye is on other's side when it is on the
      // side away from `cell`.
      if (!p.first ? e < -tol : e > tol) return other;
    }
    return kNoCell;
  }

  void drain() {
    if (!merge_ || !merged_ready_) return;
    size_t forced = 0;
    for (;;) {
      // First come, first served: a wave outwards from the eye, so that the other ways
      // into a cell are found (and pending) before it goes on.
      for (size_t next = 0; next < ready_.size();) {
        const CellId d = ready_[next++];
        if (next == ready_.size()) ready_.clear(), next = 0;
        if (state_[size_t(d)] != kPending) continue;
        const CellId b = blocker(d);
        if (b != kNoCell) {
          waiters_[size_t(b)].push_back(d);
          continue;
        }
        expand(d);
      }
      while (forced < queued_.size() && state_[size_t(queued_[forced])] != kPending) ++forced;
      if (forced == queued_.size()) break;
      expand(queued_[forced]);
    }
  }

  static bool boxes_touch(const std::array<double, 4>& a, const std::array<double, 4>& b) {
    return !(a[2] < b[0] || b[2] < a[0] || a[3] < b[1] || b[3] < a[1]);
  }

  /// Whether `cell` lies on the avenue `a` extends (its first parents back to the eye).
  bool on_chain(int a, CellId cell) const {
    for (; a >= 0; a = out_.avenues[size_t(a)].parent)
      if (out_.avenues[size_t(a)].cell == cell) return true;
    return false;
  }

  void expand(CellId cell) {
    state_[size_t(cell)] = kIdle;
    std::vector<Piece> ps;
    ps.swap(pieces_[size_t(cell)]);
    if (hull_ && !join_hull(cell, ps)) ps.clear();  // nothing the cell was not searched through already
    // Pairs until none merges (a union made late may merge with a piece passed earlier);
    // their boxes first, made only where there is a pair to test. Each pass sweeps the
    // pieces in the order of their boxes' left sides, so a piece is tested only against
    // those whose boxes reach across its own (a cell seen in thousands of pieces from
    // outside a model would otherwise test every pair).
    if (ps.size() > 1)
      for (Piece& p : ps) p.box = box_of(doubles_of(p.mask));
    std::vector<uint8_t> gone;
    for (bool any = ps.size() > 1; any;) {
      any = false;
      std::sort(ps.begin(), ps.end(), [](const Piece& a, const Piece& b) { return a.box[0] < b.box[0]; });
      gone.assign(ps.size(), 0);
      for (size_t i = 0; i < ps.size(); ++i) {
        if (gone[i]) continue;
        for (size_t j = i + 1; j < ps.size() && ps[j].box[0] <= ps[i].box[2];) {
          if (gone[j] || !boxes_touch(ps[i].box, ps[j].box) || !ps[i].mask.absorb(ps[j].mask)) {
            ++j;
            continue;
          }
          ps[i].depth = std::max(ps[i].depth, ps[j].depth);
          ps[i].box = {std::min(ps[i].box[0], ps[j].box[0]), std::min(ps[i].box[1], ps[j].box[1]),
                       std::max(ps[i].box[2], ps[j].box[2]), std::max(ps[i].box[3], ps[j].box[3])};
          ++out_.avenues_merged;
          gone[j] = 1;
          any = true;
          j = i + 1;  // the union is larger: the pieces passed may join it now
        }
      }
      if (any) {
        size_t kept = 0;
        for (size_t k = 0; k < ps.size(); ++k)
          if (!gone[k]) {
            if (kept != k) ps[kept] = std::move(ps[k]);
            ++kept;
          }
        ps.resize(kept);
      }
    }
    for (Piece& piece : ps) {
      piece.mask.corners(corners_);
      const int self = emit(cell, corners_, piece.parent, piece.via, piece.depth);
      // Its own mask, by reference: nothing below appends avenues.
      for_each_portal_seen(cell, out_.avenues[size_t(self)].mask, piece.via, [&](const Seen& sp, const Facing& fc) {
        const CellId other = sp.other;
        Mask<T> m;
        // A hull's first parents are not its rays' chain (they may pass cells its other
        // rays meet later): the hull search ends instead where a cell has nothing new.
        if (!through(sp, fc, piece.mask, corners_, m) || (!hull_ && on_chain(self, other))) return;
        add_piece(other, std::move(m), self, sp.portal, piece.depth + 1);
      });
    }
    ps.clear();
    if (pieces_[size_t(cell)].empty()) pieces_[size_t(cell)].swap(ps);  // keep the storage
    for (CellId w : waiters_[size_t(cell)]) ready_.push_back(w);
    waiters_[size_t(cell)].clear();
  }

  /// The hull search: the pieces become one, their convex hull (Mask::hull), which holds
  /// every ray of each and perhaps rays none of them has (one piece too: its hull, grown
  /// by far less than a sample, is what keeps the search's rounding on the safe side). It
  /// goes on from the first piece's avenue, at the deepest piece's depth.
  /// What a cell was searched through is kept (its reach): a piece within one of those
  /// masks adds nothing and is dropped (false when none is left), so a cell searched again
  /// goes on with its new pieces only, and what lies beyond it is searched again only where
  /// it is new. A cell searched kHullRounds times is searched through the whole window next
  /// (no cycle of cells can then bring it anything new), so the search ends without Jones's
  /// rule that an avenue never enters a cell twice, which a hull's chain of first parents
  /// cannot keep. Pieces are left as they are when their hull has no area.
  bool join_hull(CellId cell, std::vector<Piece>& ps) {
    std::vector<Mask<T>>& reach = reach_[size_t(cell)];
    if (!reach.empty()) {
      ps.erase(std::remove_if(ps.begin(), ps.end(),
                              [&](const Piece& p) {
                                for (const Mask<T>& r : reach)
                                  if (p.mask.within(r)) return true;
                                return false;
                              }),
               ps.end());
      if (ps.empty()) return false;
    }
    const bool last = ++rounds_[size_t(cell)] > kHullRounds;
    thread_local std::vector<Point2T<T>> points;
    points.clear();
    int depth = 0;
    for (const Piece& p : ps) {
      for (size_t k = 0; k < p.mask.half_planes().size(); ++k) points.push_back(p.mask.vertex(k));
      depth = std::max(depth, p.depth);
    }
    Mask<T> h = last ? window_ : Mask<T>::hull(points);
    if (h.empty()) return true;
    out_.avenues_merged += long(ps.size()) - 1;
    ps.resize(1);
    ps[0].mask = std::move(h);
    ps[0].depth = depth;
    reach.push_back(ps[0].mask);  // only ever a mask the cell is searched through
    return true;
  }
  static constexpr uint8_t kHullRounds = 8;

  /// The box of a mask's vertices (in double: x0, y0, x1, y1), grown by far more than their rounding.
  static std::array<double, 4> box_of(const std::vector<Vec2>& mask, bool grown = true) {
    std::array<double, 4> b{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (Vec2 v : mask) b = {std::min(b[0], v.x), std::min(b[1], v.y), std::max(b[2], v.x), std::max(b[3], v.y)};
    if (!grown) return b;
    const double grow = 1e-9 * (1 + std::max({std::fabs(b[0]), std::fabs(b[1]), std::fabs(b[2]), std::fabs(b[3])}));
    return {b[0] - grow, b[1] - grow, b[2] + grow, b[3] + grow};
  }

  /// Whether an avenue already found into `cell` has a mask that holds m. The boxes first:
  /// masks of one cell are mostly disjoint, and a box not inside another's (grown) box
  /// rules containment out without the kernel's arithmetic (a wrong "no" only keeps an avenue).
  bool covered(CellId cell, const Mask<T>& m) const {
    if (last_into_[size_t(cell)] < 0) return false;
    const std::array<double, 4> box = box_of(doubles_of(m), false);
    for (int32_t a = last_into_[size_t(cell)]; a >= 0; a = reached_[size_t(a)].earlier) {
      const Reached& r = reached_[size_t(a)];
      if (box[0] < r.box[0] || box[1] < r.box[1] || box[2] > r.box[2] || box[3] > r.box[3]) continue;
      if (m.same_as(r.mask) || m.inside(r.mask)) return true;
    }
    return false;
  }

  /// Closed point-in-convex-polygon test of the eye, which lies in the polygon's plane.
  bool eye_in_polygon(const Seen& p, const Vec3T<T>& N) const {
    const size_t n = p.corners;
    for (size_t k = 0; k < n; ++k) {
      if (rounded_apart(corner(p, k), corner(p, (k + 1) % n))) continue;
      Vec3T<T> a = in(corner(p, k)), b = in(corner(p, (k + 1) % n));
      if (dotT(crossT(sub(b, a), sub(eye_, a)), N) < T(0)) return false;
    }
    return true;
  }

  const CellComplex& c_;
  const CellComplex::PortalTable* table_ = nullptr;  ///< c_'s, or own_table_
  CellComplex::PortalTable own_table_;               ///< for a complex never indexed
  VisibleSet& out_;
  Vec3T<T> eye_, right_, up_, forward_;
  Mask<T> window_;
  uint8_t* on_path_ = nullptr;  ///< per cell: on the current avenue (thread-local buffer)
  bool prune_ = true;           ///< TraverseParams::prune_covered
  /// Per avenue (same index), when pruning: its mask in T and the avenue found into the
  /// same cell before it (-1: none).
  struct Reached {
    Mask<T> mask;
    std::array<double, 4> box;  ///< box_of its mask: x0, y0, x1, y1
    int32_t earlier;
  };
  std::vector<Reached> reached_;
  int32_t* last_into_ = nullptr;  ///< per cell: the last avenue into it (thread-local buffer)
  bool merge_ = false;               ///< TraverseParams::merge_pieces (or hull_pieces)
  bool hull_ = false;                ///< TraverseParams::hull_pieces
  std::vector<Mask<T>>* reach_ = nullptr;  ///< hull search, per cell: the masks it was searched through (thread-local buffer)
  uint8_t* rounds_ = nullptr;        ///< hull search, per cell: times it was searched
  bool merged_ready_ = false;
  std::vector<Piece>* pieces_ = nullptr;        ///< per cell: pieces waiting (thread-local buffer)
  std::vector<CellId>* waiters_ = nullptr;      ///< per cell: cells waiting on it
  uint8_t* state_ = nullptr;                    ///< per cell: kIdle or kPending
  std::vector<CellId> touched_, queued_, ready_;
  Corners corners_;            ///< the merged search: the corners of the piece being expanded
  Vec3 eye_d_;                 ///< the eye in double, for culling only
  /// The sample centres of the half-tone the search is for (only_through_samples): at
  /// k + ½ in sample units, x from the window's left, y down from its top.
  struct SampleGrid {
    int per_side = 0;  ///< 0: every piece is followed
    double left = 0, top = 0, across = 1, down = 1;  ///< samples per picture-plane unit
    /// Whether the bounds of these corners, grown by 1/16 of a sample, hold a sample's centre.
    bool held(const Corners& c) const {
      const double x0 = to_double_of(c.reach.lo_x), x1 = to_double_of(c.reach.hi_x);
      const double y0 = to_double_of(c.reach.lo_y), y1 = to_double_of(c.reach.hi_y);
      constexpr double kGrow = 1.0 / 16;
      const double u0 = (x0 - left) * across - kGrow, u1 = (x1 - left) * across + kGrow;
      const double v0 = (top - y1) * down - kGrow, v1 = (top - y0) * down + kGrow;
      return std::ceil(u0 - 0.5) <= std::floor(u1 - 0.5) && std::ceil(v0 - 0.5) <= std::floor(v1 - 0.5);
    }
  };
  SampleGrid sample_;
  Camera cam_;
  bool parallel_ = false;      ///< cam_.projection == Projection::Parallel
};

/// Perspective: the search from the eye's cell. Parallel: from the cut plane, or without
/// one from the picture plane through the eye.
template <class T>
VisibleSet traverse_with(const CellComplex& c, const Camera& cam, CellId eye_cell, bool prune_covered,
                         const Plane* cut = nullptr, Join join = Join::None,
                         const TraverseParams::Strip* strip = nullptr, int samples_per_side = 0) {
  VisibleSet out;
  out.eye_cell = eye_cell;
  out.conservative = join == Join::Hull;
  auto t0 = std::chrono::steady_clock::now();
  if (cam.is_parallel()) {
    Traversal<T> t(c, cam, prune_covered, out, join);
    t.only_through_samples(cam, samples_per_side);
    t.run_cut(cut ? *cut : cam.picture_plane());
  } else {
    Traversal<T> t(c, cam, prune_covered, out, join, strip);
    t.only_through_samples(cam, samples_per_side);
    t.run(eye_cell);
  }
  out.micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  out.collect_cells();
  return out;
}

VisibleSet traverse_exact(const CellComplex& c, const Camera& cam, CellId eye_cell, bool prune_covered,
                          const Plane* cut = nullptr, Join join = Join::None,
                          const TraverseParams::Strip* strip = nullptr);
VisibleSet traverse_filtered(const CellComplex& c, const Camera& cam, CellId eye_cell, bool prune_covered,
                             const Plane* cut = nullptr, Join join = Join::None,
                             const TraverseParams::Strip* strip = nullptr);

}  // namespace avenues::detail
