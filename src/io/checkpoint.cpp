#include "src/io/checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <set>
#include <stdexcept>

#include "build_info.hpp"
#include "src/core/hash.hpp"
#include "src/io/atomic_file.hpp"
#include "src/io/hdf5_file.hpp"

namespace mpsolid {

namespace {
constexpr const char* kFormat = "mpsolid checkpoint";
// 2: peak_work; 3: bond hash of topology and geometry only; 4: each particle
// array in the content hash through its placed_array_hash (ranks write their
// own rows), the rest as in 3, which is still read.
constexpr std::int64_t kFormatVersion = 4;
constexpr std::int64_t kOldestRead = 3;

// Everything stored goes into the content hash: a damaged byte anywhere is
// found on reading. The particle arrays go in by their hashes (`arrays`, in
// their order); version 3 hashed their bytes.
std::uint64_t content_hash(const Checkpoint& c, std::int64_t version,
                           const std::vector<std::uint64_t>& arrays) {
  Fnv1a h;
  h.value(version);
  h.value(c.step);
  h.value(c.peak_work);
  h.text(c.case_toml);
  h.value(c.bond_hash);
  h.value(c.run_id);
  h.value(c.frames);
  h.value(c.history_bytes);
  h.text(c.written_by);
  for (const auto& s : c.segments) h.text(s);
  for (std::size_t a = 0; a < c.particle_arrays.size(); ++a) {
    const auto& [name, values] = c.particle_arrays[a];
    h.text(name);
    if (version == 3)
      h.bytes(values.data(), values.size() * sizeof(double));
    else
      h.value(arrays.at(a));
  }
  for (const auto& b : c.rigid_bodies) {
    h.text(b.name);
    for (double v : b.pose) h.value(v);
    if (b.work != 0) h.value(b.work);  // driven bodies only: older hashes stay
  }
  for (const auto& l : c.loads) {
    h.text(l.name);
    h.value(static_cast<std::int8_t>(l.active));
    h.value(l.cx_on);
    h.value(l.cy_on);
    // A step load keeps these at their defaults (so checkpoints written
    // before loads could vary keep their hashes).
    if (l.factor != 1 || l.cx_last != 0 || l.cy_last != 0 || l.work != 0)
      for (const double v : {l.factor, l.cx_last, l.cy_last, l.work}) h.value(v);
    for (const double v : l.surface_running) h.value(v);
    if (l.cz_on != 0 || l.cz_last != 0)  // in space: the plane's hashes stay
      for (const double v : {l.cz_on, l.cz_last}) h.value(v);
  }
  for (const auto& [name, values] : c.gas) {
    h.text(name);
    h.bytes(values.data(), values.size() * sizeof(double));
  }
  return h.value();
}

// Each particle array's placed_array_hash.
std::vector<std::uint64_t> array_hashes(const Checkpoint& c) {
  std::vector<std::uint64_t> out;
  for (const auto& [name, values] : c.particle_arrays) out.push_back(placed_array_hash(values));
  return out;
}

}  // namespace

std::vector<NamedArray> particle_state_arrays(ParticleStore& p) {
  std::vector<NamedArray> arrays;
  for (const StateArray& a : state_arrays(p.dimension)) arrays.push_back({a.name, &(p.*a.member)});
  return arrays;
}

Checkpoint capture_state(const SolverState& state, bool particle_values) {
  Checkpoint c;
  c.step = state.step;
  c.peak_work = state.peak_work;
  const ParticleStore& p = state.particles;
  c.particle_count = static_cast<std::int64_t>(p.size());
  const std::vector<std::size_t> order =
      particle_values ? p.storage_of_id() : std::vector<std::size_t>{};
  for (const StateArray& a : state_arrays(p.dimension)) {
    const std::vector<double>& values = p.*a.member;
    std::vector<double> by_id(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) by_id[k] = values[order[k]];
    c.particle_arrays.emplace_back(a.name, std::move(by_id));
  }
  for (const RigidBody& b : state.rigid_bodies)
    c.rigid_bodies.push_back({b.name, pose_values(b), b.work});
  for (const StepLoad& l : state.loads) {
    std::vector<double> running;
    for (const std::vector<double>* v : l.surface.running_fields())
      running.insert(running.end(), v->begin(), v->end());
    c.loads.push_back({l.name, l.active, l.cx_on, l.cy_on, l.factor, l.cx_last, l.cy_last, l.work,
                       l.cz_on, l.cz_last, std::move(running)});
  }
  return c;
}

namespace {
// Throws unless `c` fits the set-up state `s` of a run of `particles`
// particles whose bond table hashes to `bond_hash`.
void check_fit(const SolverState& s, std::size_t particles, std::uint64_t bond_hash,
               const Checkpoint& c, const std::string& source) {
  auto refuse = [&](const std::string& why) {
    throw InputError(fmt::format("{}: the checkpoint does not fit this case: {}", source, why));
  };
  std::vector<std::string> needed;
  for (const StateArray& a : state_arrays(s.particles.dimension)) needed.push_back(a.name);
  std::vector<std::string> stored;
  for (const auto& [name, values] : c.particle_arrays) stored.push_back(name);
  if (stored != needed)
    refuse(fmt::format("it holds the particle arrays [{}], this build needs [{}]",
                       fmt::join(stored, ", "), fmt::join(needed, ", ")));
  if (c.particle_count != static_cast<std::int64_t>(particles))
    refuse(fmt::format("it has {} particles, the case has {}", c.particle_count, particles));
  for (const auto& [name, values] : c.particle_arrays)
    if (c.particle_offsets.empty() && values.size() != particles)
      refuse(fmt::format("it has {} particles, the case has {}", values.size(), particles));
  if (bond_hash != c.bond_hash)
    refuse(fmt::format(
        "the bond table differs (hash {:016x} in the checkpoint, {:016x} here): it was written by "
        "another build ({}) or for another lattice; this build is {} {}",
        c.bond_hash, bond_hash, c.written_by, build_info::version, build_info::git_commit));
  if (c.rigid_bodies.size() != s.rigid_bodies.size())
    refuse(fmt::format("it has {} rigid bodies, the case has {}", c.rigid_bodies.size(),
                       s.rigid_bodies.size()));
  for (std::size_t b = 0; b < c.rigid_bodies.size(); ++b)
    if (c.rigid_bodies[b].name != s.rigid_bodies[b].name)
      refuse(fmt::format("rigid body '{}' in the checkpoint, '{}' in the case",
                         c.rigid_bodies[b].name, s.rigid_bodies[b].name));
    else if (c.rigid_bodies[b].pose.size() != pose_size(s.rigid_bodies[b].dimension))
      refuse(fmt::format("rigid body '{}' has a pose of {} numbers in the checkpoint, {} here",
                         c.rigid_bodies[b].name, c.rigid_bodies[b].pose.size(),
                         pose_size(s.rigid_bodies[b].dimension)));
  if (c.loads.size() != s.loads.size())
    refuse(fmt::format("it has {} loads, the case has {}", c.loads.size(), s.loads.size()));
  for (std::size_t l = 0; l < c.loads.size(); ++l)
    if (c.loads[l].name != s.loads[l].name)
      refuse(fmt::format("load '{}' in the checkpoint, '{}' in the case", c.loads[l].name,
                         s.loads[l].name));
    else if (s.loads[l].is_pressure() &&
             c.loads[l].surface_running.size() != s.loads[l].surface.running_size())
      refuse(fmt::format(
          "load '{}' keeps {} values of its surface nodes in the checkpoint, {} in the case",
          c.loads[l].name, c.loads[l].surface_running.size(), s.loads[l].surface.running_size()));
}

// The bodies, loads, step and peak work of `c` into `s` (checked to fit).
void restore_items(SolverState& s, const Checkpoint& c) {
  for (std::size_t b = 0; b < c.rigid_bodies.size(); ++b) {
    const RigidBodyState& from = c.rigid_bodies[b];
    RigidBody& to = s.rigid_bodies[b];
    set_pose_values(to, from.pose.data());
    to.work = from.work;
  }
  for (std::size_t l = 0; l < c.loads.size(); ++l) {
    s.loads[l].active = c.loads[l].active;
    s.loads[l].cx_on = c.loads[l].cx_on;
    s.loads[l].cy_on = c.loads[l].cy_on;
    s.loads[l].factor = c.loads[l].factor;
    s.loads[l].cx_last = c.loads[l].cx_last;
    s.loads[l].cy_last = c.loads[l].cy_last;
    s.loads[l].work = c.loads[l].work;
    s.loads[l].cz_on = c.loads[l].cz_on;
    s.loads[l].cz_last = c.loads[l].cz_last;
    if (StepLoad& load = s.loads[l]; load.is_pressure()) {
      auto at = c.loads[l].surface_running.begin();
      for (std::vector<double>* v : load.surface.running_fields()) {
        std::copy_n(at, v->size(), v->begin());
        at += static_cast<long>(v->size());
      }
      if (load.active) pressure_forces(load);
    }
  }
  s.step = c.step;
  s.peak_work = c.peak_work;
}
}  // namespace

void restore_state(SolverState& s, const Checkpoint& c, const std::string& source) {
  ParticleStore& p = s.particles;
  if (!c.particle_offsets.empty())
    throw std::logic_error("restore_state: a checkpoint read without its particle values");
  check_fit(s, p.size(), s.bonds.hash(), c, source);
  const std::vector<NamedArray> arrays = particle_state_arrays(p);
  const std::vector<std::size_t> order = p.storage_of_id();
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    const std::vector<double>& by_id = c.particle_arrays[a].second;
    std::vector<double>& values = *arrays[a].values;
    for (std::size_t k = 0; k < p.size(); ++k) values[order[k]] = by_id[k];
  }
  restore_items(s, c);
}

void restore_state_without_particles(SolverState& s, std::size_t particles, std::uint64_t bond_hash,
                                     const Checkpoint& c, const std::string& source) {
  check_fit(s, particles, bond_hash, c, source);
  restore_items(s, c);
}

std::uintmax_t write_checkpoint(const std::filesystem::path& path, const Checkpoint& c,
                                const RowPlacer& placer) {
  const std::filesystem::path staged = staging_path(path);
  {
    h5::File file = h5::File::create(staged);
    file.write_string("format", kFormat);
    file.set_attribute<std::int64_t>("format_version", kFormatVersion);
    file.set_attribute<std::int64_t>("step", c.step);
    file.set_attribute<double>("peak_work", c.peak_work);
    file.set_attribute<std::uint64_t>("bond_hash", c.bond_hash);
    file.set_attribute<std::uint64_t>("run_id", c.run_id);
    file.set_attribute<std::int64_t>("frames", c.frames);
    file.set_attribute<std::uint64_t>("history_bytes", c.history_bytes);
    file.set_attribute<std::int64_t>("particle_count", c.particle_count);
    file.write_string("case", c.case_toml);
    file.write_string("written_by", c.written_by);
    file.write_strings("segments", c.segments);

    // The particle arrays: written here, or reserved and written in place by
    // the placer (each rank its own particles), which hashes them.
    const h5::Group particles = file.create_group("particles");
    std::vector<std::string> order;
    RowPlacement placement{
        RowPlacement::Content::checkpoint, std::filesystem::absolute(staged).string(), {}, {}};
    const auto count = static_cast<std::size_t>(c.particle_count);
    for (const auto& [name, values] : c.particle_arrays) {
      if (placer)
        placement.offsets.push_back(particles.reserve<double>(name, count));
      else
        particles.write(name, values);
      order.push_back(name);
    }
    particles.write_strings("_order", order);
    const std::vector<std::uint64_t> hashes =
        placer ? placer(placement).array_hashes : array_hashes(c);
    file.set_attribute<std::uint64_t>("content_hash", content_hash(c, kFormatVersion, hashes));

    const h5::Group bodies = file.create_group("rigid_bodies");
    std::vector<std::string> body_names;
    std::vector<double> pose;
    for (const auto& b : c.rigid_bodies) {
      body_names.push_back(b.name);
      pose.insert(pose.end(), b.pose.begin(), b.pose.end());
    }
    bodies.write_strings("names", body_names);
    // In space the pose has its own dataset, so a plane build refuses it by name.
    const bool space = !c.rigid_bodies.empty() && c.rigid_bodies[0].pose.size() == pose_size(3);
    bodies.write(space ? "state3" : "state", pose, pose_size(space ? 3 : 2));
    std::vector<double> work;
    for (const auto& b : c.rigid_bodies) work.push_back(b.work);
    bodies.write("work", work);

    const h5::Group loads = file.create_group("loads");
    std::vector<std::string> load_names;
    std::vector<std::int8_t> active;
    std::vector<double> centroid, varying;
    for (const auto& l : c.loads) {
      load_names.push_back(l.name);
      active.push_back(l.active ? 1 : 0);
      centroid.insert(centroid.end(), {l.cx_on, l.cy_on});
      varying.insert(varying.end(), {l.factor, l.cx_last, l.cy_last, l.work});
    }
    loads.write_strings("names", load_names);
    loads.write("active", active);
    loads.write("centroid_on", centroid, 2);
    loads.write("varying", varying, 4);
    // In space, each load's centroid z when it switched on and at the last
    // step's start (written only where one is not 0).
    std::vector<double> centroid_z;
    for (const auto& l : c.loads) centroid_z.insert(centroid_z.end(), {l.cz_on, l.cz_last});
    if (std::any_of(centroid_z.begin(), centroid_z.end(), [](double z) { return z != 0; }))
      loads.write("centroid_z", centroid_z, 2);
    // Pressures' nodes, load after load (each x then y), and how many per load.
    std::vector<double> surfaces;
    std::vector<std::int64_t> surface_sizes;
    for (const auto& l : c.loads) {
      surfaces.insert(surfaces.end(), l.surface_running.begin(), l.surface_running.end());
      surface_sizes.push_back(static_cast<std::int64_t>(l.surface_running.size()));
    }
    loads.write("surface_sizes", surface_sizes);
    loads.write("surfaces", surfaces);
    if (!c.gas.empty()) {
      const h5::Group gas = file.create_group("gas");
      std::vector<std::string> names;
      for (const auto& [name, values] : c.gas) {
        gas.write(name, values);
        names.push_back(name);
      }
      gas.write_strings("_order", names);
    }
    file.close();
  }
  const std::uintmax_t bytes = std::filesystem::file_size(staged);
  publish_staged_file(path);
  return bytes;
}

Checkpoint read_checkpoint(const std::filesystem::path& path, ParticleRows rows) {
  if (!std::filesystem::exists(path))
    throw InputError(
        fmt::format("{}: no checkpoint (is this the output folder of a run?)", path.string()));
  Checkpoint c;
  std::uint64_t stored_hash = 0;
  std::int64_t version = 0;
  try {
    const h5::File file = h5::File::open(path, false);
    if (!file.has("format") || file.read_string("format") != kFormat)
      throw h5::Error("it is not an mpsolid checkpoint");
    version = file.attribute<std::int64_t>("format_version");
    if (version < kOldestRead || version > kFormatVersion)
      throw InputError(fmt::format(
          "{}: checkpoint format version {}, this build reads versions {} to {} ({}); resume "
          "it with the mpsolid that wrote it ({}) or run the case afresh",
          path.string(), version, kOldestRead, kFormatVersion,
          version < kFormatVersion ? "an older format" : "a newer format",
          file.has("written_by") ? file.read_string("written_by") : "unknown"));
    c.step = file.attribute<std::int64_t>("step");
    c.peak_work = file.attribute<double>("peak_work");
    c.bond_hash = file.attribute<std::uint64_t>("bond_hash");
    c.run_id = file.attribute<std::uint64_t>("run_id");
    c.frames = file.attribute<std::int64_t>("frames");
    c.history_bytes = file.attribute<std::uint64_t>("history_bytes");
    const auto n = file.attribute<std::int64_t>("particle_count");
    c.particle_count = n;
    stored_hash = file.attribute<std::uint64_t>("content_hash");
    if (c.step < 0 || c.frames < 0 || n < 0) throw h5::Error("negative step, frames or particles");
    c.case_toml = file.read_string("case");
    c.written_by = file.read_string("written_by");
    c.segments = file.read_strings("segments");

    const h5::Group particles = file.open_group("particles");
    // In place only where every array can be (format 4 hashes them as the
    // ranks read them).
    bool placed = rows == ParticleRows::placed && version >= 4;
    for (const std::string& name : particles.read_strings("_order")) {
      if (rows == ParticleRows::values) {
        c.particle_arrays.emplace_back(name,
                                       particles.read<double>(name, static_cast<std::size_t>(n)));
        continue;
      }
      c.particle_arrays.emplace_back(name, std::vector<double>{});
      const std::optional<std::uint64_t> offset =
          particles.placed_offset<double>(name, static_cast<std::size_t>(n));
      placed = placed && offset.has_value();
      if (placed) c.particle_offsets.push_back(*offset);
    }
    // Those written before damping get their damping_loss from the reading
    // of the values below.
    const auto has = [&](const char* name) {
      return std::any_of(c.particle_arrays.begin(), c.particle_arrays.end(),
                         [&](const auto& a) { return a.first == name; });
    };
    if (!placed || (has("omega") && !has("damping_loss"))) c.particle_offsets.clear();

    const h5::Group bodies = file.open_group("rigid_bodies");
    const std::vector<std::string> body_names = bodies.read_strings("names");
    const bool space = bodies.has("state3");
    const std::size_t width = pose_size(space ? 3 : 2);
    const std::vector<double> pose =
        bodies.read<double>(space ? "state3" : "state", body_names.size(), width);
    for (std::size_t b = 0; b < body_names.size(); ++b) {
      const auto at = pose.begin() + static_cast<long>(width * b);
      c.rigid_bodies.push_back({body_names[b], {at, at + static_cast<long>(width)}, 0.0});
    }
    // Checkpoints written before driven bodies hold no work: none was done.
    if (bodies.has("work")) {
      const std::vector<double> work = bodies.read<double>("work", body_names.size());
      for (std::size_t b = 0; b < body_names.size(); ++b) c.rigid_bodies[b].work = work[b];
    }

    const h5::Group loads = file.open_group("loads");
    const std::vector<std::string> load_names = loads.read_strings("names");
    const std::vector<std::int8_t> active = loads.read<std::int8_t>("active", load_names.size());
    const std::vector<double> centroid = loads.read<double>("centroid_on", load_names.size(), 2);
    // Checkpoints written before loads could vary hold step loads only.
    std::vector<double> varying;
    if (loads.has("varying"))
      varying = loads.read<double>("varying", load_names.size(), 4);
    else  // factor 1, nothing since
      for (std::size_t l = 0; l < load_names.size(); ++l)
        varying.insert(varying.end(), {1.0, 0.0, 0.0, 0.0});
    for (std::size_t l = 0; l < load_names.size(); ++l) {
      const double* v = varying.data() + 4 * l;
      c.loads.push_back({load_names[l],
                         active[l] != 0,
                         centroid[2 * l],
                         centroid[2 * l + 1],
                         v[0],
                         v[1],
                         v[2],
                         v[3],
                         0.0,
                         0.0,
                         {}});
    }
    if (loads.has("centroid_z")) {
      const std::vector<double> z = loads.read<double>("centroid_z", load_names.size(), 2);
      for (std::size_t l = 0; l < load_names.size(); ++l) {
        c.loads[l].cz_on = z[2 * l];
        c.loads[l].cz_last = z[2 * l + 1];
      }
    }
    // Checkpoints written before pressures hold none.
    if (loads.has("surface_sizes")) {
      const auto sizes = loads.read<std::int64_t>("surface_sizes", load_names.size());
      std::size_t total = 0;
      for (const std::int64_t size : sizes) {
        if (size < 0) throw h5::Error("a negative surface size");
        total += static_cast<std::size_t>(size);
      }
      const std::vector<double> surfaces = loads.read<double>("surfaces", total);
      std::size_t at = 0;
      for (std::size_t l = 0; l < load_names.size(); ++l) {
        const auto size = static_cast<std::size_t>(sizes[l]);
        c.loads[l].surface_running.assign(surfaces.begin() + static_cast<long>(at),
                                          surfaces.begin() + static_cast<long>(at + size));
        at += size;
      }
    }
    if (file.has("gas")) {
      const h5::Group gas = file.open_group("gas");
      for (const std::string& name : gas.read_strings("_order"))
        c.gas.emplace_back(
            name, gas.read<double>(name, static_cast<std::size_t>(gas.info(name).dims.at(0))));
    }
  } catch (const h5::Error& e) {
    throw InputError(fmt::format("{}: damaged or not a checkpoint ({})", path.string(), e.what()));
  }
  c.content_hash = stored_hash;
  c.format_version = version;
  if (rows == ParticleRows::placed) {
    // Read in place by the ranks, which then hash them; else not read here.
    if (c.particle_offsets.empty()) c.particle_arrays.clear();
    return c;
  }
  check_placed_content(c, array_hashes(c), path.string());
  // Checkpoints written before damping hold no damping_loss: nothing was lost.
  const auto named = [&](const char* name) {
    return std::find_if(c.particle_arrays.begin(), c.particle_arrays.end(),
                        [&](const auto& a) { return a.first == name; });
  };
  if (named("damping_loss") == c.particle_arrays.end() && named("omega") != c.particle_arrays.end())
    c.particle_arrays.emplace(named("omega") + 1, "damping_loss",
                              std::vector<double>(named("omega")->second.size(), 0.0));
  return c;
}

void check_placed_content(const Checkpoint& c, const std::vector<std::uint64_t>& array_hashes,
                          const std::string& source) {
  if (content_hash(c, c.format_version, array_hashes) != c.content_hash)
    throw InputError(fmt::format(
        "{}: damaged checkpoint: its contents do not match the hash stored with them", source));
}

}  // namespace mpsolid
