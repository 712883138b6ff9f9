#include "src/distributed/state_slice.hpp"

#include <algorithm>

namespace mpsolid {

namespace {
// The evolving fields of a rigid body and of a load, as doubles: what moves
// between ranks besides the particles.
std::size_t fields_of(const RigidBody* b) {
  return pose_size(b->dimension) + 1;
}
void read_fields(const RigidBody& b, double* out) {
  const std::vector<double> pose = pose_values(b);
  *std::copy(pose.begin(), pose.end(), out) = b.work;
}
void write_fields(RigidBody& b, const double* in) {
  set_pose_values(b, in);
  b.work = in[pose_size(b.dimension)];
}
// A pressure's running step: its nodes' positions at the step's start (its
// forces follow from them, or from its given node forces).
std::size_t fields_of(const StepLoad* l) {
  return 9 + l->surface.running_size();
}
void read_fields(const StepLoad& l, double* out) {
  out[0] = l.active ? 1.0 : 0.0;
  for (const double x :
       {l.cx_on, l.cy_on, l.cz_on, l.factor, l.cx_last, l.cy_last, l.cz_last, l.work})
    *++out = x;
  ++out;
  for (const std::vector<double>* v : l.surface.running_fields())
    out = std::copy(v->begin(), v->end(), out);
}
void write_fields(StepLoad& l, const double* in) {
  l.active = in[0] != 0.0;
  for (double* x :
       {&l.cx_on, &l.cy_on, &l.cz_on, &l.factor, &l.cx_last, &l.cy_last, &l.cz_last, &l.work})
    *x = *++in;
  ++in;
  for (std::vector<double>* v : l.surface.running_fields()) {
    std::copy_n(in, v->size(), v->begin());
    in += v->size();
  }
  if (l.is_pressure() && l.active) pressure_forces(l);
}

// Whether a slice of `owned` carries the item: a force when one of its
// ranges holds it whole (it is kept whole); a rigid body when they hold any
// of it (every rank holding some of a split body has its whole pose); a
// pressure when the slice carries the shared items (every part holds it,
// with the same running step).
bool holds(Range item, const std::vector<Range>& owned) {
  return std::any_of(owned.begin(), owned.end(),
                     [&](Range r) { return item.begin >= r.begin && item.end <= r.end; });
}
bool carries(const RigidBody& b, const std::vector<Range>& owned, bool) {
  return std::any_of(owned.begin(), owned.end(), [&](Range r) {
    return std::max(b.range.begin, r.begin) < std::min(b.range.end, r.end);
  });
}
bool carries(const StepLoad& l, const std::vector<Range>& owned, bool shared) {
  return l.is_pressure() ? shared : holds(l.range, owned);
}

template <class Item>
void append_items(const std::vector<Item>& items, const std::vector<Range>& owned, bool shared,
                  std::vector<double>& out) {
  for (const Item& item : items) {
    if (!carries(item, owned, shared)) continue;
    out.resize(out.size() + fields_of(&item));
    read_fields(item, out.data() + out.size() - fields_of(&item));
  }
}
template <class Item>
void read_items(std::vector<Item>& items, const std::vector<Range>& owned, bool shared,
                const std::vector<double>& in, std::size_t& at) {
  for (Item& item : items) {
    if (!carries(item, owned, shared)) continue;
    write_fields(item, in.data() + at);
    at += fields_of(&item);
  }
}
}  // namespace

void StateSlice::append(const SolverState& state, const std::vector<Range>& owned,
                        std::vector<double>& out, bool shared) {
  for (const StateArray& a : state_arrays(state.particles.dimension)) {
    const std::vector<double>& v = state.particles.*a.member;
    for (const Range r : owned)
      out.insert(out.end(), v.begin() + static_cast<long>(r.begin),
                 v.begin() + static_cast<long>(r.end));
  }
  append_items(state, owned, out, shared);
}

void StateSlice::append_items(const SolverState& state, const std::vector<Range>& owned,
                              std::vector<double>& out, bool shared) {
  mpsolid::append_items(state.rigid_bodies, owned, shared, out);
  mpsolid::append_items(state.loads, owned, shared, out);
}

void StateSlice::read_items(SolverState& state, const std::vector<Range>& owned,
                            const std::vector<double>& in, std::size_t& at, bool shared) {
  mpsolid::read_items(state.rigid_bodies, owned, shared, in, at);
  mpsolid::read_items(state.loads, owned, shared, in, at);
}

void StateSlice::read(SolverState& state, const std::vector<Range>& owned,
                      const std::vector<double>& in, std::size_t& at, bool shared) {
  for (const StateArray& a : state_arrays(state.particles.dimension)) {
    std::vector<double>& v = state.particles.*a.member;
    for (const Range r : owned) {
      std::copy_n(in.begin() + static_cast<long>(at), r.size(),
                  v.begin() + static_cast<long>(r.begin));
      at += r.size();
    }
  }
  read_items(state, owned, in, at, shared);
}

}  // namespace mpsolid
