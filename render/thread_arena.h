// Avenues — the TBB arena a piece of parallel work runs in, by thread count: a picture's
// bands and a scene's lights keep to HalftoneOptions::threads (in an MPI job, a rank's share
// of its machine's cores), not to every core TBB sees.
#pragma once

#include <tbb/task_arena.h>

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

}  // namespace avenues
