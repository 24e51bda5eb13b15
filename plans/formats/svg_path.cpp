// Avenues — an SVG path's outline as polygons (see svg_path.h).
#include "plans/formats/svg_path.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>

namespace avenues {

std::optional<std::vector<std::vector<Vec2>>> svg_path_polygons(std::string_view d, int pieces) {
  std::vector<std::vector<Vec2>> out;
  std::vector<Vec2> poly;
  size_t i = 0;
  auto skip = [&] {
    while (i < d.size() && (std::isspace(static_cast<unsigned char>(d[i])) || d[i] == ',')) ++i;
  };
  auto number = [&](double& v) {
    skip();
    const char* b = d.data() + i;
    const char* e = d.data() + d.size();
    if (b < e && *b == '+') ++b;  // from_chars reads no leading '+'
    const auto [end, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || !std::isfinite(v)) return false;
    i = size_t(end - d.data());
    return true;
  };
  auto flag = [&](bool& f) {  // a flag may touch what follows ("a1 1 0 011,1")
    skip();
    if (i >= d.size() || (d[i] != '0' && d[i] != '1')) return false;
    f = d[i++] == '1';
    return true;
  };
  auto finish = [&] {
    while (poly.size() > 1 && length(poly.front() - poly.back()) < 1e-12) poly.pop_back();
    if (!poly.empty()) out.push_back(std::move(poly));
    poly.clear();
  };
  Vec2 cur{0, 0}, start{0, 0}, last_control{0, 0};
  char last = 0;  // the previous command, upper case (S and T reflect C's and Q's control points)
  char cmd = 0;
  auto to = [&](Vec2 p) {
    if (poly.empty()) poly.push_back(cur);
    poly.push_back(p);
    cur = p;
  };
  while (true) {
    skip();
    if (i >= d.size()) break;
    const size_t at = i;
    if (std::isalpha(static_cast<unsigned char>(d[i]))) cmd = d[i++];
    else if (std::toupper(static_cast<unsigned char>(cmd)) == 'Z') return std::nullopt;  // numbers after a closepath
    else if (cmd == 0) return std::nullopt;  // numbers before any command
    const bool rel = std::islower(static_cast<unsigned char>(cmd)) != 0;
    const Vec2 base = rel ? cur : Vec2{0, 0};
    const char up = char(std::toupper(static_cast<unsigned char>(cmd)));
    double x = 0, y = 0;
    switch (up) {
      case 'M':
        if (!number(x) || !number(y)) return std::nullopt;
        finish();
        cur = start = base + Vec2{x, y};
        poly.push_back(cur);
        cmd = rel ? 'l' : 'L';  // coordinates after a moveto's pair are linetos
        break;
      case 'L':
        if (!number(x) || !number(y)) return std::nullopt;
        to(base + Vec2{x, y});
        break;
      case 'H':
        if (!number(x)) return std::nullopt;
        to({base.x + x, cur.y});
        break;
      case 'V':
        if (!number(y)) return std::nullopt;
        to({cur.x, base.y + y});
        break;
      case 'Z':
        finish();
        cur = start;
        break;
      case 'C':
      case 'S':
      case 'Q':
      case 'T': {
        Vec2 c1, c2, p;
        const bool cubic = up == 'C' || up == 'S';
        if (up == 'C') {
          double a, b;
          if (!number(a) || !number(b) || !number(x) || !number(y)) return std::nullopt;
          c1 = base + Vec2{a, b};
          c2 = base + Vec2{x, y};
        } else if (up == 'S') {
          c1 = last == 'C' || last == 'S' ? cur + (cur - last_control) : cur;
          if (!number(x) || !number(y)) return std::nullopt;
          c2 = base + Vec2{x, y};
        } else if (up == 'Q') {
          if (!number(x) || !number(y)) return std::nullopt;
          c1 = c2 = base + Vec2{x, y};
        } else {
          c1 = c2 = last == 'Q' || last == 'T' ? cur + (cur - last_control) : cur;
        }
        if (!number(x) || !number(y)) return std::nullopt;
        p = base + Vec2{x, y};
        const Vec2 p0 = cur;
        for (int k = 1; k <= pieces; ++k) {
          const double t = double(k) / pieces, s = 1 - t;
          to(cubic ? (s * s * s) * p0 + (3 * s * s * t) * c1 + (3 * s * t * t) * c2 + (t * t * t) * p
                   : (s * s) * p0 + (2 * s * t) * c1 + (t * t) * p);
        }
        last_control = cubic ? c2 : c1;
        break;
      }
      case 'A': {
        double rx, ry, phi_deg;
        bool large, sweep;
        if (!number(rx) || !number(ry) || !number(phi_deg) || !flag(large) || !flag(sweep) || !number(x) ||
            !number(y))
          return std::nullopt;
        const Vec2 p0 = cur, p1 = base + Vec2{x, y};
        rx = std::fabs(rx), ry = std::fabs(ry);
        if (rx == 0 || ry == 0 || length(p1 - p0) == 0) {  // a straight line, or nothing
          if (length(p1 - p0) > 0) to(p1);
          break;
        }
        // SVG 1.1 F.6.5: the centre, from the ends, radii, rotation and flags.
        const double phi = phi_deg * std::numbers::pi / 180, cs = std::cos(phi), sn = std::sin(phi);
        const Vec2 h = 0.5 * (p0 - p1);
        const Vec2 q{cs * h.x + sn * h.y, -sn * h.x + cs * h.y};
        const double lambda = (q.x * q.x) / (rx * rx) + (q.y * q.y) / (ry * ry);
        if (lambda > 1) rx *= std::sqrt(lambda), ry *= std::sqrt(lambda);  // too small: scaled up
        const double num = rx * rx * ry * ry - rx * rx * q.y * q.y - ry * ry * q.x * q.x;
        const double den = rx * rx * q.y * q.y + ry * ry * q.x * q.x;
        double k = den > 0 ? std::sqrt(std::max(0.0, num / den)) : 0;
        if (large == sweep) k = -k;
        const Vec2 cq{k * rx * q.y / ry, -k * ry * q.x / rx};
        const Vec2 mid = 0.5 * (p0 + p1);
        const Vec2 c{cs * cq.x - sn * cq.y + mid.x, sn * cq.x + cs * cq.y + mid.y};
        auto angle = [](Vec2 u) { return std::atan2(u.y, u.x); };
        const double t0 = angle({(q.x - cq.x) / rx, (q.y - cq.y) / ry});
        double dt = angle({(-q.x - cq.x) / rx, (-q.y - cq.y) / ry}) - t0;
        if (sweep && dt < 0) dt += 2 * std::numbers::pi;
        if (!sweep && dt > 0) dt -= 2 * std::numbers::pi;
        const int n = std::max(2, int(std::ceil(pieces * std::fabs(dt) / std::numbers::pi)));
        for (int j = 1; j < n; ++j) {
          const double t = t0 + dt * j / n;
          const Vec2 e{rx * std::cos(t), ry * std::sin(t)};
          to({cs * e.x - sn * e.y + c.x, sn * e.x + cs * e.y + c.y});
        }
        to(p1);  // the end exactly as given
        break;
      }
      default:
        return std::nullopt;
    }
    if (i == at) return std::nullopt;  // (every command reads something: no loop in place)
    last = up;
  }
  finish();
  return out;
}

std::vector<Vec2> svg_path_outline(std::string_view d) {
  std::vector<Vec2> best;
  if (const auto polys = svg_path_polygons(d))
    for (const auto& poly : *polys)
      if (poly.size() >= 3 && std::fabs(signed_area(poly)) > std::fabs(signed_area(best))) best = poly;
  return best;
}

}  // namespace avenues
