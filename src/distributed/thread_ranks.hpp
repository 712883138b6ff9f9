#pragma once
// The threads of one team as the ranks of a decomposed step
// (docs/performance.md): each thread steps its own part of the state in its
// own memory, and its halos and reductions go through mailboxes in shared
// memory, one per thread. A thread writes only its own mailbox and reads the
// others' after they publish, so what crosses between threads in a step is
// the halos' values and one counter line per thread per call; nothing on
// the hot path is written by two threads.
//
// Every call is a rendezvous of the whole team: each thread publishes its
// letters and its call count, then waits for every other thread's count.
// Letters alternate between two sets by the call's parity: a thread
// rewrites the set of call n at call n + 2, after seeing every other thread
// reach call n + 1, which each did after reading call n's letters. So one
// counter per thread is the only synchronisation, and no call waits twice.
#include <cstdint>
#include <memory>
#include <vector>

#include "src/distributed/rank_group.hpp"

namespace mpsolid {

// The team's mailboxes, shared by its threads (each writes only its own).
class ThreadMailboxes {
 public:
  explicit ThreadMailboxes(int threads);
  ~ThreadMailboxes();
  ThreadMailboxes(const ThreadMailboxes&) = delete;
  ThreadMailboxes& operator=(const ThreadMailboxes&) = delete;
  int size() const { return size_; }

  struct Mailbox;  // thread_ranks.cpp

 private:
  friend class ThreadRanks;
  int size_;
  std::unique_ptr<Mailbox[]> boxes_;
};

// One thread's view of the team as ranks: thread `rank` of `boxes`. Every
// thread of the team makes the same calls in the same order, as MPI ranks do.
class ThreadRanks final : public RankGroup {
 public:
  ThreadRanks(ThreadMailboxes& boxes, int rank) : boxes_(boxes), rank_(rank) {}

  int rank() const override { return rank_; }
  int size() const override { return boxes_.size(); }
  std::vector<double> all_gather(const std::vector<double>& mine) const override;
  void exchange(const std::vector<int>& peers, const std::vector<std::vector<double>>& out,
                std::vector<std::vector<double>>& in) const override;
  std::int64_t max(std::int64_t mine) const override;
  bool posts() const override { return true; }
  void post(const std::vector<int>& peers,
            const std::vector<std::vector<double>>& out) const override;
  void collect(const std::vector<int>& peers, std::vector<std::vector<double>>& in) const override;
  // Seconds this thread has waited for the others' letters, all calls.
  double waited_seconds() const { return waited_; }

 private:
  // This thread's letters for the next call (the call's parity's set).
  ThreadMailboxes::Mailbox& mine() const;
  // Publishes this thread's letters of the call, then waits for every
  // other thread's; returns the call's parity.
  std::size_t publish_and_wait() const;
  void publish() const;
  std::size_t wait_for_all() const;

  ThreadMailboxes& boxes_;
  int rank_;
  mutable std::size_t calls_ = 0;
  mutable double waited_ = 0;
};

}  // namespace mpsolid
