// Tests of Mask::absorb (visibility/mask.h), the union of two masks that the merged search
// (TraverseParams::merge_pieces) makes of two avenues into one cell: in float, double and
// exact rationals, two masks parted by one line become one exactly when their union is
// convex, and a junction where the outline runs straight on keeps one line, not two.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <CGAL/Gmpq.h>

#include "visibility/mask.h"

using namespace avenues;

namespace {

template <class T>
class MaskMerge : public ::testing::Test {};

using Kinds = ::testing::Types<float, double, CGAL::Gmpq>;
TYPED_TEST_SUITE(MaskMerge, Kinds);

template <class T>
double as_double(const T& x) {
  if constexpr (std::is_floating_point_v<T>) return double(x);
  else return x.to_double();
}

/// The unit square cut by the line x = c (through the eye's picture plane, as a portal edge
/// would cut it): the left piece keeps x <= c, the right x >= c, with exactly opposite
/// coefficients, as the two sides of one portal edge give them.
template <class T>
std::pair<Mask<T>, Mask<T>> halves(T c) {
  Mask<T> left = Mask<T>::window(T(0), T(1), T(0), T(1)), right = left;
  left.clip({T(-1), T(0), c});
  right.clip({T(1), T(0), T(0) - c});
  return {left, right};
}

template <class T>
double area(const Mask<T>& m) {
  return 0.5 * as_double(m.area2());
}

}  // namespace

TYPED_TEST(MaskMerge, TwoHalvesOfASquareBecomeTheSquareWithFourSides) {
  using T = TypeParam;
  auto [left, right] = halves<T>(T(3) / T(8));
  ASSERT_EQ(left.half_planes().size(), 4u);
  ASSERT_EQ(right.half_planes().size(), 4u);
  ASSERT_TRUE(left.absorb(right));
  // The bottom and top edges ran straight across the cut: one line each, not two.
  EXPECT_EQ(left.half_planes().size(), 4u);
  EXPECT_NEAR(area(left), 1.0, 1e-6);
  for (const auto& v : left.polygon()) {
    EXPECT_TRUE(std::fabs(as_double(v.x)) < 1e-6 || std::fabs(as_double(v.x) - 1) < 1e-6);
    EXPECT_TRUE(std::fabs(as_double(v.y)) < 1e-6 || std::fabs(as_double(v.y) - 1) < 1e-6);
  }
}

TYPED_TEST(MaskMerge, PiecesWhoseUnionIsNotConvexStayApart) {
  using T = TypeParam;
  // The right half cut lower: the union is an L, so they must not merge.
  auto [left, right] = halves<T>(T(1) / T(2));
  right.clip({T(0), T(-1), T(1) / T(2)});  // y <= 1/2
  const auto before = left.half_planes().size();
  EXPECT_FALSE(left.absorb(right));
  EXPECT_EQ(left.half_planes().size(), before);
  EXPECT_NEAR(area(left), 0.5, 1e-6);
  // Disjoint masks that share no line do not merge either.
  Mask<T> far = Mask<T>::window(T(3), T(4), T(0), T(1));
  EXPECT_FALSE(left.absorb(far));
}

TYPED_TEST(MaskMerge, ATriangleAndATrapezoidMakeATriangleWithATurnAtTheCut) {
  using T = TypeParam;
  // The triangle y >= 0, y <= x, x <= 1 cut at x = 1/2: the pieces merge back into the
  // triangle; at the cut the outline turns (no straight run), so three sides remain.
  Mask<T> tri = Mask<T>::window(T(-10), T(10), T(-10), T(10));
  tri.clip({T(0), T(1), T(0)});   // y >= 0
  tri.clip({T(1), T(-1), T(0)});  // y <= x
  tri.clip({T(-1), T(0), T(1)});  // x <= 1
  ASSERT_EQ(tri.half_planes().size(), 3u);
  Mask<T> a = tri, b = tri;
  a.clip({T(-1), T(0), T(1) / T(2)});
  b.clip({T(1), T(0), T(-1) / T(2)});
  EXPECT_NEAR(area(a) + area(b), 0.5, 1e-6);
  ASSERT_TRUE(b.absorb(a));
  EXPECT_EQ(b.half_planes().size(), 3u);
  EXPECT_NEAR(area(b), 0.5, 1e-6);
}

TYPED_TEST(MaskMerge, PiecesFarFromTheOriginMergeAsNearIt) {
  using T = TypeParam;
  // The same halves 10^4 picture units off centre (a wide view's edge): the cut's
  // coefficients are large, the pieces still merge into one quadrilateral. (In float a
  // mask there must be wider than float's sign bound, about 0.3 units: 100 units here.)
  const T w = std::is_same_v<T, float> ? T(100) : T(1);
  Mask<T> left = Mask<T>::window(T(10000), T(10000) + w, T(-10000), T(-10000) + w), right = left;
  left.clip({T(-1), T(0), T(10000) + w / T(4)});
  right.clip({T(1), T(0), T(0) - T(10000) - w / T(4)});
  ASSERT_TRUE(left.absorb(right));
  EXPECT_EQ(left.half_planes().size(), 4u);
  const double wd = as_double(w);
  EXPECT_NEAR(area(left), wd * wd, 1e-6 * wd * wd);
}

// Mask::hull, the hull search's join (TraverseParams::hull_pieces): two masks apart, and two
// whose union is not convex, become one convex mask holding both, with the hull's area
// (exactly in rationals; grown by far less than a sample in floating point).
TYPED_TEST(MaskMerge, TheHullOfTwoMasksHoldsBothAndNothingFarOutside) {
  using T = TypeParam;
  Mask<T> a = Mask<T>::window(T(0), T(1), T(0), T(1));
  Mask<T> b = Mask<T>::window(T(2), T(3), T(1), T(2));  // apart: the hull is a hexagon
  b.clip({T(-1), T(-1), T(5) - T(1) / T(2)});            // its corner (3, 2) cut off
  std::vector<Point2T<T>> points;
  for (const Mask<T>* m : {&a, &b})
    for (const auto& v : m->polygon()) points.push_back(v);
  points.push_back({T(1) / T(2), T(1) / T(2)});  // inside: changes nothing
  const Mask<T> h = Mask<T>::hull(points);
  ASSERT_FALSE(h.empty());
  // The hull of (0,0) (1,0) (3,1) (3,1.5) (2.5,2) (2,2) (0,1): 7 corners, area 3.875 by the shoelace formula.
  EXPECT_EQ(h.half_planes().size(), 7u);
  EXPECT_NEAR(area(h), 3.875, (std::is_same_v<T, float> ? 0.1 : 1e-6));  // each side moved out by 1e-3 (float), 1e-8 (double) of 4
  for (const Mask<T>* m : {&a, &b})
    for (const auto& v : m->polygon())
      for (const HalfPlane<T>& l : h.half_planes()) EXPECT_GE(as_double(l.a * v.x + l.b * v.y + l.c), 0.0);
  // A corner stays where it is (within the growth).
  bool corner = false;
  for (const auto& v : h.polygon())
    corner = corner || (std::fabs(as_double(v.x) - 2.5) < 2e-2 && std::fabs(as_double(v.y) - 2) < 2e-2);
  EXPECT_TRUE(corner);
  // Collinear points span no area: no hull.
  std::vector<Point2T<T>> line{{T(0), T(0)}, {T(1), T(1)}, {T(2), T(2)}};
  EXPECT_TRUE(Mask<T>::hull(line).empty());
}

namespace {

// Mask::hull in double, on the corners of the seven pieces of view that reached one cell of
// the Viking room (view 51 of its random views, seed 1992). Two of them lie 2.6e-14 apart,
// 3.5e-6 from a third, and about 3.5e-9 off the line from that third on to the next corner.
// Kept as corners, they ended a side far shorter than the hull's growth; moving the sides
// out turned it by 9e-4, and the outline through the hull's vertices, which is what a
// picture is cut to, passed 2.5e-5 inside a point the hull holds, 0.03 away. The outline
// must stay convex and hold every point.
TEST(MaskHull, CornersNearTheChordOfTheirNeighboursLeaveTheOutlineConvex) {
  using P = Point2T<double>;
  std::vector<P> points{
      {-1.0702187525479792, -0.51786210588086001}, {-1.0168099531006518, -0.48579269486628623},
      {-0.96600537180481327, -0.45037620481814306}, {-0.98530269356260314, -0.44223539300955655},
      {-1.0448294673796794, -0.50142061563537432}, {-1.0448294741960458, -0.50142066319189171},
      {-0.96600537180480572, -0.45037620481813795}, {-1.1315830107231066, -0.41274561779132179},
      {-1.0992075158057686, -0.39418585667718209}, {-1.1265433306923813, -0.38265499257116514},
      {-1.0992074813026169, -0.39418587123139065}, {-1.0992048588880323, -0.39418436789102906},
      {-1.1265427527999525, -0.3826515421251962}, {-1.1265433306923549, -0.38265499257117669},
      {-1.0702187525479798, -0.51786210588086001}, {-1.0448294741960455, -0.5014206631918916},
      {-1.0441415683784974, -0.49662127258154276}, {-1.0743190028120457, -0.51632168070201967},
      {-0.98946384437616375, -0.44047996051454502}, {-0.99323792718933235, -0.43888781740175314},
      {-1.0019677633795718, -0.44848588281867646}, {-1.044828695718993, -0.50142015907020421},
      {-0.96915045704129454, -0.449049412045879}, {-0.9894638443761643, -0.44047996051454535},
      {-1.0019677633795718, -0.44848588281867646}, {-1.0174921133315664, -0.46555421298517397},
      {-1.0441415607574607, -0.49662121941098974}, {-1.0448294741960458, -0.50142066319189171},
  };
  const std::vector<P> input = points;
  const Mask<double> h = Mask<double>::hull(points);
  ASSERT_FALSE(h.empty());
  const std::vector<P> outline = h.polygon();
  const size_t n = outline.size();
  for (size_t k = 0; k < n; ++k) {
    const P o = outline[(k + n - 1) % n], p = outline[k], q = outline[(k + 1) % n];
    EXPECT_GT((p.x - o.x) * (q.y - p.y) - (p.y - o.y) * (q.x - p.x), 0.0) << "the outline turns back at corner " << k;
    const double side = std::hypot(q.x - p.x, q.y - p.y);
    for (const P& x : input)
      EXPECT_GE(((q.x - p.x) * (x.y - p.y) - (q.y - p.y) * (x.x - p.x)) / side, -1e-12)
          << "(" << x.x << ", " << x.y << ") outside the outline's side " << k;
  }
}

}  // namespace
