#include "src/distributed/decomposition.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace mpsolid {

std::size_t Decomposition::piece_of(std::size_t i) const {
  // The last piece that starts at or before i (empty pieces share a start).
  const auto after = std::upper_bound(starts.begin(), starts.end() - 1, i);
  return static_cast<std::size_t>(after - starts.begin()) - 1;
}

int Decomposition::owner_of(std::size_t i) const {
  const std::size_t piece = piece_of(i);
  return owners.empty() ? static_cast<int>(piece) : owners[piece];
}

std::vector<int> Decomposition::owners_of(Range r) const {
  std::vector<int> out;
  if (r.empty()) return out;
  for (std::size_t k = piece_of(r.begin); k + 1 < starts.size() && starts[k] < r.end; ++k)
    if (starts[k + 1] > starts[k]) out.push_back(owners.empty() ? static_cast<int>(k) : owners[k]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Range Decomposition::owned(int rank) const {
  if (!owners.empty()) throw std::logic_error("Decomposition::owned: a cut in pieces, not slabs");
  return {starts[static_cast<std::size_t>(rank)], starts[static_cast<std::size_t>(rank) + 1]};
}

std::vector<Range> Decomposition::pieces(int rank) const {
  if (owners.empty()) return {owned(rank)};
  std::vector<Range> out;
  for (std::size_t k = 0; k < owners.size(); ++k)
    if (owners[k] == rank) out.push_back({starts[k], starts[k + 1]});
  return out;
}

std::vector<std::vector<Range>> Decomposition::pieces_by_rank() const {
  std::vector<std::vector<Range>> out(static_cast<std::size_t>(ranks()));
  for (std::size_t k = 0; k + 1 < starts.size(); ++k)
    out[static_cast<std::size_t>(owners.empty() ? static_cast<int>(k) : owners[k])].push_back(
        {starts[k], starts[k + 1]});
  return out;
}

Decomposition decomposition_in_pieces(std::vector<std::size_t> starts, std::vector<int> owners,
                                      int ranks) {
  if (starts.size() != owners.size() + 1 || ranks < 1)
    throw std::invalid_argument("decomposition_in_pieces: a start per piece and one more");
  Decomposition d;
  d.rank_count = ranks;
  d.starts.push_back(starts.front());
  for (std::size_t k = 0; k < owners.size(); ++k) {
    if (owners[k] < 0 || owners[k] >= ranks)
      throw std::invalid_argument("decomposition_in_pieces: a piece's rank out of range");
    if (starts[k + 1] < starts[k])
      throw std::invalid_argument("decomposition_in_pieces: pieces out of order");
    if (starts[k + 1] == starts[k]) continue;
    if (!d.owners.empty() && d.owners.back() == owners[k])
      d.starts.back() = starts[k + 1];
    else {
      d.owners.push_back(owners[k]);
      d.starts.push_back(starts[k + 1]);
    }
  }
  // Slabs when each rank owns at most one piece, in rank order.
  bool slabs = true;
  for (std::size_t k = 0; k + 1 < d.owners.size(); ++k)
    slabs = slabs && d.owners[k] < d.owners[k + 1];
  if (!slabs) return d;
  Decomposition s;
  std::size_t at = d.starts.front(), k = 0;
  for (int r = 0; r < ranks; ++r) {
    s.starts.push_back(at);
    if (k < d.owners.size() && d.owners[k] == r) at = d.starts[++k];
  }
  s.starts.push_back(at);
  return s;
}

std::vector<double> particle_work(const BondTable& bonds) {
  std::vector<double> work(bonds.particle_count());
  for (std::size_t i = 0; i < work.size(); ++i)
    work[i] = static_cast<double>(bonds.end(i) - bonds.begin(i) + 1);
  return work;
}

Decomposition decompose(const BondTable& bonds, int ranks, const std::vector<Range>& keep_whole) {
  return decompose_costs(particle_work(bonds), ranks, keep_whole);
}

namespace {
// The cut of n particles whose work before particle i is work(i) (work(0)
// = 0, non-decreasing): each boundary nearest r / ranks of the work, never
// before the last one, and moved down to the start of a range kept whole.
template <class WorkBefore>
Decomposition cut_work(std::size_t n, int ranks, const std::vector<Range>& keep_whole,
                       WorkBefore&& work) {
  if (ranks < 1) throw std::invalid_argument("decompose: at least one rank");
  Decomposition d;
  d.starts.assign(static_cast<std::size_t>(ranks) + 1, n);
  d.starts[0] = 0;
  std::size_t c = 0;
  const double total = work(n);
  for (int r = 1; r < ranks; ++r) {
    const double target = total * r / ranks;
    while (c < n && work(c + 1) <= target) ++c;
    if (c < n && target - work(c) > work(c + 1) - target) ++c;
    std::size_t cut = c;
    for (const Range& whole : keep_whole)
      if (cut > whole.begin && cut < whole.end) cut = whole.begin;
    d.starts[static_cast<std::size_t>(r)] =
        std::max(d.starts[static_cast<std::size_t>(r) - 1], cut);
  }
  return d;
}
}  // namespace

Decomposition decompose_costs(const std::vector<double>& cost, int ranks,
                              const std::vector<Range>& keep_whole) {
  const std::size_t n = cost.size();
  // Work before each particle.
  std::vector<double> work(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) work[i + 1] = work[i] + cost[i];
  return cut_work(n, ranks, keep_whole, [&](std::size_t i) { return work[i]; });
}

Decomposition decompose_count(std::size_t particles, int ranks,
                              const std::vector<Range>& keep_whole) {
  return cut_work(particles, ranks, keep_whole,
                  [](std::size_t i) { return static_cast<double>(i); });
}

HaloPlan plan_halo(const BondTable& bonds, const Decomposition& d, int rank) {
  HaloPlan plan;
  std::map<int, std::vector<std::uint32_t>> receive, send;
  std::vector<std::uint32_t> ghosts;
  for (const Range mine : d.pieces(rank))
    for (std::size_t i = mine.begin; i < mine.end; ++i)
      for (std::uint32_t k = bonds.begin(i); k < bonds.end(i); ++k) {
        const std::uint32_t j = bonds.neighbor[k];
        if ((j >= mine.begin && j < mine.end) || d.owner_of(j) == rank) continue;
        ghosts.push_back(j);
        // The bond table is symmetric: j's owner needs i as a ghost too.
        send[d.owner_of(j)].push_back(static_cast<std::uint32_t>(i));
      }
  const auto unique_sorted = [](std::vector<std::uint32_t>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  unique_sorted(ghosts);
  for (const std::uint32_t g : ghosts) receive[d.owner_of(g)].push_back(g);
  plan.ghosts = std::move(ghosts);
  for (auto& [peer, list] : receive) {
    plan.peers.push_back(peer);
    plan.receive.push_back(std::move(list));
    std::vector<std::uint32_t>& out = send[peer];
    unique_sorted(out);
    plan.send.push_back(std::move(out));
  }
  return plan;
}

}  // namespace mpsolid
