// Avenues — a walkthrough session's own measurements (see walk_stats.h).
#include "app/walk_stats.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/atomic_file.h"

namespace avenues::app {

Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  auto at = [&](double q) { return v[std::min(v.size() - 1, size_t(std::ceil(q * double(v.size()))) - (q > 0 ? 1 : 0))]; };
  p.median = at(0.5), p.p95 = at(0.95), p.p99 = at(0.99), p.max = v.back();
  for (double x : v) p.mean += x / double(v.size());
  return p;
}

nlohmann::json to_json(const Percentiles& p) {
  return {{"median", p.median}, {"p95", p.p95}, {"p99", p.p99}, {"mean", p.mean}, {"max", p.max}};
}

long resident_kb() {
  std::ifstream in("/proc/self/statm");
  long pages = 0, resident = 0;
  if (!(in >> pages >> resident)) return 0;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void WalkReport::sample_process(long frame) {
  if (frame == 99) rss_kb_100 = resident_kb();
  if (frame == 9) cpu_s_10 = cpu_seconds();
}

void WalkReport::finish() {
  rss_kb_last = resident_kb();
  cpu_s_last = cpu_seconds();
}

nlohmann::json WalkReport::to_json(const std::string& plan) const {
  nlohmann::json j;
  j["plan"] = plan;
  j["frames"] = work_ms.size();
  j["frame_ms"] = app::to_json(percentiles(frame_ms));
  j["work_ms"] = app::to_json(percentiles(work_ms));
  j["render_ms"] = app::to_json(percentiles(render_ms));
  j["rendered_frames"] = render_ms.size();
  j["reduced_frames"] = reduced_frames;
  j["refined_frames"] = refined_frames;
  j["show_ms"] = app::to_json(percentiles(show_ms));
  j["swap_ms"] = app::to_json(percentiles(swap_ms));
  j["rss_kb"] = {{"frame_100", rss_kb_100}, {"last", rss_kb_last}};
  if (work_ms.size() > 10) j["cpu_ms_per_frame"] = 1000 * (cpu_s_last - cpu_s_10) / double(work_ms.size() - 10);
  j["last"] = last;
  j["screenshots"] = shots;
  return j;
}

void write_stats(const std::string& path, const std::string& plan, const WalkReport& report) {
  write_file_atomically(path, report.to_json(plan).dump(2) + "\n");
}

}  // namespace avenues::app
