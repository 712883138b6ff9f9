#include "src/app/thread_choice.hpp"

#include <fmt/format.h>

#include <cstdlib>

#include "src/core/types.hpp"

namespace mpsolid {

ThreadChoice choose_threads(int requested, int cores) {
  ThreadChoice c;
  if (requested > 0) {
    c.threads = requested;
    c.source = "--threads";
  } else if (const char* env = std::getenv("OMP_NUM_THREADS"); env && *env) {
    // OpenMP allows a list ("4,2") for nested levels; the first is ours.
    const std::string text(env);
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || value < 1 || (used < text.size() && text[used] != ','))
      throw InputError(fmt::format(
          "OMP_NUM_THREADS = '{}': expected a whole number >= 1 (or unset it to use all {} "
          "cores)",
          text, cores));
    c.threads = value;
    c.source = "OMP_NUM_THREADS";
  } else {
    c.threads = cores;
    c.source = "all cores";
  }
  if (c.threads > cores)
    c.warning = fmt::format(
        "{} threads ({}) on {} cores: the threads take turns on the cores and every step waits "
        "for the slowest, so the run is slower than with {} (the result is the same bits)",
        c.threads, c.source, cores, cores);
  return c;
}

}  // namespace mpsolid
