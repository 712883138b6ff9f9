#include "src/distributed/thread_ranks.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <new>
#include <stdexcept>

#include "src/core/parallel.hpp"

namespace mpsolid {

namespace {
constexpr std::size_t kLine = 64;

// Letters start on a cache line of their own, so a letter of b bytes is
// ceil(b / 64) lines crossing (what the halos' tallies count), and no line
// of it is shared with anything its writer touches between calls.
template <class T>
struct LineAligned {
  using value_type = T;
  LineAligned() = default;
  template <class U>
  LineAligned(const LineAligned<U>&) {}
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{kLine}));
  }
  void deallocate(T* p, std::size_t) { ::operator delete (p, std::align_val_t{kLine}); }
  friend bool operator==(const LineAligned&, const LineAligned&) { return true; }
};
using Letter = std::vector<double, LineAligned<double>>;

// Copies `values` into `letter`, resizing only when the length changes (so
// a letter's header, which the readers also read, stays clean from call to
// call).
template <class Values>
void write_letter(Letter& letter, const Values& values) {
  if (letter.size() != values.size()) letter.resize(values.size());
  std::copy(values.begin(), values.end(), letter.begin());
}
}  // namespace

struct ThreadMailboxes::Mailbox {
  struct Letters {
    std::vector<Letter> to;  // per destination rank
    Letter gathered;
    std::int64_t value = 0;
  };
  alignas(kLine) std::atomic<std::size_t> calls{0};  // the owner's calls published
  alignas(kLine) std::array<Letters, 2> letters;     // by the call's parity
};

ThreadMailboxes::ThreadMailboxes(int threads)
    : size_(threads), boxes_(std::make_unique<Mailbox[]>(static_cast<std::size_t>(threads))) {
  if (threads < 1) throw std::invalid_argument("ThreadMailboxes: at least one thread");
}
ThreadMailboxes::~ThreadMailboxes() = default;

ThreadMailboxes::Mailbox& ThreadRanks::mine() const {
  return boxes_.boxes_[static_cast<std::size_t>(rank_)];
}

void ThreadRanks::publish() const {
  mine().calls.store(calls_, std::memory_order_release);
}

std::size_t ThreadRanks::wait_for_all() const {
  for (int r = 0; r < size(); ++r)
    if (r != rank_)
      waited_ += wait_until_reaches(boxes_.boxes_[static_cast<std::size_t>(r)].calls, calls_);
  return calls_ & 1;
}

std::size_t ThreadRanks::publish_and_wait() const {
  publish();
  return wait_for_all();
}

std::vector<double> ThreadRanks::all_gather(const std::vector<double>& mine_values) const {
  const std::size_t parity = ++calls_ & 1;
  write_letter(mine().letters[parity].gathered, mine_values);
  publish_and_wait();
  std::vector<double> all;
  for (int r = 0; r < size(); ++r) {
    const Letter& l = boxes_.boxes_[static_cast<std::size_t>(r)].letters[parity].gathered;
    all.insert(all.end(), l.begin(), l.end());
  }
  return all;
}

void ThreadRanks::exchange(const std::vector<int>& peers,
                           const std::vector<std::vector<double>>& out,
                           std::vector<std::vector<double>>& in) const {
  post(peers, out);
  collect(peers, in);
}

void ThreadRanks::post(const std::vector<int>& peers,
                       const std::vector<std::vector<double>>& out) const {
  if (peers.size() != out.size())
    throw std::invalid_argument("exchange: one message each way per peer");
  const std::size_t parity = ++calls_ & 1;
  std::vector<Letter>& to = mine().letters[parity].to;
  if (to.size() != static_cast<std::size_t>(size())) to.resize(static_cast<std::size_t>(size()));
  for (std::size_t k = 0; k < peers.size(); ++k)
    write_letter(to[static_cast<std::size_t>(peers[k])], out[k]);
  publish();
}

void ThreadRanks::collect(const std::vector<int>& peers,
                          std::vector<std::vector<double>>& in) const {
  if (peers.size() != in.size())
    throw std::invalid_argument("exchange: one message each way per peer");
  const std::size_t parity = wait_for_all();
  for (std::size_t k = 0; k < peers.size(); ++k) {
    const Letter& letter = boxes_.boxes_[static_cast<std::size_t>(peers[k])].letters[parity].to.at(
        static_cast<std::size_t>(rank_));
    if (letter.size() != in[k].size())
      throw std::logic_error("exchange: a thread's message is not the planned size");
    std::copy(letter.begin(), letter.end(), in[k].begin());
  }
}

std::int64_t ThreadRanks::max(std::int64_t mine_value) const {
  const std::size_t parity = ++calls_ & 1;
  mine().letters[parity].value = mine_value;
  publish_and_wait();
  std::int64_t most = mine_value;
  for (int r = 0; r < size(); ++r)
    most = std::max(most, boxes_.boxes_[static_cast<std::size_t>(r)].letters[parity].value);
  return most;
}

}  // namespace mpsolid
