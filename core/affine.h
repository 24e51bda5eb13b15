// Avenues — an affine map of 3D space (a 3 × 4 matrix: the linear part, then the
// translation), as scene files place their nodes: each node's map within its parent's.
// Part of core/, below every other module.
#pragma once

#include <array>
#include <cmath>

#include "core/geometry.h"

namespace avenues {

struct Affine3 {
  std::array<std::array<double, 4>, 3> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};

  Vec3 apply(Vec3 p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3], m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  /// This map after `o`: (this * o).apply(p) == apply(o.apply(p)).
  Affine3 operator*(const Affine3& o) const {
    Affine3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) {
        double s = j == 3 ? m[i][3] : 0;
        for (int k = 0; k < 3; ++k) s += m[i][k] * o.m[k][j];
        r.m[i][j] = s;
      }
    return r;
  }
  /// The determinant of the linear part: negative for a map that mirrors (turning a
  /// triangle's corners the other way round).
  double det() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }

  static Affine3 translation(Vec3 t) {
    Affine3 a;
    a.m[0][3] = t.x, a.m[1][3] = t.y, a.m[2][3] = t.z;
    return a;
  }
  static Affine3 scaling(Vec3 s) {
    Affine3 a;
    a.m[0][0] = s.x, a.m[1][1] = s.y, a.m[2][2] = s.z;
    return a;
  }
  /// A right-handed turn by `radians` about `axis` (made unit here; a zero axis: no turn).
  static Affine3 rotation(Vec3 axis, double radians) {
    const double l = length(axis);
    Affine3 a;
    if (!(l > 0) || !std::isfinite(l)) return a;
    const Vec3 u = (1 / l) * axis;
    const double c = std::cos(radians), s = std::sin(radians), t = 1 - c;
    a.m[0] = {t * u.x * u.x + c, t * u.x * u.y - s * u.z, t * u.x * u.z + s * u.y, 0};
    a.m[1] = {t * u.x * u.y + s * u.z, t * u.y * u.y + c, t * u.y * u.z - s * u.x, 0};
    a.m[2] = {t * u.x * u.z - s * u.y, t * u.y * u.z + s * u.x, t * u.z * u.z + c, 0};
    return a;
  }
};

}  // namespace avenues
