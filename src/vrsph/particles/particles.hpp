// Particle storage: one structure of arrays per resolution level, fluid, wall and buffer particles
// together with a kind per particle. Every array has one entry per particle and is permuted
// together by the cell sort (CellGrid::sort), so index i means the same particle in all of them.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "vrsph/core/vec.hpp"

namespace vrsph {

enum class Kind : std::uint8_t { fluid = 0, wall = 1, buffer = 2 };

inline std::string_view kind_name(Kind k) {
  switch (k) {
    case Kind::fluid: return "fluid";
    case Kind::wall: return "wall";
    case Kind::buffer: return "buffer";
  }
  return "unknown";
}

template <int D>
struct ParticleSet {
  // Persistent state (checkpointed).
  std::vector<std::uint64_t> id;  // permanent particle id
  std::vector<Kind> kind;
  std::vector<Vec<D>> pos;        // m
  std::vector<Vec<D>> vel;        // m/s
  std::vector<double> rho;        // kg/m^3
  std::vector<double> mass;       // kg
  std::vector<Vec<D>> shift;      // last shifting displacement, m (output; kept through sorts)

  // Derived per force evaluation (not checkpointed).
  std::vector<double> p;          // pressure, Pa
  std::vector<Vec<D>> acc;        // dv/dt without gravity, m/s^2
  std::vector<double> drho;       // drho/dt, kg/m^3/s

  // Start-of-step copies for the symplectic scheme.
  std::vector<Vec<D>> pos0;
  std::vector<Vec<D>> vel0;
  std::vector<double> rho0;

  std::size_t size() const { return pos.size(); }

  void resize(std::size_t n) {
    id.resize(n);
    kind.resize(n);
    pos.resize(n);
    vel.resize(n);
    rho.resize(n);
    mass.resize(n);
    shift.resize(n);
    p.resize(n);
    acc.resize(n);
    drho.resize(n);
    pos0.resize(n);
    vel0.resize(n);
    rho0.resize(n);
  }

  void push_back(std::uint64_t id_, Kind k, const Vec<D>& x, const Vec<D>& v, double rho_,
                 double m) {
    const std::size_t n = size();
    resize(n + 1);
    id[n] = id_;
    kind[n] = k;
    pos[n] = x;
    vel[n] = v;
    rho[n] = rho_;
    mass[n] = m;
  }

  // Keeps the particles with keep[i] != 0, in order (persistent state only; derived arrays are
  // resized and hold stale values until the next pass). Returns the number removed.
  std::size_t compact(const std::vector<std::uint8_t>& keep) {
    std::size_t w = 0;
    for (std::size_t i = 0; i < size(); ++i) {
      if (!keep[i]) continue;
      if (w != i) {
        id[w] = id[i];
        kind[w] = kind[i];
        pos[w] = pos[i];
        vel[w] = vel[i];
        rho[w] = rho[i];
        mass[w] = mass[i];
        shift[w] = shift[i];
      }
      ++w;
    }
    const std::size_t removed = size() - w;
    resize(w);
    return removed;
  }

  std::size_t count(Kind k) const {
    std::size_t c = 0;
    for (Kind x : kind) c += (x == k);
    return c;
  }
};

}  // namespace vrsph
