// mpsolid.Simulation: a case set up and stepped from Python, its particle
// arrays as read-only numpy views of the store (no copies).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "python/bindings/bindings.hpp"
#include "python/bindings/case_handle.hpp"
#include "python/bindings/threads.hpp"
#include "src/core/parallel.hpp"
#include "src/solver/gas_coupling.hpp"
#include "src/solver/simulation.hpp"

namespace py = pybind11;

namespace mpsolid::python {

namespace {

// Steps between looks at Python's signals: about 2e6 particle-steps (a
// tenth of a second on one core), at most 1000. Batches end on multiples of
// it, so an interrupted advance stops at one.
std::int64_t batch_steps_for(std::size_t particles) {
  return std::clamp<std::int64_t>(
      2'000'000 / static_cast<std::int64_t>(std::max<std::size_t>(1, particles)), 1, 1000);
}

class SimulationHandle {
 public:
  SimulationHandle(const CaseSpec& spec, int threads)
      : threads_((set_thread_count(threads), threads)),
        sim_(spec),
        batch_(batch_steps_for(sim_.particles().size())) {}

  // Runs f on the solver with the GIL released and this Simulation's threads.
  template <class F>
  auto with_solver(F&& f) {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(solver_mutex());
    set_thread_count(threads_);
    return f();
  }

  // Steps to `target` in batches with the GIL released, looking at Python's
  // signals between batches: a KeyboardInterrupt leaves the state at the end
  // of the last whole batch. The fields (strain, pressure) are fresh after.
  void advance_to(std::int64_t target) {
    if (busy_) throw std::runtime_error("this Simulation is already stepping in another thread");
    busy_ = true;
    struct Idle {
      bool& busy;
      ~Idle() { busy = false; }
    } idle{busy_};
    bool interrupted = false;
    while (sim_.step() < target && !interrupted) {
      const std::int64_t next = std::min(target, (sim_.step() / batch_ + 1) * batch_);
      with_solver([&] { sim_.advance(next - sim_.step()); });
      interrupted = PyErr_CheckSignals() != 0;
    }
    with_solver([&] { sim_.refresh_fields(); });
    if (interrupted) throw py::error_already_set();
  }

  Simulation& sim() { return sim_; }
  int threads() const { return threads_; }
  void set_threads(int threads) { threads_ = threads; }
  std::int64_t batch() const { return batch_; }

 private:
  int threads_;
  Simulation sim_;
  std::int64_t batch_;
  bool busy_ = false;  // read and written with the GIL held
};

// The first step whose time is at or after t.
std::int64_t first_step_at(const CaseSpec& spec, double t) {
  const double guess = std::ceil(t / spec.dt);
  if (!(guess <= kMaxSteps))
    throw InputError(fmt::format("run_to({}): more than 2^53 steps of dt = {} s", t, spec.dt));
  auto k = static_cast<std::int64_t>(std::max(0.0, guess));
  while (k > 0 && spec.time_at(k - 1) >= t) --k;
  while (spec.time_at(k) < t) ++k;
  return k;
}

py::dict diagnostics_dict(const Diagnostics& d) {
  py::dict out;
  out["kinetic_energy"] = d.kinetic_energy;
  out["strain_energy"] = d.strain_energy;
  out["external_work"] = d.external_work;
  out["momentum_x"] = d.momentum_x;
  out["momentum_y"] = d.momentum_y;
  out["angular_momentum"] = d.angular_momentum;  // about z
  out["momentum_z"] = d.momentum_z;              // in space; 0 in the plane
  out["angular_momentum_x"] = d.angular_momentum_x;
  out["angular_momentum_y"] = d.angular_momentum_y;
  out["max_speed"] = d.max_speed;
  out["damping_loss"] = d.damping_loss;      // 0 without [damping]
  out["contact_energy"] = d.contact_energy;  // 0 without [contact]
  out["contact_min_distance"] = d.contact_min_distance;
  return out;
}

// The gas's figures (history.csv's gas columns), or None without a gas.
py::object gas_dict(const Simulation& sim, const Diagnostics& d) {
  if (!sim.gas()) return py::none();
  const GasFigures& g = d.gas;
  py::dict out;
  out["steps"] = g.gas_steps;
  out["time"] = g.gas_time;
  out["mass"] = g.mass;
  out["energy"] = g.energy;
  out["inflow_energy"] = g.inflow_energy;
  out["wall_work"] = g.wall_work;
  out["solid_work"] = g.solid_work;
  out["lost_energy"] = g.lost_energy;
  out["coupling_error"] = g.coupling_error;
  py::dict probes;
  for (std::size_t k = 0; k < sim.spec().gas.probes.size(); ++k)
    probes[py::str(sim.spec().gas.probes[k].name)] = py::make_tuple(g.probe_p[k], g.probe_rho[k]);
  out["probes"] = probes;
  return out;
}

// A read-only view of `data`, kept alive by `owner` (the Simulation).
template <class T>
py::array view(const py::object& owner, const std::vector<T>& v) {
  using N = NumberOf_t<T>;  // a Kind as its integer (KIND_NAMES names it)
  static_assert(sizeof(N) == sizeof(T));
  const auto* data = reinterpret_cast<const N*>(v.data());
  py::array a(py::dtype::of<N>(), {v.size()}, {sizeof(N)}, data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

std::uintptr_t address_of(SimulationHandle& h, const std::string& name) {
  std::optional<std::uintptr_t> address;
  for_each_particle_array(h.sim().particles(), [&](const auto& info, const auto& v) {
    if (name == info.name) address = reinterpret_cast<std::uintptr_t>(v.data());
  });
  if (!address) throw py::key_error(name);
  return *address;
}

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<SimulationHandle> cls(
      m, "Simulation",
      "A case set up and ready to step (no outputs). The particle arrays are read-only numpy "
      "views of the solver's store, in storage order [wall | elastic | rigid], not id order: "
      "sort by `ids` for id order.");
  cls.def(py::init([](const CaseHandle& c, const py::object& threads) {
            const CaseSpec spec = c.spec();
            const int n = chosen_threads(threads);
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(solver_mutex());
            return std::make_unique<SimulationHandle>(spec, n);
          }),
          py::arg("case"), py::arg("threads") = py::none(),
          "Sets the case up (dt chosen for time.dt = \"auto\"). threads=None: OMP_NUM_THREADS "
          "if set, else every core, as the command line.")
      .def(
          "advance",
          [](SimulationHandle& h, std::int64_t steps) {
            if (steps < 0) throw py::value_error("advance: steps must be >= 0");
            if (static_cast<double>(h.sim().step()) + static_cast<double>(steps) > kMaxSteps)
              throw py::value_error("advance: more than 2^53 steps in all");
            h.advance_to(h.sim().step() + steps);
          },
          py::arg("steps"),
          "Advances `steps` time steps, the GIL released. Ctrl-C raises KeyboardInterrupt with "
          "the state at the end of the last whole batch (see batch_steps).")
      .def(
          "run_to",
          [](SimulationHandle& h, double t) {
            if (!std::isfinite(t)) throw py::value_error("run_to: t must be finite");
            if (t < h.sim().time())
              throw py::value_error(fmt::format(
                  "run_to({}): before the current time {} s (step {}); a Simulation only goes "
                  "forward",
                  t, h.sim().time(), h.sim().step()));
            h.advance_to(first_step_at(h.sim().spec(), t));
          },
          py::arg("t"),
          "Advances to the first step whose time is at or after t (s); t may lie past the "
          "case's end.")
      .def_property_readonly("time", [](SimulationHandle& h) { return h.sim().time(); })
      .def_property_readonly("step", [](SimulationHandle& h) { return h.sim().step(); })
      .def_property_readonly("dt", [](SimulationHandle& h) { return h.sim().spec().dt; })
      .def_property_readonly("end_time", [](SimulationHandle& h) { return h.sim().spec().end; })
      .def_property_readonly("name", [](SimulationHandle& h) { return h.sim().spec().name; })
      .def_property_readonly("model", [](SimulationHandle& h) { return h.sim().spec().model; })
      .def_property_readonly("particle_count",
                             [](SimulationHandle& h) { return h.sim().particles().size(); })
      .def_property_readonly("batch_steps", &SimulationHandle::batch,
                             "Steps between looks at Ctrl-C; advance stops on multiples of it.")
      .def_property(
          "threads", &SimulationHandle::threads,
          [](SimulationHandle& h, const py::object& n) {
            if (n.is_none()) throw py::value_error("threads: give a count from 1 to 4096");
            h.set_threads(chosen_threads(n));
          },
          "OpenMP threads of the next steps (the same bits at any count).")
      .def_property_readonly(
          "body_names",
          [](SimulationHandle& h) {
            std::vector<std::string> names;
            for (const BodySpec& b : h.sim().spec().bodies) names.push_back(b.name);
            return names;
          },
          "Body names; `bodies` holds indices into this list.")
      .def_property_readonly(
          "ranges",
          [](SimulationHandle& h) {
            const ParticleStore& p = h.sim().particles();
            py::dict r;
            r["wall"] = py::make_tuple(p.walls.begin, p.walls.end);
            r["elastic"] = py::make_tuple(p.elastic.begin, p.elastic.end);
            r["rigid"] = py::make_tuple(p.rigid.begin, p.rigid.end);
            return r;
          },
          "Storage index ranges [begin, end) of each kind.")
      .def_property_readonly("initial_energy",
                             [](SimulationHandle& h) { return h.sim().initial_energy(); })
      .def(
          "resolved_toml", [](SimulationHandle& h) { return h.sim().spec().resolved_toml; },
          "The case as run (an automatic dt filled in).")
      .def(
          "diagnostics",
          [](SimulationHandle& h) {
            const Diagnostics d = h.with_solver([&] { return h.sim().diagnostics(); });
            py::dict out = diagnostics_dict(d);
            out["gas"] = gas_dict(h.sim(), d);
            return out;
          },
          "Energies (J per depth), momenta and the largest speed of the current state; with a "
          "gas, `gas`: its steps, mass, energy, exchanges and probes (p, rho).")
      .def_property_readonly(
          "gas_conserved",
          [](py::object self) -> py::object {
            const Simulation& sim = self.cast<SimulationHandle&>().sim();
            if (!sim.gas()) return py::none();
            const GasGrid<2>& g = sim.gas()->gas().grid();
            const auto rows = static_cast<py::ssize_t>(g.extent(1));
            const auto columns = static_cast<py::ssize_t>(g.extent(0));
            py::dict out;
            const char* names[] = {"rho", "rho_u", "rho_v", "E"};
            for (int v = 0; v < GasSolver<2>::kVars; ++v) {
              const std::vector<double>& q = sim.gas()->gas().conserved(v);
              py::array a(py::dtype::of<double>(), {rows, columns},
                          {static_cast<py::ssize_t>(sizeof(double) * columns),
                           static_cast<py::ssize_t>(sizeof(double))},
                          q.data(), self);
              py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
              out[names[v]] = a;
            }
            return out;
          },
          "The gas's conserved variables (rho, rho_u, rho_v, E per cell volume) as read-only "
          "views of the solver's arrays, rows along y, the grid's two ghost layers on every "
          "side included (interior cell (i, j) at [j + 2, i + 2]); None without a gas.")
      .def(
          "gas_fields",
          [](SimulationHandle& h) -> py::object {
            if (!h.sim().gas()) return py::none();
            const GasFrame f = h.with_solver([&] { return h.sim().gas_frame(); });
            const auto ny = static_cast<py::ssize_t>(f.ny), nx = static_cast<py::ssize_t>(f.nx);
            py::dict out;
            out["density"] = py::array_t<double>({ny, nx}, f.density.data());
            out["pressure"] = py::array_t<double>({ny, nx}, f.pressure.data());
            out["velocity"] = py::array_t<double>({ny, nx, py::ssize_t{2}}, f.velocity.data());
            out["solid"] = py::array_t<std::int8_t>({ny, nx}, f.solid.data());
            out["x0"] = f.x0;
            out["y0"] = f.y0;
            out["cell"] = f.h;
            return out;
          },
          "The gas's density, pressure, velocity (ny x nx, x fastest; NaN inside a body) and "
          "solid flag now, as copies, with the grid's corner and cell; None without a gas.")
      .def(
          "check_stability",
          [](SimulationHandle& h) {
            Diagnostics d;
            const StabilityVerdict v = h.with_solver([&] { return h.sim().check_stability(&d); });
            const ParticleStore& p = h.sim().particles();
            py::dict out;
            out["ok"] = v.ok;
            out["criterion"] = v.criterion;
            out["particle"] = v.particle;
            out["particle_id"] = v.particle < p.size() ? py::cast(p.id[v.particle]) : py::none();
            out["neighbor_id"] = v.has_neighbor ? py::cast(p.id[v.neighbor]) : py::none();
            out["value"] = v.value;
            out["limit"] = v.limit;
            out["diagnostics"] = v.ok ? py::object(diagnostics_dict(d)) : py::none();
            return out;
          },
          "The run loop's blow-up checks of the current state: ok, the failed criterion and "
          "particle (storage index and id), value and limit.")
      .def("_address", &address_of, py::arg("name"),
           "The address of the store's array `name` (for the zero-copy test).");
  // Every array of the store's table, under its name; PARTICLE_ARRAYS maps
  // each name to its role.
  // An array of 3D stores only is in SPACE_ONLY_ARRAYS (z), one of 2D
  // stores only in PLANE_ONLY_ARRAYS (theta); a simulation of the other
  // dimension has no such attribute.
  py::dict arrays;
  py::list space_only, plane_only;
  for_each_particle_member([&](const auto& info, auto member) {
    const std::string name = info.name;
    const bool plane = info.present_in(2), space = info.present_in(3);
    cls.def_property_readonly(
        info.name,
        [member, name, plane, space](py::object self) {
          const ParticleStore& p = self.cast<SimulationHandle&>().sim().particles();
          if (!(p.dimension == 3 ? space : plane))
            throw py::attribute_error(name + ": a " + std::to_string(p.dimension) +
                                      "D simulation has no " + name);
          return view(self, p.*member);
        },
        info.what);
    arrays[info.name] = role_name(info.role);
    if (!plane) space_only.append(info.name);
    if (!space) plane_only.append(info.name);
  });
  m.attr("PARTICLE_ARRAYS") = arrays;
  m.attr("SPACE_ONLY_ARRAYS") = py::tuple(space_only);
  m.attr("PLANE_ONLY_ARRAYS") = py::tuple(plane_only);
  py::dict kind_names;
  for (Kind k : {Kind::wall, Kind::elastic, Kind::rigid})
    kind_names[py::int_(static_cast<int>(k))] = kind_name(k);
  m.attr("KIND_NAMES") = kind_names;
}

}  // namespace mpsolid::python
