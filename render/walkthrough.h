// Avenues — a walkthrough as a series of drawings.
//
// Jones 1971 moved the eye with sense switches and had a new view drawn each time, hoping
// for "the illusion of continuous motion" at "about ... sixteen frames per second". Here a
// straight walk is cut into N frames: eye and centre of interest both move in a straight
// line, at even steps, from the first pair to the second. Each frame's eye is located
// afresh (from the previous frame's cell, a short walk through portals), so each frame is
// drawn from its own avenues of sight; a frame whose eye is inside a solid is an error that
// names the frame.
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "visibility/camera.h"

namespace avenues {

struct WalkFrame {
  Camera camera;  ///< the lens (fov, size, near) of the walk's, at this frame's eye
  CellId cell = kNoCell;  ///< the cell holding the eye
};

/// `frames` >= 1 cameras from (from_eye, from_look) to (to_eye, to_look), ends included (one
/// frame: the first pair alone). `lens` gives field of view, image size and near plane.
/// Throws std::runtime_error naming the frame ("frame 3 of 10: the eye (x, y, z) is inside
/// wall 'north' (plan.toml:12)") for an eye inside a solid or outside the far box, or one
/// that would look at itself.
std::vector<WalkFrame> walk_frames(const CellComplex& complex, Vec3 from_eye, Vec3 from_look, Vec3 to_eye,
                                   Vec3 to_look, int frames, const Camera& lens);

/// The file of frame `k` (from 0) of `frames`: "walk.svg" → "walk-0001.svg", the number
/// counting from 1 and padded to at least four digits.
std::string frame_path(const std::string& path, int k, int frames);

}  // namespace avenues
