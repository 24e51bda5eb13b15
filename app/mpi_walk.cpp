// Avenues — a walk's frames spread over the ranks of an MPI job (see mpi_walk.h).
//
// The hand-out, on rank 0's answering thread (the other ranks block only in their own
// MPI calls):
//
//   rank r -> 0   kTagAsk    {kReady, -1} first, then {kDone, k} after frame k, or
//                            {kFailed, k} followed by kTagError (the message's text)
//   0 -> rank r   kTagFrame  the next frame to render, or -1: stop
//
// Rank 0 polls (MPI_Iprobe, then a millisecond's sleep) instead of blocking in MPI_Recv,
// which Open MPI spins in: the thread must not take a core from rank 0's own rendering.
// For the same reason the ranks meet at the end in a polled MPI_Ibarrier before
// MPI_Finalize, while rank 0 encodes the film.
#include "app/mpi_walk.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <thread>

#if AVENUES_HAVE_MPI
#include <mpi.h>
#endif

namespace avenues::app {

#if AVENUES_HAVE_MPI

namespace {

constexpr int kTagAsk = 1, kTagError = 2, kTagFrame = 3;
constexpr int64_t kReady = 0, kDone = 1, kFailed = 2;

/// Started by an MPI launcher: Open MPI's mpirun, or a PMI/PMIx one such as Slurm's srun.
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int s) { g_stop_signal = s; }

void nap() { std::this_thread::sleep_for(std::chrono::milliseconds(1)); }

}  // namespace

MpiWalk::MpiWalk() {
  if (!launched_by_mpi()) return;
  int provided = MPI_THREAD_SINGLE;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
    throw std::runtime_error("cannot join the MPI job (MPI_Init_thread failed)");
  initialised_ = true;
  threads_ = provided >= MPI_THREAD_SERIALIZED;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &local_ranks_);
  MPI_Comm_free(&node);
}

MpiWalk::~MpiWalk() {
  if (!initialised_) return;
  MPI_Request done;
  MPI_Ibarrier(MPI_COMM_WORLD, &done);
  for (int flag = 0; MPI_Test(&done, &flag, MPI_STATUS_IGNORE), !flag;) nap();
  MPI_Finalize();
}

bool MpiWalk::broadcast(std::string& bytes, bool ok) {
  if (ranks_ == 1) return ok;
  int64_t size = rank_ == 0 ? (ok ? int64_t(bytes.size()) : -1) : 0;
  MPI_Bcast(&size, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
  if (size < 0) return false;
  if (rank_ != 0) bytes.resize(size_t(size));
  constexpr int64_t kChunk = int64_t(1) << 30;  // MPI counts are ints
  for (int64_t at = 0; at < size; at += kChunk)
    MPI_Bcast(bytes.data() + at, int(std::min(kChunk, size - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
  return true;
}

std::string MpiWalk::share(const std::vector<int64_t>& todo, int64_t frames,
                           const std::function<void(int64_t)>& render, const std::function<void(int64_t)>& progress) {
  rendered_.assign(size_t(ranks_), 0);
  if (ranks_ == 1) {
    for (int64_t k : todo) {
      render(k);
      progress(++rendered_[0]);
    }
    return "";
  }
  const std::string of = " (of " + std::to_string(frames) + ")";

  if (rank_ != 0) {
    int64_t ask[2] = {kReady, -1};
    for (;;) {
      MPI_Send(ask, 2, MPI_INT64_T, 0, kTagAsk, MPI_COMM_WORLD);
      int64_t k = -1;
      MPI_Recv(&k, 1, MPI_INT64_T, 0, kTagFrame, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (k < 0) return "";
      std::string error;
      try {
        render(k);
        ask[0] = kDone;
        ask[1] = k;
        continue;
      } catch (const std::bad_alloc&) {
        error = "out of memory";
      } catch (const std::exception& e) {
        error = e.what();
      }
      ask[0] = kFailed;
      ask[1] = k;
      MPI_Send(ask, 2, MPI_INT64_T, 0, kTagAsk, MPI_COMM_WORLD);
      MPI_Send(error.data(), int(error.size()), MPI_CHAR, 0, kTagError, MPI_COMM_WORLD);
      return "rank " + std::to_string(rank_) + " failed at frame " + std::to_string(k + 1) + of + ": " + error;
    }
  }

  // Rank 0: the frames handed out from one counter, to the other ranks by the answering
  // thread and to this one by its own loop.
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::atomic<int64_t> done{0};
  std::mutex lock;                                 // guards what follows
  std::string failure;                             // the first
  std::vector<int64_t> working(size_t(ranks_), -1);  // each rank's frame, for a stop report
  auto take = [&]() -> int64_t {
    if (stop) return -1;
    const size_t i = next.fetch_add(1);
    return i < todo.size() ? todo[i] : -1;
  };
  auto fail = [&](int rank, int64_t k, const std::string& what) {
    std::lock_guard<std::mutex> hold(lock);
    if (failure.empty()) failure = "rank " + std::to_string(rank) + " failed at frame " + std::to_string(k + 1) + of + ": " + what;
    stop = true;
  };
  auto finished = [&](int rank) {
    const int64_t n = ++done;
    std::lock_guard<std::mutex> hold(lock);
    working[size_t(rank)] = -1;
    ++rendered_[size_t(rank)];
    progress(n);
  };
  // Stopped by the launcher (a rank died) or the user: what was in progress, then out.
  auto check_signal = [&] {
    if (!g_stop_signal) return;
    std::string busy;
    {
      std::lock_guard<std::mutex> hold(lock);
      for (size_t r = 0; r < working.size(); ++r)
        if (working[r] >= 0) busy += (busy.empty() ? "" : ", ") + ("frame " + std::to_string(working[r] + 1)) + " on rank " + std::to_string(r);
    }
    std::fprintf(stderr,
                 "\navenues: the walk was stopped (signal %d: a rank died, or the job was cancelled) with %lld of %zu "
                 "frames left to do rendered%s%s; the frames done are complete: run the same command with --resume "
                 "to finish the walk\n",
                 int(g_stop_signal), static_cast<long long>(done.load()), todo.size(), busy.empty() ? "" : "; in progress: ",
                 busy.c_str());
    std::fflush(stderr);
    std::_Exit(2);
  };

  auto answer = [&] {
    int asking = ranks_ - 1;
    while (asking > 0) {
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, kTagAsk, MPI_COMM_WORLD, &flag, &st);
      if (!flag) {
        check_signal();
        nap();
        continue;
      }
      const int r = st.MPI_SOURCE;
      int64_t ask[2];
      MPI_Recv(ask, 2, MPI_INT64_T, r, kTagAsk, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (ask[0] == kFailed) {
        MPI_Probe(r, kTagError, MPI_COMM_WORLD, &st);
        int n = 0;
        MPI_Get_count(&st, MPI_CHAR, &n);
        std::string what(size_t(n), '\0');
        MPI_Recv(what.data(), n, MPI_CHAR, r, kTagError, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        fail(r, ask[1], what);
        --asking;
        continue;
      }
      if (ask[0] == kDone) finished(r);
      const int64_t k = take();
      {
        std::lock_guard<std::mutex> hold(lock);
        working[size_t(r)] = k;
      }
      MPI_Send(&k, 1, MPI_INT64_T, r, kTagFrame, MPI_COMM_WORLD);
      if (k < 0) --asking;
    }
  };

  struct sigaction act {}, old_term {}, old_int {};
  act.sa_handler = on_stop_signal;
  sigemptyset(&act.sa_mask);
  sigaction(SIGTERM, &act, &old_term);
  sigaction(SIGINT, &act, &old_int);
  if (threads_) {
    std::thread answering(answer);
    for (int64_t k; (k = take()) >= 0;) {
      {
        std::lock_guard<std::mutex> hold(lock);
        working[0] = k;
      }
      try {
        render(k);
      } catch (const std::bad_alloc&) {
        fail(0, k, "out of memory");
        break;
      } catch (const std::exception& e) {
        fail(0, k, e.what());
        break;
      }
      finished(0);
      check_signal();
    }
    answering.join();
  } else {
    answer();  // MPI without threads: rank 0 only hands out the frames
  }
  sigaction(SIGTERM, &old_term, nullptr);
  sigaction(SIGINT, &old_int, nullptr);
  return failure;
}

#else  // without MPI: one process, rank 0 of 1

MpiWalk::MpiWalk() = default;
MpiWalk::~MpiWalk() = default;

bool MpiWalk::broadcast(std::string&, bool ok) { return ok; }

std::string MpiWalk::share(const std::vector<int64_t>& todo, int64_t, const std::function<void(int64_t)>& render,
                           const std::function<void(int64_t)>& progress) {
  rendered_.assign(1, 0);
  for (int64_t k : todo) {
    render(k);
    progress(++rendered_[0]);
  }
  return "";
}

#endif

}  // namespace avenues::app
