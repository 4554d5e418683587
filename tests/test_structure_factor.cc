// The structure factor of phi (analysis/structure_factor.h, MODEL.md section 10): on a uniform
// periodic patch it is the discrete Fourier transform of the vertex values, so a field of known
// modes gives its shells to round-off; on a sphere, a spherical harmonic of degree l puts its
// power into S_l at second order in the cell size, and the mean wave number is its degree.
#include <membrane/analysis/spherical_modes.h>
#include <membrane/analysis/structure_factor.h>
#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/field_space.h>
#include <membrane/surface/projection.h>
#include <membrane/surface/surface.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

using namespace Membrane;

namespace
{
  /// The ghosted nodal field f(vertex) of the scalar space.
  template <typename F>
  Vector nodal_field(const FieldSpace &scalars, const F &f)
  {
    Vector owned = scalars.make_owned();
    for_each_free_vertex(scalars, [&](const auto &cell, const unsigned int v, const auto &dofs) {
      owned[dofs[0]] = f(cell->vertex(v));
    });
    owned.compress(dealii::VectorOperation::insert);
    scalars.constraints().distribute(owned); // the periodic copies
    return scalars.ghosted_copy(owned);
  }
} // namespace

// phi = 0.3 cos(2 pi 3 x) + 0.2 sin(2 pi (x + y)) - 0.5: the amplitudes 0.15 at k = +-(3, 0) and
// 0.1 at +-(1, 1); shell 3 (2.5 <= |k| < 3.5) has 8 wave vectors in a half plane, shell 1 has 4.
TEST(StructureFactor, PatchShellsOfKnownModes)
{
  Triangulation tria(MPI_COMM_WORLD);
  make_periodic_unit_square(tria, 32);
  Surface surface(tria, true);
  surface.setup();
  const auto  &scalars = surface.scalar_space();
  const Vector phi     = nodal_field(scalars, [](const dealii::Point<spacedim> &x) {
    return 0.3 * std::cos(2 * M_PI * 3 * x[0]) + 0.2 * std::sin(2 * M_PI * (x[0] + x[1])) - 0.5;
  });
  const StructureFactor S = patch_structure_factor(scalars, phi, 5);
  ASSERT_EQ(S.power.size(), 5u);
  EXPECT_EQ(S.multiplicity[0], 4u);  // (1,0), (0,1), (1,1), (1,-1)
  EXPECT_EQ(S.multiplicity[2], 8u);  // (3,0), (3,+-1), (2,+-2), (1,+-3), (0,3)
  EXPECT_NEAR(S.power[0], 0.1 * 0.1 / 4, 1e-15);
  EXPECT_NEAR(S.power[1], 0, 1e-15);
  EXPECT_NEAR(S.power[2], 0.15 * 0.15 / 8, 1e-15);
  // q_1 = (2 pi sqrt 2 0.01 + 2 pi 3 0.0225) / (0.01 + 0.0225), over the modes themselves
  const double q1 = 2 * M_PI * (std::sqrt(2.0) * 0.01 + 3 * 0.0225) / (0.01 + 0.0225);
  EXPECT_NEAR(S.mean_wavenumber, q1, 1e-12);
}

// phi = Y_2,1 + 0.5 Y_3,-2 on spheres of radius 0.7 (its power 1/5 at l = 2 and 0.25/7 at l = 3):
// the projection's error falls at second order, and nothing leaks into the other degrees beyond it.
TEST(StructureFactor, SphereDegreesOfKnownHarmonics)
{
  std::vector<double> errors;
  for (const unsigned int n : {8u, 16u})
    {
      ReferenceSurfaceOptions options;
      options.type           = "sphere";
      options.cells_per_side = n;
      options.radius         = 0.7;
      Triangulation tria(MPI_COMM_WORLD);
      make_closed_surface(tria, options);
      Surface surface(tria, false);
      surface.setup();
      const Vector phi = nodal_field(surface.scalar_space(), [](const dealii::Point<spacedim> &x) {
        const dealii::Tensor<1, spacedim> direction = x / x.norm();
        return real_spherical_harmonic(2, 1, direction) + 0.5 * real_spherical_harmonic(3, -2, direction);
      });
      const StructureFactor S = sphere_structure_factor(surface, phi, 4);
      std::cout << n << " cells per side: S_1..4 = " << S.power[0] << ", " << S.power[1] << ", " << S.power[2]
                << ", " << S.power[3] << ", mean degree " << S.mean_wavenumber << std::endl;
      errors.push_back(std::abs(S.power[1] / 0.2 - 1) + std::abs(S.power[2] / (0.25 / 7) - 1));
      EXPECT_LT(S.power[0] + S.power[3], 1e-3 * S.power[1]);
      EXPECT_EQ(S.multiplicity[1], 5u);
      EXPECT_NEAR(S.mean_wavenumber, (2 * 1.0 + 3 * 0.25) / 1.25, 0.02);
    }
  const double order = std::log2(errors[0] / errors[1]);
  std::cout << "observed order " << order << std::endl;
  EXPECT_GT(order, 1.5);
  EXPECT_LT(errors[1], 0.03); // 0.024 on 16 cells per side
}
