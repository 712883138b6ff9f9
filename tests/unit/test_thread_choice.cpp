// The thread count of a run: --threads, else OMP_NUM_THREADS, else every
// core; a bad OMP_NUM_THREADS is bad input; more threads than cores warn.
#include <gtest/gtest.h>

#include <cstdlib>

#include "src/app/thread_choice.hpp"
#include "src/core/types.hpp"

namespace mpsolid {
namespace {

class Environment {
 public:
  explicit Environment(const char* value) {
    if (const char* old = std::getenv("OMP_NUM_THREADS")) saved_ = old;
    if (value)
      ::setenv("OMP_NUM_THREADS", value, 1);
    else
      ::unsetenv("OMP_NUM_THREADS");
  }
  ~Environment() {
    if (saved_.empty())
      ::unsetenv("OMP_NUM_THREADS");
    else
      ::setenv("OMP_NUM_THREADS", saved_.c_str(), 1);
  }

 private:
  std::string saved_;
};

TEST(ThreadChoice, FlagThenEnvironmentThenCores) {
  {
    Environment env("3");
    EXPECT_EQ(choose_threads(2, 8).threads, 2);
    EXPECT_EQ(choose_threads(2, 8).source, "--threads");
    EXPECT_EQ(choose_threads(0, 8).threads, 3);
    EXPECT_EQ(choose_threads(0, 8).source, "OMP_NUM_THREADS");
  }
  {
    Environment env("4,2");  // nested levels: the first is ours
    EXPECT_EQ(choose_threads(0, 8).threads, 4);
  }
  {
    Environment env(nullptr);
    EXPECT_EQ(choose_threads(0, 8).threads, 8);
    EXPECT_EQ(choose_threads(0, 8).source, "all cores");
  }
}

TEST(ThreadChoice, BadEnvironmentIsBadInput) {
  for (const char* bad : {"abc", "0", "-2", "3x", "2.5"}) {
    Environment env(bad);
    EXPECT_THROW(choose_threads(0, 4), InputError) << bad;
    EXPECT_NO_THROW(choose_threads(1, 4)) << "--threads wins over " << bad;
  }
}

TEST(ThreadChoice, MoreThreadsThanCoresWarn) {
  Environment env(nullptr);
  EXPECT_TRUE(choose_threads(2, 2).warning.empty());
  const ThreadChoice many = choose_threads(5, 2);
  EXPECT_EQ(many.threads, 5);
  EXPECT_NE(many.warning.find("5 threads"), std::string::npos) << many.warning;
  EXPECT_NE(many.warning.find("2 cores"), std::string::npos) << many.warning;
}

}  // namespace
}  // namespace mpsolid
