// An ordered sum computed by ranks holding contiguous parts of its range
// (src/distributed/ordered_sum_parts.hpp): the serial sum's bits for any
// cut, whether or not the cuts fall on the sum's chunks, through messages;
// and with a cut in many pieces per rank (bands), every shared chunk
// finished on the ranks (threads as ranks) to the same bits, only chunk
// sums left to gather.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "src/core/ordered_sum.hpp"
#include "src/distributed/ordered_sum_parts.hpp"
#include "tests/support/thread_team.hpp"

namespace mpsolid {
namespace {

// Terms of very different sizes, so that a changed order changes the bits.
std::array<double, 3> term(std::size_t i) {
  const double x = static_cast<double>(i);
  return {std::sin(x) * std::pow(10.0, static_cast<double>(i % 17) - 8.0), 1.0 / (1.0 + x),
          std::cos(0.37 * x) * 1e6 + 1e-9 * x};
}

bool same_bits(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::memcmp(a.data(), b.data(), sizeof a) == 0;
}

// The parts of ranks holding [cuts[r], cuts[r + 1]), sent as messages and
// read back in rank order.
std::array<double, 3> over_ranks(std::size_t begin, std::size_t end,
                                 const std::vector<std::size_t>& cuts) {
  std::vector<OrderedSumPart<3>> parts;
  for (std::size_t r = 0; r + 1 < cuts.size(); ++r) {
    std::vector<double> message{42.0};  // something before it
    ordered_sum_part<3>(begin, end, {cuts[r], cuts[r + 1]}, term).append_to(message);
    std::size_t at = 1;
    parts.push_back(OrderedSumPart<3>::read(message, at));
    EXPECT_EQ(at, message.size());
  }
  return combine_ordered_sum(parts);
}

TEST(OrderedSumParts, AnyCutGivesTheSerialBits) {
  std::mt19937 random(7);
  for (const auto& [begin, end] : {std::pair<std::size_t, std::size_t>{0, 4096},
                                   {37, 5000},
                                   {511, 513},
                                   {100, 100 + 3 * kSumChunk}}) {
    const std::array<double, 3> serial = ordered_sum<3>(begin, end, term);
    for (int trial = 0; trial < 50; ++trial) {
      const int ranks = 1 + trial % 4;
      // Cuts anywhere around the range, some before or past it (a rank with
      // none of it), some on chunk boundaries.
      std::vector<std::size_t> cuts{0};
      for (int r = 1; r < ranks; ++r) {
        std::uniform_int_distribution<std::size_t> at(0, end + 100);
        std::size_t c = at(random);
        if (trial % 3 == 0) c = begin + (c / kSumChunk) * kSumChunk;
        cuts.push_back(c);
      }
      cuts.push_back(end + 200);
      std::sort(cuts.begin(), cuts.end());
      EXPECT_TRUE(same_bits(over_ranks(begin, end, cuts), serial))
          << "range [" << begin << ", " << end << "), " << ranks << " ranks";
    }
  }
}

TEST(OrderedSumParts, ChunkSumsAddedOutOfOrderWouldDiffer) {
  // The test's terms are sensitive to order: adding the same terms in one
  // run instead of by chunks changes the bits, so the test above can fail.
  const std::array<double, 3> serial = ordered_sum<3>(37, 5000, term);
  std::array<double, 3> plain{};
  for (std::size_t i = 37; i < 5000; ++i)
    for (std::size_t k = 0; k < 3; ++k) plain[k] += term(i)[k];
  EXPECT_FALSE(same_bits(plain, serial));
}

// A cut in pieces of random widths (some narrower than a chunk, some wider)
// dealt to the ranks in turn, as bands deal a body's rows.
Decomposition random_pieces(std::size_t n, int ranks, std::mt19937& random) {
  std::uniform_int_distribution<std::size_t> width(1, 2 * kSumChunk);
  std::vector<std::size_t> starts{0};
  std::vector<int> owners;
  for (int r = 0; starts.back() < n; r = (r + 1) % ranks) {
    owners.push_back(r);
    starts.push_back(std::min(n, starts.back() + width(random)));
  }
  return decomposition_in_pieces(starts, owners, ranks);
}

TEST(OrderedSumParts, SharedChunksFinishedOnTheRanksGiveTheSerialBits) {
  std::mt19937 random(11);
  const std::size_t n = 9000;
  for (const auto& [begin, end] :
       {std::pair<std::size_t, std::size_t>{0, n}, {37, 8000}, {1000, 1001}}) {
    const std::array<double, 3> serial = ordered_sum<3>(begin, end, term);
    for (int trial = 0; trial < 12; ++trial) {
      const int ranks = 2 + trial % 3;
      const Decomposition d = random_pieces(n, ranks, random);
      std::vector<std::vector<double>> messages(static_cast<std::size_t>(ranks));
      testing::as_ranks(ranks, [&](const RankGroup& world, int me) {
        const OrderedSumPart<3> mine = finish_shared_chunks(
            ordered_sum_part<3>(begin, end, d.pieces(me), term), begin, end, d, world);
        for (const auto& piece : mine.pieces) EXPECT_TRUE(piece.whole);
        mine.append_to(messages[static_cast<std::size_t>(me)]);
      });
      std::vector<OrderedSumPart<3>> parts;
      for (const std::vector<double>& m : messages) {
        std::size_t at = 0;
        parts.push_back(OrderedSumPart<3>::read(m, at));
      }
      EXPECT_TRUE(same_bits(combine_ordered_sum(parts), serial))
          << "range [" << begin << ", " << end << "), " << ranks << " ranks, "
          << d.starts.size() - 1 << " pieces";
    }
  }
}

TEST(OrderedSumParts, AShortMessageIsAnError) {
  std::vector<double> message;
  ordered_sum_part<3>(0, 2000, {100, 1500}, term).append_to(message);
  message.pop_back();
  std::size_t at = 0;
  EXPECT_THROW(OrderedSumPart<3>::read(message, at), std::runtime_error);
}

}  // namespace
}  // namespace mpsolid
