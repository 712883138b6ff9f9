#include "src/distributed/part_message.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace mpsolid {

namespace {
// Message values are doubles; enumerations travel as their integers.
template <class T>
double as_double(T v) {
  return static_cast<double>(static_cast<NumberOf_t<T>>(v));
}
template <class T>
T from_double(double v) {
  return static_cast<T>(static_cast<NumberOf_t<T>>(v));
}

// Values into pieces of at most kPartPieceValues, each sent when full.
class Writer {
 public:
  explicit Writer(const std::function<void(const std::vector<double>&)>& send) : send_(send) {
    out_.reserve(kPartPieceValues);
  }
  void put(double v) {
    out_.push_back(v);
    if (out_.size() == kPartPieceValues) {
      send_(out_);
      out_.clear();
    }
  }
  template <class T>
  void put(const std::vector<T>& v) {
    put(static_cast<double>(v.size()));
    for (const T& x : v) put(as_double(x));
  }
  void put(const std::string& s) { put(std::vector<char>(s.begin(), s.end())); }
  void put(Range r) {
    put(static_cast<double>(r.begin));
    put(static_cast<double>(r.end));
  }
  // Sends the last piece (perhaps empty: the reader then knows the end).
  void finish() { send_(out_); }

 private:
  const std::function<void(const std::vector<double>&)>& send_;
  std::vector<double> out_;
};

// Values from the pieces, the next received when one is used up: full
// pieces, then a short one (perhaps empty) that ends the message.
class Reader {
 public:
  explicit Reader(const std::function<std::vector<double>()>& receive) : receive_(receive) {}
  double get() {
    while (at_ == in_.size()) next();
    return in_[at_++];
  }
  template <class T>
  T get_as() {
    return static_cast<T>(get());
  }
  template <class T>
  std::vector<T> get_vector() {
    std::vector<T> v(get_as<std::size_t>());
    for (T& x : v) x = from_double<T>(get());
    return v;
  }
  std::string get_string() {
    const std::vector<char> chars = get_vector<char>();
    return {chars.begin(), chars.end()};
  }
  Range get_range() {
    const auto begin = get_as<std::size_t>();
    return {begin, get_as<std::size_t>()};
  }
  // Every value read, and nothing left.
  bool done() {
    if (at_ != in_.size()) return false;
    if (!last_) next();  // a full piece is followed by one more
    return at_ == in_.size();
  }

 private:
  void next() {
    if (last_) throw std::logic_error("a rank's part: the message ended early");
    in_ = receive_();
    at_ = 0;
    last_ = in_.size() < kPartPieceValues;
  }
  const std::function<std::vector<double>()>& receive_;
  std::vector<double> in_;
  std::size_t at_ = 0;
  bool last_ = false;
};

void put_particles(Writer& w, const ParticleStore& p) {
  w.put(static_cast<double>(p.dimension));
  for_each_particle_array(p, [&](const auto&, const auto& v) { w.put(v); });
}
ParticleStore get_particles(Reader& r) {
  ParticleStore p;
  p.dimension = static_cast<int>(r.get());
  for_each_particle_array(p, [&](const auto&, auto& v) {
    v = r.get_vector<typename std::decay_t<decltype(v)>::value_type>();
  });
  p.set_kind_ranges();
  return p;
}

void put_history(Writer& w, const LoadHistory& h) {
  for (const double v : {static_cast<double>(h.kind), h.rise_time, h.duration, h.decay}) w.put(v);
  w.put(h.times);
  w.put(h.factors);
}
LoadHistory get_history(Reader& r) {
  LoadHistory h;
  h.kind = static_cast<LoadHistory::Kind>(r.get_as<int>());
  for (double* v : {&h.rise_time, &h.duration, &h.decay}) *v = r.get();
  h.times = r.get_vector<double>();
  h.factors = r.get_vector<double>();
  return h;
}

// A rigid body's make-up and motion in message order (its pose goes as
// pose_values).
template <class Body>
auto body_constants(Body& b) {
  using Field = std::conditional_t<std::is_const_v<Body>, const double*, double*>;
  auto& m = b.motion;
  return std::vector<Field>{&b.xg0,
                            &b.yg0,
                            &b.zg0,
                            &b.orbital_inertia,
                            &b.orbital_moments[0],
                            &b.orbital_moments[1],
                            &b.orbital_moments[2],
                            &b.axes[0],
                            &b.axes[1],
                            &b.axes[2],
                            &b.axes[3],
                            &b.spin_inertia,
                            &b.mass_total,
                            &b.work,
                            &m.velocity[0],
                            &m.velocity[1],
                            &m.velocity[2],
                            &m.spin[0],
                            &m.spin[1],
                            &m.spin[2],
                            &m.start};
}

void put_body(Writer& w, const RigidBody& b) {
  w.put(b.name);
  w.put(b.range);
  w.put(static_cast<double>(b.dimension));
  w.put(pose_values(b));
  for (const double* v : body_constants(b)) w.put(*v);
  for (const std::vector<double>* v : {&b.dx0, &b.dy0, &b.dz0}) w.put(*v);
  w.put(b.motion.on ? 1.0 : 0.0);
  put_history(w, b.motion.history);
}
RigidBody get_body(Reader& r) {
  RigidBody b;
  b.name = r.get_string();
  b.range = r.get_range();
  b.dimension = r.get_as<int>();
  set_pose_values(b, r.get_vector<double>().data());
  for (double* v : body_constants(b)) *v = r.get();
  for (std::vector<double>* v : {&b.dx0, &b.dy0, &b.dz0}) *v = r.get_vector<double>();
  b.motion.on = r.get() != 0.0;
  b.motion.history = get_history(r);
  return b;
}

void put_load(Writer& w, const StepLoad& l) {
  w.put(l.name);
  w.put(l.range);
  for (const double v :
       {l.fx, l.fy, l.fz, l.start, static_cast<double>(l.first_step), l.active ? 1.0 : 0.0, l.cx_on,
        l.cy_on, l.cz_on, l.factor, l.cx_last, l.cy_last, l.cz_last, l.work})
    w.put(v);
  put_history(w, l.history);
  const PressureSurface& s = l.surface;
  for (const double v : {s.pressure, s.depth}) w.put(v);
  for (const auto* v :
       {&s.offsets, &s.particle, &s.hosted, &s.from, &s.to, &s.quad, &s.targets, &s.slot})
    w.put(*v);
  w.put(s.weight);
  for (const std::vector<double>* v : s.running_fields()) w.put(*v);
}
StepLoad get_load(Reader& r) {
  StepLoad l;
  l.name = r.get_string();
  l.range = r.get_range();
  l.fx = r.get();
  l.fy = r.get();
  l.fz = r.get();
  l.start = r.get();
  l.first_step = r.get_as<std::int64_t>();
  l.active = r.get() != 0.0;
  for (double* v :
       {&l.cx_on, &l.cy_on, &l.cz_on, &l.factor, &l.cx_last, &l.cy_last, &l.cz_last, &l.work})
    *v = r.get();
  l.history = get_history(r);
  PressureSurface& s = l.surface;
  for (double* v : {&s.pressure, &s.depth}) *v = r.get();
  for (auto* v : {&s.offsets, &s.particle, &s.hosted, &s.from, &s.to, &s.quad, &s.targets, &s.slot})
    *v = r.get_vector<std::uint32_t>();
  s.weight = r.get_vector<double>();
  for (std::vector<double>* v : s.running_fields()) *v = r.get_vector<double>();
  s.size_forces();
  if (l.is_pressure() && l.active) pressure_forces(l);
  return l;
}

template <class Item, class Put>
void put_items(Writer& w, const std::vector<Item>& items, Put put) {
  w.put(static_cast<double>(items.size()));
  for (const Item& item : items) put(w, item);
}
template <class Item, class Get>
std::vector<Item> get_items(Reader& r, Get get) {
  std::vector<Item> items(r.get_as<std::size_t>());
  for (Item& item : items) item = get(r);
  return items;
}
}  // namespace

LocalPart local_part(const SolverState& global, const Decomposition& d, int rank) {
  LocalPart part;
  part.decomposition = d;
  const HaloPlan plan = plan_halo(global.bonds, d, rank);
  part.layout = local_layout(d, plan, rank, global.contact.candidates);
  part.halo = local_halo(plan, part.layout);
  part.state = local_solver_state(global, part.layout);
  part.moving_begin = global.particles.moving().begin;
  part.body_ranges = global.body_ranges;
  part.probes = global.probes;
  return part;
}

void pack_local_part(const LocalPart& part,
                     const std::function<void(const std::vector<double>&)>& send) {
  Writer w(send);
  w.put(part.decomposition.starts);
  w.put(part.decomposition.owners);
  w.put(static_cast<double>(part.decomposition.rank_count));
  w.put(part.layout.global_of);
  w.put(part.layout.owned);
  put_items(w, part.layout.owned_pieces, [](Writer& o, Range range) { o.put(range); });
  w.put(static_cast<double>(part.moving_begin));
  put_items(w, part.body_ranges, [](Writer& o, Range range) { o.put(range); });
  w.put(part.probes);
  w.put(part.halo.peers);
  put_items(w, part.halo.send, [](Writer& o, const auto& list) { o.put(list); });
  put_items(w, part.halo.receive, [](Writer& o, const auto& list) { o.put(list); });
  const SolverState& s = part.state;
  put_particles(w, s.particles);
  w.put(s.bonds.offsets);
  w.put(s.bonds.neighbor);
  for (const double v : {s.bonds.geometry.l0, s.bonds.geometry.re, s.bonds.geometry.volume})
    w.put(v);
  put_items(w, s.rigid_bodies, put_body);
  put_items(w, s.loads, put_load);
  put_items(w, s.holds, [](Writer& o, const HeldRange& h) {
    o.put(h.range);
    o.put(h.x ? 1.0 : 0.0);
    o.put(h.y ? 1.0 : 0.0);
    o.put(h.z ? 1.0 : 0.0);
  });
  const ContactState& c = s.contact;
  for (const double v : {c.parameters.distance, c.parameters.stiffness, c.parameters.skin,
                         c.parameters.min_distance, static_cast<double>(c.first_moving)})
    w.put(v);
  w.put(c.candidates);
  w.put(c.group);
  w.put(static_cast<double>(s.step));
  w.put(s.peak_work);
  for (const double v : {s.damping.coefficient, static_cast<double>(s.damping.first_step),
                         static_cast<double>(s.damping.end_step)})
    w.put(v);
  w.finish();
}

LocalPart unpack_local_part(const std::function<std::vector<double>()>& receive) {
  Reader r(receive);
  LocalPart part;
  part.decomposition.starts = r.get_vector<std::size_t>();
  part.decomposition.owners = r.get_vector<int>();
  part.decomposition.rank_count = r.get_as<int>();
  part.layout.global_of = r.get_vector<std::uint32_t>();
  part.layout.owned = r.get_range();
  part.layout.set_owned_pieces(get_items<Range>(r, [](Reader& in) { return in.get_range(); }));
  part.moving_begin = r.get_as<std::size_t>();
  part.body_ranges = get_items<Range>(r, [](Reader& in) { return in.get_range(); });
  part.probes = r.get_vector<std::size_t>();
  part.halo.peers = r.get_vector<int>();
  const auto list = [](Reader& in) { return in.get_vector<std::uint32_t>(); };
  part.halo.send = get_items<std::vector<std::uint32_t>>(r, list);
  part.halo.receive = get_items<std::vector<std::uint32_t>>(r, list);
  SolverState& s = part.state;
  s.particles = get_particles(r);
  auto offsets = r.get_vector<std::uint32_t>();
  auto neighbor = r.get_vector<std::uint32_t>();
  BondGeometry geometry;
  geometry.l0 = r.get();
  geometry.re = r.get();
  geometry.volume = r.get();
  geometry.dimension = s.particles.dimension;
  s.bonds = make_bond_table(s.particles, std::move(offsets), std::move(neighbor), geometry);
  s.rigid_bodies = get_items<RigidBody>(r, get_body);
  s.loads = get_items<StepLoad>(r, get_load);
  s.holds = get_items<HeldRange>(r, [](Reader& in) {
    HeldRange h;
    h.range = in.get_range();
    h.x = in.get() != 0.0;
    h.y = in.get() != 0.0;
    h.z = in.get() != 0.0;
    return h;
  });
  ContactState& c = s.contact;
  c.parameters.distance = r.get();
  c.parameters.stiffness = r.get();
  c.parameters.skin = r.get();
  c.parameters.min_distance = r.get();
  c.first_moving = r.get_as<std::size_t>();
  c.candidates = r.get_vector<std::uint32_t>();
  c.group = r.get_vector<std::int32_t>();
  c.zero_forces(s.particles.dimension);
  s.step = r.get_as<std::int64_t>();
  s.peak_work = r.get();
  s.damping.coefficient = r.get();
  s.damping.first_step = r.get_as<std::int64_t>();
  s.damping.end_step = r.get_as<std::int64_t>();
  if (!r.done()) throw std::logic_error("a rank's part: the message is longer than its part");
  return part;
}

void append_owned_items(const SolverState& local, const LocalLayout& layout,
                        std::vector<double>& out) {
  // The pieces, each after its length (the last one short, perhaps empty).
  const std::function<void(const std::vector<double>&)> send = [&](const std::vector<double>& p) {
    out.push_back(static_cast<double>(p.size()));
    out.insert(out.end(), p.begin(), p.end());
  };
  Writer w(send);
  put_items(w, local.rigid_bodies, [&](Writer& to, RigidBody b) {
    b.range = layout.global_of_owned(b.range);
    put_body(to, b);
  });
  std::vector<StepLoad> forces;
  for (const StepLoad& l : local.loads)
    if (!l.is_pressure()) forces.push_back(l);
  put_items(w, forces, [&](Writer& to, StepLoad l) {
    l.range = layout.global_of_owned(l.range);
    put_load(to, l);
  });
  w.finish();
}

void read_owned_items(const std::vector<double>& in, std::size_t& at, SolverState& head) {
  const std::function<std::vector<double>()> receive = [&] {
    const auto n = static_cast<std::size_t>(in.at(at));
    if (at + 1 + n > in.size()) throw std::runtime_error("a rank's bodies and loads cut short");
    std::vector<double> piece(in.begin() + static_cast<long>(at + 1),
                              in.begin() + static_cast<long>(at + 1 + n));
    at += 1 + n;
    return piece;
  };
  Reader r(receive);
  for (RigidBody& b : get_items<RigidBody>(r, get_body)) head.rigid_bodies.push_back(std::move(b));
  for (StepLoad& l : get_items<StepLoad>(r, get_load)) head.loads.push_back(std::move(l));
  if (!r.done()) throw std::runtime_error("a rank's bodies and loads: values left over");
}

void merge_rigid_bodies(SolverState& head, const std::vector<std::string>& body_names) {
  std::vector<RigidBody> bodies;
  for (RigidBody& b : head.rigid_bodies) {
    for (std::size_t k = 0; k < body_names.size() && k < head.body_ranges.size(); ++k)
      if (body_names[k] == b.name) b.range = head.body_ranges[k];
    b.dx0.clear();
    b.dy0.clear();
    b.dz0.clear();
    if (std::none_of(bodies.begin(), bodies.end(),
                     [&](const RigidBody& kept) { return kept.name == b.name; }))
      bodies.push_back(std::move(b));
  }
  std::sort(bodies.begin(), bodies.end(),
            [](const RigidBody& a, const RigidBody& b) { return a.range.begin < b.range.begin; });
  head.rigid_bodies = std::move(bodies);
}

}  // namespace mpsolid
