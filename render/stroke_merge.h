// Avenues — each stroke once on paper.
//
// The pieces of one real line are already one union (view_lines.h), but two different lines
// can still lie on one line of the picture: touching collinear pieces (a convex line running
// on into a concave one), or lines that happen to line up with the eye. A pen should pass
// over any stretch of paper once. Strokes on one picture line (directions within 1e-9 rad,
// offsets within 1e-6 px) are merged where they overlap or touch; where they differ in
// weight or layer, the heavier pen keeps the overlap (outline over crease), then
// architecture over furniture, and the other stroke keeps only what is left. Strokes
// shorter than 1e-9 px are dropped. Every endpoint written is an endpoint of an input
// stroke, so exact ends stay exact.
#pragma once

#include <vector>

#include "render/drawing.h"

namespace avenues {

/// [px] A stroke shorter than this draws nothing: merge_collinear drops it, and a drawing
/// need not make it (a line seen end-on).
constexpr double kShortestStroke = 1e-9;

/// Rewrites `strokes` so that no two share a piece of positive length and no two that touch
/// end to end on one line have the same weight and layer. Untouched strokes keep their order.
/// The picture's directions are merged on up to `threads` threads (0: as many as TBB
/// offers); the result is the same with any number.
void merge_collinear(std::vector<Stroke>& strokes, int threads = 1);

}  // namespace avenues
