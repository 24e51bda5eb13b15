// Avenues — the hull search of one view on several threads (see strips.h).
#include "visibility/strips.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "core/thread_arena.h"

namespace avenues {

std::vector<double> strip_edges(const Camera& camera, int strips, const VisibleSet* last) {
  std::vector<double> edges;
  const double hw = camera.half_width(), lo = camera.shift_x - hw, hi = camera.shift_x + hw;
  if (strips < 2 || camera.is_parallel() || !(hi > lo)) return edges;
  // Each avenue's mask centre, weighed by what an avenue cost the search that found it: a
  // set searched in strips has each strip's time, and one strip's avenues can cost a fifth
  // more than another's (the 64 x 64 grid's view over its walls: 2.5 against 2.0 us).
  std::vector<std::pair<double, double>> centres;  // (x, weight)
  if (last) {
    const size_t n = last->avenues.size();
    const bool timed = !last->strips.empty() && last->strip_micros.size() == last->strips.size();
    size_t strip = 0;
    double weight = 1;
    for (size_t i = 0; i < n; ++i) {
      if (timed && strip < last->strips.size() && i == size_t(last->strips[strip])) {
        const size_t end = strip + 1 < last->strips.size() ? size_t(last->strips[strip + 1]) : n;
        weight = end > i && last->strip_micros[strip] > 0 ? last->strip_micros[strip] / double(end - i) : 1;
        ++strip;
      }
      const Avenue& a = last->avenues[i];
      if (a.mask.empty()) continue;
      double x = 0;
      for (Vec2 m : a.mask) x += m.x;
      x /= double(a.mask.size());
      if (std::isfinite(x)) centres.push_back({std::clamp(x, lo, hi), weight});
    }
  }
  // A few avenues say little of where the work lies.
  if (centres.size() >= size_t(8 * strips)) {
    std::sort(centres.begin(), centres.end());
    double total = 0;
    for (const auto& [x, w] : centres) total += w;
    double sum = 0;
    size_t i = 0;
    for (int k = 1; k < strips; ++k) {
      const double share = total * k / strips;
      while (i + 1 < centres.size() && sum + centres[i].second <= share) sum += centres[i++].second;
      edges.push_back(centres[i].first);
    }
  } else {
    for (int k = 1; k < strips; ++k) edges.push_back(lo + (hi - lo) * k / strips);
  }
  // Each strip at least a tenth of its even width: from the left, then from the right.
  const double least = 0.1 * (hi - lo) / strips;
  double before = lo;
  for (double& e : edges) before = e = std::max(e, before + least);
  double after = hi;
  for (auto e = edges.rbegin(); e != edges.rend(); ++e) after = *e = std::min(*e, after - least);
  return edges;
}

VisibleSet find_visible_in_strips(const CellComplex& complex, const Camera& camera, CellId eye_cell,
                                  const TraverseParams& params, const std::vector<double>& edges, int threads) {
  const double hw = camera.half_width(), lo = camera.shift_x - hw, hi = camera.shift_x + hw;
  std::vector<double> cuts;
  for (double e : edges)
    if (e > lo && e < hi && (cuts.empty() || e > cuts.back())) cuts.push_back(e);
  if (!params.hull_pieces || camera.is_parallel() || cuts.empty()) return find_visible(complex, camera, eye_cell, params);

  const auto t0 = std::chrono::steady_clock::now();
  const size_t n = cuts.size() + 1;
  std::vector<VisibleSet> parts(n);
  for_each_chunk(threads, n, n, [&](size_t k, size_t, size_t) {
    TraverseParams p = params;
    p.strip = TraverseParams::Strip{k == 0 ? lo : cuts[k - 1], k + 1 == n ? hi : cuts[k]};
    parts[k] = find_visible(complex, camera, eye_cell, p);
  });

  VisibleSet out;
  out.eye_cell = eye_cell;
  out.conservative = true;
  size_t total = 0;
  for (const VisibleSet& part : parts) {
    total += part.avenues.size();
    out.portals_tested += part.portals_tested;
    out.avenues_pruned += part.avenues_pruned;
    out.avenues_merged += part.avenues_merged;
    out.masks_settled += part.masks_settled;
  }
  // Strip after strip, each in its own order: a wave outwards from the eye, so that what
  // is near comes first within its own part of the picture, the only part where it can
  // hide anything (a picture that drops what lies behind what it has drawn wants it so).
  // Interleaved by depth instead, the walk's scene took 12 % longer to build: one strip's
  // neighbouring cells no longer came one after the other.
  out.avenues.reserve(total);
  for (VisibleSet& part : parts) {
    const int first = int(out.avenues.size());
    out.strips.push_back(first);
    out.strip_micros.push_back(part.micros);
    for (Avenue& a : part.avenues) {
      if (a.parent >= 0) a.parent += first;
      out.avenues.push_back(std::move(a));
    }
  }
  out.micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  out.collect_cells();
  return out;
}

FrameSearches::FrameSearches(int threads, double from)
    : threads_(std::clamp(arena_for(threads).max_concurrency(), 1, 8)), from_(from) {}

void FrameSearches::judge(double micros) {
  next_on_ = threads_ > 1 && micros >= (next_on_ ? from_ / 2 : from_);
}

VisibleSet FrameSearches::find(const CellComplex& complex, const Camera& camera, CellId eye_cell,
                               const TraverseParams& params) {
  const bool on = next_on_ && params.hull_pieces && !camera.is_parallel();
  VisibleSet v = on ? find_visible_in_strips(complex, camera, eye_cell, params,
                                              edges_.empty() ? strip_edges(camera, threads_) : edges_, threads_)
                     : find_visible(complex, camera, eye_cell, params);
  // As many threads as strips were searched (none when no cut fell inside the window).
  used_ = v.strips.empty() ? 1 : std::min(threads_, int(v.strips.size()));
  judge(v.micros);
  edges_.clear();
  if (next_on_) edges_ = strip_edges(camera, threads_, &v);
  return v;
}

void FrameSearches::find_pair(const CellComplex& complex, const Camera& left, CellId left_cell, const Camera& right,
                              CellId right_cell, const TraverseParams& params, VisibleSet& left_set,
                              VisibleSet& right_set) {
  used_ = next_on_ ? std::min(threads_, 2) : 1;
  for_each_chunk(used_, 2, 2, [&](size_t eye, size_t, size_t) {
    if (eye == 0) left_set = find_visible(complex, left, left_cell, params);
    else right_set = find_visible(complex, right, right_cell, params);
  });
  judge(std::max(left_set.micros, right_set.micros));
  edges_.clear();
}

}  // namespace avenues
