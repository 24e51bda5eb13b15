// Avenues — the half-tone renderer: bands of rows over threads, spans lit and encoded (see
// halftone.h).
#include "render/halftone.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>

#include "core/thread_arena.h"
#include "render/effects.h"
#include "render/pixel_fill.h"
#include "render/raster_srgb.h"
#include "render/scanline.h"

namespace avenues {

namespace {

/// [pixels] rows per band: enough bands to share among threads, few enough that presetting
/// each band's active list (a pass over the edges that began above it) stays cheap.
constexpr int kBandRows = 24;

using Clock = std::chrono::steady_clock;
double micros_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

/// What the shading of a polygon's span needs, prepared once per picture.
struct PolygonLook {
  std::array<float, 3> linear{};   ///< colour (RGB, or luminance in [0]) of a Constant shade times its I
  std::array<uint8_t, 3> code{};   ///< that, encoded (Constant shades only)
  std::array<float, 3> colour{};   ///< the material's colour (RGB, or luminance in [0])
  bool constant = false;
  bool lit = false;                ///< a Lit shade lit per sample (lit_samples)
  bool piecewise = false;          ///< lit, every term constant: one colour per run lit alike (lit_runs)
  int light_channels = 1;          ///< lit: intensities per sample, 1 or 3 (coloured light)
  std::array<float, 3> unpieced{};  ///< piecewise: the linear colour where no piece meets a span
};

/// The linear colour of a flat Lit shade (every term Constant) where the terms t for which
/// lit(t) holds reach: the ambient plus those terms, each channel at most 1, times the
/// material's `colour`. One function for the runs and for the looks: the same sums.
template <class Lit>
std::array<float, 3> lit_colour(const SurfaceShade& shade, const LightTerm* terms, const std::array<float, 3>& colour,
                                int light_channels, Lit lit) {
  std::array<float, 3> light = shade.lit_ambient;
  for (int t = 0; t < shade.terms; ++t)
    if (lit(t))
      for (size_t c = 0; c < 3; ++c) light[c] += terms[t].diffuse * terms[t].colour[c];
  std::array<float, 3> linear{};
  for (size_t c = 0; c < 3; ++c) linear[c] = colour[c] * std::min(light[light_channels == 3 ? c : 0], 1.0f);
  return linear;
}

/// Scans bands of rows into the picture; one per thread, reused from band to band (its
/// counters add up over the bands it painted).
class BandPainter {
 public:
  /// A painter for no picture yet (reset() before painting).
  BandPainter() = default;

  /// Readies the painter for picture number `picture`, reusing the storage of the last one.
  void reset(uint64_t picture, const ScreenScene& scene, const EdgeTable& table, const EdgeTable* pieces,
             const std::vector<PolygonLook>& looks, const PolygonLook& background, int per_side, int channels,
             Image& out, std::vector<int32_t>* items) {
    picture_ = picture;
    scene_ = &scene;
    engine_.reset(table, scene.implicit_lines);
    looks_ = &looks;
    background_ = &background;
    s_ = per_side;
    ch_ = channels;
    out_ = &out;
    items_ = items;
    intensity_.resize(size_t(scene.raster.width) * (scene.light_terms.empty() ? 1 : 3));
    sum_.resize(per_side > 1 ? size_t(out.width) * size_t(channels) : 0);
    row_sum_.resize(sum_.size());
    if (pieces && painted_on_.size() < scene.polygons.size()) {  // (lit in runs only where there are pieces of light)
      painted_on_.resize(scene.polygons.size(), 0);  // stamped with the picture: never cleared
      painted_.resize(scene.polygons.size());
    }
    run_codes_.fill(RunCode{});
    if (!pieces) secondary_.reset();
    else if (secondary_) secondary_->reset(*pieces);
    else secondary_.emplace(*pieces);
    pixels_ = 0;
  }
  /// The picture last readied for (reset), 0: none.
  uint64_t picture() const { return picture_; }

  void paint(int y0, int y1) {
    engine_.start(y0 * s_);
    if (secondary_) secondary_->start(y0 * s_);
    for (int y = y0; y < y1; ++y) {
      uint8_t* dst = out_->row(y);
      if (s_ == 1) {
        const SpanRow& spans = engine_.scan();
        if (secondary_) secondary_->scan();
        // The same spans (and pieces of light) as the row above, each of one colour or of
        // runs lit alike: the same pixels.
        if (y > y0 && like_last_row()) {
          std::memcpy(dst, out_->row(y - 1), size_t(out_->width) * size_t(ch_));
          pixels_ += row_pixels_;
          if (items_) {
            const size_t w = size_t(scene_->raster.width);
            std::memcpy(items_->data() + size_t(y) * w, items_->data() + size_t(y - 1) * w, w * sizeof(int32_t));
          }
          continue;
        }
        const long before = pixels_;
        row_alike_ = true;
        for (const Span& sp : spans) write_span(dst, sp, y);
        row_pixels_ = pixels_ - before;
        keep_items(spans, y);
        continue;
      }
      // Several samples a pixel: each row of samples is summed on its own (row_sum_), then
      // added to its pixels' sums. A row of samples like the one before it (the same spans
      // and pieces of light, no sample lit by its own place: `row_alike_`) has the same sums:
      // they are added again. A pixel row whose rows of samples are all the row above's last
      // one, under a row above made of that one row over and over (`uniform_`), sums to the
      // row above's pixels by the same steps: they are copied.
      bool copy = y > y0 && uniform_;
      bool uniform = true;
      for (int k = 0; k < s_; ++k) {
        const int row = y * s_ + k;
        const SpanRow& spans = engine_.scan();
        if (secondary_) secondary_->scan();
        const bool same = (k > 0 || y > y0) && like_last_row();
        if (k > 0) uniform &= same;
        copy &= same;
        if (same) {
          pixels_ += row_pixels_;
        } else {
          std::fill(row_sum_.begin(), row_sum_.end(), 0.0f);
          const long before = pixels_;
          row_alike_ = true;
          for (const Span& sp : spans) add_span(sp, row);
          row_pixels_ = pixels_ - before;
        }
        keep_items(spans, row);
        if (k == 0) std::copy(row_sum_.begin(), row_sum_.end(), sum_.begin());
        else
          for (size_t i = 0; i < sum_.size(); ++i) sum_[i] += row_sum_[i];
      }
      uniform_ = uniform;
      if (copy) {
        std::memcpy(dst, out_->row(y - 1), size_t(out_->width) * size_t(ch_));
        continue;
      }
      const float mean = 1.0f / float(s_ * s_);
      for (size_t i = 0; i < sum_.size(); ++i) dst[i] = encoder_(sum_[i] * mean);
    }
  }
  const ScanCounters& counters() const { return engine_.counters(); }
  long pixels() const { return pixels_; }

 private:
  const PolygonLook& look_of(int32_t polygon) const { return polygon < 0 ? *background_ : (*looks_)[size_t(polygon)]; }

  /// Whether the row of samples just scanned has the last one's spans and pieces of light,
  /// the last one being lit alike along it (`row_alike_`): the same pixels or sums.
  bool like_last_row() const {
    return row_alike_ && engine_.repeated() && (!secondary_ || secondary_->repeated());
  }

  /// Intensities of the span's samples into intensity_ (non-constant shades).
  const float* light(const Span& sp, int row) {
    const size_t p = size_t(sp.polygon);
    const SurfaceShade& shade = scene_->shades[p];
    if (shade.kind == SurfaceShade::Kind::Lit) return light_lit(sp, row, shade, (*looks_)[p].light_channels);
    shade_samples(shade, scene_->polygons[p].depth, scene_->raster, row, sp.x0, sp.x1, intensity_.data());
    return intensity_.data();
  }

  /// A Lit shade: the secondary scan says, per light, which samples it reaches (its lit
  /// pieces, less its shadow polygons); lit_samples adds up the lights there.
  const float* light_lit(const Span& sp, int row, const SurfaceShade& shade, int channels) {
    const LightTerm* terms = mask_lights(sp, shade);
    const size_t p = size_t(sp.polygon);
    lit_samples(shade.lit_ambient, terms, shade.terms, masks_.data(), scene_->polygons[p].depth, scene_->raster, row,
                sp.x0, sp.x1, channels, intensity_.data());
    return intensity_.data();
  }

  /// Calls f(t, piece, shadow) for each piece of light (shadow false) or of shadow of the
  /// shade's lights that need a scan (t: the light's term), each light's lit pieces before
  /// its shadow pieces, while f returns true. Returns whether it never returned false.
  template <class F>
  bool all_pieces(const SurfaceShade& shade, F f) const {
    const LightTerm* terms = scene_->light_terms.data() + shade.first_term;
    for (int t = 0; t < shade.terms; ++t) {
      const LightTerm& term = terms[t];
      if (!term.needs_scan()) continue;
      const int32_t shadows = term.first_piece + term.lit_pieces;
      for (int32_t i = term.first_piece; i < shadows + term.shadow_pieces; ++i)
        if (!f(t, i, i >= shadows)) return false;
    }
    return true;
  }

  /// Calls f(t, from, to, shadow) for each piece, as all_pieces, that has samples [from, to)
  /// within the span on this row.
  template <class F>
  void pieces_within(const Span& sp, const SurfaceShade& shade, F f) const {
    all_pieces(shade, [&](int t, int32_t piece, bool shadow) {
      const Span c = secondary_->span_of(piece);
      const int32_t from = std::max(c.x0, sp.x0), to = std::min(c.x1, sp.x1);
      if (from < to) f(t, from, to, shadow);
      return true;
    });
  }

  /// A flat Lit shade (every light's term constant): the span cut into runs lit alike,
  /// each of one colour: f(from, to, state, linear), `linear()` the run's linear colour and
  /// `state` the word of its lights' states (nullptr: the shade has over 64 terms, or no
  /// piece meets the span). The runs are found from the pieces' spans themselves, not
  /// sample by sample: each piece's ends, sorted, are where some
  /// light may begin or cease to reach, and between two ends every light's state is fixed
  /// (lit: the whole polygon or within a lit piece, and within no shadow piece). The
  /// states are bits, 64 terms a word.
  template <class F>
  void lit_runs(const Span& sp, const PolygonLook& look, F f) {
    const SurfaceShade& shade = scene_->shades[size_t(sp.polygon)];
    const LightTerm* terms = scene_->light_terms.data() + shade.first_term;
    ends_.clear();
    pieces_within(sp, shade, [&](int t, int32_t from, int32_t to, bool shadow) {
      const int32_t counter = 2 * t + shadow;
      ends_.push_back(piece_end(from, counter, true));
      ends_.push_back(piece_end(to, counter, false));
    });
    if (ends_.empty()) return f(sp.x0, sp.x1, nullptr, [&] { return look.unpieced; });  // no piece on this row's span: one run
    // Per word of terms: lit everywhere (no scan needed), lit but where shadowed (whole),
    // within some lit piece, within some shadow piece; then the run's state and the next.
    const size_t words = (size_t(shade.terms) + 63) / 64;
    if (bits_.size() < 6 * words) bits_.resize(6 * words);
    uint64_t *always = bits_.data(), *whole = always + words, *in_lit = whole + words, *in_shadow = in_lit + words;
    uint64_t *run = in_shadow + words, *next = run + words;
    std::fill(always, run, uint64_t(0));
    for (int t = 0; t < shade.terms; ++t) {
      const uint64_t bit = uint64_t(1) << (t % 64);
      if (!terms[t].needs_scan()) always[t / 64] |= bit;
      else if (terms[t].whole) whole[t / 64] |= bit;
    }
    auto state = [&](uint64_t* out) {
      for (size_t w = 0; w < words; ++w) out[w] = always[w] | ((whole[w] | in_lit[w]) & ~in_shadow[w]);
    };
    auto colour = [&](const uint64_t* lit) {
      return lit_colour(shade, terms, look.colour, look.light_channels, [&](int t) { return lit[t / 64] >> (t % 64) & 1; });
    };
    // By x: a few ends (most spans) by insertion.
    if (ends_.size() > 16) std::sort(ends_.begin(), ends_.end());
    else
      for (size_t i = 1; i < ends_.size(); ++i)
        for (size_t j = i; j > 0 && ends_[j] < ends_[j - 1]; --j) std::swap(ends_[j], ends_[j - 1]);
    // Per term, the lit pieces and the shadow pieces the samples are in: only those the
    // ends step are read, so only they are cleared.
    if (inside_.size() < 2 * size_t(shade.terms)) inside_.resize(2 * size_t(shade.terms));
    for (const uint64_t end : ends_) inside_[uint32_t(end) >> 1] = 0;
    // A run goes on while no light's state changes: the same runs as sample by sample.
    auto step = [&](uint64_t end) {
      const uint32_t counter = uint32_t(end) >> 1;
      int32_t& count = inside_[counter];
      const bool was = count > 0;
      count += end & 1 ? 1 : -1;
      if (was != (count > 0)) (counter % 2 ? in_shadow : in_lit)[counter / 128] ^= uint64_t(1) << (counter / 2 % 64);
    };
    int32_t run_from = sp.x0;
    size_t e = 0;
    for (int32_t x = sp.x0; x < sp.x1;) {
      for (; e < ends_.size() && end_x(ends_[e]) <= x; ++e) step(ends_[e]);
      state(next);
      bool changed = false;  // (a loop, not std::equal: that is a call to memcmp)
      for (size_t w = 0; w < words; ++w) changed |= next[w] != run[w];
      if (x > sp.x0 && changed) {
        f(run_from, x, words == 1 ? run : nullptr, [&] { return colour(run); });
        run_from = x;
      }
      std::swap(run, next);
      x = e < ends_.size() ? end_x(ends_[e]) : sp.x1;
    }
    f(run_from, sp.x1, words == 1 ? run : nullptr, [&] { return colour(run); });
  }

  /// Per light term of the span's shade, which of its samples the light reaches (masks_;
  /// nullptr: all), from the secondary scan's spans of its pieces. Returns the terms.
  const LightTerm* mask_lights(const Span& sp, const SurfaceShade& shade) {
    const int n = sp.x1 - sp.x0;
    const LightTerm* terms = scene_->light_terms.data() + shade.first_term;
    masks_.resize(size_t(shade.terms));
    mask_buffer_.resize(size_t(shade.terms) * size_t(n));
    for (int t = 0; t < shade.terms; ++t) {
      const LightTerm& term = terms[t];
      if (!term.needs_scan()) {
        masks_[size_t(t)] = nullptr;
        continue;
      }
      uint8_t* mask = mask_buffer_.data() + size_t(t) * size_t(n);
      masks_[size_t(t)] = mask;
      std::memset(mask, term.whole ? 1 : 0, size_t(n));
    }
    // Lit pieces set their samples, then shadow pieces clear theirs.
    pieces_within(sp, shade, [&](int t, int32_t from, int32_t to, bool shadow) {
      std::memset(mask_buffer_.data() + size_t(t) * size_t(n) + size_t(from - sp.x0), shadow ? 0 : 1, size_t(to - from));
    });
    return terms;
  }

  /// Whether every piece of light or shadow of the shade's lights is on this row as on the
  /// row before.
  bool pieces_unmoved(const SurfaceShade& shade) const {
    return all_pieces(shade, [&](int, int32_t piece, bool) { return secondary_->unmoved(piece); });
  }

  /// The code of a run of `polygon` lit as `state` says, `linear()` its colour: kept for the
  /// picture by (polygon, state), since a lit floor's runs take the same few colours on row
  /// after row (its summed terms and their encoding done once).
  template <class Linear>
  std::array<uint8_t, 3> run_code(int32_t polygon, const uint64_t* state, Linear&& linear) {
    auto encode = [&](const std::array<float, 3>& l) {
      return std::array<uint8_t, 3>{encoder_(l[0]), encoder_(l[1]), encoder_(l[2])};
    };
    if (!state) return encode(linear());
    RunCode& kept = run_codes_[(uint64_t(uint32_t(polygon)) * 0x9E3779B97F4A7C15ull ^ *state) % run_codes_.size()];
    if (kept.polygon != polygon || kept.state != *state) kept = {polygon, *state, encode(linear())};
    return kept.code;
  }

  /// One sample per pixel: straight into the picture.
  void write_span(uint8_t* dst, const Span& sp, int row) {
    const PolygonLook& look = look_of(sp.polygon);
    if (sp.polygon >= 0) pixels_ += sp.x1 - sp.x0;
    uint8_t* at = dst + size_t(sp.x0) * size_t(ch_);
    if (look.constant) return fills_.of(look.code).fill(at, size_t(sp.x1 - sp.x0), ch_);
    if (look.piecewise) {
      // The polygon's span as on the row above, under pieces of light and shadow as there:
      // the same runs, the same pixels.
      const size_t p = size_t(sp.polygon);
      const bool again = painted_on_[p] == painted_stamp(row - 1) && painted_[p].x0 == sp.x0 &&
                         painted_[p].x1 == sp.x1 && pieces_unmoved(scene_->shades[p]);
      painted_on_[p] = painted_stamp(row);
      painted_[p] = sp;
      if (again) return void(std::memcpy(at, out_->row(row - 1) + size_t(sp.x0) * size_t(ch_), size_t(sp.x1 - sp.x0) * size_t(ch_)));
    }
    if (look.piecewise)
      return lit_runs(sp, look, [&](int from, int to, const uint64_t* state, auto&& linear) {
        fills_.of(run_code(sp.polygon, state, linear)).fill(dst + size_t(from) * size_t(ch_), size_t(to - from), ch_);
      });
    row_alike_ = false;  // lit sample by sample: another row, other samples
    const float* in = light(sp, row);
    if (look.light_channels == 3) {
      for (int i = 0; i < sp.x1 - sp.x0; ++i)
        for (int c = 0; c < ch_; ++c) at[i * ch_ + c] = encoder_(look.colour[size_t(c)] * in[3 * i + c]);
      return;
    }
    for (int i = 0; i < sp.x1 - sp.x0; ++i)
      for (int c = 0; c < ch_; ++c) at[i * ch_ + c] = encoder_(look.colour[size_t(c)] * in[i]);
  }

  /// Several samples per pixel: summed per pixel in linear light, pixel by pixel over the
  /// samples of the span that fall in it.
  void add_span(const Span& sp, int row) {
    const PolygonLook& look = look_of(sp.polygon);
    if (sp.polygon >= 0) pixels_ += sp.x1 - sp.x0;
    if (look.piecewise)
      return lit_runs(sp, look, [&](int from, int to, const uint64_t*, auto&& run_linear) {
        const std::array<float, 3> linear = run_linear();
        for (int px = from / s_; px * s_ < to; ++px) {
          const float k = float(std::min(to, (px + 1) * s_) - std::max(from, px * s_));
          float* sum = &row_sum_[size_t(px) * size_t(ch_)];
          for (int c = 0; c < ch_; ++c) sum[c] += k * linear[size_t(c)];
        }
      });
    if (!look.constant) row_alike_ = false;  // lit sample by sample: another row, other samples
    const float* in = look.constant ? nullptr : light(sp, row);
    for (int px = sp.x0 / s_; px * s_ < sp.x1; ++px) {
      const int from = std::max(sp.x0, px * s_), to = std::min(sp.x1, (px + 1) * s_);
      float* sum = &row_sum_[size_t(px) * size_t(ch_)];
      if (look.constant) {
        for (int c = 0; c < ch_; ++c) sum[c] += float(to - from) * look.linear[size_t(c)];
        continue;
      }
      if (look.light_channels == 3) {
        for (int c = 0; c < ch_; ++c) {
          float light_sum = 0;
          for (int i = from; i < to; ++i) light_sum += in[3 * (i - sp.x0) + c];
          sum[c] += look.colour[size_t(c)] * light_sum;
        }
        continue;
      }
      float light_sum = 0;
      for (int i = from; i < to; ++i) light_sum += in[i - sp.x0];
      for (int c = 0; c < ch_; ++c) sum[c] += look.colour[size_t(c)] * light_sum;
    }
  }

  void keep_items(const SpanRow& spans, int row) {
    if (!items_) return;
    int32_t* dst = items_->data() + size_t(row) * size_t(scene_->raster.width);
    for (const Span& sp : spans) std::fill(dst + sp.x0, dst + sp.x1, sp.polygon);
  }

  uint64_t picture_ = 0;
  const ScreenScene* scene_ = nullptr;
  ScanlineEngine engine_;
  std::optional<SecondaryScan> secondary_;  ///< Bouknight's secondary scan, when the scene has pieces
  const std::vector<PolygonLook>* looks_ = nullptr;
  const PolygonLook* background_ = nullptr;
  int s_ = 1, ch_ = 1;
  Image* out_ = nullptr;
  std::vector<int32_t>* items_ = nullptr;
  const SrgbEncoder& encoder_ = srgb_encoder();
  FillColours fills_;  ///< the colours of the spans filled lately, ready to fill with
  // Written by this painter's thread alone: in lines of their own (core/cache_lines.h).
  OwnLines<float> intensity_, sum_;
  OwnLines<float> row_sum_;    ///< several samples a pixel: the last row of samples' sums per pixel
  OwnLines<const uint8_t*> masks_;  ///< per light term of the span's shade: lit samples (nullptr: all)
  OwnLines<uint8_t> mask_buffer_;
  /// lit_runs: where a piece's span begins or ends within the span (x >= 0), and the
  /// counter it steps (2·term, + 1 for a shadow piece), as one word (x, counter, begins):
  /// sorted by x as words, and read back whole (a struct's fields stored one by one and
  /// loaded together would wait for the stores).
  static uint64_t piece_end(int32_t x, int32_t counter, bool begins) {
    return uint64_t(uint32_t(x)) << 32 | uint64_t(uint32_t(counter)) << 1 | uint64_t(begins);
  }
  static int32_t end_x(uint64_t end) { return int32_t(end >> 32); }
  OwnLines<uint64_t> ends_;
  OwnLines<int32_t> inside_;
  OwnLines<uint64_t> bits_;  ///< lit_runs: the terms' states, 64 a word
  long pixels_ = 0;
  /// Per polygon lit in runs: the picture and the row its span was last painted on
  /// (painted_stamp), and that span.
  OwnLines<uint64_t> painted_on_;
  uint64_t painted_stamp(int row) const { return picture_ << 32 | uint64_t(uint32_t(row + 1)); }
  SpanRow painted_;
  /// run_code(): codes of runs lit in pieces, by polygon and lights' states, for this picture.
  struct RunCode {
    int32_t polygon = -1;
    uint64_t state = 0;
    std::array<uint8_t, 3> code{};
  };
  std::array<RunCode, 16> run_codes_{};
  bool row_alike_ = false;  ///< the row of samples last painted or summed is of its spans alone (none lit by its place)
  long row_pixels_ = 0;     ///< its pixels counted
  /// Several samples a pixel: the row last painted was one row of samples over and over.
  bool uniform_ = false;
};

PolygonLook look_of(const SurfaceShade& shade, const std::vector<LightTerm>& terms, bool colour,
                    const SrgbEncoder& enc) {
  PolygonLook look;
  look.colour = colour ? shade.colour : std::array<float, 3>{luminance(shade.colour[0], shade.colour[1], shade.colour[2]), 0, 0};
  look.constant = shade.kind == SurfaceShade::Kind::Constant;
  for (size_t c = 0; c < 3; ++c) look.linear[c] = look.colour[c] * shade.intensity;
  if (shade.kind == SurfaceShade::Kind::Lit) {
    look.light_channels = shade.coloured ? 3 : 1;
    const LightTerm* own = terms.data() + shade.first_term;
    auto flat = [](const LightTerm& t) { return t.kind == LightTerm::Kind::Constant; };
    // Lit alike everywhere (flat, no light partly cut off): a constant after all.
    look.constant = std::all_of(own, own + shade.terms, [&](const LightTerm& t) { return flat(t) && !t.needs_scan(); });
    look.lit = !look.constant;
    look.piecewise = look.lit && std::all_of(own, own + shade.terms, flat);
    if (look.constant) look.linear = lit_colour(shade, own, look.colour, look.light_channels, [](int) { return true; });
    if (look.piecewise)
      look.unpieced = lit_colour(shade, own, look.colour, look.light_channels,
                                 [&](int t) { return !own[t].needs_scan() || own[t].whole; });
  }
  for (size_t c = 0; c < 3; ++c) look.code[c] = enc(look.linear[c]);
  return look;
}

}  // namespace

int samples_per_side(int samples) {
  switch (samples) {
    case 1: return 1;
    case 4: return 2;
    case 16: return 4;
  }
  throw std::invalid_argument("samples per pixel must be 1, 4 or 16, not " + std::to_string(samples));
}

SceneOptions scene_options(const HalftoneOptions& options) {
  SceneOptions s;
  s.per_side = samples_per_side(options.samples);
  s.shading = options.shading;
  s.cull_back_faces = options.cull_back_faces;
  s.detail_samples = options.detail_samples;
  s.objects_within = options.objects_within;
  s.drop_hidden = options.drop_hidden;
  s.threads = options.threads;
  return s;
}

std::vector<std::pair<std::string, double>> RenderStats::fields() const {
  return {{"render_us", render_us},
          {"polygons", double(polygons)},
          {"edges", double(edges)},
          {"scanlines", double(scanlines)},
          {"intersections", double(intersections)},
          {"spans", double(spans)},
          {"pixels", double(pixels)},
          {"implicit_lines", double(implicit_lines)},
          {"depth_sorts", double(depth_sorts)},
          {"depth_comparisons", double(depth_comparisons)},
          {"active_max", double(active_max)},
          {"active_mean", active_mean},
          {"threads", double(threads)},
          {"light_pieces", double(light_pieces)},
          {"effects_us", effects_us}};
}

void RenderStats::add(const RenderStats& o) {
  render_us += o.render_us;
  polygons += o.polygons;
  edges += o.edges;
  scanlines += o.scanlines;
  intersections += o.intersections;
  spans += o.spans;
  pixels += o.pixels;
  implicit_lines += o.implicit_lines;
  depth_sorts += o.depth_sorts;
  depth_comparisons += o.depth_comparisons;
  active_max = std::max(active_max, o.active_max);
  active_mean = scanlines > 0 ? double(intersections) / double(scanlines) : 0;
  threads = std::max(threads, o.threads);
  light_pieces += o.light_pieces;
  effects_us += o.effects_us;
}

struct FrameStorage::Parts {
  ScreenScene scene;
  EdgeTable table, pieces;
  std::vector<PolygonLook> looks;
  tbb::enumerable_thread_specific<BandPainter> painters;
  uint64_t pictures = 0;  ///< pictures scanned with these parts
  /// Each cell's objects, made for the complex and the objects named beside it.
  ObjectsByCell by_cell;
  const CellComplex* by_cell_complex = nullptr;
  const std::vector<PlacedObject>* by_cell_objects = nullptr;
  size_t by_cell_count = 0, by_cell_cells = 0;
  const ObjectsByCell& objects_by_cell_of(const CellComplex& complex, const std::vector<PlacedObject>& objects) {
    if (by_cell_complex != &complex || by_cell_objects != &objects || by_cell_count != objects.size() ||
        by_cell_cells != complex.cells.size()) {
      by_cell = objects_by_cell(complex.cells.size(), objects);
      by_cell_complex = &complex, by_cell_objects = &objects;
      by_cell_count = objects.size(), by_cell_cells = complex.cells.size();
    }
    return by_cell;
  }
};

FrameStorage::FrameStorage() : parts_(std::make_unique<Parts>()) {}
FrameStorage::~FrameStorage() = default;

namespace {

/// The scan of a scene into `out` with `parts`' edge tables and painters, kept for the next.
void scan_scene(const ScreenScene& scene, const HalftoneOptions& options, Image& out, RenderStats* stats,
                std::vector<int32_t>* item_buffer, FrameStorage::Parts& parts) {
  const auto t0 = Clock::now();
  const int s = samples_per_side(options.samples);
  const RasterMap& raster = scene.raster;
  const int channels = options.colour ? 3 : 1;
  out.resize(raster.width / s, raster.height / s, channels);
  if (item_buffer) item_buffer->assign(size_t(raster.width) * size_t(raster.height), -1);

  const SrgbEncoder& enc = srgb_encoder();
  std::vector<PolygonLook>& looks = parts.looks;
  looks.clear();
  looks.reserve(scene.shades.size());
  for (const SurfaceShade& shade : scene.shades) looks.push_back(look_of(shade, scene.light_terms, options.colour, enc));
  SurfaceShade background;
  background.colour = {float(options.background[0]), float(options.background[1]), float(options.background[2])};
  background.intensity = 1;
  const PolygonLook back = look_of(background, scene.light_terms, options.colour, enc);

  EdgeTable& table = parts.table;
  table.build(raster.width, raster.height, scene.polygons, scene.clips);
  // Bouknight's secondary scan, only when some light is cut off somewhere.
  const EdgeTable* pieces = nullptr;
  if (!scene.pieces.empty()) {
    static const std::vector<ClipRegion> kNoClips;
    parts.pieces.build(raster.width, raster.height, scene.pieces, kNoClips);
    pieces = &parts.pieces;
  }
  const int bands = (out.height + kBandRows - 1) / kBandRows;
  // Each thread's painter, readied once per picture: the first band it paints resets it.
  const uint64_t picture = ++parts.pictures;
  tbb::task_arena& arena = arena_for(options.threads);
  arena.execute([&] {
    tbb::parallel_for(0, bands, [&](int band) {
      BandPainter& painter = parts.painters.local();
      if (painter.picture() != picture)
        painter.reset(picture, scene, table, pieces, looks, back, s, channels, out, item_buffer);
      painter.paint(band * kBandRows, std::min(out.height, (band + 1) * kBandRows));
    });
  });

  if (stats) {
    ScanCounters total;
    RenderStats r;
    for (const BandPainter& p : parts.painters) {  // sums and a maximum: the same in any order
      if (p.picture() != picture) continue;  // a thread that painted no band of this picture
      total.add(p.counters());
      r.pixels += p.pixels();
    }
    r.polygons = long(scene.polygons.size());
    r.edges = table.edge_count();
    r.scanlines = total.scanlines;
    r.intersections = total.intersections;
    r.spans = total.spans;
    r.implicit_lines = total.implicit_lines;
    r.depth_sorts = total.depth_sorts;
    r.depth_comparisons = total.depth_comparisons;
    r.active_max = total.active_max;
    r.active_mean = total.scanlines > 0 ? double(total.intersections) / double(total.scanlines) : 0;
    r.threads = arena.max_concurrency();
    r.light_pieces = long(scene.pieces.size());
    *stats = r;
  }
  if (options.dither != Dither::None) out = dither(out, options.dither);
  if (stats) stats->render_us = micros_since(t0);
}

}  // namespace

void render_scene(const ScreenScene& scene, const HalftoneOptions& options, Image& out, RenderStats* stats,
                  std::vector<int32_t>* item_buffer) {
  FrameStorage storage;
  scan_scene(scene, options, out, stats, item_buffer, storage.parts());
}

void render_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const SceneEffects& effects,
                 const Camera& camera, const VisibleSet& visible, const HalftoneOptions& options, Image& out,
                 FrameStorage& storage, RenderStats* stats) {
  const auto t0 = Clock::now();
  const EffectPlan& plan = effects.plan;
  SceneOptions so = scene_options(options);
  so.shading = plan.shading;
  if (!plan.lighting.at_eye) {
    so.lighting = &plan.lighting;
    so.shadows = &effects.shadows;
  }
  FrameStorage::Parts& parts = storage.parts();
  so.objects_by_cell = &parts.objects_by_cell_of(complex, objects);
  screen_scene_of_view(complex, objects, camera, visible, so, parts.scene);
  parts.scene.implicit_lines = plan.implicit_lines.on;
  scan_scene(parts.scene, options, out, stats, nullptr, parts);
  if (stats) stats->render_us = micros_since(t0);
}

void render_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const SceneEffects& effects,
                 const Camera& camera, const VisibleSet& visible, const HalftoneOptions& options, Image& out,
                 RenderStats* stats) {
  FrameStorage storage;
  render_view(complex, objects, effects, camera, visible, options, out, storage, stats);
}

void render_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const Camera& camera,
                 const VisibleSet& visible, const HalftoneOptions& options, Image& out, RenderStats* stats) {
  const auto t0 = Clock::now();
  if (options.plan_effects) {
    const SceneEffects effects = prepare_effects(complex, objects, options);
    render_view(complex, objects, effects, camera, visible, options, out, stats);
    if (stats) {
      stats->effects_us = effects.prepare_us;
      stats->render_us = micros_since(t0);
    }
    return;
  }
  const ScreenScene scene = screen_scene_of_view(complex, objects, camera, visible, scene_options(options));
  render_scene(scene, options, out, stats);
  if (stats) stats->render_us = micros_since(t0);
}

Image render_view(const CellComplex& complex, const Camera& camera, const VisibleSet& visible,
                  const HalftoneOptions& options, RenderStats* stats) {
  Image out;
  render_view(complex, place_objects(complex), camera, visible, options, out, stats);
  return out;
}

Image render_stereo_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const Camera& left,
                         const Camera& right, StereoComposite composite, const HalftoneOptions& options,
                         RenderStats* stats, const TraverseParams& search) {
  if (composite == StereoComposite::Anaglyph && options.dither != Dither::None)
    throw std::invalid_argument("an anaglyph cannot be dithered: 1-bit grey cannot carry its colours");
  const auto t0 = Clock::now();
  HalftoneOptions each = options;
  each.dither = Dither::None;  // dithered once, after composing
  Image views[2];
  RenderStats total;
  const Camera* eyes[2] = {&left, &right};
  std::optional<SceneEffects> effects;  // decided once for both eyes
  if (options.plan_effects) effects.emplace(prepare_effects(complex, objects, options));
  for (int k = 0; k < 2; ++k) {
    const Location at = complex.locate(eyes[k]->eye, eyes[k]->forward);
    if (at.what != Location::What::Cell)
      throw std::runtime_error(std::string(k == 0 ? "the left" : "the right") + " eye is not in free space" +
                               (at.solid.empty() ? std::string() : " (inside " + at.solid + ")"));
    const VisibleSet visible = find_visible(complex, *eyes[k], at.cell, search);
    RenderStats one;
    if (effects) render_view(complex, objects, *effects, *eyes[k], visible, each, views[k], &one);
    else render_view(complex, objects, *eyes[k], visible, each, views[k], &one);
    total.add(one);
  }
  Image out = stereo_composite(views[0], views[1], composite);
  if (options.dither != Dither::None) out = dither(out, options.dither);
  if (stats) {
    *stats = total;
    if (effects) stats->effects_us = effects->prepare_us;
    stats->render_us = micros_since(t0);
  }
  return out;
}

Image render_meshes(const std::vector<Mesh>& meshes, const std::vector<MeshPaint>& paints, const Camera& camera,
                    const HalftoneOptions& options, RenderStats* stats) {
  const auto t0 = Clock::now();
  Image out;
  render_scene(screen_scene_of_meshes(meshes, paints, camera, scene_options(options)), options, out, stats);
  if (stats) stats->render_us = micros_since(t0);
  return out;
}

Image render_meshes(const std::vector<Mesh>& meshes, const Camera& camera, const HalftoneOptions& options,
                    RenderStats* stats) {
  return render_meshes(meshes, {}, camera, options, stats);
}

}  // namespace avenues
