#include "src/solver/distributed_step.hpp"

namespace mpsolid {

LocalHalo local_halo(const HaloPlan& plan, const LocalLayout& layout) {
  LocalHalo halo;
  halo.peers = plan.peers;
  const auto to_local = [&](const std::vector<std::uint32_t>& global) {
    std::vector<std::uint32_t> local;
    for (const std::uint32_t g : global)
      local.push_back(static_cast<std::uint32_t>(layout.local_of(g)));
    return local;
  };
  for (const auto& list : plan.send) halo.send.push_back(to_local(list));
  for (const auto& list : plan.receive) halo.receive.push_back(to_local(list));
  return halo;
}

void exchange_halo(const Communicator& world, const LocalHalo& halo, ParticleStore& p,
                   std::initializer_list<std::vector<double> ParticleStore::*> arrays) {
  const std::size_t width = arrays.size();
  std::vector<std::vector<double>> out(halo.peers.size());
  for (std::size_t k = 0; k < halo.peers.size(); ++k) {
    out[k].reserve(width * halo.send[k].size());
    for (const std::uint32_t i : halo.send[k])
      for (const auto array : arrays) out[k].push_back((p.*array)[i]);
  }
  const std::vector<std::vector<double>> in = world.exchange(halo.peers, out);
  for (std::size_t k = 0; k < halo.peers.size(); ++k) {
    std::size_t at = 0;
    for (const std::uint32_t i : halo.receive[k])
      for (const auto array : arrays) (p.*array)[i] = in[k][at++];
  }
}

}  // namespace mpsolid
