#pragma once
// The ranks of a run (docs/mpi.md): MPI's world communicator when the build
// has MPI (MPSOLID_HAVE_MPI) and the program started it, one rank otherwise.
// What the decomposed step needs (RankGroup), and rank 0's messages to the
// ranks that follow it. Every call is collective over the ranks involved and
// returns the same data at any timing, so results never depend on message
// order.
#include <cstdint>
#include <string>
#include <vector>

#include "src/distributed/rank_group.hpp"

namespace mpsolid {

class Communicator final : public RankGroup {
 public:
  // The world: every rank of the run (one, without MPI or before MpiSession).
  static const Communicator& world();

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  // The ranks on this rank's node (sharing its memory), this one included.
  int node_size() const { return node_size_; }
  std::vector<double> all_gather(const std::vector<double>& mine) const override;
  void exchange(const std::vector<int>& peers, const std::vector<std::vector<double>>& out,
                std::vector<std::vector<double>>& in) const override;
  std::int64_t max(std::int64_t mine) const override;
  // A message to one rank, and one from it (any length: the receiver
  // learns it). Messages between two ranks arrive in the order sent.
  void send(int to, const std::vector<double>& values) const;
  std::vector<double> receive(int from) const;
  void barrier() const;
  // Rank 0's value, on every rank (the text is resized on the others).
  void broadcast(std::int64_t& value) const;
  void broadcast(std::string& text) const;
  // Ends every rank of the run with `code` (a failure on one rank must not
  // leave the others waiting in a collective call).
  [[noreturn]] void abort(int code) const;

 private:
  Communicator(int rank, int size, int node_size = 1)
      : rank_(rank), size_(size), node_size_(node_size) {}
  int rank_ = 0, size_ = 1, node_size_ = 1;
  friend class MpiSession;
};

// Starts MPI for the program's lifetime when the build has it (a no-op
// otherwise); the world communicator reflects it from then on.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

// True when an MPI launcher started this process (mpirun, mpiexec, srun
// with PMI or PMIx): its environment names the job's size or this rank.
bool launched_by_mpi();

// The job's rank count and this process's rank as the launcher's
// environment names them (Open MPI's; PMI's under MPICH; PMIx's and the
// step's task count under srun); 1 and 0 when it names none. A build
// without MPI reads them to refuse a job of several ranks, whose every rank
// would run the whole case alone.
int launcher_job_size();
int launcher_rank();
// Under srun: the step's task count and this task's number (SLURM's
// SLURM_STEP_NUM_TASKS and SLURM_PROCID; 0 and 0 outside a step). srun
// without an MPI plugin starts tasks that are not one MPI job.
int slurm_step_tasks();
int slurm_task();

// "Open MPI 4.1.4" (the library's own words), or "none" in a build without MPI.
std::string mpi_library_version();

}  // namespace mpsolid
