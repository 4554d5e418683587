// The interface indicator of local refinement (source/surface/adaptivity.cc) refines
// where phi is sharp, not where it merely lies between the phases: on a flat 32 x 32
// patch with xi = 0.03 (h = xi / 0.96), a stripe between two straight interfaces with the
// equilibrium profile tanh(3 s / (4 xi)) is refined along both, the same profile four times broader
// (the state of a smooth start before the interface has sharpened) is not refined at all,
// and refined cells that no longer hold a sharp interface are coarsened.
#include "fixed_surface.h"

#include <membrane/surface/adaptivity.h>
#include <membrane/surface/initial_shapes.h>

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

namespace
{
  /// A 16 x 16 patch refined once, bent by two cosine modes of amplitude 0.02 (slopes below 0.13,
  /// normal curvatures up to 1.6), phi = -1; the centre vertex (vertex 3 of child 0) of the family
  /// whose parent is centred at (6.5, 4.5) / 16 moved by `offset` times the parent's size 1/16
  /// along the coordinate axis `component`.
  void curved_patch_with_moved_vertex(Testing::FixedSurface &setup, const unsigned int component, const double offset)
  {
    setup.tria.refine_global(1);
    setup.surface.setup();
    set_cosine_modes(setup.surface, {{0.02, 1, 1, 0}, {0.02, 1, -1, 0}});
    InitialPhaseOptions uniform;
    uniform.type          = "uniform";
    uniform.uniform_value = -1;
    setup.set_phase(uniform);
    Vector displaced = setup.surface.vector_space().make_owned();
    displaced        = setup.surface.displacement();
    for (const auto &cell : setup.surface.vector_space().dof_handler().active_cell_iterators())
      if (cell->parent()->center().distance(dealii::Point<3>(6.5 / 16, 4.5 / 16, 0)) < 1e-9 &&
          cell == cell->parent()->child(0))
        {
          const auto dof  = cell->vertex_dof_index(3, component);
          displaced[dof] = displaced[dof] + offset / 16;
        }
    displaced.compress(dealii::VectorOperation::insert);
    setup.surface.set_displacement(displaced);
    setup.update_geometry();
  }
} // namespace

// Coarsening drops the inner vertices of a family of four cells; refining again would put them
// back at the Hermite midpoints of the parent (Smooth new vertices). Where the surface is smooth
// they lie there already up to O(h^4), and every family the indicators allow is coarsened; a
// family whose centre vertex is off that surface by 1 % of the parent's size (a mesh-scale
// feature that the coarse mesh cannot carry, and whose loss changes the bending energy) is kept
// at Coarsening tolerance 3e-3, and coarsened at 1 (no bound) and 0.02.
TEST(Adaptivity, CoarseningKeepsFamiliesTheCoarseMeshCannotCarry)
{
  Testing::FixedSurface setup(16);
  const unsigned int    base = setup.tria.n_global_levels() - 1; // the level of the 16 x 16 cells
  curved_patch_with_moved_vertex(setup, 2, 0.01);                  // raised along z

  AdaptivityOptions options;
  options.max_level = 1;
  const auto coarsened = [&](const double tolerance) {
    options.coarsening_tolerance = tolerance;
    return mark(setup, options, base).second;
  };
  EXPECT_EQ(coarsened(1), 4 * 256u);
  EXPECT_EQ(coarsened(0.02), 4 * 256u);
  EXPECT_EQ(coarsened(3e-3), 4 * 255u);
  EXPECT_EQ(coarsened(0), 0u);
}

// Only the normal part of an inner vertex's offset from the Hermite point changes the surface: a
// centre vertex moved by 1 % of the parent's size along x, nearly tangential on this surface (slopes
// below 0.13), is another parametrization of the same surface, and its family is coarsened at
// Coarsening tolerance 3e-3 (the same move along z keeps it: the test above).
TEST(Adaptivity, CoarseningIgnoresTangentialOffsets)
{
  Testing::FixedSurface setup(16);
  const unsigned int    base = setup.tria.n_global_levels() - 1;
  curved_patch_with_moved_vertex(setup, 0, 0.01); // moved along x

  AdaptivityOptions options;
  options.max_level            = 1;
  options.coarsening_tolerance = 3e-3;
  EXPECT_EQ(mark(setup, options, base).second, 4 * 256u);
}
