#include "src/core/parallel.hpp"

#include <omp.h>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define MPSOLID_PAUSE() _mm_pause()
#else
#define MPSOLID_PAUSE() ((void)0)
#endif

#include <chrono>
#include <memory>
#include <thread>

#include "src/core/float_mode.hpp"

namespace mpsolid {

void set_thread_count(int threads) {
  omp_set_num_threads(threads > 0 ? threads : 1);
}
int thread_count() {
  return omp_get_max_threads();
}
int available_cores() {
  return omp_get_num_procs();
}

namespace detail {
thread_local TeamSlot team_slot;

void fork_join_blocks(std::size_t begin, std::size_t end,
                      void (*block)(void*, std::size_t, std::size_t), void* context) {
  const std::size_t count = end - begin;
  // Below this size the team wake-up costs more than the work.
  constexpr std::size_t kMinPerThread = 128;
  const int threads = omp_get_max_threads();
  SubnormalModeScope mode;
  if (threads == 1 || count < 2 * kMinPerThread || omp_in_parallel()) {
    block(context, begin, end);
    return;
  }
#pragma omp parallel num_threads(threads)
  {
    SubnormalModeScope thread_mode;
    const Range r = static_block(begin, end, static_cast<std::size_t>(omp_get_thread_num()),
                                 static_cast<std::size_t>(omp_get_num_threads()));
    if (r.begin < r.end) block(context, r.begin, r.end);
  }
}

namespace {
using Clock = std::chrono::steady_clock;

struct alignas(64) Padded {
  std::atomic<std::size_t> value{0};
};
}  // namespace

// One per team, on the stack of the thread that starts it: teams started by
// different threads of a program do not share it.
struct TeamState {
  explicit TeamState(std::size_t threads)
      : counters(std::make_unique<Padded[]>(2 * threads)), size(threads) {}
  std::unique_ptr<Padded[]> counters;  // 2 x team size chunk counters
  std::size_t size;
  Padded arrived, generation;
};

namespace {
std::atomic<std::int64_t> total_wait_ns{0};
thread_local Clock::duration thread_wait{};

// Spin this long at a barrier before yielding the core.
constexpr auto kSpin = std::chrono::microseconds(20);
}  // namespace

std::atomic<std::size_t>& chunk_counter(std::size_t parity, std::size_t rank) {
  TeamState& team = *team_slot.team;
  return team.counters[parity * team.size + rank].value;
}

void run_team(void (*body)(void*), void* context) {
  const int threads = omp_get_max_threads();
  SubnormalModeScope mode;
  if (threads == 1 || omp_in_parallel()) {
    body(context);
    return;
  }
  TeamState team(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    SubnormalModeScope thread_mode;
    thread_wait = {};
    team_slot = {static_cast<std::size_t>(omp_get_thread_num()),
                 static_cast<std::size_t>(omp_get_num_threads()), 0, &team};
    body(context);
    team_slot = {};
    total_wait_ns.fetch_add(
        std::chrono::duration_cast<std::chrono::nanoseconds>(thread_wait).count(),
        std::memory_order_relaxed);
  }
}

// A counting barrier: the last thread to arrive opens the next generation.
// The others wait for it (wait_until_reaches: a step's phases are
// microseconds apart, and on a busy machine a waiting thread gives its core
// to the thread it waits for, or to another process, instead of burning it).
void team_barrier() {
  TeamState& team_state = *team_slot.team;
  const std::size_t generation = team_state.generation.value.load(std::memory_order_acquire);
  if (team_state.arrived.value.fetch_add(1, std::memory_order_acq_rel) + 1 == team_slot.size) {
    team_state.arrived.value.store(0, std::memory_order_relaxed);
    team_state.generation.value.store(generation + 1, std::memory_order_release);
  } else {
    wait_until_reaches(team_state.generation.value, generation + 1);
  }
}
}  // namespace detail

double wait_until_reaches(const std::atomic<std::size_t>& counter, std::size_t value) {
  using detail::Clock, detail::kSpin, detail::thread_wait;
  if (counter.load(std::memory_order_acquire) >= value) return 0.0;
  const auto start = Clock::now();
  while (counter.load(std::memory_order_acquire) < value) {
    if (Clock::now() - start < kSpin)
      MPSOLID_PAUSE();
    else
      std::this_thread::yield();
  }
  const Clock::duration waited = Clock::now() - start;
  thread_wait += waited;
  return std::chrono::duration<double>(waited).count();
}

double team_wait_seconds() {
  return 1e-9 * static_cast<double>(detail::total_wait_ns.load(std::memory_order_relaxed));
}

}  // namespace mpsolid
