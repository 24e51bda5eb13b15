// Avenues — a stereo pair on paper (see stereo_drawing.h).
#include "render/stereo_drawing.h"

#include <algorithm>
#include <filesystem>

#include "core/atomic_file.h"

namespace avenues {

Drawing side_by_side(const Drawing& left, const Drawing& right) {
  Drawing d;
  d.width = left.width + right.width;
  d.height = std::max(left.height, right.height);
  d.title = left.title;
  d.strokes = left.strokes;
  const Vec2 shift{double(left.width), 0};
  for (Stroke s : right.strokes) {
    s.a = s.a + shift;
    s.b = s.b + shift;
    d.strokes.push_back(s);
  }
  return d;
}

std::array<std::string, 2> stereo_pair_paths(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string stem = p.stem().string(), ext = p.extension().string();
  return {(p.parent_path() / (stem + "-left" + ext)).string(), (p.parent_path() / (stem + "-right" + ext)).string()};
}

DrawingStats write_stereo_drawing(const Drawing& left, const Drawing& right, StereoLayout layout,
                                  const std::string& path, const PageOptions& page) {
  switch (layout) {
    case StereoLayout::Parallel: return write_drawing(side_by_side(left, right), path, page);
    case StereoLayout::Cross: return write_drawing(side_by_side(right, left), path, page);
    case StereoLayout::Pair: break;
  }
  const auto paths = stereo_pair_paths(path);
  const EncodedDrawing l = encode_drawing(left, paths[0], page), r = encode_drawing(right, paths[1], page);
  write_files_atomically({{paths[0], l.bytes}, {paths[1], r.bytes}});  // both or neither
  return {l.stats.lines + r.stats.lines, l.stats.penup_mm_before + r.stats.penup_mm_before,
          l.stats.penup_mm_after + r.stats.penup_mm_after};
}

}  // namespace avenues
