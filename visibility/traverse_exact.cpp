// Avenues — the exact kernels: the same traversal in GMP rationals (CGAL::Gmpq), so that
// every sign is right, and "filtered": CGAL's lazy exact numbers, which evaluate in
// interval arithmetic and recompute exactly only the comparisons an interval cannot
// decide. Kept in their own translation unit: they are the slow references.
#include <CGAL/Gmpq.h>
#include <CGAL/Lazy_exact_nt.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "visibility/traverse.h"

namespace avenues::detail {

using Lazy = CGAL::Lazy_exact_nt<CGAL::Gmpq>;

template <>
double to_double_of<CGAL::Gmpq>(const CGAL::Gmpq& x) { return x.to_double(); }
/// Its interval, where that is as narrow as a rounding; else its exact value, rounded:
/// after a long chain of operations (a mask clipped by many portals) the interval can be
/// a billionth wide, and an avenue's mask would then be off by more than the exact
/// kernel's (random view 6 of curved-walls: a cell's view 2.8e-9 smaller merged than
/// apart).
template <>
double to_double_of<Lazy>(const Lazy& x) {
  const CGAL::Interval_nt<false>& i = x.approx();
  const double scale = std::max(std::fabs(i.inf()), std::fabs(i.sup()));
  if (i.sup() - i.inf() <= 4 * std::numeric_limits<double>::epsilon() * scale) return CGAL::to_double(i);
  return x.exact().to_double();
}

VisibleSet traverse_exact(const CellComplex& c, const Camera& cam, CellId eye_cell, bool prune_covered,
                          const Plane* cut, Join join, const TraverseParams::Strip* strip) {
  return traverse_with<CGAL::Gmpq>(c, cam, eye_cell, prune_covered, cut, join, strip);
}

VisibleSet traverse_filtered(const CellComplex& c, const Camera& cam, CellId eye_cell, bool prune_covered,
                             const Plane* cut, Join join, const TraverseParams::Strip* strip) {
  return traverse_with<Lazy>(c, cam, eye_cell, prune_covered, cut, join, strip);
}

}  // namespace avenues::detail
