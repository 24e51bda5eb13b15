// Avenues — what a walkthrough session measures of its own frames (for --stats-json and
// `avenues bench walk`): each frame's period, its work split into render, show and swap,
// how many frames the frame budget reduced or refined, the process's memory and CPU time.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace avenues::app {

/// Order statistics of a sample (nearest rank); all zero for an empty one.
struct Percentiles {
  double median = 0, p95 = 0, p99 = 0, mean = 0, max = 0;
};
Percentiles percentiles(std::vector<double> v);
nlohmann::json to_json(const Percentiles& p);

/// Resident memory of this process [kB] (Linux /proc/self/statm); 0 when unknown.
long resident_kb();
/// CPU time of this process, all threads, user and system [s].
double cpu_seconds();

/// What a session measured.
struct WalkReport {
  std::vector<double> frame_ms;   ///< period of each frame (start to next start)
  std::vector<double> work_ms;    ///< time spent on each frame (poll to swap)
  std::vector<double> render_ms;  ///< visibility, render and composition, for frames that rendered
  std::vector<double> show_ms;    ///< upload, blit and overlays, every frame
  std::vector<double> swap_ms;    ///< glfwSwapBuffers, every frame
  long reduced_frames = 0;        ///< frames rendered below full detail to keep to the frame budget
  long refined_frames = 0;        ///< frames rendered again at full detail once the eye stopped
  long rss_kb_100 = 0, rss_kb_last = 0;
  double cpu_s_10 = 0, cpu_s_last = 0;  ///< [s] CPU time of the process (all threads) after frame 10, and at the end
  nlohmann::json last;            ///< the last pose and view
  nlohmann::json shots = nlohmann::json::array();

  /// After frame `frame` (from 0): samples memory after the 100th and CPU time after the 10th.
  void sample_process(long frame);
  /// At the end: the process's memory and CPU time.
  void finish();
  /// The report as --stats-json writes it, for the plan file `plan`.
  nlohmann::json to_json(const std::string& plan) const;
};

/// Writes report.to_json(plan) to `path` atomically.
void write_stats(const std::string& path, const std::string& plan, const WalkReport& report);

}  // namespace avenues::app
