// A stand-alone replica of the paper model's step (docs/performance.md, "The
// streaming step"): the slot pass, the strain gather and the force gather
// with the integration, on a lattice the size of the 0.25 mm rod (400 x 180
// particles, the rod's 6 bond directions, the solver's slot fields and
// vectorised gathers). It runs them as three passes over everything, then
// as one sweep of tiles with a lag (the slots of tile t + 2, the strain of
// tile t + 1, the forces and integration of tile t), checks that both give
// the same bits, and times them at 1 thread. Not part of the build:
//   g++ -O3 -march=native -ffp-contract=off -fno-math-errno \
//       bench/prototypes/streaming_step.cpp -o /tmp/streaming_step
//   TILE_ROWS=2 /tmp/streaming_step
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>
constexpr size_t W = 400, ROWS = 180, n = W * ROWS, ND = 6;
const size_t offs[ND] = {1, 2, W - 1, W, W + 1, 2 * W};
enum { R0X, R0Y, COEF, K, VC, RX, RY, UX, UY, IL, TERM, NF };
struct State {
  std::vector<double> x, y, c, s, vx, vy, p, f[NF];
};
void init(State& st) {
  st.x.resize(n);
  st.y.resize(n);
  st.c.assign(n, 1.0);
  st.s.assign(n, 0.0);
  st.vx.assign(n, 0);
  st.vy.assign(n, 0);
  st.p.assign(n, 0);
  for (auto& a : st.f) a.assign(ND * n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    st.x[i] = 0.001 * (i % W) + 1e-6 * std::sin(i);
    st.y[i] = 0.001 * (i / W);
  }
  for (size_t d = 0; d < ND; ++d)
    for (size_t i = 0; i + offs[d] < n; ++i) {
      size_t j = i + offs[d];
      st.f[R0X][d * n + i] = 0.001 * (double)((long)(j % W) - (long)(i % W));
      st.f[R0Y][d * n + i] = 0.001 * (double)((long)(j / W) - (long)(i / W));
      st.f[COEF][d * n + i] = 0.3;
      st.f[K][d * n + i] = 1e3;
      st.f[VC][d * n + i] = 1e-7;
    }
}
static inline void slot_range(State& st, size_t b, size_t e) {  // owners [b, e)
  for (size_t d = 0; d < ND; ++d) {
    const size_t end = std::min(e, n - offs[d]);
    if (b >= end) continue;
    const size_t o = offs[d];
    double* __restrict F[NF];
    for (int q = 0; q < NF; ++q) F[q] = st.f[q].data() + d * n;
    const double* __restrict x = st.x.data();
    const double* __restrict y = st.y.data();
    const double* __restrict c = st.c.data();
    const double* __restrict s = st.s.data();
    double* __restrict rxo = F[RX];
    double* __restrict ryo = F[RY];
    double* __restrict uxo = F[UX];
    double* __restrict uyo = F[UY];
    double* __restrict ilo = F[IL];
    double* __restrict to = F[TERM];
    const double* __restrict r0x = F[R0X];
    const double* __restrict r0y = F[R0Y];
    const double* __restrict co = F[COEF];
    for (size_t i = b; i < end; ++i) {
      const size_t j = i + o;
      double rc = c[i] * c[j] - s[i] * s[j], rs = s[i] * c[j] + c[i] * s[j];
      double ax = x[j] - x[i], ay = y[j] - y[i];
      double ux = ax - (rc * r0x[i] - rs * r0y[i]), uy = ay - (rs * r0x[i] + rc * r0y[i]);
      double il = 1.0 / std::sqrt(ax * ax + ay * ay);
      rxo[i] = ax;
      ryo[i] = ay;
      uxo[i] = ux;
      uyo[i] = uy;
      ilo[i] = il;
      to[i] = co[i] * ((ux * ax + uy * ay) * il);
    }
  }
}
static thread_local double ACC[3][1 << 17];
static inline void strain_range(State& st, size_t b, size_t e) {
  const double* __restrict t = st.f[TERM].data();
  double* __restrict p = st.p.data();
  double* __restrict acc = ACC[0];
  for (size_t i = b; i < e; ++i) acc[i - b] = 0;
  for (size_t d = 0; d < ND; ++d) {
    const size_t o = offs[d];
    const size_t lo = std::max(b, o);
    for (size_t i = lo; i < e; ++i) acc[i - b] += t[d * n + i - o];
    const size_t hi = std::min(e, n - o);
    for (size_t i = b; i < hi; ++i) acc[i - b] += t[d * n + i];
  }
  for (size_t i = b; i < e; ++i) p[i] = -1e6 * acc[i - b];
}
static inline void force_range(State& st, size_t b, size_t e, double dt) {
  const double* __restrict p = st.p.data();
  double* __restrict ax = ACC[1];
  double* __restrict ay = ACC[2];
  for (size_t i = b; i < e; ++i) ax[i - b] = ay[i - b] = 0;
  for (size_t d = 0; d < ND; ++d) {
    const size_t o = offs[d];
    const double* __restrict k = st.f[K].data() + d * n;
    const double* __restrict vc = st.f[VC].data() + d * n;
    const double* __restrict il = st.f[IL].data() + d * n;
    const double* __restrict rx = st.f[RX].data() + d * n;
    const double* __restrict ry = st.f[RY].data() + d * n;
    const double* __restrict ux = st.f[UX].data() + d * n;
    const double* __restrict uy = st.f[UY].data() + d * n;
    for (size_t i = std::max(b, o); i < e; ++i) {
      size_t sl = i - o;
      double cc = vc[sl] * (p[i] + p[i - o]) * il[sl];
      ax[i - b] -= k[sl] * ux[sl] - cc * rx[sl];
      ay[i - b] -= k[sl] * uy[sl] - cc * ry[sl];
    }
    for (size_t i = b; i < std::min(e, n - o); ++i) {
      size_t sl = i;
      double cc = vc[sl] * (p[i] + p[i + o]) * il[sl];
      ax[i - b] += k[sl] * ux[sl] - cc * rx[sl];
      ay[i - b] += k[sl] * uy[sl] - cc * ry[sl];
    }
  }
  for (size_t i = b; i < e; ++i) {
    st.vx[i] += dt * ax[i - b];
    st.vy[i] += dt * ay[i - b];
    st.x[i] += dt * st.vx[i];
    st.y[i] += dt * st.vy[i];
  }
}
int main() {
  const double dt = 1e-7;
  const int steps = 60;
  State a, b;
  init(a);
  init(b);
  auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    slot_range(a, 0, n);
    strain_range(a, 0, n);
    force_range(a, 0, n, dt);
  }
  auto t1 = std::chrono::steady_clock::now();
  const size_t T =
      std::atoi(getenv("TILE_ROWS") ? getenv("TILE_ROWS") : "4") * W;  // tile >= 2 rows
  for (int k = 0; k < steps; ++k) {
    const size_t tiles = (n + T - 1) / T;
    for (size_t t = 0; t < tiles + 2; ++t) {
      if (t < tiles) slot_range(b, t * T, std::min(n, (t + 1) * T));
      if (t >= 1 && t - 1 < tiles) strain_range(b, (t - 1) * T, std::min(n, t * T));
      if (t >= 2) force_range(b, (t - 2) * T, std::min(n, (t - 1) * T), dt);
    }
  }
  auto t2 = std::chrono::steady_clock::now();
  const bool same = std::memcmp(a.x.data(), b.x.data(), n * 8) == 0 &&
                    std::memcmp(a.vy.data(), b.vy.data(), n * 8) == 0;
  std::printf(
      "tile %zu rows: three passes %.0f us/step, one sweep %.0f us/step (%.2fx), same bits: %s\n",
      T / W, std::chrono::duration<double, std::micro>(t1 - t0).count() / steps,
      std::chrono::duration<double, std::micro>(t2 - t1).count() / steps,
      std::chrono::duration<double>(t1 - t0).count() /
          std::chrono::duration<double>(t2 - t1).count(),
      same ? "yes" : "NO");
}
