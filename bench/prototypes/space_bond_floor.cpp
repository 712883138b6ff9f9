// The floor of the space kernels' arithmetic on this machine
// (docs/performance.md, "How far the design can go"): the passes of
// finite_strain (deformation gradient and law, consistent hourglass stress,
// forces) and of the paper model (strain, then forces and torques) on a cube
// lattice of 16 x 16 x LAYERS particles with 32 entries each, eight particles
// at a time with unit-stride partners, no irregular row, no boundary mask, no
// integration, no halo: everything the solver pays beyond the bond
// arithmetic and its loads left out. Two designs each:
// - gather: every particle sums its 32 entries in registers (each bond from
//   both ends: the solver's design, whose sums do not depend on the threads);
// - once: each bond computed by its lower end and added to both ends' sums
//   in memory (Newton's third law, as LAMMPS's bonds).
// Each with r0 as one constant per direction (a change of bits in the
// solver, whose r0 = x0_j - x0_i differ in the last bits) and with r0 from
// the sites (the solver's). It prints ns per particle-step, and scaled to the
// rod in space's 14.6 bonds per particle (the bond part's share; the law's
// per-particle cost scaled too, so a lower bound for the rod).
// Not part of the build (one line):
//   g++ -O3 -march=native -ffp-contract=off -fno-math-errno
//   bench/prototypes/space_bond_floor.cpp -o /tmp/space_bond_floor
// then /tmp/space_bond_floor LAYERS STEPS (16 150: 4,096 particles).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {
using L = double __attribute__((vector_size(64)));
using M = std::array<L, 9>;
L ld(const double* p) {
  L v;
  std::memcpy(&v, p, 64);
  return v;
}
void st(double* p, L v) {
  std::memcpy(p, &v, 64);
}
void add(double* p, L v) {
  st(p, ld(p) + v);
}
L lane_log(L v) {
  for (int k = 0; k < 8; ++k) v[k] = std::log(v[k]);
  return v;
}
L lane_sqrt(L v) {
  for (int k = 0; k < 8; ++k) v[k] = std::sqrt(v[k]);
  return v;
}
L lane_sign(L v) {
  const L one = L{} + 1.0;
  return v < 0.0 ? -one : one;
}
M product(const M& a, const M& b) {
  M c;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) {
      L s = a[r * 3] * b[k];
      for (int m = 1; m < 3; ++m) s += a[r * 3 + m] * b[m * 3 + k];
      c[r * 3 + k] = s;
    }
  return c;
}

bool kR0FromSites = false;
constexpr long kNx = 16, kNy = 16, kPlane = kNx * kNy;
constexpr double kL0 = 1e-3, kRe = 2.1e-3, kVolume = 1e-9, kPenalty = 0.1;

struct Lattice {
  long n = 0, pad = 0, total = 0;
  std::vector<long> offset;  // the 32 entries' j - i; the first 16 owned (j > i)
  std::vector<std::array<double, 3>> r0;
  std::vector<double> wl;  // w0 / |r0|^2
  // A field of `components` arrays of `total` values.
  std::vector<double> field(int components, double v = 0) const {
    return std::vector<double>(static_cast<std::size_t>(components * total), v);
  }
};

Lattice make_lattice(long layers) {
  Lattice lat;
  for (int owned = 1; owned >= 0; --owned)
    for (int c = -2; c <= 2; ++c)
      for (int b = -2; b <= 2; ++b)
        for (int a = -2; a <= 2; ++a) {
          const int d2 = a * a + b * b + c * c;
          // |r0| <= 2 l0 without (2,1,0): 6 + 12 + 8 + 6 = 32 neighbours.
          if (d2 == 0 || d2 == 5 || d2 > 4 || (d2 == 4 && (a * b != 0 || b * c != 0 || a * c != 0)))
            continue;
          const long o = a + b * kNx + c * kPlane;
          if ((o > 0) != (owned == 1)) continue;
          const double len = std::sqrt(double(d2)) * kL0;
          lat.offset.push_back(o);
          lat.r0.push_back({a * kL0, b * kL0, c * kL0});
          lat.wl.push_back((kRe / len - 1.0) / (len * len));
        }
  lat.n = kPlane * layers;
  lat.pad = 2 * kPlane + 2 * kNx + 2 + 16;
  lat.total = lat.n + 2 * lat.pad;
  return lat;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct State {
  std::vector<double> x, x0, q, mu, lambda, young, a_inv;
};

State make_state(const Lattice& lat) {
  State s{lat.field(3),      lat.field(3),        lat.field(4), lat.field(1, 8e5),
          lat.field(1, 4e6), lat.field(1, 2.4e6), lat.field(9)};
  double axx = 0;
  for (std::size_t e = 0; e < lat.offset.size(); ++e)
    axx += lat.wl[e] * lat.r0[e][0] * lat.r0[e][0];
  for (long i = 0; i < lat.total; ++i) {
    const long k = i - lat.pad;
    const double a = double(((k % kNx) + kNx) % kNx), b = double(((k / kNx) % kNy + kNy) % kNy),
                 c = double(k / kPlane);
    s.x[i] = a * kL0 * (1 + 1e-3) + 1e-7 * std::sin(double(i));
    s.x[lat.total + i] = b * kL0;
    s.x[2 * lat.total + i] = c * kL0 + 1e-7 * std::cos(double(i));
    s.x0[i] = a * kL0;
    s.x0[lat.total + i] = b * kL0;
    s.x0[2 * lat.total + i] = c * kL0;
    const double turn = 1e-3 * std::sin(0.1 * double(i));
    s.q[i] = std::cos(turn);
    s.q[lat.total + i] = 0.3 * std::sin(turn);
    s.q[2 * lat.total + i] = 0.5 * std::sin(turn);
    s.q[3 * lat.total + i] = std::sqrt(0.66) * std::sin(turn);
    for (int d = 0; d < 3; ++d) s.a_inv[(d * 4) * lat.total + i] = 1.0 / axx;
  }
  return s;
}

// The corrected-gradient passes (kernels/gradient_gather_model.hpp's operations).
struct FiniteStrain {
  const Lattice& lat;
  State& s;
  std::vector<double> g = lat.field(9), f = lat.field(9), sa = lat.field(9), q = lat.field(9),
                      force = lat.field(3);
  long t = lat.total;
  L at(const std::vector<double>& v, int c, long i) const { return ld(&v[c * t + i]); }
  // F = G A^-1, the neo-Hookean V P(F) A^-1.
  void law(long i, const M& gi) {
    M ai;
    for (int c = 0; c < 9; ++c) ai[c] = at(s.a_inv, c, i);
    const M fi = product(gi, ai);
    L jac = fi[0] * (fi[4] * fi[8] - fi[5] * fi[7]) - fi[1] * (fi[3] * fi[8] - fi[5] * fi[6]) +
            fi[2] * (fi[3] * fi[7] - fi[4] * fi[6]);
    jac = jac < 0.5 ? L{} + 0.5 : jac;  // the edges of an unpadded block
    const L log_j = lane_log(jac);
    const M cof = {fi[4] * fi[8] - fi[5] * fi[7], fi[5] * fi[6] - fi[3] * fi[8],
                   fi[3] * fi[7] - fi[4] * fi[6], fi[2] * fi[7] - fi[1] * fi[8],
                   fi[0] * fi[8] - fi[2] * fi[6], fi[1] * fi[6] - fi[0] * fi[7],
                   fi[1] * fi[5] - fi[2] * fi[4], fi[2] * fi[3] - fi[0] * fi[5],
                   fi[0] * fi[4] - fi[1] * fi[3]};
    const L mu = ld(&s.mu[i]), lambda = ld(&s.lambda[i]);
    M stress;
    for (int k = 0; k < 9; ++k) {
      const L fit = cof[k] / jac;
      stress[k] = kVolume * (mu * (fi[k] - fit) + lambda * log_j * fit);
    }
    const M stress_a = product(stress, ai);
    for (int c = 0; c < 9; ++c) {
      st(&f[c * t + i], fi[c]);
      st(&sa[c * t + i], stress_a[c]);
    }
  }
  // (S + Q) A^-1 from the summed Q.
  void finish_hourglass(long i, const M& qi) {
    M ai;
    for (int c = 0; c < 9; ++c) ai[c] = at(s.a_inv, c, i);
    const M qa = product(qi, ai);
    for (int c = 0; c < 9; ++c) st(&q[c * t + i], at(sa, c, i) + qa[c]);
  }
  // g_ij's row a, scaled by -h/2, and the bond's traction row a.
  L gap_row(long i, long j, int a, const L r0[3], L r) const {
    L turned = (at(f, a * 3, i) + at(f, a * 3, j)) * r0[0];
    for (int c = 1; c < 3; ++c) turned += (at(f, a * 3 + c, i) + at(f, a * 3 + c, j)) * r0[c];
    return r - 0.5 * turned;
  }
  L traction_row(long i, long j, int a, const L r0[3]) const {
    L tr = (at(q, a * 3, i) + at(q, a * 3, j)) * r0[0];
    for (int c = 1; c < 3; ++c) tr += (at(q, a * 3 + c, i) + at(q, a * 3 + c, j)) * r0[c];
    return tr;
  }
  L stiffness(long i, long j, double wl) const {
    return kPenalty * (0.5 * (ld(&s.young[i]) + ld(&s.young[j]))) * wl;
  }
  void r_of(long i, long j, L r[3]) const {
    for (int d = 0; d < 3; ++d) r[d] = at(s.x, d, j) - at(s.x, d, i);
  }
  void r0_of(std::size_t e, L r0[3]) const {
    for (int d = 0; d < 3; ++d) r0[d] = L{} + lat.r0[e][d];
  }
  void r0_of(long i, long j, std::size_t e, L r0[3]) const {
    if (!kR0FromSites) return r0_of(e, r0);
    for (int d = 0; d < 3; ++d) r0[d] = at(s.x0, d, j) - at(s.x0, d, i);
  }

  void step_gather(bool consistent) {
    for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
      M gi{};
      for (std::size_t e = 0; e < lat.offset.size(); ++e) {
        L r[3], r0[3];
        r_of(i, i + lat.offset[e], r);
        r0_of(i, i + lat.offset[e], e, r0);
        for (int a = 0; a < 3; ++a) {
          const L scaled = lat.wl[e] * r[a];
          for (int c = 0; c < 3; ++c) gi[a * 3 + c] += scaled * r0[c];
        }
      }
      law(i, gi);
    }
    if (consistent) {
      for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
        M qi{};
        for (std::size_t e = 0; e < lat.offset.size(); ++e) {
          const long j = i + lat.offset[e];
          L r[3], r0[3];
          r_of(i, j, r);
          r0_of(i, j, e, r0);
          const L h = stiffness(i, j, lat.wl[e]);
          for (int a = 0; a < 3; ++a) {
            const L scaled = (-0.5 * h) * gap_row(i, j, a, r0, r[a]);
            for (int c = 0; c < 3; ++c) qi[a * 3 + c] += scaled * r0[c];
          }
        }
        finish_hourglass(i, qi);
      }
    } else {
      q = sa;
    }
    for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
      L fi[3] = {};
      for (std::size_t e = 0; e < lat.offset.size(); ++e) {
        const long j = i + lat.offset[e];
        L r[3], r0[3];
        r_of(i, j, r);
        r0_of(i, j, e, r0);
        const L h = stiffness(i, j, lat.wl[e]);
        for (int a = 0; a < 3; ++a)
          fi[a] += lat.wl[e] * traction_row(i, j, a, r0) + h * gap_row(i, j, a, r0, r[a]);
      }
      for (int d = 0; d < 3; ++d) st(&force[d * t + i], fi[d]);
    }
  }

  void step_once() {
    const std::size_t owned = lat.offset.size() / 2;
    std::fill(g.begin(), g.end(), 0.0);
    for (std::size_t e = 0; e < owned; ++e)
      for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
        const long j = i + lat.offset[e];
        L r[3], r0[3];
        r_of(i, j, r);
        r0_of(i, j, e, r0);
        for (int a = 0; a < 3; ++a) {
          const L scaled = lat.wl[e] * r[a];
          for (int c = 0; c < 3; ++c) {
            const L term = scaled * r0[c];  // the same at both ends
            add(&g[(a * 3 + c) * t + i], term);
            add(&g[(a * 3 + c) * t + j], term);
          }
        }
      }
    for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
      M gi;
      for (int c = 0; c < 9; ++c) gi[c] = at(g, c, i);
      law(i, gi);
    }
    std::fill(g.begin(), g.end(), 0.0);  // now Q
    for (std::size_t e = 0; e < owned; ++e)
      for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
        const long j = i + lat.offset[e];
        L r[3], r0[3];
        r_of(i, j, r);
        r0_of(i, j, e, r0);
        const L h = stiffness(i, j, lat.wl[e]);
        for (int a = 0; a < 3; ++a) {
          const L scaled = (-0.5 * h) * gap_row(i, j, a, r0, r[a]);
          for (int c = 0; c < 3; ++c) {
            const L term = scaled * r0[c];
            add(&g[(a * 3 + c) * t + i], term);
            add(&g[(a * 3 + c) * t + j], term);
          }
        }
      }
    for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
      M qi;
      for (int c = 0; c < 9; ++c) qi[c] = at(g, c, i);
      finish_hourglass(i, qi);
    }
    std::fill(force.begin(), force.end(), 0.0);
    for (std::size_t e = 0; e < owned; ++e)
      for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
        const long j = i + lat.offset[e];
        L r[3], r0[3];
        r_of(i, j, r);
        r0_of(i, j, e, r0);
        const L h = stiffness(i, j, lat.wl[e]);
        for (int a = 0; a < 3; ++a) {
          const L term = lat.wl[e] * traction_row(i, j, a, r0) + h * gap_row(i, j, a, r0, r[a]);
          add(&force[a * t + i], term);
          add(&force[a * t + j], -term);
        }
      }
  }
};

// The paper model's passes (kernels/paper_gather_model.hpp's operations).
struct Paper {
  const Lattice& lat;
  State& s;
  std::vector<double> strain = lat.field(1), pressure = lat.field(1, 1e3), force = lat.field(6);
  long t = lat.total;
  struct Bond {
    L r[3], u[3], length;
  };
  Bond bond(long i, long j, std::size_t e) const {
    L qa[4], qb[4];
    for (int c = 0; c < 4; ++c) {
      qa[c] = ld(&s.q[c * t + i]);
      qb[c] = ld(&s.q[c * t + j]);
    }
    const L side = lane_sign(qa[0] * qb[0] + qa[1] * qb[1] + qa[2] * qb[2] + qa[3] * qb[3]);
    const L w = qa[0] + side * qb[0];
    const L v[3] = {qa[1] + side * qb[1], qa[2] + side * qb[2], qa[3] + side * qb[3]};
    const L twice_inv = 2.0 / (w * w + v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    L r0[3];
    for (int d = 0; d < 3; ++d)
      r0[d] = kR0FromSites ? ld(&s.x0[d * t + j]) - ld(&s.x0[d * t + i]) : L{} + lat.r0[e][d];
    const L c[3] = {v[1] * r0[2] - v[2] * r0[1], v[2] * r0[0] - v[0] * r0[2],
                    v[0] * r0[1] - v[1] * r0[0]};
    const L cc[3] = {v[1] * c[2] - v[2] * c[1], v[2] * c[0] - v[0] * c[2],
                     v[0] * c[1] - v[1] * c[0]};
    Bond k;
    for (int d = 0; d < 3; ++d) {
      k.r[d] = ld(&s.x[d * t + j]) - ld(&s.x[d * t + i]);
      k.u[d] = k.r[d] - (r0[d] + twice_inv * (w * c[d] + cc[d]));
    }
    k.length = lane_sqrt(k.r[0] * k.r[0] + k.r[1] * k.r[1] + k.r[2] * k.r[2]);
    return k;
  }
  L strain_term(const Bond& k, std::size_t e) const {
    return lat.wl[e] * ((k.u[0] * k.r[0] + k.u[1] * k.r[1] + k.u[2] * k.r[2]) / k.length);
  }
  // The bond's force on i (its torque on i and on j are the same).
  void force_terms(long i, long j, std::size_t e, const Bond& k, L f[3], L tau[3]) const {
    const L spring = lat.wl[e] * (ld(&s.mu[i]) + ld(&s.mu[j]));
    const L c = lat.wl[e] * (ld(&pressure[i]) + ld(&pressure[j])) * (1.0 / k.length);
    for (int d = 0; d < 3; ++d) f[d] = spring * k.u[d] - c * k.r[d];
    tau[0] = spring * (k.r[1] * k.u[2] - k.r[2] * k.u[1]);
    tau[1] = spring * (k.r[2] * k.u[0] - k.r[0] * k.u[2]);
    tau[2] = spring * (k.r[0] * k.u[1] - k.r[1] * k.u[0]);
  }

  void step_gather() {
    for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
      L eps{};
      for (std::size_t e = 0; e < lat.offset.size(); ++e)
        eps += strain_term(bond(i, i + lat.offset[e], e), e);
      st(&strain[i], eps);
      st(&pressure[i], -ld(&s.lambda[i]) * eps);
    }
    for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
      L sum[6] = {};
      for (std::size_t e = 0; e < lat.offset.size(); ++e) {
        const long j = i + lat.offset[e];
        L f[3], tau[3];
        force_terms(i, j, e, bond(i, j, e), f, tau);
        for (int d = 0; d < 3; ++d) {
          sum[d] += f[d];
          sum[3 + d] += tau[d];
        }
      }
      for (int d = 0; d < 6; ++d) st(&force[d * t + i], sum[d]);
    }
  }

  void step_once() {
    const std::size_t owned = lat.offset.size() / 2;
    std::fill(strain.begin(), strain.end(), 0.0);
    for (std::size_t e = 0; e < owned; ++e)
      for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
        const long j = i + lat.offset[e];
        const L term = strain_term(bond(i, j, e), e);
        add(&strain[i], term);
        add(&strain[j], term);
      }
    for (long i = lat.pad; i < lat.pad + lat.n; i += 8)
      st(&pressure[i], -ld(&s.lambda[i]) * ld(&strain[i]));
    std::fill(force.begin(), force.end(), 0.0);
    for (std::size_t e = 0; e < owned; ++e)
      for (long i = lat.pad; i < lat.pad + lat.n; i += 8) {
        const long j = i + lat.offset[e];
        L f[3], tau[3];
        force_terms(i, j, e, bond(i, j, e), f, tau);
        for (int d = 0; d < 3; ++d) {
          add(&force[d * t + i], f[d]);
          add(&force[d * t + j], -f[d]);
          add(&force[(3 + d) * t + i], tau[d]);
          add(&force[(3 + d) * t + j], tau[d]);
        }
      }
  }
};

}  // namespace

int main(int argc, char** argv) {
  const long layers = argc > 1 ? std::atol(argv[1]) : 8;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 300;
  const int rounds = 5;
  const Lattice lat = make_lattice(layers);
  State s = make_state(lat);
  FiniteStrain fs{lat, s};
  Paper paper{lat, s};
  const char* names[] = {"finite_strain gather, consistent hourglass (3 passes)",
                         "finite_strain gather, no hourglass pass (2 passes)",
                         "finite_strain once per bond (3 passes)", "paper gather (2 passes)",
                         "paper once per bond (2 passes)"};
  constexpr int kDesigns = 5;
  std::vector<double> best(2 * kDesigns, 1e30);
  for (int round = 0; round < rounds; ++round)
    for (int v = 0; v < 2 * kDesigns; ++v) {  // interleaved
      kR0FromSites = v >= kDesigns;
      const int design = v % kDesigns;
      const auto t0 = std::chrono::steady_clock::now();
      for (int step = 0; step < steps; ++step) {
        if (design == 0) fs.step_gather(true);
        if (design == 1) fs.step_gather(false);
        if (design == 2) fs.step_once();
        if (design == 3) paper.step_gather();
        if (design == 4) paper.step_once();
      }
      best[v] = std::min(best[v], seconds_since(t0) / (double(steps) * double(lat.n)) * 1e9);
    }
  std::printf(
      "%ld particles, %zu entries each, fields %.1f MB; best of %d rounds, ns per particle-step\n",
      lat.n, lat.offset.size(), double(lat.total) * 43 * 8 / 1e6, rounds);
  std::printf("%-56s %18s %18s\n", "design", "r0 per direction", "r0 from the sites");
  for (int v = 0; v < kDesigns; ++v)
    std::printf("%-56s %8.1f (%6.1f) %8.1f (%6.1f)\n", names[v], best[v], best[v] * 14.6 / 16.0,
                best[kDesigns + v], best[kDesigns + v] * 14.6 / 16.0);
  std::printf("(in brackets: scaled to the rod in space's 14.6 bonds per particle)\n");
  double check = 0;
  for (long i = lat.pad; i < lat.pad + lat.n; ++i) check += fs.force[i] + paper.force[i];
  std::printf("(check %g)\n", check);
}
