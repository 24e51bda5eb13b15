// Avenues — the TBB arena a piece of parallel work runs in, by thread count: a picture's
// bands, a scene's lights and a search's strips keep to the threads asked for
// (HalftoneOptions::threads; in an MPI job, a rank's share of its machine's cores), not to
// every core TBB sees.
#pragma once

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace avenues {

/// The arena of at most `threads` threads (0: as many as TBB offers). One per thread count,
/// made once: creating an arena each frame costs more than scanning a band. Never destroyed
/// (TBB may be gone by the time statics are).
tbb::task_arena& arena_for(int threads);

/// Starts the worker threads of arena_for(threads) now, in the background (an empty task
/// enqueued: this returns at once). A one-shot picture (`avenues view`, `drawing`) calls it
/// before reading its plan, so that the 2–4 ms TBB takes to start its threads pass while the
/// plan is read and decomposed, not in the frame that needs them.
void start_threads(int threads);

/// Calls f(chunk, begin, end) for `chunks` contiguous ranges splitting [0, n) evenly, on
/// arena_for(threads); one thread runs them in order, here. The ranges depend on n and
/// `chunks` alone, so a caller that keeps each chunk's output apart and joins them in
/// chunk order gets the same result with any number of threads.
template <class F>
void for_each_chunk(int threads, size_t n, size_t chunks, F&& f) {
  chunks = std::max<size_t>(1, std::min(chunks, n));
  auto run = [&](size_t k) { f(k, n * k / chunks, n * (k + 1) / chunks); };
  if (threads == 1 || chunks == 1) {
    for (size_t k = 0; k < chunks; ++k) run(k);
    return;
  }
  arena_for(threads).execute([&] { tbb::parallel_for(size_t(0), chunks, run); });
}

}  // namespace avenues
