// Avenues — one TBB arena per thread count (see thread_arena.h).
#include "core/thread_arena.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

namespace avenues {

tbb::task_arena& arena_for(int threads) {
  static std::mutex lock;
  static auto* arenas = new std::map<int, std::unique_ptr<tbb::task_arena>>;
  const std::lock_guard<std::mutex> hold(lock);
  auto& a = (*arenas)[std::max(threads, 0)];
  if (!a) a = std::make_unique<tbb::task_arena>(threads > 0 ? threads : int(tbb::task_arena::automatic));
  return *a;
}

void start_threads(int threads) { arena_for(threads).enqueue([] {}); }

}  // namespace avenues
