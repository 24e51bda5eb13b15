// Avenues — the camera: Crow's eye space (Crow 1981, "the eyepoint and the centre of
// interest"), with +z up in the world.
//
// Camera space: X to the right, Y up, Z forward (the direction of view). The picture
// plane is Z = 1; a direction (X, Y, Z) with Z > 0 meets it at image point
// (x, y) = (X/Z, Y/Z). The window on that plane is centred at (shift_x, shift_y) —
// non-zero for the off-axis frusta of a stereo pair — and spans 2·tan(fov/2) across
// the image width; its height follows the image's aspect ratio. Raster coordinates:
// x to the right, rows from the top, pixel (i, j) covering [i, i+1) × [j, j+1) with
// its sample at the centre (i + ½, j + ½).
//
// A parallel projection (an architect's plan, section, elevation or axonometric) keeps the
// same camera space, but every ray runs along Z: the picture plane is Z = 0, through the
// eye, and a point (X, Y, Z) is seen at image point (x, y) = (X, Y) [m]; the window spans
// view_width across the image width. Its rays start on the picture plane (or on a cut plane,
// visible_set.h), never behind it.
#pragma once

#include <cstdint>

#include "core/geometry.h"

namespace avenues {

enum class Projection : uint8_t {
  Perspective,  ///< rays from the eye; image point (X/Z, Y/Z)
  Parallel,     ///< rays along forward from the picture plane; image point (X, Y) in metres
};

/// Picture-plane point → raster position [px], the window's half sizes worked out once
/// (Camera::raster_from_image works them out, a tangent in perspective, at every call):
/// the same arithmetic, so the same doubles. For loops over many points.
struct ImageToRaster {
  double left = 0, top = 0;     ///< the window's left and top on the picture plane
  double across = 1, down = 1;  ///< its width and height there
  double width = 1, height = 1; ///< [px]
  Vec2 operator()(Vec2 xy) const { return {(xy.x - left) / across * width, (top - xy.y) / down * height}; }
};

struct Camera {
  Vec3 eye;                        ///< [m] world
  Vec3 right{1, 0, 0}, up{0, 0, 1}, forward{0, 1, 0};  ///< orthonormal, world
  double fov_deg = 60;             ///< horizontal field of view, (0, 179]
  int width = 1280, height = 720;  ///< [px] > 0
  double near = 0.01;              ///< [m] > 0, for drawing (visibility itself needs no near plane)
  double shift_x = 0, shift_y = 0; ///< window centre on the picture plane (off-axis frustum)
  Projection projection = Projection::Perspective;
  double view_width = 0;           ///< [m] > 0 for Parallel: the window's width on the picture plane

  /// A parallel projection from `eye` towards `look`, view_width metres across.
  static Camera parallel(Vec3 eye, Vec3 look, double view_width, int width, int height);
  bool is_parallel() const { return projection == Projection::Parallel; }
  /// The plane through the eye across the direction of view, facing along it: a parallel
  /// projection's picture plane, where its rays start when no cut says otherwise.
  Plane picture_plane() const { return {forward, -dot(forward, eye)}; }
  /// Eye looking at a centre of interest; +z is up (looking straight up or down keeps +y as "up").
  static Camera look_at(Vec3 eye, Vec3 look, double fov_deg, int width, int height);
  /// Eye with a heading (yaw, degrees anticlockwise from +x) and pitch (degrees up).
  static Camera yaw_pitch(Vec3 eye, double yaw_deg, double pitch_deg, double fov_deg, int width, int height);

  double half_width() const;   ///< tan(fov/2), or view_width/2 when parallel: half the window's width on the picture plane
  double half_height() const;  ///< half_width · height / width

  /// World point → camera space (X right, Y up, Z forward).
  Vec3 camera_from_world(Vec3 p) const {
    Vec3 d = p - eye;
    return {dot(d, right), dot(d, up), dot(d, forward)};
  }
  /// Camera-space point → picture-plane point: (X/Z, Y/Z), or (X, Y) when parallel.
  Vec2 image_from_camera(Vec3 p) const { return is_parallel() ? Vec2{p.x, p.y} : Vec2{p.x / p.z, p.y / p.z}; }
  /// Picture-plane point → raster position [px] (rows top to bottom).
  Vec2 raster_from_image(Vec2 xy) const { return image_to_raster()(xy); }
  /// The same map, for many points.
  ImageToRaster image_to_raster() const;
  /// Raster position [px] → picture-plane point.
  Vec2 image_from_raster(Vec2 px) const;
  /// World direction through a raster position (not normalised); forward when parallel.
  Vec3 ray_through_raster(Vec2 px) const;
  /// Where that ray starts: the eye, or when parallel its point on the picture plane.
  Vec3 ray_origin_at_raster(Vec2 px) const;
};

}  // namespace avenues
