#pragma once
// `krug sweep` and `krug ballistic` on MPI ranks (an app-level driver: the library knows nothing of
// MPI). Rank 0 parses the command, makes the variants, hands them out one at a time to whichever rank
// is free (itself included: it runs one at a time too) and writes the tables; every other rank waits
// for a variant, runs it as a `krug run` child process exactly as `--jobs` does, and reports its exit
// code. The outputs go to the shared folder given with --out. This header has no MPI in it:
// mpi_workers.cpp is compiled with MPI, mpi_none.cpp without.
#include <atomic>
#include <csignal>
#include <memory>
#include <string>

#include "study.hpp"

namespace krug::app {

// Whether this krug was built with MPI (cmake -DKRUG_MPI=ON or AUTO with MPI found).
bool mpi_built();

// The number of ranks an MPI launcher (mpirun, srun) started, from its environment
// (OMPI_COMM_WORLD_SIZE, PMI_SIZE); -1 when started by one that gives only the rank
// (OMPI_COMM_WORLD_RANK, PMI_RANK, PMIX_RANK); 0 when not started by one.
int launched_ranks();

// How to get a krug that runs on MPI ranks (for the message of a build without it).
std::string mpi_build_hint();

// MPI_Init on construction; on destruction rank 0 tells every other rank to stop, and MPI_Finalize.
class MpiStudy {
 public:
  MpiStudy();
  ~MpiStudy();
  MpiStudy(const MpiStudy&) = delete;
  MpiStudy& operator=(const MpiStudy&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Rank 0: the ranks as the workers of a study (slots = size: rank 0 runs one too).
  Workers workers(const std::atomic<bool>& interrupted, const volatile std::sig_atomic_t& signal_number);
  // Every other rank: runs what rank 0 hands out until it says stop. An interruption is passed on to
  // the running child (which writes its checkpoint and an interrupted summary).
  void serve(const std::atomic<bool>& interrupted, const volatile std::sig_atomic_t& signal_number);

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace krug::app
