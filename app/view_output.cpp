// Avenues — `avenues view ... -o FILE`: the picture of the view, chosen by FILE's extension.
//
//   .svg .pdf .eps .dxf .hpgl .plt   the hidden-line drawing (render/view_lines.h)
//   .png .pgm .ppm .pbm              the scanline half-tone picture (render/halftone.h),
//                                    with --samples, --shading and --dither
//
// with --stereo (drawings: parallel, cross, pair; pictures: anaglyph, parallel, cross; two
// eyes, off-axis, never toe-in) and --frames N (a straight walk to --to-eye/--to-look,
// one numbered file per frame).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <iostream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/option_checks.h"
#include "core/atomic_file.h"
#include "core/file_name.h"
#include "render/drawing.h"
#include "render/effects.h"
#include "render/halftone.h"
#include "render/raster.h"
#include "render/scene_objects.h"
#include "render/stereo_drawing.h"
#include "render/view_lines.h"
#include "render/walkthrough.h"
#include "visibility/stereo.h"

namespace avenues::app {

namespace {

bool is_drawing(const std::string& path) { return is_drawing_path(path); }

/// The composite a stereo picture takes (--stereo), or an error naming the file.
StereoComposite composite_of(const std::string& stereo, const std::string& path) {
  StereoComposite composite;
  if (!parse_stereo_composite(stereo, composite))
    throw std::runtime_error("--stereo wants anaglyph, parallel or cross for pictures, not '" + stereo + "' (" + path + ")");
  return composite;
}

/// The layout a stereo drawing takes (--stereo), or an error naming the file.
StereoLayout layout_of(const std::string& stereo, const std::string& path) {
  StereoLayout layout;
  if (!parse_stereo_layout(stereo, layout))
    throw std::runtime_error("--stereo wants parallel, cross or pair for drawings, not '" + stereo + "' (" + path + ")");
  return layout;
}

double micros_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
}

void add_drawing_stats(nlohmann::json& stats, const DrawingStats& d, double render_us, const std::string& path) {
  stats["lines"] = d.lines;
  stats["render_us"] = render_us;
  const std::string ext = lower_extension(path);
  if (ext == ".hpgl" || ext == ".plt") stats["penup_mm"] = {{"before", d.penup_mm_before}, {"after", d.penup_mm_after}};
}

HalftoneOptions halftone_options(const ViewOptions& opt) {
  HalftoneOptions o;
  o.samples = samples_option(opt.samples);
  if (!parse_shading(opt.shading, o.shading.model))
    throw std::runtime_error("--shading wants flat, smooth or auto, not '" + opt.shading + "'");
  if (!parse_dither(opt.dither, o.dither))
    throw std::runtime_error("--dither wants none, bayer or fs, not '" + opt.dither + "'");
  o.lights = lights_option(opt.lights);
  o.object_shadows = object_shadows_option(opt.object_shadows);
  if (!std::isfinite(opt.falloff)) throw std::runtime_error("--falloff wants a distance in metres");
  o.shading.falloff_start = opt.falloff;
  return o;
}

void add_render_stats(nlohmann::json& stats, const RenderStats& rs) {
  for (const auto& [key, value] : rs.fields()) stats[key] = value;
}

/// The plan's objects placed, what reading their meshes let pass told once.
std::vector<PlacedObject> objects_of(const LoadedPlan& plan) {
  std::vector<std::string> said;
  std::vector<PlacedObject> objects = place_objects(plan.complex, &said);
  print_warnings(plan.path, said);
  return objects;
}

/// The picture warm_view_picture() started, if any (taken once).
std::future<Image>& warm_picture() {
  static std::future<Image> warm;
  return warm;
}

/// One view's half-tone picture (no stereo, no frames), its counters into `rs`.
Image view_picture(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs, const ViewOptions& opt,
                   RenderStats& rs) {
  Image picture = warm_picture().valid() ? warm_picture().get() : Image{};  // its storage, kept by render_view
  render_view(plan.complex, objects_of(plan), v.camera, vs, halftone_options(opt), picture, &rs);
  return picture;
}

/// What the hidden-line drawings of `view` draw: shadow outlines when asked for.
LineOptions line_options_of(const ViewOptions& opt) {
  LineOptions o;
  o.shadows = opt.shadow_lines;
  return o;
}

/// One view's hidden-line drawing (no stereo, no frames); [µs] its time into `render_us`.
Drawing view_drawing(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs, const ViewOptions& opt,
                     double& render_us) {
  const CellComplex& c = plan.complex;
  const LineOptions line_options = line_options_of(opt);
  const LineScene scene = prepare_line_scene(c, line_options);
  auto t0 = std::chrono::steady_clock::now();
  // Lines need exact masks: a view searched by hull (for half-tones) is searched again.
  const VisibleSet exact = vs.conservative ? find_visible(c, v.camera, v.eye_cell, exact_masks(v.search)) : VisibleSet{};
  Drawing d = draw_view(c, scene, v.camera, vs.conservative ? exact : vs, line_options);
  render_us = micros_since(t0);
  return d;
}

/// A straight walk's half-tone frames, each rendered once and written to every one of
/// `paths` (PATH-0001.png, ...), as a run of its own for each would write them; each
/// file's figures into its `stats`.
void write_picture_frames(const LoadedPlan& plan, const ViewSetup& v, const ViewOptions& opt,
                          const std::vector<std::string>& paths, const std::vector<nlohmann::json*>& stats) {
  const CellComplex& c = plan.complex;
  const HalftoneOptions o = halftone_options(opt);
  const std::vector<PlacedObject> objects = objects_of(plan);
  const auto frames = walk_frames(c, v.viewpoint.eye, v.viewpoint.look, parse_vec3(opt.to_eye, "--to-eye"),
                                  parse_vec3(opt.to_look, "--to-look"), opt.frames, v.camera);
  RenderStats total;
  Image frame;
  FrameStorage storage;  // the half-tone's arrays, kept from frame to frame
  const SceneEffects effects = prepare_effects(c, objects, o, v.kernel);  // once for every frame
  for (size_t k = 0; k < frames.size(); ++k) {
    VisibleSet fv = find_visible(c, frames[k].camera, frames[k].cell, v.search);
    RenderStats rs;
    render_view(c, objects, effects, frames[k].camera, fv, o, frame, storage, &rs);
    for (const std::string& path : paths) write_image(frame, frame_path(path, int(k), int(frames.size())));
    total.add(rs);
  }
  for (size_t i = 0; i < paths.size(); ++i) {
    add_render_stats(*stats[i], total);
    (*stats[i])["frames"] = frames.size();
    (*stats[i])["first_frame"] = frame_path(paths[i], 0, int(frames.size()));
  }
}

/// A straight walk's hidden-line frames, each drawn once and written to every one of
/// `paths`, as a run of its own for each would write them; each file's figures into its
/// `stats`. Every frame's eye is checked before any is written.
void write_drawing_frames(const LoadedPlan& plan, const ViewSetup& v, const ViewOptions& opt,
                          const std::vector<std::string>& paths, const std::vector<nlohmann::json*>& stats) {
  const CellComplex& c = plan.complex;
  const LineOptions line_options = line_options_of(opt);
  const LineScene scene = prepare_line_scene(c, line_options);
  const auto frames = walk_frames(c, v.viewpoint.eye, v.viewpoint.look, parse_vec3(opt.to_eye, "--to-eye"),
                                  parse_vec3(opt.to_look, "--to-look"), opt.frames, v.camera);
  std::vector<size_t> lines(paths.size(), 0);
  double render_us = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    auto t0 = std::chrono::steady_clock::now();
    VisibleSet fv = find_visible(c, frames[k].camera, frames[k].cell, exact_masks(v.search));
    Drawing d = draw_view(c, scene, frames[k].camera, fv, line_options);
    render_us += micros_since(t0);
    for (size_t i = 0; i < paths.size(); ++i) lines[i] += write_drawing(d, frame_path(paths[i], int(k), int(frames.size()))).lines;
  }
  for (size_t i = 0; i < paths.size(); ++i) {
    (*stats[i])["frames"] = frames.size();
    (*stats[i])["lines"] = lines[i];
    (*stats[i])["render_us"] = render_us;
    (*stats[i])["first_frame"] = frame_path(paths[i], 0, int(frames.size()));
  }
}

/// A stereo pair's half-tone composite, rendered once and written to every one of `paths`,
/// as a run of its own for each would write it; each file's figures into its `stats`.
void write_stereo_pictures(const LoadedPlan& plan, const ViewSetup& v, const ViewOptions& opt,
                           const std::vector<std::string>& paths, const std::vector<nlohmann::json*>& stats) {
  const CellComplex& c = plan.complex;
  const StereoComposite composite = composite_of(opt.stereo, paths.front());
  StereoRig rig = stereo_rig(c, v.camera, {opt.interocular, opt.converge});
  if (rig.problem != StereoRig::Problem::None) throw std::runtime_error(rig.message());
  RenderStats rs;
  const Image picture =
      render_stereo_view(c, objects_of(plan), rig.left, rig.right, composite, halftone_options(opt), &rs, v.search);
  for (size_t i = 0; i < paths.size(); ++i) {
    write_image(picture, paths[i]);
    add_render_stats(*stats[i], rs);
    (*stats[i])["stereo"] = {{"layout", opt.stereo}, {"interocular", opt.interocular}, {"converge", opt.converge},
                             {"left_cell", rig.left_at.cell}, {"right_cell", rig.right_at.cell}};
  }
}

/// A stereo pair's hidden-line drawings, drawn once and laid out into every one of
/// `paths`, as a run of its own for each would write them; each file's figures into its
/// `stats`.
void write_stereo_drawings(const LoadedPlan& plan, const ViewSetup& v, const ViewOptions& opt,
                           const std::vector<std::string>& paths, const std::vector<nlohmann::json*>& stats) {
  const CellComplex& c = plan.complex;
  const LineOptions line_options = line_options_of(opt);
  const LineScene scene = prepare_line_scene(c, line_options);
  const StereoLayout layout = layout_of(opt.stereo, paths.front());
  StereoRig rig = stereo_rig(c, v.camera, {opt.interocular, opt.converge});
  if (rig.problem != StereoRig::Problem::None) throw std::runtime_error(rig.message());
  auto t0 = std::chrono::steady_clock::now();
  VisibleSet lv = find_visible(c, rig.left, rig.left_at.cell, exact_masks(v.search));
  VisibleSet rv = find_visible(c, rig.right, rig.right_at.cell, exact_masks(v.search));
  Drawing left = draw_view(c, scene, rig.left, lv, line_options), right = draw_view(c, scene, rig.right, rv, line_options);
  const double render_us = micros_since(t0);
  for (size_t i = 0; i < paths.size(); ++i) {
    add_drawing_stats(*stats[i], write_stereo_drawing(left, right, layout, paths[i]), render_us, paths[i]);
    (*stats[i])["stereo"] = {{"layout", to_string(layout)},
                             {"interocular", opt.interocular},
                             {"converge", opt.converge},
                             {"left_cell", rig.left_at.cell},
                             {"right_cell", rig.right_at.cell},
                             {"eyes_apart", rig.eyes_apart()}};
  }
  if (rig.eyes_apart())
    std::cout << "note: the two eyes stand in different cells (" << rig.left_at.cell << " and " << rig.right_at.cell
              << "); each sees through its own avenues\n";
}

/// The half-tone picture(s): one view, a stereo composite, or walk frames.
void write_picture(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs, const ViewOptions& opt,
                   const std::string& path, nlohmann::json& stats) {
  if (opt.frames == 0 && opt.stereo.empty()) {
    RenderStats rs;
    write_image(view_picture(plan, v, vs, opt, rs), path);
    add_render_stats(stats, rs);
    return;
  }
  const std::vector<nlohmann::json*> each{&stats};
  (opt.frames > 0 ? write_picture_frames : write_stereo_pictures)(plan, v, opt, {path}, each);
}

}  // namespace

void warm_view_picture(const ViewOptions& opt) {
  int w = 0, h = 0;
  if (!opt.stereo.empty() || opt.frames > 0 || !parse_size(opt.size, w, h)) return;
  warm_picture() = std::async(std::launch::async, [w, h] {
    Image picture;
    picture.resize(w, h, 3);  // touched (zeroed) here; a grey picture takes a third of it
    return picture;
  });
}

void check_view_output(const std::string& path, const std::string& stereo) {
  const bool picture = is_raster_path(path);
  if (!picture && !is_drawing(path))
    throw std::runtime_error("cannot write '" + path + "': unknown picture format '" + lower_extension(path) +
                             "' (drawings: " + drawing_extensions() + "; half-tone pictures: " + raster_extensions() +
                             ")");
  if (stereo.empty()) return;
  if (picture) composite_of(stereo, path);
  else layout_of(stereo, path);
}

std::string explain_view_effects(const LoadedPlan& plan, const ViewOptions& opt) {
  const CellComplex& c = plan.complex;
  const HalftoneOptions o = halftone_options(opt);
  std::string out = explain_effects(prepare_effects(c, place_objects(c), o).plan);
  if (std::any_of(opt.outputs.begin(), opt.outputs.end(), is_drawing))
    out += std::string("shadow outlines: ") + (opt.shadow_lines ? "on" : "off") + " \u2014 " +
           (opt.shadow_lines ? (c.lights.empty() ? "asked for, but the plan has no light to cast them"
                                                 : "asked for (--shadow-lines)")
                             : "not asked for (--shadow-lines)") +
           "\n";
  return out;
}

void write_view_output(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs, const ViewOptions& opt,
                       const std::string& path, nlohmann::json& stats) {
  check_view_output(path, "");
  if (is_raster_path(path)) return write_picture(plan, v, vs, opt, path, stats);
  if (opt.frames == 0 && opt.stereo.empty()) {
    double render_us = 0;
    const Drawing d = view_drawing(plan, v, vs, opt, render_us);
    add_drawing_stats(stats, write_drawing(d, path), render_us, path);
    return;
  }
  const std::vector<nlohmann::json*> each{&stats};
  (opt.frames > 0 ? write_drawing_frames : write_stereo_drawings)(plan, v, opt, {path}, each);
}

nlohmann::json write_view_outputs(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs,
                                  const ViewOptions& opt) {
  nlohmann::json each = nlohmann::json::array();
  if (opt.frames > 0 || !opt.stereo.empty()) {  // each frame or pair made once, whatever the files of each kind
    std::vector<nlohmann::json> one(opt.outputs.size());
    std::vector<std::string> pictures, drawings;
    std::vector<nlohmann::json*> picture_stats, drawing_stats;
    for (size_t i = 0; i < opt.outputs.size(); ++i) {
      one[i]["file"] = opt.outputs[i];
      const bool raster = is_raster_path(opt.outputs[i]);
      (raster ? pictures : drawings).push_back(opt.outputs[i]);
      (raster ? picture_stats : drawing_stats).push_back(&one[i]);
    }
    if (!pictures.empty())
      (opt.frames > 0 ? write_picture_frames : write_stereo_pictures)(plan, v, opt, pictures, picture_stats);
    if (!drawings.empty())
      (opt.frames > 0 ? write_drawing_frames : write_stereo_drawings)(plan, v, opt, drawings, drawing_stats);
    for (nlohmann::json& j : one) each.push_back(std::move(j));
    return each;
  }
  // One picture and one drawing, however many files of each kind; then every file or none.
  RenderStats rs;
  Image picture;
  if (std::any_of(opt.outputs.begin(), opt.outputs.end(), is_raster_path)) picture = view_picture(plan, v, vs, opt, rs);
  double render_us = 0;
  Drawing drawing;
  if (std::any_of(opt.outputs.begin(), opt.outputs.end(), is_drawing)) drawing = view_drawing(plan, v, vs, opt, render_us);
  std::vector<std::pair<std::string, std::string>> files;
  for (const std::string& out : opt.outputs) {
    nlohmann::json one;
    one["file"] = out;
    if (is_raster_path(out)) {
      files.emplace_back(out, encode_image(picture, out));
      add_render_stats(one, rs);
    } else {
      EncodedDrawing e = encode_drawing(drawing, out);
      add_drawing_stats(one, e.stats, render_us, out);
      files.emplace_back(out, std::move(e.bytes));
    }
    each.push_back(std::move(one));
  }
  write_files_atomically(files);  // all of them or none
  return each;
}

}  // namespace avenues::app
