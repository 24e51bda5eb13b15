// Avenues — the camera (see camera.h).
#include "visibility/camera.h"
#include "core/angles.h"

#include <cmath>

namespace avenues {

namespace {
Vec3 normalize(Vec3 v) { return (1.0 / length(v)) * v; }
}  // namespace

Camera Camera::look_at(Vec3 eye, Vec3 look, double fov_deg, int width, int height) {
  Camera c;
  c.eye = eye;
  c.fov_deg = fov_deg;
  c.width = width;
  c.height = height;
  Vec3 f = look - eye;
  if (!(length(f) > 0)) f = {0, 1, 0};
  c.forward = normalize(f);
  // Right is horizontal (perpendicular to world up); looking straight up or down, take +x.
  Vec3 r = cross(c.forward, Vec3{0, 0, 1});
  c.right = length(r) > 1e-12 ? normalize(r) : Vec3{1, 0, 0};
  c.up = cross(c.right, c.forward);
  return c;
}

Camera Camera::yaw_pitch(Vec3 eye, double yaw_deg, double pitch_deg, double fov_deg, int width, int height) {
  double y = rad_from_deg(yaw_deg), p = rad_from_deg(pitch_deg);
  Vec3 dir{std::cos(p) * std::cos(y), std::cos(p) * std::sin(y), std::sin(p)};
  return look_at(eye, eye + dir, fov_deg, width, height);
}

Camera Camera::parallel(Vec3 eye, Vec3 look, double view_width, int width, int height) {
  Camera c = look_at(eye, look, 60, width, height);
  c.projection = Projection::Parallel;
  c.view_width = view_width;
  return c;
}

double Camera::half_width() const { return is_parallel() ? view_width / 2 : std::tan(rad_from_deg(fov_deg) / 2); }
double Camera::half_height() const { return half_width() * height / width; }

ImageToRaster Camera::image_to_raster() const {
  const double hw = half_width(), hh = hw * height / width;  // half_height()
  return {shift_x - hw, shift_y + hh, 2 * hw, 2 * hh, double(width), double(height)};
}

Vec2 Camera::image_from_raster(Vec2 px) const {
  const double hw = half_width(), hh = half_height();
  return {shift_x - hw + px.x / width * 2 * hw, shift_y + hh - px.y / height * 2 * hh};
}

Vec3 Camera::ray_through_raster(Vec2 px) const {
  if (is_parallel()) return forward;
  Vec2 xy = image_from_raster(px);
  return xy.x * right + xy.y * up + forward;
}

Vec3 Camera::ray_origin_at_raster(Vec2 px) const {
  if (!is_parallel()) return eye;
  Vec2 xy = image_from_raster(px);
  return eye + xy.x * right + xy.y * up;
}

}  // namespace avenues
