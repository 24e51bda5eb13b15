// Avenues — a polygon soup's free space as the leaves of a BSP of its polygons (see
// soup_bsp.h).
//
// Exactness. Every polygon is kept "plane-based": its supporting plane, and for each edge
// the plane that cuts it there (its inside on that plane's negative side). A vertex is the
// meeting point of the support and the planes of its two edges, so every vertex anywhere
// in the tree is the meeting of three planes of the input (a triangle's support or edge
// planes, or the far box's): coordinates never grow with the number of cuts, and every
// side test is exact. A vertex is known to lie on the planes it was made from (and their
// opposites, made once per plane) by identity; any other side test takes the interval
// filter, and where that cannot decide (the many vertices lying exactly on a plane) the
// sign of two determinants of the planes' integer coefficients (side_of_meeting), never
// a rational point.
//
// The stages, timed into CellComplex::timings:
//   decompose — a cell (the far box to start with) with its triangle fragments: while a
//               fragment lies inside the cell (not on its boundary), cut the cell by the
//               plane of one (the cheapest by splits and balance, axis-aligned preferred,
//               estimated in doubles on a sample); fragments on that plane go to both sides
//               as boundary. A cell all of whose fragments lie on its boundary is a leaf.
//               First, where the soup's walls end under a large empty space (the air over
//               a grid of open boxes), the far box is cut at their tops (empty_space_cut),
//               so that the space stays one cell and no plane of the soup slices it.
//   cells     — each leaf face not on the far box is pushed down the other side of the
//               node that made it, into the pieces facing each neighbouring leaf; each piece
//               minus the leaf's fragments on that face is portal, the rest opaque. Leaves
//               are then joined across faces wholly open between them wherever the union
//               stays convex (join_leaves), and the joined faces' outlines made from the
//               rounded corners. Rounded to double once.
#include "cells/soup_bsp.h"

#include "cells/shared_planes.h"

#include "core/memory_reserve.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/intersections.h>

#include <boost/container/small_vector.hpp>
#include <tbb/blocked_range.h>
#include <tbb/concurrent_unordered_map.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#ifndef CGAL_HAS_THREADS
#error "soup_bsp.cpp shares CGAL's lazy numbers between threads: it needs CGAL_HAS_THREADS"
#endif

namespace avenues {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using FT = K::FT;
using P3 = K::Point_3;
using Pl = K::Plane_3;
using CGAL::ON_NEGATIVE_SIDE;
using CGAL::ON_ORIENTED_BOUNDARY;
using CGAL::ON_POSITIVE_SIDE;
using Side = CGAL::Oriented_side;
using Sides = boost::container::small_vector<Side, 16>;

constexpr int kInterior = INT_MIN;  ///< a fragment not (yet) on any cell boundary

/// A convex polygon: edge i runs from v[i] to v[i+1] on plane e[i], the polygon on e[i]'s
/// negative side. No three consecutive vertices are collinear.
/// Stored inline up to eight corners (nearly every polygon here: a triangle cut a few
/// times), so that cutting one allocates nothing.
struct Poly {
  Pl support;
  boost::container::small_vector<P3, 8> v;
  boost::container::small_vector<Pl, 8> e;
};

/// A piece of an input triangle in a cell.
struct Frag {
  Poly poly;
  int tri = -1;
  int on = kInterior;  ///< the node whose plane it lies on (a boundary fragment), or kInterior
};

/// A face of a cell: its polygon with an outward support; `id` the node whose plane made
/// it (the neighbours lie in that node's child `toward`), or -1-k for far-box face k.
struct CellFace {
  Poly poly;
  int id = -1;
  int toward = 0;
};

struct Node {
  Pl plane;
  Pl opposite;  ///< plane.opposite(), the one of opposite_of (split's identity test)
  int child[2] = {-1, -1};  ///< negative side, positive side
  int leaf = -1;
};

P3 meet(const Pl& a, const Pl& b, const Pl& c) {
  const auto r = CGAL::intersection(a, b, c);
  if (r)
    if (const P3* p = boost::get<P3>(&*r)) return *p;
  throw std::logic_error("soup bsp: three planes of a vertex do not meet in a point");
}

enum class Where { Neg, Pos, On, Both };

/// What is made of a plane once and kept with it, by its representation (each entry keeps
/// its plane alive, so no other plane can take its address): its opposite, so that a
/// vertex made on h's opposite is known to lie on h by identity (split), as one made on h
/// is; and its exact coefficients as integers, up to a positive factor (every plane here
/// comes from doubles, so a power of two clears every denominator). The planes this file
/// makes (plane_through, plane_of) get their integers from their doubles as they are made,
/// without asking CGAL for the plane's exact value: that would build CGAL's rational plane
/// once per plane, under a std::call_once whose first call costs a futex system call (on
/// the duplex as a soup, 700,000 of them). One table per thread, emptied by decompose_soup
/// when it ends.
using Coefficients = std::array<mpz_class, 4>;
struct PlaneFacts {
  Pl plane;
  std::optional<Pl> opposite;
  bool integers_made = false;
  std::optional<Coefficients> integers;
};
thread_local std::unordered_map<CGAL::Handle::Id_type, PlaneFacts> plane_facts;
/// The table's entries last asked for, by representation address: a lookup here is one
/// load where the table's is two cache misses (its bucket and its node).
struct RecentFacts {
  CGAL::Handle::Id_type id = 0;
  PlaneFacts* facts = nullptr;
};
constexpr size_t kRecentFacts = size_t(1) << 12;
thread_local std::array<RecentFacts, kRecentFacts> recent_facts;

void forget_plane_facts() {
  plane_facts.clear();
  recent_facts.fill({});
}

PlaneFacts& facts_of(const Pl& h) {
  const CGAL::Handle::Id_type id = h.id();
  RecentFacts& r = recent_facts[(size_t(id) >> 6) & (kRecentFacts - 1)];
  if (r.facts && r.id == id) return *r.facts;
  auto [it, fresh] = plane_facts.try_emplace(id);
  if (fresh) it->second.plane = h;
  r = {id, &it->second};
  return it->second;  // stays valid as the table grows (a node-based map)
}

const Pl& opposite_of(const Pl& h) {
  PlaneFacts& f = facts_of(h);
  if (!f.opposite) {
    f.opposite = h.opposite();
    PlaneFacts& g = facts_of(*f.opposite);
    g.opposite = h;
    if (f.integers_made) {
      g.integers_made = true;
      if (f.integers) {
        g.integers.emplace();
        for (size_t k = 0; k < 4; ++k) (*g.integers)[k] = -(*f.integers)[k];
      }
    }
  }
  return *f.opposite;
}

const std::optional<Coefficients>& integer_plane(const Pl& h) {
  PlaneFacts& f = facts_of(h);
  if (f.integers_made) return f.integers;
  f.integers_made = true;
  const auto& e = CGAL::exact(h);
  const mpq_class q[4] = {e.a(), e.b(), e.c(), e.d()};
  mp_bitcnt_t shift = 0;
  for (const mpq_class& x : q) {
    const mpz_class& den = x.get_den();
    const mp_bitcnt_t low = mpz_scan1(den.get_mpz_t(), 0);
    if (mpz_sizeinbase(den.get_mpz_t(), 2) != low + 1) return f.integers;  // more than a single bit set
    shift = std::max(shift, low);
  }
  f.integers.emplace();
  for (size_t k = 0; k < 4; ++k) {
    const mp_bitcnt_t low = mpz_scan1(q[k].get_den().get_mpz_t(), 0);
    mpz_mul_2exp((*f.integers)[k].get_mpz_t(), q[k].get_num().get_mpz_t(), shift - low);
  }
  return f.integers;
}

/// Doubles as integers on a common scale: value k is out[k] · 2^E exactly, E ≤ 0 the
/// least binary exponent of their 53-bit mantissas (so 0 and small integers stay whole).
template <size_t N>
long to_common_integers(const std::array<double, N>& in, std::array<mpz_class, N>& out) {
  long E = 0;
  std::array<int, N> exp{};
  for (size_t k = 0; k < N; ++k) {
    if (in[k] == 0) continue;
    std::frexp(in[k], &exp[k]);
    E = std::min(E, long(exp[k]) - 53);
  }
  for (size_t k = 0; k < N; ++k) {
    if (in[k] == 0) {
      out[k] = 0;
      continue;
    }
    int e = 0;
    const double m = std::ldexp(std::frexp(in[k], &e), 53);  // a whole number below 2^53
    out[k] = m;
    mpz_mul_2exp(out[k].get_mpz_t(), out[k].get_mpz_t(), mp_bitcnt_t(long(e) - 53 - E));
  }
  return E;
}

/// The plane a·x + b·y + c·z + d = 0, its integers known as it is made.
Pl plane_of(double a, double b, double c, double d) {
  const Pl h(a, b, c, d);
  std::array<mpz_class, 4> z;
  to_common_integers(std::array<double, 4>{a, b, c, d}, z);
  PlaneFacts& f = facts_of(h);
  f.integers_made = true;
  f.integers = z;
  return h;
}

/// The plane through p, q and r + t, oriented as CGAL's Plane_3(p, q, r + t) is
/// (its normal (p − r) × (q − r)), its integers known as it is made: the same formula in
/// integers on a common scale 2^E, so a positive multiple of CGAL's exact plane. t is a
/// small integer vector (a unit axis for an edge's plane), or zero.
Pl plane_through(const P3& p, const P3& q, const P3& r, const std::array<int, 3>& t) {
  const K::Vector_3 tv(t[0], t[1], t[2]);
  const Pl h = t == std::array<int, 3>{0, 0, 0} ? Pl(p, q, r) : Pl(p, q, r + tv);
  // The corners are the soup's doubles (intervals of no width); otherwise CGAL is asked.
  std::array<double, 9> d{};
  const P3* corner[3] = {&p, &q, &r};
  for (size_t i = 0; i < 3; ++i) {
    const auto& a = CGAL::approx(*corner[i]);
    const CGAL::Interval_nt<false> c[3] = {a.x(), a.y(), a.z()};
    for (size_t j = 0; j < 3; ++j) {
      if (c[j].inf() != c[j].sup()) return h;
      d[3 * i + j] = c[j].inf();
    }
  }
  std::array<mpz_class, 9> X;
  const long E = to_common_integers(d, X);
  mpz_class R[3];
  for (size_t j = 0; j < 3; ++j) {
    R[j] = X[6 + j];
    if (t[j] != 0) R[j] += mpz_class(t[j]) << mp_bitcnt_t(-E);  // t_j in the points' scale
  }
  const mpz_class rp[3] = {X[0] - R[0], X[1] - R[1], X[2] - R[2]};
  const mpz_class rq[3] = {X[3] - R[0], X[4] - R[1], X[5] - R[2]};
  Coefficients z;
  z[0] = rp[1] * rq[2] - rq[1] * rp[2];
  z[1] = rp[2] * rq[0] - rq[2] * rp[0];
  z[2] = rp[0] * rq[1] - rq[0] * rp[1];
  z[3] = -(z[0] * R[0] + z[1] * R[1] + z[2] * R[2]);
  // In the points' own scale: (A, B, C)·2^{2E} and D·2^{3E}; times 2^{-3E}: (A, B, C)·2^{-E}, D.
  for (size_t k = 0; k < 3; ++k) mpz_mul_2exp(z[k].get_mpz_t(), z[k].get_mpz_t(), mp_bitcnt_t(-E));
  PlaneFacts& f = facts_of(h);
  f.integers_made = true;
  f.integers = std::move(z);
  return h;
}

/// The 2 × 2 minors of rows p and q of a matrix of planes, over the column pairs (0, 1),
/// (0, 2), (0, 3), (1, 2), (1, 3), (2, 3) in that order: m(j, k) = p_j·q_k − p_k·q_j. t is
/// scratch (the callers keep their integers, and their limbs, from call to call).
void pair_minors(const Coefficients& p, const Coefficients& q, mpz_class (&m)[6], mpz_class& t) {
  static constexpr size_t kPairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (size_t i = 0; i < 6; ++i) {
    const size_t j = kPairs[i][0], k = kPairs[i][1];
    m[i] = p[j] * q[k];
    t = p[k] * q[j];
    m[i] -= t;
  }
}

/// det N, the 3 × 3 determinant of the normals of planes p, q and r (in rows), from p and
/// q's pair_minors m: r_2·m(0,1) − r_1·m(0,2) + r_0·m(1,2). t is scratch.
void normals_det(const mpz_class (&m)[6], const Coefficients& r, mpz_class& out, mpz_class& t) {
  out = r[2] * m[0];
  t = r[1] * m[1];
  out -= t;
  t = r[0] * m[3];
  out += t;
}

/// The side of h on which the point where planes p, q, r meet lies, from the planes alone:
/// with M the 4 × 4 matrix of p, q, r, h and N the 3 × 3 of p, q, r's normals, h at that
/// point is det M / det N (Cramer: the cofactors of M's last row are orthogonal to p, q, r
/// and end in det N). Integers throughout: no rational point is made. det M by Laplace's
/// expansion in the 2 × 2 minors of rows p, q and of rows r, h; det N from the first ones.
/// nullopt when the three do not meet in one point (det N = 0).
std::optional<Side> side_of_meeting(const Coefficients& p, const Coefficients& q,
                                    const Coefficients& r, const Coefficients& h) {
  // Kept per thread: their limbs stay allocated from one call to the next (this is the
  // hottest exact test of the decomposition; fresh integers cost a malloc and free each).
  thread_local mpz_class top[6], bottom[6], t, n, det;
  pair_minors(p, q, top, t);
  pair_minors(r, h, bottom, t);
  normals_det(top, r, n, t);
  const int sn = sgn(n);
  if (sn == 0) return std::nullopt;
  // det M = Σ ± top(j,k) · bottom(complement): (01)(23) − (02)(13) + (03)(12) + (12)(03) − (13)(02) + (23)(01).
  det = top[0] * bottom[5];
  t = top[1] * bottom[4];
  det -= t;
  t = top[2] * bottom[3];
  det += t;
  t = top[3] * bottom[2];
  det += t;
  t = top[4] * bottom[1];
  det -= t;
  t = top[5] * bottom[0];
  det += t;
  const int sign = sgn(det) * sn;
  return sign > 0 ? ON_POSITIVE_SIDE : sign < 0 ? ON_NEGATIVE_SIDE : ON_ORIENTED_BOUNDARY;
}

/// The side of h on which vertex i of p lies: its interval first; where that cannot tell
/// (the vertex on h, or within rounding of it), exactly from the three planes it is the
/// meeting of (p's support and its two edges').
Side side_of_vertex(const Pl& h, const Poly& p, size_t i) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const CGAL::Uncertain<Side> u =
        CGAL::Simple_cartesian<CGAL::Interval_nt<false>>().oriented_side_3_object()(CGAL::approx(h), CGAL::approx(p.v[i]));
    if (CGAL::is_certain(u)) return CGAL::get_certain(u);
  }
  const size_t n = p.v.size();
  const auto &a = integer_plane(p.support), &b = integer_plane(p.e[(i + n - 1) % n]), &c = integer_plane(p.e[i]),
             &d = integer_plane(h);
  if (a && b && c && d)
    if (const std::optional<Side> side = side_of_meeting(*a, *b, *c, *d)) return *side;
  return h.oriented_side(p.v[i]);
}

/// The part of p not on side `drop` of the plane the signs `s` were taken against; its new
/// edge lies on `cut` (that plane oriented with the kept part on its negative side).
void clip(const Poly& p, const Sides& s, const Pl& cut, Side drop, Poly& out) {
  const Side keep = drop == ON_POSITIVE_SIDE ? ON_NEGATIVE_SIDE : ON_POSITIVE_SIDE;
  out.support = p.support;
  out.v.clear();
  out.e.clear();
  const size_t n = p.v.size();
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    if (s[i] != drop) {
      out.v.push_back(p.v[i]);
      out.e.push_back(s[i] == ON_ORIENTED_BOUNDARY && s[j] == drop ? cut : p.e[i]);
    }
    if ((s[i] == keep && s[j] == drop) || (s[i] == drop && s[j] == keep)) {
      out.v.push_back(meet(p.support, p.e[i], cut));
      out.e.push_back(s[i] == keep ? cut : p.e[i]);
    }
  }
}

/// Where p lies against h (whose opposite_of is o); when it crosses, its parts on each side
/// (either may be null).
Where split(const Poly& p, const Pl& h, const Pl& o, Poly* neg, Poly* pos) {
  const size_t n = p.v.size();
  auto same = [&](const Pl& e) { return CGAL::identical(h, e) || CGAL::identical(o, e); };
  if (same(p.support)) return Where::On;
  Sides s(n);
  bool any_neg = false, any_pos = false;
  for (size_t i = 0; i < n; ++i) {
    // A vertex lies on the planes it was made from (its edges' and the support), and on
    // their opposites: known without asking, where asking would take the exact path.
    s[i] = same(p.e[i]) || same(p.e[(i + n - 1) % n]) ? ON_ORIENTED_BOUNDARY : side_of_vertex(h, p, i);
    any_neg |= s[i] == ON_NEGATIVE_SIDE;
    any_pos |= s[i] == ON_POSITIVE_SIDE;
  }
  if (!any_neg && !any_pos) return Where::On;
  if (!any_pos) return Where::Neg;
  if (!any_neg) return Where::Pos;
  if (neg) clip(p, s, h, ON_POSITIVE_SIDE, *neg);
  if (pos) clip(p, s, o, ON_NEGATIVE_SIDE, *pos);
  return Where::Both;
}

Where split(const Poly& p, const Pl& h, Poly* neg, Poly* pos) { return split(p, h, opposite_of(h), neg, pos); }

bool same_plane(const Pl& a, const Pl& b) { return CGAL::identical(a, b) || a == b; }

/// The axis along which h's normal is largest (h is never parallel to it).
int dominant_axis(const Pl& h) {
  if (const PlaneFacts& f = facts_of(h); f.integers) {
    const Coefficients& z = *f.integers;
    const int ab = mpz_cmpabs(z[0].get_mpz_t(), z[1].get_mpz_t()), ac = mpz_cmpabs(z[0].get_mpz_t(), z[2].get_mpz_t());
    if (ab >= 0 && ac >= 0) return 0;
    return mpz_cmpabs(z[1].get_mpz_t(), z[2].get_mpz_t()) >= 0 ? 1 : 2;
  }
  const FT a = CGAL::abs(h.a()), b = CGAL::abs(h.b()), c = CGAL::abs(h.c());
  if (a >= b && a >= c) return 0;
  return b >= c ? 1 : 2;
}

/// Far-box face k (axis k/2, the high side when k is odd), outward.
Pl box_plane(const Box3& box, int k) {
  const int axis = k / 2;
  const bool hi = k % 2 == 1;
  const double at = axis == 0 ? (hi ? box.hi.x : box.lo.x) : axis == 1 ? (hi ? box.hi.y : box.lo.y) : (hi ? box.hi.z : box.lo.z);
  double n[3] = {0, 0, 0};
  n[axis] = hi ? 1 : -1;
  return plane_of(n[0], n[1], n[2], hi ? -at : at);
}

/// The far box's six face planes (face k as box_plane), made once per decomposition.
using FarPlanes = std::array<Pl, 6>;
FarPlanes far_planes(const Box3& box) {
  FarPlanes f;
  for (int k = 0; k < 6; ++k) f[size_t(k)] = box_plane(box, k);
  return f;
}

/// The plane h cut by the far box's faces across its dominant axis: a quad on h.
Poly quad_on(const Pl& h, const FarPlanes& far) {
  const int k = dominant_axis(h), u = (k + 1) % 3, w = (k + 2) % 3;
  const Pl &ulo = far[size_t(2 * u)], &uhi = far[size_t(2 * u + 1)];
  const Pl &wlo = far[size_t(2 * w)], &whi = far[size_t(2 * w + 1)];
  Poly q;
  q.support = h;
  q.v = {meet(h, ulo, wlo), meet(h, uhi, wlo), meet(h, uhi, whi), meet(h, ulo, whi)};
  q.e = {wlo, uhi, whi, ulo};
  return q;
}

/// h inside a convex cell: the far box's quad on h, cut by each face plane of the cell.
/// Empty when h misses the cell's interior.
Poly section(const Pl& h, const std::vector<CellFace>& faces, const FarPlanes& far) {
  Poly q = quad_on(h, far);
  Poly part;
  for (const CellFace& f : faces) {
    const Where w = split(q, f.poly.support, &part, nullptr);
    if (w == Where::Pos) return {};
    if (w == Where::Both) std::swap(q, part);
  }
  return q;
}

/// True when the vertices run counter-clockwise about the support's normal n. From the
/// planes alone, where they have integers: edge 0 runs along the line where the support
/// meets e[0] and leaves the polygon at v[1] into e[1]'s positive side, so it runs along
/// +(n × m0) (m0, m1 the normals of e[0], e[1]) exactly when m1 · (n × m0) > 0, and then
/// the inside, on e[0]'s negative side, is on its left.
bool ccw_about_normal(const Poly& p) {
  const PlaneFacts &n = facts_of(p.support), &e0 = facts_of(p.e[0]), &e1 = facts_of(p.e[1]);
  if (n.integers && e0.integers && e1.integers) {
    mpz_class m[6], det, t;  // m1 · (n × m0) = det of the normals of n, e[0], e[1]
    pair_minors(*n.integers, *e0.integers, m, t);
    normals_det(m, *e1.integers, det, t);
    if (sgn(det) != 0) return sgn(det) > 0;
  }
  return CGAL::orientation(p.v[0], p.v[1], p.v[2], p.v[0] + p.support.orthogonal_vector()) == CGAL::POSITIVE;
}

/// The point where planes p, q and r meet, from their integer coefficients by Cramer's
/// rule (x_j = −det N_j / det N, N_j the normals with column j taken from the offsets),
/// each coordinate rounded as CGAL rounds an exact value (the middle of the tightest
/// interval about it). nullopt when the three do not meet in one point.
std::optional<Vec3> meeting_rounded(const Coefficients& p, const Coefficients& q, const Coefficients& r) {
  mpz_class m[6], n, t;  // m: (0,1), (0,2), (0,3), (1,2), (1,3), (2,3)
  pair_minors(p, q, m, t);
  normals_det(m, r, n, t);
  if (sgn(n) == 0) return std::nullopt;
  const mpz_class num[3] = {r[3] * m[3] + r[1] * m[5] - r[2] * m[4], r[2] * m[2] - r[0] * m[5] - r[3] * m[1],
                            r[0] * m[4] - r[1] * m[2] + r[3] * m[0]};
  double out[3];
  for (size_t j = 0; j < 3; ++j) {
    mpq_class x(-num[j], n);
    x.canonicalize();
    out[j] = CGAL::to_double(CGAL::Interval_nt<false>(CGAL::to_interval(x)));
  }
  return Vec3{out[0], out[1], out[2]};
}

/// The corners of the decomposition's polygons rounded to double, each once: the middle
/// of its interval when that is tight, else its exact value rounded (from the integer
/// coefficients of the three planes it is the meeting of, or CGAL's exact point where a
/// plane has none). A corner's double depends on nothing but the corner, so it is the same
/// wherever and on whichever thread it is asked for; the exact ones are kept, so each is
/// worked out once. Safe to use from many threads while no plane's facts are being added.
class Rounding {
 public:
  explicit Rounding(const std::unordered_map<CGAL::Handle::Id_type, PlaneFacts>& facts) : facts_(facts) {}

  Vec3 corner(const Poly& p, size_t i) {
    const P3& q = p.v[i];
    const auto& a = CGAL::approx(q);
    auto tight = [](const CGAL::Interval_nt<false>& x) { return x.sup() - x.inf() <= 1e-12 * std::max(1.0, std::fabs(x.inf())); };
    if (tight(a.x()) && tight(a.y()) && tight(a.z())) return {CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z())};
    if (const auto it = exact_.find(q.id()); it != exact_.end()) return it->second;
    const size_t n = p.v.size();
    const Coefficients *s = integers(p.support), *e0 = integers(p.e[(i + n - 1) % n]), *e1 = integers(p.e[i]);
    std::optional<Vec3> r;
    if (s && e0 && e1) r = meeting_rounded(*s, *e0, *e1);
    if (!r) {
      CGAL::exact(q);
      const auto& b = CGAL::approx(q);
      r = Vec3{CGAL::to_double(b.x()), CGAL::to_double(b.y()), CGAL::to_double(b.z())};
    }
    exact_.emplace(q.id(), *r);
    return *r;
  }

  std::vector<Vec3> corners(const Poly& p, bool reverse) {
    std::vector<Vec3> out;
    out.reserve(p.v.size());
    for (size_t i = 0; i < p.v.size(); ++i) out.push_back(corner(p, i));
    if (reverse) std::reverse(out.begin(), out.end());
    return out;
  }

 private:
  const Coefficients* integers(const Pl& h) const {
    const auto it = facts_.find(h.id());
    return it != facts_.end() && it->second.integers ? &*it->second.integers : nullptr;
  }

  const std::unordered_map<CGAL::Handle::Id_type, PlaneFacts>& facts_;
  tbb::concurrent_unordered_map<CGAL::Handle::Id_type, Vec3> exact_;
};

/// Area [m²] of a rounded convex polygon, as a fan from its first vertex.
double area_of(const std::vector<Vec3>& p) {
  Vec3 s{0, 0, 0};
  for (size_t i = 1; i + 1 < p.size(); ++i) s = s + cross(p[i] - p[0], p[i + 1] - p[0]);
  return length(s) / 2;
}

/// Width [m] of a rounded convex polygon: the least, over its edges, of the distance from
/// the edge's line to the farthest corner.
double width_of(const std::vector<Vec3>& p) {
  double w = HUGE_VAL;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3 a = p[i], e = p[(i + 1) % p.size()] - a;
    const double l = length(e);
    if (!(l > 0)) continue;
    double far = 0;
    for (const Vec3& q : p) far = std::max(far, length(cross(e, q - a)) / l);
    w = std::min(w, far);
  }
  return w;
}

/// Drops each corner of p within `near` [m] (in every coordinate) of the corner kept
/// before it, and appends to `cut` the piece each drop cuts off (the corner with its two
/// neighbours then), so that those can stay opaque and the face stays covered.
void drop_close_corners(std::vector<Vec3>& p, double near, std::vector<std::vector<Vec3>>& cut) {
  auto close = [near](Vec3 a, Vec3 b) {
    return std::fabs(a.x - b.x) <= near && std::fabs(a.y - b.y) <= near && std::fabs(a.z - b.z) <= near;
  };
  const size_t n = p.size();
  std::vector<Vec3> kept;
  for (size_t i = 0; i < n; ++i) {
    if (!kept.empty() && close(kept.back(), p[i])) cut.push_back({kept.back(), p[i], p[(i + 1) % n]});
    else kept.push_back(p[i]);
  }
  while (kept.size() > 1 && close(kept.back(), kept.front())) {
    if (kept.size() > 2) cut.push_back({kept[kept.size() - 2], kept.back(), kept.front()});
    kept.pop_back();
  }
  p = std::move(kept);
}

/// [m] how narrow a corner's interval must be for its middle to place a halving plane.
constexpr double kPlacedWithin = 1e-3;

/// A polygon's corners to within their intervals (for estimates, not for the output): the
/// middles of those no wider than `within` [m] along any axis (every corner by default).
std::vector<Vec3> approx_corners(const Poly& p, double within = HUGE_VAL) {
  std::vector<Vec3> v;
  for (const P3& q : p.v) {
    const auto& a = CGAL::approx(q);
    if (!(std::max({a.x().sup() - a.x().inf(), a.y().sup() - a.y().inf(), a.z().sup() - a.z().inf()}) <= within))
      continue;
    v.push_back({CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z())});
  }
  return v;
}

/// Bounds of a polygon from its vertices' intervals, which hold the exact points: a cheap
/// rejection that never rejects a true overlap. (An interval's middle is no bound: a vertex
/// where nearly parallel planes meet can have an interval millimetres wide, and a fragment
/// covering a piece was once culled by such middles on one side of a face and not on the
/// other, so the face lost that part.)
Box3 interval_bounds(const Poly& p) {
  Box3 b;
  for (const P3& q : p.v) {
    const auto& a = CGAL::approx(q);
    b.add({a.x().inf(), a.y().inf(), a.z().inf()});
    b.add({a.x().sup(), a.y().sup(), a.z().sup()});
  }
  return b;
}

bool boxes_meet(const Box3& a, const Box3& b, double tol) {
  return a.lo.x <= b.hi.x + tol && b.lo.x <= a.hi.x + tol && a.lo.y <= b.hi.y + tol && b.lo.y <= a.hi.y + tol &&
         a.lo.z <= b.hi.z + tol && b.lo.z <= a.hi.z + tol;
}

/// A triangle as a plane-based polygon on `support` (its own plane, or one it lies on
/// within a rounding: cells/shared_planes.h), oriented as the triangle a, b, c: its edge
/// planes hold the edge and the support's dominant axis (small coefficients: differences of
/// input coordinates), so its corners are a, b and c moved along that axis onto the
/// support, and two triangles on one support that share an edge share its corners exactly.
/// `on_support[i]`: corner i lies on the support as it is (kept as the input point).
Poly triangle_poly(const Pl& support, const P3& a, const P3& b, const P3& c, const std::array<bool, 3>& on_support) {
  Poly p;
  p.support = support;
  const int k = dominant_axis(p.support);
  const std::array<int, 3> axis{k == 0 ? 1 : 0, k == 1 ? 1 : 0, k == 2 ? 1 : 0};
  const std::array<const P3*, 3> corner{&a, &b, &c};
  for (size_t i = 0; i < 3; ++i) {
    const P3 &s = *corner[i], &t = *corner[(i + 1) % 3], &o = *corner[(i + 2) % 3];
    const Pl e = plane_through(s, t, s, axis);
    p.e.push_back(e.oriented_side(o) == ON_POSITIVE_SIDE ? opposite_of(e) : e);
  }
  for (size_t i = 0; i < 3; ++i) p.v.push_back(on_support[i] ? *corner[i] : meet(p.support, p.e[(i + 2) % 3], p.e[i]));
  return p;
}

/// The approximate plane of a triangle, for choosing splitters in doubles.
struct ApproxPlane {
  Vec3 n;
  double d = 0;
  bool axis = false;  ///< exactly perpendicular to an axis
};

struct Builder {
  const Box3& box;
  FarPlanes far;
  std::vector<Node> nodes;
  std::vector<ApproxPlane> approx;
  std::vector<Pl> support_of;  ///< per triangle, its exact plane
  double tol = 0;              ///< [m] "on a plane" in the cost estimate

  struct Leaf {
    std::vector<CellFace> faces;
    std::vector<Frag> frags;  ///< all on its boundary
  };
  std::vector<Leaf> leaves;
  SoupBspStats stats;
  size_t leaf_budget = 0;  ///< more leaves throw SoupTooCluttered; 0: no limit

  /// The splitter for a cell: the plane of one of its interior fragments, the cheapest by
  /// 8·splits + |front − back| on a sample, non-axis-aligned planes paying extra. `lopsided`:
  /// whether even that one leaves nearly every sampled fragment on one side and cuts none
  /// worth counting (a convex cluster, such as a sphere's faces, where each face's plane has
  /// all the others behind it).
  int choose(const std::vector<Frag>& frags, const std::vector<size_t>& interior, bool* lopsided = nullptr) const {
    constexpr size_t kCandidates = 12, kSample = 64;
    const size_t m = interior.size();
    const size_t cstep = std::max<size_t>(1, m / kCandidates), sstep = std::max<size_t>(1, m / kSample);
    int best = -1;
    double best_cost = HUGE_VAL;
    for (size_t ci = 0; ci < m; ci += cstep) {
      const int tri = frags[interior[ci]].tri;
      const ApproxPlane& h = approx[size_t(tri)];
      double front = 0, back = 0, cut = 0, on = 0;
      for (size_t si = 0; si < m; si += sstep) {
        bool neg = false, pos = false;
        for (const P3& q : frags[interior[si]].poly.v) {
          const auto& a = CGAL::approx(q);
          const double s = dot(h.n, Vec3{CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z())}) + h.d;
          neg |= s < -tol, pos |= s > tol;
        }
        if (neg && pos) cut += 1;
        else if (neg) back += 1;
        else if (pos) front += 1;
        else on += 1;
      }
      const double n = front + back + cut + on;
      const double cost = 8 * cut + std::fabs(front - back) - on + (h.axis ? 0 : 0.25 * n);
      if (cost < best_cost) {
        best_cost = cost, best = tri;
        if (lopsided) *lopsided = std::min(front, back) + cut + on <= n / 16;
      }
    }
    return best;
  }

  /// Where no fragment's plane divides a large cell's fragments (choose's `lopsided`), each
  /// such plane would peel off one fragment: a chain as deep as the cluster is large, every
  /// level handling every fragment again (a sphere of 18,000 triangles took minutes). Such a
  /// cell is halved instead by an axis-aligned plane (exact: its offset is a double) through
  /// the median of the fragments' middles along their longest extent; fragments it crosses
  /// are cut like any others, and leaves of free space it parts are joined again where
  /// their union is convex. None when the fragments have no extent (all in one plane).
  std::optional<Pl> halving(const std::vector<Frag>& frags, const std::vector<size_t>& interior) const {
    Box3 b;
    std::vector<Vec3> middles;
    for (size_t i : interior) {
      // A corner whose interval is wider than a millimetre says little of where it is (its
      // middle can lie metres off): the fragment's other corners place it.
      const std::vector<Vec3> corners = approx_corners(frags[i].poly, kPlacedWithin);
      if (corners.empty()) continue;
      Vec3 m{0, 0, 0};
      for (const Vec3 p : corners) {
        b.add(p);
        m = m + p;
      }
      middles.push_back((1.0 / double(corners.size())) * m);
    }
    if (middles.empty()) return std::nullopt;
    const Vec3 e = b.hi - b.lo;
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
    auto coord = [axis](Vec3 p) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; };
    const double lo = coord(b.lo), hi = coord(b.hi);
    if (!(hi - lo > 1e3 * tol)) return std::nullopt;
    std::nth_element(middles.begin(), middles.begin() + std::ptrdiff_t(middles.size() / 2), middles.end(),
                     [&](Vec3 p, Vec3 q) { return coord(p) < coord(q); });
    // Inside the fragments' extent, clear of its ends: the plane crosses the cell.
    const double at = std::clamp(coord(middles[middles.size() / 2]), lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo));
    return plane_of(axis == 0 ? 1 : 0, axis == 1 ? 1 : 0, axis == 2 ? 1 : 0, -at);
  }

  /// A level plane at the top or the foot of the cell's interior fragments that leaves them
  /// all on one side and a slab of the cell, at least a fifth of its height, empty on the
  /// other: the air over a cluster (a grid of open boxes) parted from it in one piece, where
  /// every plane of the cluster, run on across it, would slice it into a column over each
  /// box and corridor. Only where the fragments reach it along an edge at least, each of
  /// those that touch it standing steeply on it (walls under their tops, within 60° of
  /// upright): a plane through one corner of a turned model, or along a face nearly level,
  /// would leave a wedge of free space thinner than rounding beside it, and one holding a
  /// floor changes which slivers rounding leaves for no gain. Exact: its offset is a
  /// double, and each fragment's side is asked exactly. Tried on the far box and the boxes
  /// such cuts make of it only.
  std::optional<Pl> empty_space_cut(const std::vector<CellFace>& faces, const std::vector<Frag>& frags,
                                    const std::vector<size_t>& interior) const {
    constexpr double kShare = 0.2;
    std::vector<Vec3> corners;
    std::vector<size_t> first;  // per interior fragment, its first corner in `corners`
    Box3 fb, cb;
    for (size_t i : interior) {
      first.push_back(corners.size());
      for (Vec3 p : approx_corners(frags[i].poly)) corners.push_back(p), fb.add(p);
    }
    first.push_back(corners.size());
    for (const CellFace& f : faces)
      for (Vec3 p : approx_corners(f.poly)) cb.add(p);
    const double margin = 1e3 * tol, height = cb.hi.z - cb.lo.z;
    if (!(height > 0)) return std::nullopt;
    // The fragments' top, then their foot, the wider empty slab first.
    std::vector<std::pair<double, double>> levels;  // (empty height, level)
    if (cb.hi.z - fb.hi.z > kShare * height && fb.hi.z > cb.lo.z + margin) levels.push_back({cb.hi.z - fb.hi.z, fb.hi.z});
    if (fb.lo.z - cb.lo.z > kShare * height && fb.lo.z < cb.hi.z - margin) levels.push_back({fb.lo.z - cb.lo.z, fb.lo.z});
    if (levels.size() == 2 && levels[1].first > levels[0].first) std::swap(levels[0], levels[1]);
    for (const auto& [gap, at] : levels) {
      // The fragments reach it along an edge at least (two corners on it, as a grid's wall
      // tops do), and each that touches it stands steeply on it.
      const Vec3* one = nullptr;
      bool two = false, steep = true;
      for (size_t f = 0; f + 1 < first.size() && steep; ++f) {
        bool touches = false;
        for (size_t k = first[f]; k < first[f + 1]; ++k) {
          if (corners[k].z != at) continue;
          touches = true;
          if (!one) one = &corners[k];
          else two = two || !(corners[k] == *one);
        }
        if (!touches) continue;
        const Vec3 n = approx[size_t(frags[interior[f]].tri)].n;
        steep = std::fabs(n.z) <= 0.5 * length(n);
      }
      if (!two || !steep) continue;
      const Pl h = plane_of(0, 0, 1, -at);
      const Pl o = opposite_of(h);
      bool clear = true;
      for (size_t i : interior)
        if (split(frags[i].poly, h, o, nullptr, nullptr) == Where::Both) {
          clear = false;
          break;
        }
      if (clear) return h;
    }
    return std::nullopt;
  }

  void build(std::vector<CellFace> root_faces, std::vector<Frag> root_frags) {
    struct Task {
      int node;
      std::vector<CellFace> faces;
      std::vector<Frag> frags;
      int depth;
      bool boxed = false;  ///< the far box cut by empty_space_cut alone: a box
    };
    nodes.emplace_back();
    std::vector<Task> stack;
    stack.push_back({0, std::move(root_faces), std::move(root_frags), 0, true});
    while (!stack.empty()) {
      check_memory_reserve();  // a model sliced finely can outgrow the machine (core/memory_reserve.h)
      Task t = std::move(stack.back());
      stack.pop_back();
      std::vector<size_t> interior;
      for (size_t i = 0; i < t.frags.size(); ++i)
        if (t.frags[i].on == kInterior) interior.push_back(i);
      if (interior.empty()) {
        nodes[size_t(t.node)].leaf = int(leaves.size());
        stats.depth = std::max(stats.depth, t.depth);
        stats.fragments += t.frags.size();
        leaves.push_back({std::move(t.faces), std::move(t.frags)});
        if (leaf_budget > 0 && leaves.size() > leaf_budget)
          throw SoupTooCluttered("the soup's planes cut space into more than " + std::to_string(leaf_budget) + " leaves");
        continue;
      }
      const int id = t.node;
      constexpr size_t kHalveFrom = 1024;  ///< interior fragments; fewer make a chain short enough
      bool lopsided = false;
      const std::optional<Pl> empty = t.boxed ? empty_space_cut(t.faces, t.frags, interior) : std::nullopt;
      const int tri = empty ? -1 : choose(t.frags, interior, &lopsided);
      std::optional<Pl> halve;
      if (lopsided && interior.size() >= kHalveFrom) halve = halving(t.frags, interior);
      Pl h = empty ? *empty : halve ? *halve : support_of[size_t(tri)];
      // The new face on h, cut to the cell. A halving plane is placed from the fragments'
      // corners as doubles, and a corner whose interval is wide can still mislead it (where
      // a chain of cuts met nearly parallel planes): where it misses the cell, the chosen
      // fragment's own plane, which crosses it, cuts instead.
      Poly cap = section(h, t.faces, far);
      if (cap.v.size() < 3 && halve) {
        h = support_of[size_t(tri)];
        cap = section(h, t.faces, far);
        ++stats.halvings_missed;
      }
      if (cap.v.size() < 3) throw std::logic_error("soup bsp: a splitting plane misses its cell");
      const Pl o = opposite_of(h);
      nodes[size_t(id)].plane = h;
      nodes[size_t(id)].opposite = o;
      ++stats.nodes;
      Task neg{int(nodes.size()), {}, {}, t.depth + 1, bool(empty)}, pos{int(nodes.size()) + 1, {}, {}, t.depth + 1, bool(empty)};
      nodes[size_t(id)].child[0] = neg.node, nodes[size_t(id)].child[1] = pos.node;
      nodes.emplace_back();
      nodes.emplace_back();
      // The cell's faces, cut; then the cap, outward for each side.
      for (CellFace& f : t.faces) {
        CellFace a{{}, f.id, f.toward}, b{{}, f.id, f.toward};
        switch (split(f.poly, h, o, &a.poly, &b.poly)) {
          case Where::Neg: neg.faces.push_back(std::move(f)); break;
          case Where::Pos: pos.faces.push_back(std::move(f)); break;
          case Where::Both:
            neg.faces.push_back(std::move(a));
            pos.faces.push_back(std::move(b));
            break;
          case Where::On: throw std::logic_error("soup bsp: a splitting plane holds a face of its cell");
        }
      }
      neg.faces.push_back({cap, id, 1});
      cap.support = o;
      pos.faces.push_back({std::move(cap), id, 0});
      for (Frag& f : t.frags) {
        Frag a{{}, f.tri, f.on}, b{{}, f.tri, f.on};
        switch (split(f.poly, h, o, &a.poly, &b.poly)) {
          case Where::Neg: neg.frags.push_back(std::move(f)); break;
          case Where::Pos: pos.frags.push_back(std::move(f)); break;
          case Where::Both:
            neg.frags.push_back(std::move(a));
            pos.frags.push_back(std::move(b));
            break;
          case Where::On:
            f.on = id;
            neg.frags.push_back(f);
            pos.frags.push_back(std::move(f));
            break;
        }
      }
      stack.push_back(std::move(pos));
      stack.push_back(std::move(neg));
    }
    stats.leaves = leaves.size();
  }

  /// The pieces of face f (of leaf `self`) facing each leaf below `node`.
  void neighbours(int node, const Poly& f, int self, std::vector<std::pair<int, Poly>>& out) const {
    std::vector<std::pair<int, Poly>> stack{{node, f}};
    while (!stack.empty()) {
      auto [n, p] = std::move(stack.back());
      stack.pop_back();
      const Node& nd = nodes[size_t(n)];
      if (nd.leaf >= 0) {
        if (nd.leaf != self) out.emplace_back(nd.leaf, std::move(p));
        continue;
      }
      Poly a, b;
      switch (split(p, nd.plane, nd.opposite, &a, &b)) {
        case Where::Neg: stack.emplace_back(nd.child[0], std::move(p)); break;
        case Where::Pos: stack.emplace_back(nd.child[1], std::move(p)); break;
        case Where::Both:
          stack.emplace_back(nd.child[0], std::move(a));
          stack.emplace_back(nd.child[1], std::move(b));
          break;
        case Where::On: throw std::logic_error("soup bsp: a face lies on a plane of the other side");
      }
    }
  }
};

/// `piece` minus convex `hole` (same plane): the convex pieces outside it go to `rest`;
/// the part inside is returned (empty when they do not overlap).
Poly subtract(Poly piece, const Poly& hole, std::vector<Poly>& rest) {
  Poly in, out;
  for (const Pl& e : hole.e) {
    switch (split(piece, e, &in, &out)) {
      case Where::Neg: break;
      case Where::Pos:
      case Where::On:
        rest.push_back(std::move(piece));
        return {};
      case Where::Both:
        rest.push_back(std::move(out));
        std::swap(piece, in);
        break;
    }
  }
  return piece;
}

/// What leaf `self` sees across one face toward leaf `other`.
struct Contact {
  int other = -1;
  std::vector<Poly> opaque;  ///< covered by the leaf's fragments on the face
  std::vector<MaterialId> material;
  std::vector<Poly> open;    ///< not covered: portals (from the lower-numbered leaf)
};

/// The side of h (whose opposite_of is o) on which corner i of p lies: on it when p's
/// support or one of the corner's two edges is h or o, known by identity; else side_of_vertex.
Side side_of_corner(const Pl& h, const Pl& o, const Poly& p, size_t i) {
  auto same = [&](const Pl& e) { return CGAL::identical(h, e) || CGAL::identical(o, e); };
  const size_t n = p.v.size();
  if (same(p.support) || same(p.e[i]) || same(p.e[(i + n - 1) % n])) return ON_ORIENTED_BOUNDARY;
  return side_of_vertex(h, p, i);
}

/// Leaves joined into one convex cell (Teller 1992 §3 and qbsp merge a BSP's leaves the same
/// way): every splitting plane runs on across the whole cell it cuts, far beyond the polygon
/// it came from, so free space away from the scene ends up in many leaves whose common faces
/// hold nothing. Two unions g and h are joined across a face when that face, on g's side and
/// on h's, is open onto the other alone (no fragment on it: no opaque piece), and every corner
/// of each lies inside every face plane of the other (but the shared one): then g ∪ h is the
/// intersection of both sets of half-spaces, convex, exactly.
struct Union {
  struct Face {
    Pl plane;                               ///< outward: every part's support
    std::vector<std::pair<int, int>> parts; ///< (leaf, face of the leaf) on this plane
  };
  std::vector<int> leaves;  ///< empty once joined into another
  std::vector<Face> faces;
};

std::vector<Union> join_leaves(const std::vector<Builder::Leaf>& leaves,
                               const std::vector<std::vector<std::vector<Contact>>>& contacts, std::vector<int>& union_of,
                               double crack) {
  const size_t n = leaves.size();
  std::vector<Union> u(n);
  union_of.resize(n);
  for (size_t l = 0; l < n; ++l) {
    union_of[l] = int(l);
    u[l].leaves = {int(l)};
    for (size_t k = 0; k < leaves[l].faces.size(); ++k) u[l].faces.push_back({leaves[l].faces[k].poly.support, {{int(l), int(k)}}});
  }
  // Leaf faces holding a crack (an open piece no wider than `crack`), which no join crosses:
  // told once, not at every look at the face.
  std::vector<std::vector<char>> cracked(n);
  for (size_t l = 0; l < n; ++l) {
    cracked[l].assign(contacts[l].size(), 0);
    if (crack > 0)
      for (size_t k = 0; k < contacts[l].size(); ++k)
        for (const Contact& c : contacts[l][k])
          for (const Poly& p : c.open) cracked[l][k] = cracked[l][k] || !(width_of(approx_corners(p)) > crack);
  }
  // The union that face f of union g is wholly open onto, or -1.
  auto open_onto = [&](int g, const Union::Face& f) {
    int h = -1;
    for (const auto& [l, k] : f.parts) {
      if (leaves[size_t(l)].faces[size_t(k)].id < 0) return -1;  // the far box
      const std::vector<Contact>& cs = contacts[size_t(l)][size_t(k)];
      if (cs.empty() || cracked[size_t(l)][size_t(k)]) return -1;
      for (const Contact& c : cs) {
        const int o = union_of[size_t(c.other)];
        if (!c.opaque.empty() || o == g || (h >= 0 && o != h)) return -1;
        h = o;
      }
    }
    return h;
  };
  // Every corner of a's faces but skip_a inside every face plane of b but skip_b.
  auto inside = [&](const Union& a, size_t skip_a, const Union& b, size_t skip_b) {
    for (size_t q = 0; q < b.faces.size(); ++q) {
      if (q == skip_b) continue;
      const Pl& h = b.faces[q].plane;
      const Pl& o = opposite_of(h);
      for (size_t f = 0; f < a.faces.size(); ++f) {
        if (f == skip_a) continue;
        for (const auto& [l, k] : a.faces[f].parts) {
          const Poly& p = leaves[size_t(l)].faces[size_t(k)].poly;
          for (size_t i = 0; i < p.v.size(); ++i)
            if (side_of_corner(h, o, p, i) == ON_POSITIVE_SIDE) return false;
        }
      }
    }
    return true;
  };
  for (bool joined = true; joined;) {
    joined = false;
    for (size_t g = 0; g < n; ++g)
      for (size_t f = 0; f < u[g].faces.size(); ++f) {
        const int h = open_onto(int(g), u[g].faces[f]);
        if (h < 0) continue;
        Union &G = u[g], &H = u[size_t(h)];
        const Pl& back = opposite_of(G.faces[f].plane);
        size_t hf = 0;
        while (hf < H.faces.size() && !same_plane(H.faces[hf].plane, back)) ++hf;
        if (hf == H.faces.size() || open_onto(h, H.faces[hf]) != int(g)) continue;
        if (!inside(H, hf, G, f) || !inside(G, f, H, hf)) continue;
        std::vector<Union::Face> faces;
        for (size_t q = 0; q < G.faces.size(); ++q)
          if (q != f) faces.push_back(std::move(G.faces[q]));
        const size_t from_g = faces.size();
        for (size_t q = 0; q < H.faces.size(); ++q) {
          if (q == hf) continue;
          size_t j = 0;
          while (j < from_g && !same_plane(faces[j].plane, H.faces[q].plane)) ++j;
          if (j < from_g) faces[j].parts.insert(faces[j].parts.end(), H.faces[q].parts.begin(), H.faces[q].parts.end());
          else faces.push_back(std::move(H.faces[q]));
        }
        G.faces = std::move(faces);
        for (int l : H.leaves) union_of[size_t(l)] = int(g);
        G.leaves.insert(G.leaves.end(), H.leaves.begin(), H.leaves.end());
        H.leaves.clear();
        H.faces.clear();
        joined = true;
        f = size_t(-1);  // g has new faces: look at them all again
      }
  }
  return u;
}

/// The rounded corners of coplanar convex polygons whose union is convex (a union's face
/// made of several leaves' faces), counter-clockwise seen from inside (about −n, n the
/// outward normal): the hull of the rounded corners, with exact predicates on those doubles,
/// so that corners the join leaves in the middle of a straight edge go.
std::vector<Vec3> joined_face(const std::vector<const Poly*>& parts, Vec3 n, Rounding& rounding) {
  std::vector<Epick::Point_3> pts;
  for (const Poly* p : parts)
    for (size_t i = 0; i < p->v.size(); ++i) {
      const Vec3 r = rounding.corner(*p, i);
      pts.emplace_back(r.x, r.y, r.z);
    }
  std::vector<Epick::Point_3> hull;
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  if (ax >= ay && ax >= az) CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull), CGAL::Projection_traits_yz_3<Epick>());
  else if (ay >= az) CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull), CGAL::Projection_traits_xz_3<Epick>());
  else CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull), CGAL::Projection_traits_xy_3<Epick>());
  std::vector<Vec3> out;
  for (const Epick::Point_3& p : hull) out.push_back({p.x(), p.y(), p.z()});
  Vec3 newell{0, 0, 0};
  for (size_t i = 0; i < out.size(); ++i) newell = newell + cross(out[i] - out[0], out[(i + 1) % out.size()] - out[0]);
  if (dot(newell, n) > 0) std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace

SoupBspStats decompose_soup(const std::vector<SoupTriangle>& triangles, const Box3& box, CellComplex& out,
                            size_t leaf_budget) {
  struct ForgetPlanes {
    ~ForgetPlanes() { forget_plane_facts(); }
  } forget;  // on every way out
  const double scale = box.magnitude();
  Builder b{box, far_planes(box), {}, {}, {}, 1e-12 * scale, {}, {}};
  b.leaf_budget = leaf_budget;
  std::vector<Frag> frags;
  std::vector<CellFace> root;
  std::vector<MaterialId> material;
  {
    ScopedStageTimer timer(out.timings, "decompose");
    // Nearly coplanar neighbours on one plane (cells/shared_planes.h): each plane exact,
    // made once, and in doubles for choosing splitters.
    const SharedPlanes shared = shared_planes(triangles);
    std::vector<std::optional<Pl>> exact_plane(shared.planes.size());
    auto as_point = [](Vec3 p) { return P3(p.x, p.y, p.z); };
    auto approx_plane = [](const std::array<Vec3, 3>& p) {
      ApproxPlane h;
      h.n = cross(p[1] - p[0], p[2] - p[0]);
      h.n = (1.0 / length(h.n)) * h.n;
      h.d = -dot(h.n, p[0]);
      h.axis = (p[0].x == p[1].x && p[1].x == p[2].x) || (p[0].y == p[1].y && p[1].y == p[2].y) ||
               (p[0].z == p[1].z && p[1].z == p[2].z);
      return h;
    };
    for (size_t i = 0; i < triangles.size(); ++i) {
      const SoupTriangle& t = triangles[i];
      const P3 a = as_point(t.p[0]), c1 = as_point(t.p[1]), c2 = as_point(t.p[2]);
      if (CGAL::collinear(a, c1, c2)) {
        b.stats.degenerate.push_back(i);
        continue;
      }
      Frag f;
      const size_t s = size_t(shared.plane_of[i]);
      const auto& sp = shared.planes[s].p;
      // A plane's corners have area in doubles (shared_planes), so are never collinear.
      if (!exact_plane[s]) exact_plane[s] = plane_through(as_point(sp[0]), as_point(sp[1]), as_point(sp[2]), {0, 0, 0});
      ApproxPlane h = approx_plane(sp);
      if (shared.own[i]) {
        f.poly = triangle_poly(*exact_plane[s], a, c1, c2, {true, true, true});
      } else {
        const bool turned = dot(cross(t.p[1] - t.p[0], t.p[2] - t.p[0]), h.n) < 0;
        if (turned) h.n = -1.0 * h.n, h.d = -h.d;
        auto epick = [](Vec3 p) { return Epick::Point_3(p.x, p.y, p.z); };
        const Epick::Point_3 q0 = epick(sp[0]), q1 = epick(sp[1]), q2 = epick(sp[2]);
        // How far a corner moves: along the plane's dominant axis, onto the plane.
        const double along = std::max({std::fabs(h.n.x), std::fabs(h.n.y), std::fabs(h.n.z)});
        std::array<bool, 3> on{};
        for (size_t k = 0; k < 3; ++k) {
          on[k] = CGAL::orientation(q0, q1, q2, epick(t.p[k])) == CGAL::COPLANAR;
          if (!on[k]) b.stats.largest_snap = std::max(b.stats.largest_snap, std::fabs(dot(h.n, t.p[k]) + h.d) / along);
        }
        ++b.stats.snapped;
        f.poly = triangle_poly(turned ? opposite_of(*exact_plane[s]) : *exact_plane[s], a, c1, c2, on);
      }
      f.tri = int(b.support_of.size());
      b.support_of.push_back(f.poly.support);
      b.approx.push_back(h);
      material.push_back(t.material);
      frags.push_back(std::move(f));
    }
    b.stats.triangles = frags.size();
    // The far box as a cell: each face the quad on its plane, cut by the others.
    std::vector<CellFace> faces;
    for (int k = 0; k < 6; ++k) faces.push_back({quad_on(b.far[size_t(k)], b.far), -1 - k, 0});
    for (int k = 0; k < 6; ++k) {
      std::vector<CellFace> others;
      for (int j = 0; j < 6; ++j)
        if (j != k) others.push_back(faces[size_t(j)]);
      root.push_back({section(b.far[size_t(k)], others, b.far), -1 - k, 0});
    }
    b.build(std::move(root), std::move(frags));
  }

  ScopedStageTimer timer(out.timings, "cells");
  // What each leaf sees across each face, exact. (In order, on one thread: where a side
  // test falls back to exact points, it settles them, and how each point is later rounded
  // depends on that; threads would make the output depend on their timing.)
  std::vector<std::vector<std::vector<Contact>>> contacts(b.leaves.size());
  for (size_t l = 0; l < b.leaves.size(); ++l) {
    check_memory_reserve();
    const Builder::Leaf& leaf = b.leaves[l];
    contacts[l].resize(leaf.faces.size());
    for (size_t k = 0; k < leaf.faces.size(); ++k) {
      const CellFace& face = leaf.faces[k];
      if (face.id < 0) continue;  // the far box: opaque
      std::vector<std::pair<int, Poly>> pieces;
      b.neighbours(b.nodes[size_t(face.id)].child[face.toward], face.poly, int(l), pieces);
      std::vector<std::pair<const Frag*, Box3>> cover;
      for (const Frag& f : leaf.frags)
        if (f.on == face.id) cover.emplace_back(&f, interval_bounds(f.poly));
      for (auto& [other, piece] : pieces) {
        Contact c;
        c.other = other;
        // Only the fragments meeting a piece's bounds can cover part of it (a big face
        // may hold thousands of fragments and face thousands of small leaves; a face
        // tessellated finely leaves as many open pieces as it has fragments, each met by
        // a few).
        const Box3 pb = interval_bounds(piece);
        std::vector<std::pair<Poly, Box3>> open;
        open.emplace_back(std::move(piece), pb);
        std::vector<Poly> outside;
        for (const auto& [f, fb] : cover) {
          if (!boxes_meet(fb, pb, b.tol)) continue;
          std::vector<std::pair<Poly, Box3>> next;
          for (auto& [r, rb] : open) {
            if (!boxes_meet(fb, rb, b.tol)) {
              next.emplace_back(std::move(r), rb);
              continue;
            }
            outside.clear();
            Poly in = subtract(std::move(r), f->poly, outside);
            if (in.v.size() >= 3) {
              c.opaque.push_back(std::move(in));
              c.material.push_back(material[size_t(f->tri)]);
            }
            for (Poly& o : outside) {
              const Box3 ob = interval_bounds(o);
              next.emplace_back(std::move(o), ob);
            }
          }
          open = std::move(next);
          if (open.empty()) break;
        }
        for (auto& [r, rb] : open) c.open.push_back(std::move(r));
        contacts[l][k].push_back(std::move(c));
      }
    }
  }

  // Leaves joined into convex unions: the cells.
  std::vector<int> union_of;
  // How wide a crack left by corners moved onto a shared plane can be: twice the largest
  // move, and the rounding of the corners (as thin as drop_slivers' slivers).
  const double crack = b.stats.snapped > 0 ? 2 * b.stats.largest_snap + 1e-9 * scale : 0;  // [m]
  const std::vector<Union> unions = join_leaves(b.leaves, contacts, union_of, crack);
  std::vector<CellId> cell_of(unions.size(), kNoCell);
  const CellId base = CellId(out.cells.size());
  {
    CellId next = base;
    for (size_t g = 0; g < unions.size(); ++g)
      if (!unions[g].leaves.empty()) cell_of[g] = next++;
  }
  auto cell_of_leaf = [&](int l) { return cell_of[size_t(union_of[size_t(l)])]; };

  // Portals, from the lower-numbered leaf of each pair in two cells: convex,
  // counter-clockwise about its outward normal. A piece that rounds to no area stays opaque
  // on both sides, and so does a crack left where triangles put on another's plane moved a
  // corner their neighbours keep (no wider than twice the move: see soup_bsp.h).
  const double tiny = 1e-18 * scale * scale;  // [m²]
  struct Shared {
    std::vector<PortalId> portals;
    std::vector<std::vector<Vec3>> closed;  ///< counter-clockwise about the lower leaf's outward normal
  };
  std::map<std::pair<int, int>, Shared> shared;
  // Every point to be rounded below is rounded first in parallel (Rounding: a point's double
  // depends on nothing but the point, and the exact ones are kept); what follows on one
  // thread then finds them. Where a plane has no integers, CGAL's lazy numbers are safe to
  // share between threads (CGAL_HAS_THREADS: exact values made once, under std::call_once).
  Rounding rounding(plane_facts);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, b.leaves.size(), 64), [&](const tbb::blocked_range<size_t>& range) {
    auto tighten = [&rounding](const Poly& p) {
      for (size_t i = 0; i < p.v.size(); ++i) rounding.corner(p, i);
    };
    check_memory_reserve();
    for (size_t l = range.begin(); l != range.end(); ++l)
      for (size_t k = 0; k < b.leaves[l].faces.size(); ++k) {
        tighten(b.leaves[l].faces[k].poly);
        for (const Contact& c : contacts[l][k]) {
          for (const Poly& p : c.opaque) tighten(p);
          for (const Poly& p : c.open) tighten(p);
        }
      }
  });
  std::vector<std::vector<Plane>> planes(b.leaves.size());
  for (size_t l = 0; l < b.leaves.size(); ++l)
    for (const CellFace& face : b.leaves[l].faces) {
      const Pl& h = face.poly.support;
      Vec3 n{CGAL::to_double(h.a()), CGAL::to_double(h.b()), CGAL::to_double(h.c())};
      n = (1.0 / length(n)) * n;
      const std::vector<Vec3> poly = rounding.corners(face.poly, false);
      double d = 0;
      for (Vec3 p : poly) d -= dot(n, p);
      planes[l].push_back({n, d / double(poly.size())});
    }
  for (size_t l = 0; l < b.leaves.size(); ++l)
    for (size_t k = 0; k < b.leaves[l].faces.size(); ++k) {
      const bool about_n = ccw_about_normal(b.leaves[l].faces[k].poly);
      for (const Contact& c : contacts[l][k]) {
        if (c.other < int(l) || cell_of_leaf(c.other) == cell_of_leaf(int(l))) continue;
        Shared& s = shared[{int(l), c.other}];
        for (const Poly& p : c.open) {
          std::vector<Vec3> poly = rounding.corners(p, !about_n);
          // Corners a crack apart are one corner: the short side between them would give the
          // search a plane through the eye turned by its corners' rounding.
          if (crack > 0) drop_close_corners(poly, crack, s.closed);
          if (poly.size() < 3 || !(area_of(poly) > tiny) || (crack > 0 && !(width_of(poly) > crack))) {
            s.closed.push_back(std::move(poly));
            continue;
          }
          Portal portal;
          portal.cell[0] = cell_of_leaf(int(l)), portal.cell[1] = cell_of_leaf(c.other);
          portal.poly = std::move(poly);
          portal.plane = planes[l][k];
          portal.kind = PortalKind::Open;
          s.portals.push_back(PortalId(out.portals.size()));
          out.portals.push_back(std::move(portal));
        }
      }
    }

  // The cells: faces rounded, counter-clockwise seen from inside (about −n).
  for (const Union& un : unions) {
    if (un.leaves.empty()) continue;
    Cell cell;
    cell.kind = CellKind::Outside;
    cell.prism = false;
    // The outline seen from above is for drawings and indexing only: the hull of the
    // rounded vertices, with exact predicates on those doubles (an exact hull of the exact
    // points took a fifth of the Viking room's time in comparisons of constructed points).
    std::vector<Epick::Point_2> xy;
    cell.z0 = HUGE_VAL, cell.z1 = -HUGE_VAL;
    for (const Union::Face& uf : un.faces)
      for (const auto& [l, k] : uf.parts)
        for (size_t i = 0; i < b.leaves[size_t(l)].faces[size_t(k)].poly.v.size(); ++i) {
          const Vec3 q = rounding.corner(b.leaves[size_t(l)].faces[size_t(k)].poly, i);
          xy.emplace_back(q.x, q.y);
          cell.z0 = std::min(cell.z0, q.z), cell.z1 = std::max(cell.z1, q.z);
        }
    std::vector<Epick::Point_2> hull;
    CGAL::convex_hull_2(xy.begin(), xy.end(), std::back_inserter(hull));
    for (const Epick::Point_2& p : hull) cell.footprint.push_back({p.x(), p.y()});
    for (const Union::Face& uf : un.faces) {
      Face face;
      if (uf.parts.size() == 1) {
        const auto [l, k] = uf.parts.front();
        const CellFace& cf = b.leaves[size_t(l)].faces[size_t(k)];
        face.plane = planes[size_t(l)][size_t(k)];
        face.poly = rounding.corners(cf.poly, ccw_about_normal(cf.poly));
      } else {
        std::vector<const Poly*> polys;
        for (const auto& [l, k] : uf.parts) polys.push_back(&b.leaves[size_t(l)].faces[size_t(k)].poly);
        face.plane.n = planes[size_t(uf.parts.front().first)][size_t(uf.parts.front().second)].n;
        face.poly = joined_face(polys, face.plane.n, rounding);
        double d = 0;
        for (Vec3 p : face.poly) d -= dot(face.plane.n, p);
        face.plane.d = d / double(face.poly.size());
      }
      for (const auto& [l, k] : uf.parts) {
        const CellFace& cf = b.leaves[size_t(l)].faces[size_t(k)];
        const bool about_n = ccw_about_normal(cf.poly);
        if (cf.id < 0) face.opaque.push_back({rounding.corners(cf.poly, about_n), -1});
        for (const Contact& c : contacts[size_t(l)][size_t(k)]) {
          for (size_t i = 0; i < c.opaque.size(); ++i) face.opaque.push_back({rounding.corners(c.opaque[i], about_n), c.material[i]});
          const bool lower = l < c.other;
          const auto it = shared.find(lower ? std::pair{l, c.other} : std::pair{c.other, l});
          if (it == shared.end()) continue;
          for (PortalId p : it->second.portals) face.portals.push_back(p);
          for (const std::vector<Vec3>& poly : it->second.closed) {
            std::vector<Vec3> q = poly;
            if (lower) std::reverse(q.begin(), q.end());
            face.opaque.push_back({std::move(q), -1});
          }
        }
      }
      cell.portals.insert(cell.portals.end(), face.portals.begin(), face.portals.end());
      cell.faces.push_back(std::move(face));
    }
    // Faces with the most portals last (Cell::prism == false: in no particular order).
    std::stable_sort(cell.faces.begin(), cell.faces.end(),
                     [](const Face& x, const Face& y) { return x.portals.size() < y.portals.size(); });
    out.cells.push_back(std::move(cell));
  }
  b.stats.cells = out.cells.size() - size_t(base);
  return b.stats;
}

}  // namespace avenues
