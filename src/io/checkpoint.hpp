#pragma once
// checkpoint.h5: everything a run needs to go on to the same bits: the step,
// the evolving state in full precision (per-particle arrays in id order,
// rigid-body poses and velocities, each load's switch-on record), the
// resolved case, the bond table's hash, how much of history.csv and
// frames.h5 belongs to that step, and the run.json segments so far.
// Everything else (masses, bonds, ranges, work arrays) is rebuilt by set-up
// from the stored case; the state then overwrites the set-up state.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/frame_rows.hpp"
#include "src/core/solver_state.hpp"

namespace mpsolid {

// A per-particle state array saved and restored by name.
struct NamedArray {
  std::string name;
  std::vector<double>* values;
};

// kStateArrays of `p`, by name (see particle_store.hpp).
std::vector<NamedArray> particle_state_arrays(ParticleStore& p);

struct RigidBodyState {
  std::string name;
  std::vector<double> pose;  // pose_values (src/core/rigid_body.hpp)
  double work = 0;           // a driven body's driver's
};

struct LoadState {
  std::string name;
  bool active = false;
  double cx_on = 0, cy_on = 0;
  // A varying load's (src/core/loads.hpp): factor, centroid at the last
  // step's start, work before it.
  double factor = 1, cx_last = 0, cy_last = 0, work = 0;
  double cz_on = 0, cz_last = 0;  // in space
  // A pressure's running step (PressureSurface::running_fields): its nodes'
  // x at the last step's start, then their y; a gas load's then its given
  // node forces, x then y; in space then the nodes' z.
  std::vector<double> surface_running;
};

struct Checkpoint {
  std::int64_t step = 0;
  double peak_work = 0;               // SolverState::peak_work (the energy check's scale)
  std::string case_toml;              // the resolved case (CaseSpec::resolved_toml)
  std::uint64_t bond_hash = 0;        // BondTable::hash() of the run's bond table
  std::uint64_t run_id = 0;           // ties the checkpoint to its history.csv and frames.h5
  std::int64_t frames = 0;            // frames in frames.h5 and rows in history.csv at `step`
  std::uint64_t history_bytes = 0;    // length of history.csv (header included) at `step`
  std::string written_by;             // program version and git commit
  std::vector<std::string> segments;  // run.json segment objects so far, oldest first
  std::int64_t particle_count = 0;
  std::vector<std::pair<std::string, std::vector<double>>> particle_arrays;  // id order
  std::vector<RigidBodyState> rigid_bodies;
  std::vector<LoadState> loads;
  // The gas (a case with [gas]): named arrays, as the gas coupling saves
  // them (src/solver/gas_coupling.hpp); empty without a gas.
  std::vector<std::pair<std::string, std::vector<double>>> gas;
  // Read with ParticleRows::placed: where each particle array starts in the
  // file (row of id k at offset + 8 k), empty when they cannot be read in
  // place; the particle arrays then hold no values, and the stored content
  // hash waits for the arrays' hashes (check_placed_content).
  std::vector<std::uint64_t> particle_offsets;
  std::uint64_t content_hash = 0;
  std::int64_t format_version = 0;
};

// The evolving state and its step (the other fields are left empty).
// Without `particle_values`, the particle arrays are named but left empty
// (their rows are written in place: write_checkpoint's placer).
Checkpoint capture_state(const SolverState& state, bool particle_values = true);

// Overwrites a freshly set-up state with the checkpoint's.
// Throws InputError, naming `source`, if the checkpoint does not fit: other
// particle count, state arrays, bodies or loads, or another bond table.
void restore_state(SolverState& state, const Checkpoint& c, const std::string& source);
// The same for a state whose particles are elsewhere (over MPI ranks, rank
// 0's bodies and loads, each rank then reading its own rows): the fit
// checked against the run's `particles` and `bond_hash`, then the bodies,
// loads, step and peak work overwritten.
void restore_state_without_particles(SolverState& state, std::size_t particles,
                                     std::uint64_t bond_hash, const Checkpoint& c,
                                     const std::string& source);

// Writes `path` atomically: `path`.tmp, fsync, rename, fsync of the folder.
// With `placer`, the particle arrays (named in `c`, no values) are reserved
// and written in place by it (over MPI ranks, every rank its own particles).
// Returns the bytes written.
std::uintmax_t write_checkpoint(const std::filesystem::path& path, const Checkpoint& c,
                                const RowPlacer& placer = {});

// How read_checkpoint reads the particle arrays: their values, or only
// where they lie in the file (`placed`: over MPI ranks each rank reads its
// own rows; the arrays' names kept, their values left empty).
enum class ParticleRows : std::int8_t { values, placed };

// Reads and verifies a checkpoint (format, shapes, content hash; with
// `placed` the content hash once the ranks' rows are hashed). Throws
// InputError naming the file if it is missing, damaged or not a checkpoint.
Checkpoint read_checkpoint(const std::filesystem::path& path,
                           ParticleRows rows = ParticleRows::values);

// Throws InputError naming `source` unless the content hash stored in a
// checkpoint read with `placed` matches with its particle arrays' hashes
// (placed_array_hash, each summed over the ranks' rows).
void check_placed_content(const Checkpoint& c, const std::vector<std::uint64_t>& array_hashes,
                          const std::string& source);

}  // namespace mpsolid
