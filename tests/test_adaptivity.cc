// The interface indicator of local refinement (source/surface/adaptivity.cc) refines
// where phi is sharp, not where it merely lies between the phases: on a flat 32 x 32
// patch with xi = 0.03 (h = xi / 0.96), a stripe between two straight interfaces with the
// equilibrium profile tanh(3 s / (4 xi)) is refined along both, the same profile four times broader
// (the state of a smooth start before the interface has sharpened) is not refined at all,
// and refined cells that no longer hold a sharp interface are coarsened.
#include "fixed_surface.h"

#include <membrane/surface/adaptivity.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace Membrane;

namespace
{
  /// A stripe 0.3 < x < 0.7 with the profile tanh(3 s / (4 width)) at both interfaces
  /// (periodic: -1 at x = 0 and 1).
  void set_profile(Testing::FixedSurface &setup, const double width)
  {
    const std::string w = std::to_string(width);
    InitialPhaseOptions initial;
    initial.type       = "expression";
    initial.expression = "tanh(3 * (x - 0.3) / (4 * " + w + ")) * tanh(3 * (0.7 - x) / (4 * " + w + "))";
    setup.set_phase(initial);
  }

  std::pair<unsigned int, unsigned int> mark(Testing::FixedSurface &setup, const AdaptivityOptions &options,
                                             const unsigned int base_level)
  {
    const double xi = 0.03;
    for (const auto &cell : setup.tria.active_cell_iterators())
      {
        cell->clear_refine_flag();
        cell->clear_coarsen_flag();
      }
    return mark_cells(setup.tria, setup.surface, setup.geometry, setup.phi, xi, options, base_level);
  }
} // namespace

TEST(Adaptivity, InterfaceIndicatorRefinesSharpNotBroadProfiles)
{
  Testing::FixedSurface setup(32);
  const unsigned int    base = setup.tria.n_global_levels() - 1; // the level of the 32 x 32 cells
  AdaptivityOptions     options;
  options.max_level              = 2;
  options.interface_cells_per_xi = 1.5;

  // Broad: the slope 3 / (16 xi) is a quarter of the equilibrium's largest slope.
  set_profile(setup, 4 * 0.03);
  EXPECT_EQ(mark(setup, options, base).first, 0u);

  // Sharp: along each interface the columns of cells that the steep part crosses and
  // their vertex neighbours (3 to 6 columns of 32 cells); nothing far from x = 0.3, 0.7.
  set_profile(setup, 0.03);
  const auto [refine, coarsen] = mark(setup, options, base);
  EXPECT_GE(refine, 2 * 3 * 32u);
  EXPECT_LE(refine, 2 * 6 * 32u);
  EXPECT_EQ(coarsen, 0u);
  for (const auto &cell : setup.tria.active_cell_iterators())
    {
      if (cell->refine_flag_set())
        {
          EXPECT_LT(std::min(std::abs(cell->center()[0] - 0.3), std::abs(cell->center()[0] - 0.7)), 3.0 / 32);
        }
    }
  std::cout << refine << " of 1024 cells flagged for refinement\n";

  // Refined, and then given the broad profile (relative slope 1/4, below the coarsening
  // margin 1/2): all the 4 x refine children are coarsened again.
  setup.tria.execute_coarsening_and_refinement();
  setup.surface.setup();
  setup.update_geometry();
  set_profile(setup, 4 * 0.03);
  const auto [refine_broad, coarsen_broad] = mark(setup, options, base);
  EXPECT_EQ(refine_broad, 0u);
  EXPECT_EQ(coarsen_broad, 4 * refine);
  std::cout << coarsen_broad << " refined cells flagged for coarsening\n";
}
