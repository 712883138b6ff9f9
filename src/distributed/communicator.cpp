#include "src/distributed/communicator.hpp"

#include <cstdlib>
#include <initializer_list>
#include <stdexcept>

#ifdef MPSOLID_HAVE_MPI
// The C interface only: MPI's deprecated C++ bindings are not needed.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace mpsolid {

namespace {
void check_exchange(const std::vector<int>& peers, const std::vector<std::vector<double>>& out,
                    const std::vector<std::vector<double>>& in) {
  if (peers.size() != out.size() || peers.size() != in.size())
    throw std::invalid_argument("exchange: one message each way per peer");
}
}  // namespace

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

namespace {
// The first of the environment variables `names` that holds a number, or
// `absent`.
int launcher_number(std::initializer_list<const char*> names, int absent) {
  for (const char* name : names)
    if (const char* value = std::getenv(name); value != nullptr && *value != '\0')
      return std::atoi(value);
  return absent;
}
}  // namespace

int launcher_job_size() {
  // srun's PMIx names no size: its step's task count is the job's.
  const int pmix_size = std::getenv("PMIX_RANK") ? launcher_number({"SLURM_STEP_NUM_TASKS"}, 1) : 1;
  return launcher_number({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}, pmix_size);
}
int launcher_rank() {
  return launcher_number({"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}, 0);
}
int slurm_step_tasks() {
  return launcher_number({"SLURM_STEP_NUM_TASKS"}, 0);
}
int slurm_task() {
  return launcher_number({"SLURM_PROCID"}, 0);
}

#ifdef MPSOLID_HAVE_MPI

namespace {
Communicator*& world_slot() {
  static Communicator* world = nullptr;
  return world;
}
}  // namespace

const Communicator& Communicator::world() {
  static const Communicator one_rank(0, 1);
  return world_slot() ? *world_slot() : one_rank;
}

std::vector<double> Communicator::all_gather(const std::vector<double>& mine) const {
  if (size_ == 1) return mine;
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size_)), starts(counts.size() + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (std::size_t r = 0; r < counts.size(); ++r) starts[r + 1] = starts[r] + counts[r];
  std::vector<double> all(static_cast<std::size_t>(starts.back()));
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), starts.data(),
                 MPI_DOUBLE, MPI_COMM_WORLD);
  return all;
}

void Communicator::exchange(const std::vector<int>& peers,
                            const std::vector<std::vector<double>>& out,
                            std::vector<std::vector<double>>& in) const {
  check_exchange(peers, out, in);
  const std::size_t n = peers.size();
  // Kept between calls: the halo exchanges allocate nothing per step.
  thread_local std::vector<MPI_Request> requests;
  requests.resize(2 * n);
  constexpr int kTag = 1;
  for (std::size_t k = 0; k < n; ++k) {
    MPI_Irecv(in[k].data(), static_cast<int>(in[k].size()), MPI_DOUBLE, peers[k], kTag,
              MPI_COMM_WORLD, &requests[k]);
    MPI_Isend(out[k].data(), static_cast<int>(out[k].size()), MPI_DOUBLE, peers[k], kTag,
              MPI_COMM_WORLD, &requests[n + k]);
  }
  MPI_Waitall(static_cast<int>(2 * n), requests.data(), MPI_STATUSES_IGNORE);
}

void Communicator::send(int to, const std::vector<double>& values) const {
  constexpr int kTag = 2;
  MPI_Send(values.data(), static_cast<int>(values.size()), MPI_DOUBLE, to, kTag, MPI_COMM_WORLD);
}

std::vector<double> Communicator::receive(int from) const {
  constexpr int kTag = 2;
  MPI_Status status;
  MPI_Probe(from, kTag, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_DOUBLE, &count);
  std::vector<double> values(static_cast<std::size_t>(count));
  MPI_Recv(values.data(), count, MPI_DOUBLE, from, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return values;
}

std::int64_t Communicator::max(std::int64_t mine) const {
  std::int64_t all = mine;
  if (size_ > 1) MPI_Allreduce(&mine, &all, 1, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD);
  return all;
}

void Communicator::barrier() const {
  if (size_ > 1) MPI_Barrier(MPI_COMM_WORLD);
}

void Communicator::broadcast(std::int64_t& value) const {
  if (size_ > 1) MPI_Bcast(&value, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
}

void Communicator::broadcast(std::string& text) const {
  if (size_ == 1) return;
  std::int64_t count = static_cast<std::int64_t>(text.size());
  broadcast(count);
  text.resize(static_cast<std::size_t>(count));
  MPI_Bcast(text.data(), static_cast<int>(count), MPI_CHAR, 0, MPI_COMM_WORLD);
}

void Communicator::abort(int code) const {
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

MpiSession::MpiSession(int* argc, char*** argv) {
  int provided = 0;
  // Only the thread that started MPI calls it (OpenMP teams never do).
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node);
  int node_size = 1;
  MPI_Comm_size(node, &node_size);
  MPI_Comm_free(&node);
  world_slot() = new Communicator(rank, size, node_size);
}

MpiSession::~MpiSession() {
  delete world_slot();
  world_slot() = nullptr;
  MPI_Finalize();
}

std::string mpi_library_version() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;
  MPI_Get_library_version(text, &length);
  std::string version(text, static_cast<std::size_t>(length));
  // The first line, without the build details after the comma.
  version = version.substr(0, version.find_first_of(",\n"));
  return version;
}

#else  // one rank

const Communicator& Communicator::world() {
  static const Communicator one_rank(0, 1);
  return one_rank;
}

std::vector<double> Communicator::all_gather(const std::vector<double>& mine) const {
  return mine;
}

void Communicator::exchange(const std::vector<int>& peers,
                            const std::vector<std::vector<double>>& out,
                            std::vector<std::vector<double>>& in) const {
  check_exchange(peers, out, in);
  for (const int peer : peers)
    if (peer != 0) throw std::invalid_argument("exchange: a one-rank run has no other rank");
  in = out;  // a rank exchanging with itself gets its own message back
}

std::int64_t Communicator::max(std::int64_t mine) const {
  return mine;
}
void Communicator::send(int, const std::vector<double>&) const {
  throw std::invalid_argument("send: a one-rank run has no other rank");
}
std::vector<double> Communicator::receive(int) const {
  throw std::invalid_argument("receive: a one-rank run has no other rank");
}
void Communicator::barrier() const {}
void Communicator::broadcast(std::int64_t&) const {}
void Communicator::broadcast(std::string&) const {}
void Communicator::abort(int code) const {
  std::exit(code);
}

MpiSession::MpiSession(int*, char***) {}
MpiSession::~MpiSession() = default;

std::string mpi_library_version() {
  return "none";
}

#endif

}  // namespace mpsolid
