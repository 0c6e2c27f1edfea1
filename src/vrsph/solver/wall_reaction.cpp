#include "vrsph/solver/wall_reaction.hpp"

#include <cmath>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/physics/pressure.hpp"
#include "vrsph/physics/viscosity.hpp"

namespace vrsph {
namespace {

// The acceleration of wall particle i from fluid neighbour j, as the force pass's fluid_sweep
// forms the pair seen from i (r_ij = x_i - x_j, grad_i W_ij = F r_ij).
template <int D>
Vec<D> wall_pair(const SolverParams<D>& prm, const ParticleSet<D>& ps, std::size_t i, std::size_t j,
                 const Vec<D>& r_ij, double r2) {
  const double f = prm.kernel.f(std::sqrt(r2));
  const double rho_i = ps.rho[i], rho_j = ps.rho[j], m_j = ps.mass_of(j);
  const double vol_j = m_j / rho_j;
  const Vec<D> v_ij = ps.vel[i] - ps.vel[j];
  const double vij_dot_rij = dot(v_ij, r_ij);
  const PairReciprocals rec = pair_reciprocals(r2, prm.eta2, rho_i, rho_j);
  const double p_i = prm.eos.pressure(rho_i), p_j = prm.eos.pressure(rho_j);
  double c = pressure_pair(p_i, p_j, vol_j, 1.0 / rho_i);
  if (prm.viscosity.model == ViscosityModel::artificial) {
    c += artificial_viscosity_pair(m_j, prm.viscosity.alpha_c0_h, vij_dot_rij, rec.inv_r2eta,
                                   rec.inv_rho_sum);
  }
  Vec<D> a = (c * f) * r_ij;
  if (prm.viscosity.model == ViscosityModel::laminar) {
    const double lv =
        laminar_viscosity_pair(m_j, prm.viscosity.nu, f * r2, rec.inv_r2eta, rec.inv_rho_sum);
    a += lv * v_ij;
  }
  return a;
}

}  // namespace

template <int D>
void wall_reaction_forces(const SolverParams<D>& prm, const ParticleSet<D>& ps,
                          const CellGrid<D>& grid, std::vector<Vec<D>>& force) {
  force.assign(ps.size(), Vec<D>{});
  const std::uint32_t first = grid.group_begin(Group::wall);
  const std::uint32_t n = grid.group_end(Group::wall) - first;
  const auto& cells = grid.particle_cells();
  exec::for_each_dynamic(static_cast<std::int64_t>(n), 64, [&](std::int64_t k) {
    const std::size_t i = first + static_cast<std::size_t>(k);
    Vec<D> a{};
    grid.for_each_run(cells[i], Group::fluid, [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t j = begin; j < end; ++j) {
        if (ps.kind[j] != Kind::fluid) continue;
        const Vec<D> r_ij = ps.pos[i] - ps.pos[j];
        const double r2 = norm2(r_ij);
        if (r2 >= prm.kernel.support2 || !(r2 > 0.0)) continue;
        a += wall_pair(prm, ps, i, j, r_ij, r2);
      }
    });
    force[i] = ps.mass_of(i) * a;
  });
}

template <int D>
std::vector<Vec<D>> wall_block_forces(const Level<D>& L, const std::vector<IdRange>& blocks) {
  std::vector<Vec<D>> per_particle;
  wall_reaction_forces(L.prm, L.ps, L.grid, per_particle);
  std::vector<Vec<D>> out(blocks.size());
  for (std::size_t i = 0; i < L.ps.size(); ++i) {
    if (L.ps.kind[i] != Kind::wall) continue;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      if (!blocks[b].holds(L.ps.id[i])) continue;
      out[b] += per_particle[i];
      break;
    }
  }
  return out;
}

template void wall_reaction_forces<2>(const SolverParams<2>&, const ParticleSet<2>&,
                                      const CellGrid<2>&, std::vector<Vec<2>>&);
template void wall_reaction_forces<3>(const SolverParams<3>&, const ParticleSet<3>&,
                                      const CellGrid<3>&, std::vector<Vec<3>>&);
template std::vector<Vec<2>> wall_block_forces<2>(const Level<2>&, const std::vector<IdRange>&);
template std::vector<Vec<3>> wall_block_forces<3>(const Level<3>&, const std::vector<IdRange>&);

}  // namespace vrsph
