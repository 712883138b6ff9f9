#pragma once
// The one place that talks to OpenMP. Every physics kernel is a gather: each
// index writes only its own outputs, so any schedule gives the same bits.
#include <cstddef>
#include <type_traits>

namespace mpsolid {

void set_thread_count(int threads);
int thread_count();
int available_cores();

namespace detail {
// Splits [begin, end) into one contiguous block per thread and calls
// block(context, block_begin, block_end) on each.
void parallel_blocks(std::size_t begin, std::size_t end,
                     void (*block)(void*, std::size_t, std::size_t), void* context);
}  // namespace detail

// Runs body(i) for every i in [begin, end) across the threads. The per-index
// loop sits inside the block callback, so body is inlined there.
template <class Body>
void parallel_for(std::size_t begin, std::size_t end, Body&& body) {
  if (begin >= end) return;
  using BodyType = std::remove_reference_t<Body>;
  detail::parallel_blocks(
      begin, end,
      [](void* ctx, std::size_t b, std::size_t e) {
        BodyType& f = *static_cast<BodyType*>(ctx);
        for (std::size_t i = b; i < e; ++i) f(i);
      },
      const_cast<void*>(static_cast<const void*>(&body)));
}

}  // namespace mpsolid
