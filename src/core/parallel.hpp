#pragma once
// The one place that talks to OpenMP. Every physics kernel is a gather: each
// index writes only its own outputs, so any schedule gives the same bits.
//
// Two ways to run loops across the threads:
// - Outside a team, parallel_for opens one parallel region per call
//   (fork/join), as set-up, diagnostics and tests use it.
// - Inside run_in_team (one parallel region for many steps), every thread runs
//   the same code; parallel_blocks splits the range into one static block
//   per thread, each cut into a few chunks: a thread takes its own block's
//   chunks first, then any chunks left in the others' blocks, and the loop
//   ends with a barrier. On an idle machine every thread keeps its own
//   particles from one loop to the next; on a busy one a thread that the OS
//   has descheduled leaves its chunks to the others instead of holding
//   everybody up. Which thread runs a chunk never changes a result: every
//   kernel is a gather, each index writes only its own outputs. The
//   barrier spins for a few microseconds, then yields the core to whatever
//   else wants it, and counts the time each thread waits. Code between loops runs on every
//   thread, so it may only read shared data or write per-thread locals;
//   shared scalars are written in a serial_section (one thread) that a
//   barrier separates from their readers.
// Inside a block callback or a serial section the thread is serial: a
// parallel_for there runs inline.
#include <algorithm>
#include <atomic>
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
struct TeamState;  // the team's barrier and chunk counters (parallel.cpp)
struct TeamSlot {
  std::size_t rank = 0;
  std::size_t size = 0;
  std::size_t loop = 0;       // team loops this thread has entered (the same on every thread)
  TeamState* team = nullptr;  // shared by the team's threads, owned by run_team
};
extern thread_local TeamSlot team_slot;

// Fork/join: calls block(context, b, e) on one contiguous block per thread
// (inline when small, with 1 thread, or already inside a parallel region).
void fork_join_blocks(std::size_t begin, std::size_t end,
                      void (*block)(void*, std::size_t, std::size_t), void* context);
void run_team(void (*body)(void*), void* context);
void team_barrier();
// The chunk counter of `rank`'s block for loops of parity `parity`: two
// sets used by alternate loops, so that a loop can clear its successor's.
std::atomic<std::size_t>& chunk_counter(std::size_t parity, std::size_t rank);

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

// A team loop's chunk length in a block of `count` indices: a few chunks per
// block (the granularity a busy thread's work is taken over at), none
// shorter than 64 indices.
inline std::size_t chunk_length(std::size_t count) {
  constexpr std::size_t kChunksPerBlock = 8, kMinChunk = 64;
  return std::max(kMinChunk, (count + kChunksPerBlock - 1) / kChunksPerBlock);
}

// Seconds the team's threads have spent waiting at barriers (and for each
// other's messages: wait_until_reaches), summed over threads and teams since
// the program started (added when a team ends).
double team_wait_seconds();

// Waits until `counter` (another thread's, only ever increased) reaches
// `value`: spins for a few microseconds, then yields the core, as the
// team's barrier does; the wait counts as the team's. Returns the seconds
// waited.
double wait_until_reaches(const std::atomic<std::size_t>& counter, std::size_t value);

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
    const std::size_t rank = team_rank(), size = team_size();
    const std::size_t parity = detail::team_slot.loop++ & 1;
    // The previous loop, the other parity's last user, has passed its barrier.
    detail::chunk_counter(parity ^ 1, rank).store(0, std::memory_order_relaxed);
    {
      detail::SerialScope serial;
      for (std::size_t k = 0; k < size; ++k) {  // this thread's block first
        const std::size_t owner = (rank + k) % size;
        const Range r = static_block(begin, end, owner, size);
        const std::size_t length = chunk_length(r.size());
        std::atomic<std::size_t>& next = detail::chunk_counter(parity, owner);
        for (std::size_t c = next.fetch_add(1, std::memory_order_relaxed); c * length < r.size();
             c = next.fetch_add(1, std::memory_order_relaxed))
          block(r.begin + c * length, std::min(r.end, r.begin + (c + 1) * length));
      }
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
