#pragma once
// A fully validated case, in SI units. Produced by read_case(); everything
// downstream trusts it.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "src/core/load_history.hpp"
#include "src/core/material.hpp"
#include "src/core/option_table.hpp"
#include "src/core/region.hpp"
#include "src/core/region3.hpp"
#include "src/core/rigid_body.hpp"
#include "src/core/surface.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

// The first bending mode of a clamped-free beam along x (MODEL.md section 6):
// v_y(x) = tip_velocity f(s) / f(L) with s = x - root_x and
// f(s) = M (cos ks - cosh ks) - N (sin ks - sinh ks),
// M = sin kL + sinh kL, N = cos kL + cosh kL.
struct BendingMode {
  double root_x = 0;        // the clamped end (m)
  double length = 0;        // L (m)
  double kl = 1.875;        // k L of the mode
  double tip_velocity = 0;  // v_y at s = L (m/s)
};

// Velocity components a body's particles are held at zero in (frictionless
// rollers): for a strip whose sides may not move in y, say.
enum class Hold : std::int8_t { none = 0, x = 1, y = 2, z = 3 };

struct BodySpec {
  std::string name;
  Kind kind = Kind::elastic;
  int material = 0;  // index into CaseSpec::materials
  Shape shape;       // in the plane: the region the body fills, less its holes (m)
  Shape3 shape3;     // in space: the same
  // Initial motion: a uniform velocity, plus a spin (rad/s) about the centroid
  // of the body's sites, plus (elastic bodies) a bending mode. In the plane
  // the spin is about z (spin[2]); in space it is the angular velocity vector.
  double velocity[3] = {0, 0, 0};
  double spin[3] = {0, 0, 0};
  bool has_mode = false;
  BendingMode mode;
  Hold hold = Hold::none;
  // [bodies.NAME.motion]: a rigid body driven at a prescribed velocity (a
  // wall given a motion is read as such a rigid body).
  PrescribedMotion motion;
  // Lattice sites in the shape at spacing l0 (centres at (k + 1/2) l0).
  std::int64_t site_count(double l0, int dimension) const {
    return dimension == 3 ? count_shape3_sites(shape3, l0) : count_shape_sites(shape, l0);
  }
};

// A named probe: the particle nearest `at` in the initial configuration
// (lowest id on a tie), recorded in history.csv as probe.NAME.x / .y.
struct ProbeSpec {
  std::string name;
  double at[3] = {0, 0, 0};  // z only in space
};

// A load switched on at `start`: a total force (N over the depth) shared
// equally by a body's particles (type "step"), or an acceleration of every
// particle of a body (type "acceleration": gravity), which is the force
// m a on each particle; either times its history's factor.
struct LoadSpec {
  enum class Type { step, acceleration, pressure };
  std::string name;
  Type type = Type::step;
  int body = 0;                        // index into CaseSpec::bodies
  double force[3] = {0, 0, 0};         // step: N (z only in space)
  double acceleration[3] = {0, 0, 0};  // acceleration: m/s^2
  double pressure = 0;                 // pressure: Pa, on `surface` (positive pushes inwards)
  SurfaceSelection surface;
  double start = 0;
  LoadHistory history;
};

// [damping]: mass-proportional damping of every moving particle from
// `start` to `end` (src/core/damping.hpp).
struct DampingSpec {
  double coefficient = 0;  // 1/s; 0: no [damping] table
  double start = 0, end = 0;
};

// Blow-up checks, run every `check_interval` steps.
struct StabilitySpec {
  std::int64_t check_interval = 500;  // steps
  double max_speed = 1.0;             // in units of the largest dilatational wave speed
  double energy_tolerance = 0.1;      // |KE + PE - W - E0| / max(W, E0)
  double min_jacobian = 0.1;          // J = det F at or below this: a collapsed neighbourhood
};

// Contact between particles that are not bonded in the reference
// configuration (MODEL.md section 8): a frictionless repulsive pair force
// k (d - r) below the contact distance d, between the surface particles of
// the bodies listed. Off without a [contact] table (enabled defaults to true
// in one).
struct ContactSpec {
  bool enabled = false;
  double distance = 1.0;    // d, in units of l0, [0.5, 1.5] (MODEL.md section 8)
  double skin = 0.5;        // Verlet skin, in units of l0
  double stiffness = 0;     // K_c in Pa (the pair spring is K_c * depth); set by the reader
  std::vector<int> bodies;  // indices into CaseSpec::bodies, ascending
  // The interpenetration check: a non-bonded pair closer than this fraction
  // of the contact distance, [0.5, 1) (the stable-step bound assumes no pair
  // closer than d / 2), stops the run.
  double min_distance = 0.5;
};

// [gas]: a compressible ideal gas on a uniform grid, coupled both ways to
// the bodies it covers (MODEL.md section 9, docs/gas.md). Absent: no gas,
// and no gas code runs.
struct GasStateSpec {
  double density = 0;           // kg/m^3
  double pressure = 0;          // Pa
  double velocity[2] = {0, 0};  // m/s
  bool operator==(const GasStateSpec&) const = default;
};

struct GasSpec {
  enum class Edge { slip_wall, inflow, outflow };
  bool enabled = false;
  double gamma = 1.4;
  double cell = 0;                      // m: the cells' side
  double x[2] = {0, 0}, y[2] = {0, 0};  // m: the grid's extent
  double cfl = 0.8;                     // the gas step's Courant number, (0, 1]
  // [axis][low, high]: left, right, bottom, top.
  Edge edges[2][2] = {{Edge::slip_wall, Edge::slip_wall}, {Edge::slip_wall, Edge::slip_wall}};
  GasStateSpec initial;  // everywhere at first
  // Then each region (in name order) its own state.
  struct Region {
    std::string name;
    Shape shape;
    GasStateSpec state;
  };
  std::vector<Region> regions;
  // Then a planar shock of Mach number `mach` at x = shock_x, running along
  // +x (direction 1) or -x (-1) into the initial gas (at rest): the gas
  // behind it from Rankine-Hugoniot.
  double mach = 0;  // 0: no shock
  double shock_x = 0;
  int direction = 1;
  // What an inflow edge lets in: given, or (with a shock) the shocked gas.
  bool inflow_given = false;
  GasStateSpec inflow;
  // The bodies the gas pushes and is bounded by (indices, ascending), and
  // the pressure their unstressed state is at (a solid cell pushes with it).
  std::vector<int> bodies;
  double reference_pressure = 0;  // Pa
  // Named points where history.csv records the gas's pressure and density.
  struct Probe {
    std::string name;
    double at[2] = {0, 0};
  };
  std::vector<Probe> probes;  // in name order
};

// The most steps a run may count: step k's time k dt and every cadence stay
// exact in a double (2^53).
inline constexpr double kMaxSteps = 9007199254740992.0;

// Fewer history rows than this get a note: too few to see a run's history.
inline constexpr std::int64_t kFewHistoryRows = 20;

struct CaseSpec {
  std::string name;    // output folder name (default: the file's stem)
  std::string source;  // the case file it came from
  std::string model = "paper";
  std::string model_section;  // the case section of the model's options ("" if it has none)
  // 2: plane strain, bodies of depth D; 3: bodies in space, no depth.
  int dimension = 2;
  double l0 = 0;       // lattice spacing (m)
  double depth = 1.0;  // out-of-plane depth D (m); 1 in space, where it enters nothing
  std::vector<Material> materials;
  std::vector<BodySpec> bodies;  // in name order: this fixes the particle ids
  std::vector<LoadSpec> loads;
  DampingSpec damping;
  std::vector<ProbeSpec> probes;  // in name order
  double dt = 0;                  // s; 0 until chosen when dt_auto
  // time.dt = "auto": the step is chosen at set-up as dt_safety times the
  // model's linear stability limit 2 / omega_max (src/stable_step.hpp).
  // Compression stiffens the models, so the limit shrinks during a run: 0.4
  // is the largest safety that ran the rod at 11.2 and 55.9 kN with every
  // model that is stable there at 10 ns, at l0 = 2 and 1 mm (docs/accuracy.md).
  bool dt_auto = false;
  double dt_safety = 0.4;
  double end = 0;
  double frame_interval = 0;
  // s; a history.csv row this often (and at frames). Default: about 200
  // rows per run or every 10 us, whichever is coarser, at most frame_interval.
  double history_interval = 0;
  bool history_default = false;    // not given: a whole number of steps, no note
  double checkpoint_interval = 0;  // s; 0: only at the end of the run (and on a stop signal)
  int compression = 0;             // deflate level of frames.h5: 0 (off) to 9
  OptionValues model_options;      // the chosen model's section, defaults filled in
  StabilitySpec stability;
  ContactSpec contact;
  GasSpec gas;
  // numerics.flush_subnormals: subnormals flushed to zero in the solver's
  // loops (src/float_mode.hpp). Opt-in: faster while a wave crosses a fine
  // lattice, not bit-identical to IEEE in the far field (below 1e-270).
  bool flush_subnormals = false;
  std::string resolved_toml;  // the case with every default and override filled in
  // What the reader rounded to whole steps, in words (printed before a run
  // and kept in run.json): an end or interval that is not a multiple of dt.
  std::vector<std::string> notes;

  // A particle's volume: l0^2 D in the plane, l0^3 in space.
  double particle_volume() const { return dimension == 3 ? l0 * l0 * l0 : l0 * l0 * depth; }
  double time_at(std::int64_t step) const { return static_cast<double>(step) * dt; }
  std::int64_t particle_count() const;  // lattice sites of every body
  // About 200 history rows per run, or one every 10 us, whichever is coarser;
  // never sparser than the frames nor finer than a step (once dt is known).
  double default_history_interval() const {
    return std::min(frame_interval, std::max({end / 200.0, 1e-5, dt}));
  }
  // A defaulted history interval put on the step grid (dt must be known).
  void snap_default_history();
  std::int64_t step_count() const;            // steps to reach `end`
  std::int64_t steps_per_frame() const;       // output cadence in steps
  std::int64_t steps_per_history() const;     // history.csv cadence in steps
  std::int64_t steps_per_checkpoint() const;  // checkpoint cadence in steps; 0: none
  // Checks every number that becomes a step count once dt is known: throws
  // InputError for a count a run cannot reach exactly (over kMaxSteps), and
  // returns a note for the end and each output interval that is not a whole
  // number of steps, saying how it is rounded (checkpoints, which change no
  // result, are rounded down without a note).
  std::vector<std::string> check_step_grid() const;
  // An automatic step, once chosen: sets dt (rounded down so that the finest
  // output interval is a whole number of steps) and notes it in resolved_toml.
  void set_auto_time_step(double limit, double omega_max);
};

}  // namespace mpsolid
