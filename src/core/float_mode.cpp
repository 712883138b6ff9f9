#include "src/core/float_mode.hpp"

#include <atomic>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace mpsolid {
namespace {

std::atomic<bool> flush_enabled{false};

#if defined(__SSE2__)
// MXCSR bits: flush results to zero (FTZ, bit 15), read inputs as zero (DAZ, bit 6).
constexpr unsigned kFlushBits = 0x8040;
unsigned long read_mode() {
  return _mm_getcsr();
}
void write_mode(unsigned long mode) {
  _mm_setcsr(static_cast<unsigned>(mode));
}
unsigned long flushing(unsigned long mode, bool flush) {
  return flush ? (mode | kFlushBits) : (mode & ~static_cast<unsigned long>(kFlushBits));
}
#elif defined(__aarch64__)
// FPCR bit 24 (FZ) flushes subnormal inputs and results to zero.
constexpr unsigned long kFlushBits = 1UL << 24;
unsigned long read_mode() {
  unsigned long mode;
  __asm__ volatile("mrs %0, fpcr" : "=r"(mode));
  return mode;
}
void write_mode(unsigned long mode) {
  __asm__ volatile("msr fpcr, %0" : : "r"(mode));
}
unsigned long flushing(unsigned long mode, bool flush) {
  return flush ? (mode | kFlushBits) : (mode & ~kFlushBits);
}
#else
// Elsewhere the solver keeps the platform's default (IEEE subnormals).
unsigned long read_mode() {
  return 0;
}
void write_mode(unsigned long) {}
unsigned long flushing(unsigned long mode, bool) {
  return mode;
}
#endif

}  // namespace

void set_flush_subnormals(bool flush) {
  flush_enabled.store(flush, std::memory_order_relaxed);
}
bool flush_subnormals() {
  return flush_enabled.load(std::memory_order_relaxed);
}

SubnormalModeScope::SubnormalModeScope() : saved_(read_mode()) {
  const unsigned long wanted = flushing(saved_, flush_subnormals());
  if (wanted != saved_) write_mode(wanted);
}
SubnormalModeScope::~SubnormalModeScope() {
  if (read_mode() != saved_) write_mode(saved_);
}

}  // namespace mpsolid
