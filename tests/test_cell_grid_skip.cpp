// CellGrid::sort skips a sort that would be the identity (no particle left its cell). Where
// particles were created and deleted in equal numbers since the last sort, indices shift, and a
// particle can sit in its old cell's run but in the other group's part of the table: such a sort
// must run.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"

namespace vrsph {
namespace {

// Four fluid particles and one wall particle in one cell; the first fluid particle is deleted and
// a new fluid particle is created in the same cell, so every index still lies in the cell the
// last sort gave it, but the wall particle now sits at the fluid group's last index.
template <int D>
void created_and_deleted_in_one_cell() {
  Vec<D> lo, hi, x;
  for (int k = 0; k < D; ++k) lo[k] = 0.0, hi[k] = 1.0, x[k] = 0.1;
  CellGrid<D> grid(lo, hi, 0.25, 1);
  ParticleSet<D> ps;
  for (int n = 0; n < 4; ++n) {
    x[0] = 0.1 + 0.01 * n;
    ps.push_back(10 + n, Kind::fluid, x, Vec<D>{}, 1000.0, 1.0);
  }
  x[0] = 0.05;
  ps.push_back(99, Kind::wall, x, Vec<D>{}, 1000.0, 1.0);
  grid.sort(ps);
  const std::int64_t c = grid.particle_cells()[0];
  ASSERT_EQ(grid.cell_run(c, Group::wall).second - grid.cell_run(c, Group::wall).first, 1u);

  std::vector<std::uint8_t> keep(ps.size(), 1);
  keep[0] = 0;
  ps.compact(keep);
  x[0] = 0.2;
  ps.push_back(50, Kind::fluid, x, Vec<D>{}, 1000.0, 1.0);
  for (std::size_t i = 0; i < ps.size(); ++i)  // the trap: every index is still in cell c
    ASSERT_EQ(grid.cell_of(ps.pos[i]), c);

  grid.sort(ps);
  EXPECT_FALSE(grid.last_sort_skipped());
  const auto [wb, we] = grid.cell_run(c, Group::wall);
  ASSERT_EQ(we - wb, 1u);
  EXPECT_EQ(ps.kind[wb], Kind::wall);
  EXPECT_EQ(ps.id[wb], 99u);
  const auto [fb, fe] = grid.cell_run(c, Group::fluid);
  ASSERT_EQ(fe - fb, 4u);
  for (std::uint32_t i = fb; i < fe; ++i) EXPECT_EQ(ps.kind[i], Kind::fluid) << "index " << i;
  // Nothing moved since: now the sort may be skipped again.
  grid.sort(ps);
  EXPECT_TRUE(grid.last_sort_skipped());
}

TEST(CellGridSkip, CreatedAndDeletedInEqualNumbersSorts2D) { created_and_deleted_in_one_cell<2>(); }
TEST(CellGridSkip, CreatedAndDeletedInEqualNumbersSorts3D) { created_and_deleted_in_one_cell<3>(); }

}  // namespace
}  // namespace vrsph
