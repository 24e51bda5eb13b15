// Avenues — which effects a scene calls for, and why: the renderer assembles only those.
//
// "Simulate only the effects a scene calls for." Each stage of the half-tone beyond the bare
// scan of cell faces costs something, and most scenes need few of them:
//
//   depth resolution   only where objects stand: the faces of a convex cell never hide each
//                      other, so the scan sorts depth only among a cell's objects and its own
//                      faces (scanline.h: it never did more; the plan says where);
//   implicit lines     only if polygons interpenetrate (interpenetration.h, found at load);
//                      otherwise the scan keeps one depth order along each run;
//   shadows            only for point lights away from the eye: the traversal from each light,
//                      the shadow polygons and the secondary scan (shadows.h, scanline.h);
//   smooth shading     when asked (Smooth), or with Auto only for curved meshes (Gouraud on
//                      their curved polygons; a plane is shaded flat exactly);
//   distance falloff   only with smooth shading and a falloff distance (Wylie's law);
//   coloured light     only if a light or the ambient is not white, in a colour picture.
//
// plan_effects() decides, from the scene and the options alone; prepare_effects() also does
// the work done once per scene (the shadows), for every view of it to share; explain_effects()
// says what was decided, one line per effect, for `avenues view --explain`:
//
//   shadows: off — the plan has no light away from the eye
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "render/halftone.h"
#include "render/lighting.h"
#include "render/scene_objects.h"
#include "render/shadows.h"

namespace avenues {

/// One effect: on or off, and why, in a few words.
struct Effect {
  bool on = false;
  std::string why;
};

struct EffectPlan {
  Effect depth;           ///< depth resolution among objects and their cell's faces
  Effect implicit_lines;  ///< Bouknight's implicitly defined lines where polygons interpenetrate
  Effect shadows;         ///< point lights away from the eye: what they reach, shadow polygons, secondary scan
  Effect object_shadows;  ///< with shadows: objects' shadow polygons (Bouknight), beside the walls' (through portals)
  Effect smooth;          ///< smooth shading (Wylie): per sample on planes, Gouraud on curved meshes
  Effect falloff;         ///< Wylie's distance law
  Effect coloured;        ///< light per colour channel
  Lighting lighting;      ///< the lights the picture uses
  Shading shading;        ///< the shading the picture uses (options', BACK from a plan's ambient light at the eye)
  long interpenetration_pairs = 0;  ///< triangle pairs tested for crossing
  double plan_us = 0;     ///< [µs] deciding
};

/// Decides the effects of rendering `complex` with `objects` (place_objects) as `options` say.
EffectPlan plan_effects(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                        const HalftoneOptions& options);

/// One line per effect, "name: on — why" / "name: off — why", in a fixed order: depth,
/// implicit lines, shadows, object shadows, smooth shading, distance falloff, coloured light.
std::string explain_effects(const EffectPlan& plan);

/// A scene's effects decided and prepared, shared by every view of it (stereo eyes,
/// walkthrough frames): prepare once per scene, render many times.
struct SceneEffects {
  EffectPlan plan;
  SceneShadows shadows;   ///< empty unless plan.shadows.on
  double prepare_us = 0;  ///< [µs] planning and casting the shadows
};

/// plan_effects(), then the shadows when they are on (cast_shadows, in `kernel`); the
/// shadows' reason then says how far each light reaches.
SceneEffects prepare_effects(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                             const HalftoneOptions& options, Kernel kernel = Kernel::Double);

}  // namespace avenues
