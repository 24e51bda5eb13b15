// Avenues — a walkthrough as a series of drawings (see walkthrough.h).
#include "render/walkthrough.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace avenues {

namespace {

std::string str(Vec3 v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%g, %g, %g)", v.x, v.y, v.z);
  return b;
}

}  // namespace

std::vector<WalkFrame> walk_frames(const CellComplex& c, Vec3 from_eye, Vec3 from_look, Vec3 to_eye, Vec3 to_look,
                                   int frames, const Camera& lens) {
  if (frames < 1) throw std::runtime_error("a walk needs at least one frame, not " + std::to_string(frames));
  std::vector<WalkFrame> out;
  CellId hint = kNoCell;
  for (int k = 0; k < frames; ++k) {
    const double t = frames == 1 ? 0 : double(k) / (frames - 1);
    const Vec3 eye = from_eye + t * (to_eye - from_eye), look = from_look + t * (to_look - from_look);
    const std::string frame = "frame " + std::to_string(k + 1) + " of " + std::to_string(frames) + ": ";
    if (!(length(look - eye) > 0)) throw std::runtime_error(frame + "the eye " + str(eye) + " looks at itself");
    const Location at = c.locate(eye, look - eye, hint);
    if (at.what == Location::What::Solid)
      throw std::runtime_error(frame + "the eye " + str(eye) + " is inside " + at.solid);
    if (at.what == Location::What::OutsideBox)
      throw std::runtime_error(frame + "the eye " + str(eye) + " is outside the far box");
    WalkFrame f;
    f.camera = Camera::look_at(eye, look, lens.fov_deg, lens.width, lens.height);
    f.camera.near = lens.near;
    f.cell = hint = at.cell;
    out.push_back(f);
  }
  return out;
}

std::string frame_path(const std::string& path, int k, int frames) {
  const std::filesystem::path p(path);
  const int digits = std::max(4, int(std::to_string(frames).size()));
  std::string number = std::to_string(k + 1);
  number.insert(0, size_t(std::max(0, digits - int(number.size()))), '0');
  return (p.parent_path() / (p.stem().string() + "-" + number + p.extension().string())).string();
}

}  // namespace avenues
