// Avenues — stage timers: how many seconds each stage of a job took (Recast's
// rcScopedTimer, in spirit). One home for timing a stage: the cell builders, the mesh
// scenes and the plan loader all append to a list of StageTime through a ScopedStageTimer.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace avenues {

/// Seconds spent on one stage of a job, for `avenues cells` and the benchmarks.
struct StageTime {
  std::string stage;
  double seconds = 0;  ///< [s] wall-clock
};

/// Seconds since t0 on the steady clock.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Appends {stage, seconds} to `out` when it goes out of scope (also when unwinding).
class ScopedStageTimer {
 public:
  ScopedStageTimer(std::vector<StageTime>& out, std::string stage)
      : out_(out), stage_(std::move(stage)), t0_(std::chrono::steady_clock::now()) {}
  ~ScopedStageTimer() { out_.push_back({std::move(stage_), seconds_since(t0_)}); }
  ScopedStageTimer(const ScopedStageTimer&) = delete;
  ScopedStageTimer& operator=(const ScopedStageTimer&) = delete;

 private:
  std::vector<StageTime>& out_;
  std::string stage_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace avenues
