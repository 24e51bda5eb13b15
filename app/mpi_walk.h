// Avenues — a walk's frames spread over the ranks of an MPI job (mpirun, srun).
//
// `mpirun -np N avenues path ...` starts N processes. Rank 0 reads and decomposes the plan,
// works out every frame's camera, and broadcasts the lot (the complex as its .cells bytes,
// cells/build_cells.h: cells_bytes); then every rank renders frames, handed out one at a
// time by rank 0 as ranks become free (a slow frame holds up only itself): rank 0 answers
// the other ranks from a thread of its own and renders frames too. Rank 0 alone reports
// progress and errors. A process not started by an MPI launcher (or an Avenues built
// without MPI, AVENUES_HAVE_MPI unset) is rank 0 of 1, and MPI is never initialised: the
// walk runs as it always has. All of MPI is in mpi_walk.cpp.
//
// Faults: a rank whose frame throws reports it to rank 0, which stops handing out frames
// and returns "rank R failed at frame K: ..." once every rank has stopped. A rank that is
// killed cannot report: the launcher then stops the job (Open MPI's mpirun sends SIGTERM
// to the other ranks, and names the rank that died), and rank 0, on SIGTERM or SIGINT,
// says which frames were in progress on which ranks and how many were complete before
// it exits with status 2. Frames are written atomically, so `--resume` finishes the walk.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace avenues::app {

class MpiWalk {
 public:
  /// Joins the MPI job this process was started in (MPI_Init_thread), if any.
  MpiWalk();
  /// MPI_Finalize, if the constructor initialised MPI.
  ~MpiWalk();
  MpiWalk(const MpiWalk&) = delete;
  MpiWalk& operator=(const MpiWalk&) = delete;

  int rank() const { return rank_; }
  int ranks() const { return ranks_; }              ///< 1 without an MPI job
  int local_ranks() const { return local_ranks_; }  ///< ranks on this machine, sharing its cores

  /// Collective: rank 0's `bytes` to every rank. On rank 0, ok = false says that it failed
  /// (and will say why itself): every other rank then gets false back.
  bool broadcast(std::string& bytes, bool ok);

  /// Collective: renders the frames `todo` (their numbers, from 0; read on rank 0 only)
  /// over every rank by render(frame), which throws on failure. On rank 0, progress(done)
  /// follows the frames finished on every rank. Returns "" when every frame was rendered;
  /// else, on rank 0, the first failure, "rank R failed at frame K (of N): what", and on the
  /// rank that failed, its own. With one rank, frames are rendered in order and an
  /// exception from render() goes straight to the caller.
  std::string share(const std::vector<int64_t>& todo, int64_t frames, const std::function<void(int64_t)>& render,
                    const std::function<void(int64_t)>& progress);
  /// On rank 0 after share(): how many frames each rank rendered.
  const std::vector<int64_t>& rendered() const { return rendered_; }

 private:
  int rank_ = 0, ranks_ = 1, local_ranks_ = 1;
  bool initialised_ = false;
  bool threads_ = false;  ///< MPI lets rank 0 answer from a thread while it renders
  std::vector<int64_t> rendered_;
};

}  // namespace avenues::app
