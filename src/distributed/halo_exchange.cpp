#include "src/distributed/halo_exchange.hpp"

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

void exchange_halo(const Communicator& world, LocalHalo& halo,
                   std::initializer_list<ParticleField> fields, HaloCost& cost) {
  CommunicationTime t(cost);
  std::size_t width = 0;
  for (const ParticleField& f : fields) width += f.width;
  const std::size_t n = halo.peers.size();
  halo.out.resize(n);
  halo.in.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<double>& message = halo.out[k];
    message.clear();
    for (const std::uint32_t i : halo.send[k])
      for (const ParticleField& f : fields)
        for (std::size_t c = 0; c < f.width; ++c) message.push_back(f.at(i, c));
    halo.in[k].resize(width * halo.receive[k].size());
    cost.bytes_sent += 8.0 * static_cast<double>(message.size());
  }
  world.exchange(halo.peers, halo.out, halo.in);
  for (std::size_t k = 0; k < n; ++k) {
    const double* in = halo.in[k].data();
    for (const std::uint32_t i : halo.receive[k])
      for (const ParticleField& f : fields)
        for (std::size_t c = 0; c < f.width; ++c) f.at(i, c) = *in++;
  }
}

}  // namespace mpsolid
