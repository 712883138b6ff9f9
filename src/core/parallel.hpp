#pragma once
// The one place that talks to OpenMP. Every physics kernel is a gather: each
// index writes only its own outputs, so any schedule gives the same bits.
//
// Two ways to run loops across the threads:
// - Outside a team, parallel_for opens one parallel region per call
//   (fork/join), as set-up, diagnostics and tests use it.
// - Inside run_in_team (one parallel region for many steps), every thread runs
//   the same code; parallel_for hands each thread its static block of the
//   range and ends with a barrier, like an orphaned `omp for`. The kernels
//   are the same functions in both cases. Code between loops runs on every
//   thread, so it may only read shared data or write per-thread locals;
//   shared scalars are written in a serial_section (one thread) that a
//   barrier separates from their readers.
// Inside a block callback or a serial section the thread is serial: a
// parallel_for there runs inline.
#include <cstddef>
#include <type_traits>

#include "src/core/types.hpp"

namespace mpsolid {

void set_thread_count(int threads);
int thread_count();
int available_cores();

namespace detail {
// This thread's place in the running team; size 0 outside a team or while
// the thread is serial (then parallel_for runs inline).
struct TeamSlot {
  std::size_t rank = 0;
  std::size_t size = 0;
};
extern thread_local TeamSlot team_slot;

// Fork/join: calls block(context, b, e) on one contiguous block per thread
// (inline when small, with 1 thread, or already inside a parallel region).
void fork_join_blocks(std::size_t begin, std::size_t end,
                      void (*block)(void*, std::size_t, std::size_t), void* context);
void run_team(void (*body)(void*), void* context);
void team_barrier();

// Marks the thread serial for its lifetime (restores the slot after).
class SerialScope {
 public:
  SerialScope() : saved_(team_slot) { team_slot.size = 0; }
  ~SerialScope() { team_slot = saved_; }
  SerialScope(const SerialScope&) = delete;
  SerialScope& operator=(const SerialScope&) = delete;

 private:
  TeamSlot saved_;
};
}  // namespace detail

// Static block `rank` of `size` of [begin, end): the same split everywhere,
// so a thread keeps its particles from one loop to the next.
inline Range static_block(std::size_t begin, std::size_t end, std::size_t rank, std::size_t size) {
  const std::size_t count = end - begin;
  return {begin + count * rank / size, begin + count * (rank + 1) / size};
}

// True on a thread that runs inside a team and is not serial.
inline bool in_team() {
  return detail::team_slot.size != 0;
}
// This thread's rank in the team (0 outside a team).
inline std::size_t team_rank() {
  return detail::team_slot.rank;
}
// Threads in the team (1 outside a team).
inline std::size_t team_size() {
  return in_team() ? detail::team_slot.size : 1;
}

// Calls block(b, e) on a partition of [begin, end) into contiguous blocks,
// serially inside each block. In a team, this thread's static block, then a
// barrier; otherwise one fork/join (or inline when serial).
template <class Block>
void parallel_blocks(std::size_t begin, std::size_t end, Block&& block) {
  if (begin >= end) return;  // the same on every thread of a team: no barrier needed
  if (in_team()) {
    const Range r = static_block(begin, end, team_rank(), team_size());
    {
      detail::SerialScope serial;
      if (r.begin < r.end) block(r.begin, r.end);
    }
    detail::team_barrier();
    return;
  }
  using BlockType = std::remove_reference_t<Block>;
  detail::fork_join_blocks(
      begin, end,
      [](void* ctx, std::size_t b, std::size_t e) { (*static_cast<BlockType*>(ctx))(b, e); },
      const_cast<void*>(static_cast<const void*>(&block)));
}

// Runs body(i) for every i in [begin, end) across the threads. The per-index
// loop sits inside the block callback, so body is inlined there.
template <class Body>
void parallel_for(std::size_t begin, std::size_t end, Body&& body) {
  parallel_blocks(begin, end, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) body(i);
  });
}

// Runs body() on every thread of one parallel region (inline with 1 thread).
// Inside, parallel_for shares its range and ends with a barrier.
template <class Body>
void run_in_team(Body&& body) {
  using BodyType = std::remove_reference_t<Body>;
  detail::run_team([](void* ctx) { (*static_cast<BodyType*>(ctx))(); },
                   const_cast<void*>(static_cast<const void*>(&body)));
}

// Runs f on this thread alone, serially (no barrier).
template <class F>
void serial_section(F&& f) {
  detail::SerialScope serial;
  f();
}

}  // namespace mpsolid
