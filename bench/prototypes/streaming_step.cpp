// A stand-alone replica of the paper model's step (docs/performance.md, "The
// streaming step" and "How far the design can go"): the slot pass, the
// strain gather and the force gather with the integration, on a lattice of
// W x ROWS particles with the rod's 6 bond directions and the solver's slot
// fields. It times, at 1 thread, and checks that the first three give the
// same bits:
// - three passes over everything (today's order);
// - one sweep of tiles of 2 rows with a lag (the slots and strain of tile
//   t, the forces and integration of tile t - 2), the slots in full arrays;
// - the same sweep with the computed slot fields in a ring of 8 rows, so
//   that they never leave the cache;
// - the ring with each direction's constants (r0, coefficients) as scalars:
//   the bound of a lattice whose bonds share their constants (a change of
//   the bits in the solver, whose r0 = x0_j - x0_i differ in the last bits).
// Not part of the build (one line):
//   g++ -O3 -march=native -ffp-contract=off -fno-math-errno bench/prototypes/streaming_step.cpp
//   -o /tmp/streaming_step
// then /tmp/streaming_step 400 180 40 (the 0.25 mm rod's size; 50 23 3000: 2 mm).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {
std::size_t W = 400, ROWS = 180, n = 0;
constexpr std::size_t ND = 6;
std::size_t offs[ND];
enum { R0X, R0Y, COEF, K, VC, NC };     // constants per slot
enum { RX, RY, UX, UY, IL, TERM, NS };  // computed per slot
using Clock = std::chrono::steady_clock;

struct State {
  std::vector<double> x, y, c, s, vx, vy, p, cst[NC], f[NS];
  std::size_t ring = 0;  // 0: full arrays (n slots per direction)
  std::size_t len() const { return ring ? ring : n; }
  std::size_t map(std::size_t i) const { return ring ? i % ring : i; }
};

void init(State& st, std::size_t ring) {
  st.ring = ring;
  st.x.resize(n);
  st.y.resize(n);
  st.c.assign(n, 1.0);
  st.s.assign(n, 0.0);
  st.vx.assign(n, 0);
  st.vy.assign(n, 0);
  st.p.assign(n, 0);
  for (auto& a : st.cst) a.assign(ND * n, 0.0);
  for (auto& a : st.f) a.assign(ND * st.len(), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    st.x[i] = 0.001 * static_cast<double>(i % W) + 1e-6 * std::sin(static_cast<double>(i));
    st.y[i] = 0.001 * static_cast<double>(i / W);
  }
  for (std::size_t d = 0; d < ND; ++d)
    for (std::size_t i = 0; i + offs[d] < n; ++i) {
      const std::size_t j = i + offs[d];
      st.cst[R0X][d * n + i] = 0.001 * static_cast<double>(long(j % W) - long(i % W));
      st.cst[R0Y][d * n + i] = 0.001 * static_cast<double>(long(j / W) - long(i / W));
      st.cst[COEF][d * n + i] = 0.3;
      st.cst[K][d * n + i] = 1e3;
      st.cst[VC][d * n + i] = 1e-7;
    }
}

// A constant of slot i: its own, or its direction's first (Uniform).
template <bool Uniform>
double constant(const double* a, std::size_t i) {
  return a[Uniform ? 0 : i];
}

// Calls f(i0, i1, s0) for the pieces of [b, e) whose slots (i - shift) are
// contiguous in storage, the first at s0 (a ring wraps).
template <class F>
void pieces(const State& st, std::size_t b, std::size_t e, std::size_t shift, F&& f) {
  for (std::size_t i = b; i < e;) {
    const std::size_t s = st.map(i - shift);
    const std::size_t i1 = std::min(e, i + (st.ring ? st.ring - s : e - i));
    f(i, i1, s);
    i = i1;
  }
}

template <bool Uniform>
void slot_range(State& st, std::size_t b, std::size_t e) {
  for (std::size_t d = 0; d < ND; ++d) {
    const std::size_t o = offs[d], end = std::min(e, n - o);
    if (b >= end) continue;
    pieces(st, b, end, 0, [&](std::size_t i0, std::size_t i1, std::size_t s0) {
      const double* __restrict x = st.x.data();
      const double* __restrict y = st.y.data();
      const double* __restrict c = st.c.data();
      const double* __restrict s = st.s.data();
      const std::size_t base = d * st.len() + s0 - i0;  // slot of owner i: base + i
      double* __restrict rxo = st.f[RX].data() + base;
      double* __restrict ryo = st.f[RY].data() + base;
      double* __restrict uxo = st.f[UX].data() + base;
      double* __restrict uyo = st.f[UY].data() + base;
      double* __restrict ilo = st.f[IL].data() + base;
      double* __restrict to = st.f[TERM].data() + base;
      const double* __restrict r0x = st.cst[R0X].data() + d * n;
      const double* __restrict r0y = st.cst[R0Y].data() + d * n;
      const double* __restrict co = st.cst[COEF].data() + d * n;
      for (std::size_t i = i0; i < i1; ++i) {
        const std::size_t j = i + o;
        const double rc = c[i] * c[j] - s[i] * s[j], rs = s[i] * c[j] + c[i] * s[j];
        const double ax = x[j] - x[i], ay = y[j] - y[i];
        const double bx = constant<Uniform>(r0x, i), by = constant<Uniform>(r0y, i);
        const double ux = ax - (rc * bx - rs * by), uy = ay - (rs * bx + rc * by);
        const double il = 1.0 / std::sqrt(ax * ax + ay * ay);
        rxo[i] = ax;
        ryo[i] = ay;
        uxo[i] = ux;
        uyo[i] = uy;
        ilo[i] = il;
        to[i] = constant<Uniform>(co, i) * ((ux * ax + uy * ay) * il);
      }
    });
  }
}

thread_local double ACC[3][1 << 17];

void strain_range(State& st, std::size_t b, std::size_t e) {
  double* __restrict acc = ACC[0];
  for (std::size_t i = b; i < e; ++i) acc[i - b] = 0;
  for (std::size_t d = 0; d < ND; ++d) {
    const std::size_t o = offs[d];
    const auto add = [&](std::size_t i0, std::size_t i1, std::size_t base) {
      const double* __restrict t = st.f[TERM].data() + base;
      for (std::size_t i = i0; i < i1; ++i) acc[i - b] += t[i];
    };
    pieces(st, std::max(b, o), e, o, [&](std::size_t i0, std::size_t i1, std::size_t s0) {
      add(i0, i1, d * st.len() + s0 - i0);
    });
    pieces(st, b, std::min(e, n - o), 0, [&](std::size_t i0, std::size_t i1, std::size_t s0) {
      add(i0, i1, d * st.len() + s0 - i0);
    });
  }
  for (std::size_t i = b; i < e; ++i) st.p[i] = -1e6 * acc[i - b];
}

template <bool Uniform>
void force_range(State& st, std::size_t b, std::size_t e, double dt) {
  const double* __restrict p = st.p.data();
  double* __restrict ax = ACC[1];
  double* __restrict ay = ACC[2];
  for (std::size_t i = b; i < e; ++i) ax[i - b] = ay[i - b] = 0;
  for (std::size_t d = 0; d < ND; ++d) {
    const std::ptrdiff_t o = static_cast<std::ptrdiff_t>(offs[d]);
    // Entries of particle i in direction d: sign -1 for partner i - o (slot
    // of owner i - o), +1 for partner i + o (slot of owner i).
    const auto add = [&](std::size_t i0, std::size_t i1, std::size_t base, std::ptrdiff_t shift,
                         double sign) {
      const double* __restrict kk = st.cst[K].data() + d * n;
      const double* __restrict vc = st.cst[VC].data() + d * n;
      const double* __restrict il = st.f[IL].data() + base;
      const double* __restrict rx = st.f[RX].data() + base;
      const double* __restrict ry = st.f[RY].data() + base;
      const double* __restrict ux = st.f[UX].data() + base;
      const double* __restrict uy = st.f[UY].data() + base;
      for (std::size_t i = i0; i < i1; ++i) {
        const std::size_t sl = i + static_cast<std::size_t>(shift < 0 ? shift : 0);
        const std::size_t owner = sl;  // constants are indexed by owner
        const double cc = constant<Uniform>(vc, owner) * (p[i] + p[i + shift]) * il[sl];
        ax[i - b] += sign * (constant<Uniform>(kk, owner) * ux[sl] - cc * rx[sl]);
        ay[i - b] += sign * (constant<Uniform>(kk, owner) * uy[sl] - cc * ry[sl]);
      }
    };
    pieces(st, std::max(b, offs[d]), e, offs[d],
           [&](std::size_t i0, std::size_t i1, std::size_t s0) {
             add(i0, i1, d * st.len() + s0 - (i0 - offs[d]), -o, -1.0);
           });
    pieces(st, b, std::min(e, n - offs[d]), 0, [&](std::size_t i0, std::size_t i1, std::size_t s0) {
      add(i0, i1, d * st.len() + s0 - i0, o, 1.0);
    });
  }
  for (std::size_t i = b; i < e; ++i) {
    st.vx[i] += dt * ax[i - b];
    st.vy[i] += dt * ay[i - b];
    st.x[i] += dt * st.vx[i];
    st.y[i] += dt * st.vy[i];
  }
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

template <bool Uniform>
double three_passes(State& st, int steps, double dt) {
  const auto t0 = Clock::now();
  for (int k = 0; k < steps; ++k) {
    slot_range<Uniform>(st, 0, n);
    strain_range(st, 0, n);
    force_range<Uniform>(st, 0, n, dt);
  }
  return seconds_since(t0) / steps;
}

// Tiles of T particles: the slots and strain of tile t, the forces and
// integration of tile t - 2 (whose neighbours' pressures are then known).
template <bool Uniform>
double sweep(State& st, std::size_t T, int steps, double dt) {
  const auto t0 = Clock::now();
  const std::size_t tiles = (n + T - 1) / T;
  for (int k = 0; k < steps; ++k)
    for (std::size_t t = 0; t < tiles + 2; ++t) {
      if (t < tiles) {
        slot_range<Uniform>(st, t * T, std::min(n, (t + 1) * T));
        strain_range(st, t * T, std::min(n, (t + 1) * T));
      }
      if (t >= 2) force_range<Uniform>(st, (t - 2) * T, std::min(n, (t - 1) * T), dt);
    }
  return seconds_since(t0) / steps;
}
}  // namespace

int main(int argc, char** argv) {
  W = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 400;
  ROWS = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 180;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 40;
  n = W * ROWS;
  const std::size_t o6[ND] = {1, 2, W - 1, W, W + 1, 2 * W};
  std::copy(o6, o6 + ND, offs);
  const double dt = 1e-7;
  for (int round = 0; round < 3; ++round) {
    State a, b, c, u;
    init(a, 0);
    init(b, 0);
    init(c, 8 * W);
    init(u, 8 * W);
    const double three = three_passes<false>(a, steps, dt);
    const double full = sweep<false>(b, 2 * W, steps, dt);
    const double ring = sweep<false>(c, 2 * W, steps, dt);
    const double uniform = sweep<true>(u, 2 * W, steps, dt);
    const bool same = !std::memcmp(a.x.data(), b.x.data(), n * 8) &&
                      !std::memcmp(a.x.data(), c.x.data(), n * 8) &&
                      !std::memcmp(a.vy.data(), c.vy.data(), n * 8);
    std::printf(
        "%zu x %zu: three passes %.0f us/step (%.1f ns/particle); sweep %.2fx, ring sweep %.2fx, "
        "ring + uniform constants %.2fx (%.1f ns/particle); same bits: %s\n",
        W, ROWS, three * 1e6, three * 1e9 / static_cast<double>(n), three / full, three / ring,
        three / uniform, uniform * 1e9 / static_cast<double>(n), same ? "yes" : "NO");
  }
}
