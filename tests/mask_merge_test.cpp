// Tests of Mask::absorb (visibility/mask.h), the union of two masks that the merged search
// (TraverseParams::merge_pieces) makes of two avenues into one cell: in float, double and
// exact rationals, two masks parted by one line become one exactly when their union is
// convex, and a junction where the outline runs straight on keeps one line, not two.
#include <gtest/gtest.h>

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
