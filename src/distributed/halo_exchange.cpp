#include "src/distributed/halo_exchange.hpp"

#include <algorithm>
#include <cstring>

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

HaloTally& HaloCost::tally(const char* name) {
  auto t = std::find_if(tallies.begin(), tallies.end(),
                        [&](const HaloTally& x) { return std::strcmp(x.name, name) == 0; });
  if (t == tallies.end()) t = tallies.insert(tallies.end(), HaloTally{name});
  t->calls += 1;
  return *t;
}

void HaloTally::received(std::size_t message_bytes) {
  bytes += static_cast<double>(message_bytes);
  lines += static_cast<double>((message_bytes + 63) / 64);
}

namespace {
// A message is field by field (component by component), each over the
// listed particles in order: unit-stride writes, one strided read stream.
template <class Fields>
void pack(LocalHalo& halo, const Fields& fields, HaloCost& cost) {
  std::size_t width = 0;
  for (const ParticleField& f : fields) width += f.width;
  const std::size_t n = halo.peers.size();
  halo.out.resize(n);
  halo.in.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::vector<std::uint32_t>& send = halo.send[k];
    std::vector<double>& message = halo.out[k];
    message.resize(width * send.size());
    double* out = message.data();
    for (const ParticleField& f : fields)
      for (std::size_t c = 0; c < f.width; ++c) {
        const double* from = f.data + c * f.component_stride;
        for (const std::uint32_t i : send) *out++ = from[i * f.particle_stride];
      }
    halo.in[k].resize(width * halo.receive[k].size());
    cost.bytes_sent += 8.0 * static_cast<double>(message.size());
  }
}

template <class Fields>
void unpack(const LocalHalo& halo, const Fields& fields) {
  for (std::size_t k = 0; k < halo.peers.size(); ++k) {
    const double* in = halo.in[k].data();
    for (const ParticleField& f : fields)
      for (std::size_t c = 0; c < f.width; ++c) {
        double* to = f.data + c * f.component_stride;
        for (const std::uint32_t i : halo.receive[k]) to[i * f.particle_stride] = *in++;
      }
  }
}

void tally_received(const LocalHalo& halo, const char* name, HaloCost& cost) {
  HaloTally& tally = cost.tally(name);
  for (const std::vector<double>& message : halo.in) tally.received(8 * message.size());
}
}  // namespace

void exchange_halo(const RankGroup& world, LocalHalo& halo, const char* name,
                   std::initializer_list<ParticleField> fields, HaloCost& cost) {
  CommunicationTime t(cost);
  pack(halo, fields, cost);
  world.exchange(halo.peers, halo.out, halo.in);
  tally_received(halo, name, cost);
  unpack(halo, fields);
}

void post_halo(const RankGroup& world, LocalHalo& halo, const char* name,
               std::initializer_list<ParticleField> fields, HaloCost& cost) {
  if (!world.posts()) {
    exchange_halo(world, halo, name, fields, cost);
    return;
  }
  CommunicationTime t(cost);
  pack(halo, fields, cost);
  world.post(halo.peers, halo.out);
  tally_received(halo, name, cost);  // the sizes are the plan's
  halo.posted.assign(fields.begin(), fields.end());
}

void finish_halo(const RankGroup& world, LocalHalo& halo, HaloCost& cost) {
  if (halo.posted.empty()) return;
  CommunicationTime t(cost);
  world.collect(halo.peers, halo.in);
  unpack(halo, halo.posted);
  halo.posted.clear();
}

}  // namespace mpsolid
