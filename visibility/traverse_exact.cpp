// Avenues — the exact kernels: the same traversal in GMP rationals (CGAL::Gmpq), so that
// every sign is right, and "filtered": CGAL's lazy exact numbers, which evaluate in
// interval arithmetic and recompute exactly only the comparisons an interval cannot
// decide. Kept in their own translation unit: they are the slow references.
#include <CGAL/Gmpq.h>
#include <CGAL/Lazy_exact_nt.h>

#include "visibility/traverse.h"

namespace avenues::detail {

using Lazy = CGAL::Lazy_exact_nt<CGAL::Gmpq>;

template <>
double to_double_of<CGAL::Gmpq>(const CGAL::Gmpq& x) { return x.to_double(); }
template <>
double to_double_of<Lazy>(const Lazy& x) { return CGAL::to_double(x); }

VisibleSet traverse_exact(const CellComplex& c, const Camera& cam, CellId eye_cell, bool prune_covered,
                          const Plane* cut, Join join) {
  return traverse_with<CGAL::Gmpq>(c, cam, eye_cell, prune_covered, cut, join);
}

VisibleSet traverse_filtered(const CellComplex& c, const Camera& cam, CellId eye_cell, bool prune_covered,
                             const Plane* cut, Join join) {
  return traverse_with<Lazy>(c, cam, eye_cell, prune_covered, cut, join);
}

}  // namespace avenues::detail
