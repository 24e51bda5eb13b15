// Avenues — reading a Doom map's lumps into a Plan (see doom_map.h).
//
// The binary records, all little-endian (the Doom Wiki's "Linedef", "Sidedef", ...):
//   VERTEXES  4 bytes: x, y (int16, map units)
//   LINEDEFS 14 bytes: v1, v2, flags, special, tag, front sidedef, back sidedef (uint16; 0xFFFF none)
//            16 bytes in Hexen: v1, v2, flags (uint16), special, 5 args (uint8), front, back
//   SIDEDEFS 30 bytes: x offset, y offset (int16), upper, lower, middle texture (8 chars), sector (uint16)
//   SECTORS  26 bytes: floor, ceiling (int16), floor flat, ceiling flat (8 chars), light, special, tag
//   THINGS   10 bytes: x, y, angle [deg], type, flags (int16)
//            20 bytes in Hexen: tid, x, y, z, angle, type, flags (int16), special, 5 args (uint8)
#include "plans/formats/doom_map.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <set>

#include "plans/formats/wad_file.h"

namespace avenues {

namespace {

uint16_t u16(const uint8_t* p) { return uint16_t(p[0] | p[1] << 8); }
int16_t i16(const uint8_t* p) { return int16_t(u16(p)); }
std::string name8(const uint8_t* p) {
  std::string s;
  for (int k = 0; k < 8 && p[k] != 0; ++k) s += char(std::toupper(p[k]));
  return s;
}
std::string upper(std::string s) {
  for (char& ch : s) ch = char(std::toupper(static_cast<unsigned char>(ch)));
  return s;
}

/// Reports a repair: the element ("linedef 12") and what was done.
using Warn = std::function<void(const std::string& element, const std::string& what)>;

constexpr uint16_t kNoSide = 0xFFFF;
constexpr uint16_t kTwoSided = 0x0004;  ///< ML_TWOSIDED
constexpr int kPlayer1Start = 1;        ///< thing type

struct Sector {
  int floor = 0, ceiling = 0;  ///< [map units]
  bool sky = false;            ///< ceiling flat F_SKY1
  int light = 0;               ///< 0..255
};

/// One linedef after repairs: v1 -> v2 with its front sector on the right.
struct Line {
  int id = 0;                  ///< linedef number in the lump
  Vec2 a, b;                   ///< [map units]
  int front = -1, back = -1;   ///< sectors; back -1 for a one-sided line
};

/// The map's lumps, each checked for size; reads and names the map in messages.
class MapLumps {
 public:
  MapLumps(const WadFile& wad, const WadMap& map) : wad_(wad), map_(map), where_(wad.path + ":" + map.name) {}

  const std::string& where() const { return where_; }
  bool has(const std::string& name) const { return wad_.find(name, map_.marker + 1, map_.end) >= 0; }

  /// The records of a required lump, `record` bytes each.
  std::vector<uint8_t> records(const std::string& name, size_t record, const char* what) const {
    const long i = wad_.find(name, map_.marker + 1, map_.end);
    if (i < 0) throw PlanError({where_, 0, 0, "lump " + name}, "the map has no " + name + " lump");
    std::vector<uint8_t> bytes = wad_.read(size_t(i), where_);
    if (bytes.size() % record != 0)
      throw PlanError({where_, 0, 0, "lump " + name},
                      std::to_string(bytes.size()) + " bytes, not a whole number of " + std::to_string(record) +
                          "-byte " + what + " records: truncated or misaligned");
    return bytes;
  }

 private:
  const WadFile& wad_;
  const WadMap& map_;
  std::string where_;
};

/// The sector holding point p: odd crossings of a ray towards +x over the lines that
/// bound a sector on one side only (every line kept here has distinct sectors, so each
/// crossing toggles both). Where broken sectors leave several (or no) candidates, the
/// sector on p's side of the nearest line decides. -1 if p is beside no line at all.
int sector_at(Vec2 p, const std::vector<Line>& lines, size_t nsectors) {
  std::vector<uint8_t> odd(nsectors, 0);
  double nearest = HUGE_VAL;
  int near_sector = -1;
  for (const Line& l : lines) {
    if ((l.a.y > p.y) != (l.b.y > p.y)) {
      const double x = l.a.x + (p.y - l.a.y) * (l.b.x - l.a.x) / (l.b.y - l.a.y);
      if (x > p.x) {
        odd[size_t(l.front)] ^= 1;
        if (l.back >= 0) odd[size_t(l.back)] ^= 1;
      }
    }
    const Vec2 d = l.b - l.a;
    const double t = std::clamp(dot(p - l.a, d) / dot(d, d), 0.0, 1.0);
    const double dist = length(p - (l.a + t * d));
    if (dist < nearest) {
      nearest = dist;
      near_sector = cross(d, p - l.a) < 0 ? l.front : l.back;  // front is on the right
    }
  }
  if (near_sector >= 0 && odd[size_t(near_sector)]) return near_sector;
  for (size_t s = 0; s < nsectors; ++s)
    if (odd[s]) return int(s);
  return near_sector;
}

/// Linedefs on the same two points (a sector of no area drawn between two lines, a
/// line drawn twice) become one: oriented from the smaller end, the sectors named on
/// both its sides are the sliver between them and drop out; what is left on each side
/// bounds the line. Groups that still disagree are kept as they are.
std::vector<Line> merge_coincident(const std::vector<Line>& lines, const Warn& warn) {
  auto less = [](Vec2 p, Vec2 q) { return p.x < q.x || (p.x == q.x && p.y < q.y); };
  auto key = [&](const Line& l) {
    const Vec2 lo = less(l.a, l.b) ? l.a : l.b, hi = less(l.a, l.b) ? l.b : l.a;
    return std::array<double, 4>{lo.x, lo.y, hi.x, hi.y};
  };
  std::vector<size_t> order(lines.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) { return key(lines[i]) < key(lines[j]); });
  std::vector<uint8_t> drop(lines.size(), 0);
  std::vector<Line> merged_into(lines.begin(), lines.end());
  for (size_t g = 0; g < order.size();) {
    size_t e = g + 1;
    while (e < order.size() && key(lines[order[e]]) == key(lines[order[g]])) ++e;
    if (e - g > 1) {
      // Sides seen walking from the smaller end to the larger.
      std::set<int> right, left;
      for (size_t k = g; k < e; ++k) {
        const Line& l = lines[order[k]];
        const bool forward = less(l.a, l.b);
        right.insert(forward ? l.front : l.back);
        left.insert(forward ? l.back : l.front);
      }
      std::set<int> sliver;
      for (int s : right)
        if (s >= 0 && left.count(s)) sliver.insert(s);
      for (int s : sliver) right.erase(s), left.erase(s);
      if (right.size() > 1) right.erase(-1);
      if (left.size() > 1) left.erase(-1);
      if (right.size() <= 1 && left.size() <= 1) {
        const Line& first = lines[order[g]];
        Line m = first;
        if (!less(m.a, m.b)) std::swap(m.a, m.b);
        m.front = right.empty() ? -1 : *right.begin();
        m.back = left.empty() ? -1 : *left.begin();
        if (m.front < 0) std::swap(m.a, m.b), std::swap(m.front, m.back);
        std::string others, slivers;
        for (size_t k = g + 1; k < e; ++k) {
          others += (others.empty() ? "" : ", ") + std::to_string(lines[order[k]].id);
          drop[order[k]] = 1;
        }
        for (int s : sliver) slivers += (slivers.empty() ? "" : ", ") + std::to_string(s);
        if (m.front < 0 || m.front == m.back) drop[order[g]] = 1;
        else merged_into[order[g]] = m;
        warn("linedef " + std::to_string(first.id), "coincides with linedef" + std::string(e - g > 2 ? "s " : " ") + others + ": merged" +
                           (slivers.empty() ? "" : " (sector" + std::string(sliver.size() > 1 ? "s " : " ") + slivers +
                                                       " between them has no area)") +
                           (drop[order[g]] ? ", and dropped: it bounds nothing" : ""));
      }
    }
    g = e;
  }
  std::vector<Line> out;
  for (size_t i = 0; i < lines.size(); ++i)
    if (!drop[i]) out.push_back(merged_into[i]);
  return out;
}

/// The linedefs as lines with their sectors, repaired: a vertex or sidedef out of range,
/// a line with no side or of no length is dropped; a line with only a back side is turned
/// round; a line with one sector on both sides bounds nothing and goes silently.
std::vector<Line> repaired_lines(const std::vector<uint8_t>& lbytes, bool hexen, const std::vector<Vec2>& vertex,
                                 const std::vector<int>& side_sector, const Warn& warn) {
  const size_t record = hexen ? 16 : 14, nl = lbytes.size() / record, nv = vertex.size(), ns = side_sector.size();
  std::vector<Line> lines;
  lines.reserve(nl);
  for (size_t i = 0; i < nl; ++i) {
    const uint8_t* r = &lbytes[record * i];
    const std::string element = "linedef " + std::to_string(i);
    const uint16_t v1 = u16(r), v2 = u16(r + 2), flags = u16(r + 4);
    const uint16_t s1 = u16(r + record - 4), s2 = u16(r + record - 2);
    if (v1 >= nv || v2 >= nv) {
      warn(element, "vertex " + std::to_string(v1 >= nv ? v1 : v2) + " out of range (the map has " +
                        std::to_string(nv) + " vertices): line dropped");
      continue;
    }
    Line l;
    l.id = int(i);
    l.a = vertex[v1];
    l.b = vertex[v2];
    if (l.a == l.b) {
      warn(element, "zero length (both ends at vertex " + std::to_string(v1) + "): line dropped");
      continue;
    }
    auto side = [&](uint16_t s, const char* which) {
      if (s == kNoSide) return -1;
      if (s >= ns) {
        warn(element, std::string(which) + " sidedef " + std::to_string(s) + " out of range (the map has " +
                          std::to_string(ns) + " sidedefs): side ignored");
        return -1;
      }
      return side_sector[s];
    };
    l.front = side(s1, "front");
    l.back = side(s2, "back");
    if (l.front < 0 && l.back < 0) {
      warn(element, "no usable side: line dropped");
      continue;
    }
    if (l.front < 0) {
      std::swap(l.a, l.b);
      std::swap(l.front, l.back);
      warn(element, "only a back side: flipped to face it");
    } else if ((flags & kTwoSided) && s2 == kNoSide) {
      warn(element, "flagged two-sided but has no back sidedef: one-sided");
    }
    if (l.front == l.back) continue;  // the same sector on both sides: bounds nothing
    lines.push_back(l);
  }
  return lines;
}

/// Player 1's start (thing type 1): the eye 41 units above its sector's floor (half way
/// up a sector lower than that), looking along the thing's angle (0 = east,
/// counter-clockwise), with Doom's 90° field of view. None when there is no start.
std::optional<Viewpoint> player_view(const std::vector<uint8_t>& tbytes, bool hexen, const std::vector<Line>& lines,
                                     const std::vector<Sector>& sector, const Warn& warn) {
  const size_t record = hexen ? 20 : 10;
  for (size_t i = 0; i < tbytes.size() / record; ++i) {
    const uint8_t* r = &tbytes[record * i];
    if (i16(r + (hexen ? 10 : 6)) != kPlayer1Start) continue;
    const Vec2 p{double(i16(r + (hexen ? 2 : 0))), double(i16(r + (hexen ? 4 : 2)))};
    const double angle = i16(r + (hexen ? 8 : 4)) * std::numbers::pi / 180;
    const int s = sector_at(p, lines, sector.size());
    if (s < 0) {
      warn("thing " + std::to_string(i), "player 1 start lies in no sector: no viewpoint");
      return std::nullopt;
    }
    const Sector& sec = sector[size_t(s)];
    double eye = kDoomEyeHeight;
    if (!sec.sky && (sec.ceiling - sec.floor) * kDoomUnit <= eye) eye = std::max(0, sec.ceiling - sec.floor) * kDoomUnit / 2;
    Viewpoint v;
    v.eye = {p.x * kDoomUnit, p.y * kDoomUnit, sec.floor * kDoomUnit + eye};
    v.look = v.eye + Vec3{std::cos(angle), std::sin(angle), 0};
    v.fov_deg = 90;
    return v;
  }
  warn("lump THINGS", "no player 1 start: no viewpoint");
  return std::nullopt;
}

}  // namespace

std::vector<std::string> doom_map_names(const std::string& wad_path) {
  std::vector<std::string> names;
  for (const WadMap& m : open_wad(wad_path).maps()) names.push_back(m.name);
  return names;
}

Plan read_doom_map(const std::string& wad_path, const std::string& map_name) {
  const WadFile wad = open_wad(wad_path);
  const std::vector<WadMap> maps = wad.maps();
  const auto it = std::find_if(maps.begin(), maps.end(), [&](const WadMap& m) { return m.name == upper(map_name); });
  if (it == maps.end()) {
    std::string list;
    for (const WadMap& m : maps) list += (list.empty() ? "" : ", ") + m.name;
    throw PlanError({wad_path, 0, 0, ""}, "no map '" + map_name + "' in the file; its maps: " +
                                              (list.empty() ? std::string("none") : list));
  }
  const MapLumps lumps(wad, *it);
  const std::string& where = lumps.where();
  if (lumps.has("TEXTMAP"))
    throw PlanError({where, 0, 0, "lump TEXTMAP"},
                    "the map is in UDMF (a TEXTMAP lump), which Avenues does not read: only Doom and Hexen binary maps");
  const bool hexen = lumps.has("BEHAVIOR");

  Plan plan;
  const auto at = [&](const std::string& element) { return SourceLoc{where, 0, 0, element}; };
  auto warn = [&](const std::string& element, const std::string& what) {
    plan.warnings.push_back(at(element).str() + ": " + what);
  };

  // --- the records
  const std::vector<uint8_t> vbytes = lumps.records("VERTEXES", 4, "vertex");
  const std::vector<uint8_t> lbytes = lumps.records("LINEDEFS", hexen ? 16 : 14, hexen ? "Hexen linedef" : "linedef");
  const std::vector<uint8_t> sbytes = lumps.records("SIDEDEFS", 30, "sidedef");
  const std::vector<uint8_t> secbytes = lumps.records("SECTORS", 26, "sector");
  const std::vector<uint8_t> tbytes = lumps.records("THINGS", hexen ? 20 : 10, hexen ? "Hexen thing" : "thing");
  const size_t nv = vbytes.size() / 4, ns = sbytes.size() / 30, nsec = secbytes.size() / 26;
  if (nsec == 0) throw PlanError(at("lump SECTORS"), "the map has no sectors");

  std::vector<Vec2> vertex(nv);
  for (size_t i = 0; i < nv; ++i) vertex[i] = {double(i16(&vbytes[4 * i])), double(i16(&vbytes[4 * i + 2]))};
  std::vector<Sector> sector(nsec);
  for (size_t i = 0; i < nsec; ++i) {
    const uint8_t* r = &secbytes[26 * i];
    sector[i].floor = i16(r);
    sector[i].ceiling = i16(r + 2);
    sector[i].sky = name8(r + 12) == "F_SKY1";
    sector[i].light = std::clamp(int(i16(r + 20)), 0, 255);
  }
  // Each sidedef's sector, -1 (with one warning per sidedef) when out of range.
  std::vector<int> side_sector(ns);
  for (size_t i = 0; i < ns; ++i) {
    const uint16_t s = u16(&sbytes[30 * i + 28]);
    side_sector[i] = s < nsec ? int(s) : -1;
    if (s >= nsec)
      warn("sidedef " + std::to_string(i), "names sector " + std::to_string(s) + ", out of range (the map has " +
                                               std::to_string(nsec) + " sectors): the side is ignored");
  }

  // --- linedefs, repaired
  std::vector<Line> lines = repaired_lines(lbytes, hexen, vertex, side_sector, warn);
  lines = merge_coincident(lines, warn);
  if (lines.empty()) throw PlanError(at("lump LINEDEFS"), "no linedef bounds a sector");

  // --- the storey: lowest floor to highest ceiling of the sectors the lines bound
  std::vector<uint8_t> used(nsec, 0);
  for (const Line& l : lines) {
    used[size_t(l.front)] = 1;
    if (l.back >= 0) used[size_t(l.back)] = 1;
  }
  int lo = INT32_MAX, hi = INT32_MIN;
  for (size_t s = 0; s < nsec; ++s)
    if (used[s]) lo = std::min(lo, sector[s].floor), hi = std::max(hi, sector[s].ceiling);
  if (hi <= lo) hi = lo + 1;  // every sector closed: a sliver of a storey, all of it solid

  plan.name = wad_path.substr(wad_path.find_last_of('/') + 1) + ":" + it->name;
  plan.source = wad_path;
  plan.far_margin = 1;
  plan.outside_solid = true;
  plan.lenient = true;
  Storey storey;
  storey.name = it->name;
  storey.elevation = lo * kDoomUnit;
  storey.height = (hi - lo) * kDoomUnit;
  storey.slab = 0;
  storey.where = at("lump SECTORS");
  plan.storeys.push_back(storey);

  // Materials: one grey per light level, reflectance proportional to the light.
  std::map<int, MaterialId> by_light;
  auto material = [&](int light) {
    auto [m, fresh] = by_light.emplace(light, MaterialId(plan.materials.size()));
    if (fresh) {
      Material mat;
      mat.name = "light " + std::to_string(light);
      mat.reflectance = std::max(light, 8) / 255.0;
      mat.colour = {0.8, 0.8, 0.8};
      mat.where = at("lump SECTORS");
      plan.materials.push_back(mat);
    }
    return m->second;
  };
  Material sky;
  sky.name = "sky";
  sky.reflectance = 1;
  sky.colour = {0.55, 0.7, 0.9};
  plan.sky = MaterialId(plan.materials.size());
  plan.materials.push_back(sky);

  for (size_t s = 0; s < nsec; ++s) {
    Room room;
    room.name = "sector " + std::to_string(s);
    room.where = at(room.name);
    // A closed door (ceiling at or below its floor) keeps ceiling_at <= floor_at and no
    // sky: solid. A sector no line bounds may lie beyond the storey: clamped into it.
    room.floor_at = std::clamp(sector[s].floor - lo, 0, hi - lo) * kDoomUnit;
    room.ceiling_at = std::clamp(sector[s].ceiling - lo, 0, hi - lo) * kDoomUnit;
    room.sky = sector[s].sky && sector[s].ceiling > sector[s].floor;
    room.floor = room.ceiling = room.walls = material(sector[s].light);
    plan.rooms.push_back(room);
  }
  plan.walls.reserve(lines.size());
  for (const Line& l : lines) {
    Wall w;
    w.name = "linedef " + std::to_string(l.id);
    w.where = at(w.name);
    w.thickness = 0;
    w.height = -1;
    w.centre = {kDoomUnit * l.a, kDoomUnit * l.b};
    w.from_arc = {false};
    w.right_room = l.front;
    w.left_room = l.back;
    w.material = plan.rooms[size_t(l.front)].walls;
    if (l.back >= 0) {
      Opening o;
      o.name = "gap";
      o.kind = OpeningKind::Gap;
      o.at = 0;
      o.width = length(w.centre[1] - w.centre[0]);
      o.sill = 0;
      o.head = storey.height;
      o.where = w.where;
      w.openings.push_back(o);
    }
    plan.walls.push_back(std::move(w));
  }

  // --- the view: player 1's start, at eye height above its sector's floor
  plan.view = player_view(tbytes, hexen, lines, sector, warn);
  return plan;
}

}  // namespace avenues
