#pragma once
// Test fixture: Cahn-Hilliard on a fixed periodic patch, stepped directly
// through the library's pieces (mesh, surface, geometry, solver).
#include <membrane/cahn_hilliard.h>
#include <membrane/physics/energy.h>
#include <membrane/physics/initial_phase.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/initial_shapes.h>

namespace Membrane::Testing
{
  struct FixedSurface
  {
    Triangulation      tria{MPI_COMM_WORLD};
    Surface            surface{tria, true};
    CahnHilliardSolver solver{tria, true};
    Material           material;
    CahnHilliardOptions options;
    Geometry           geometry;
    Vector             phi;

    explicit FixedSurface(unsigned int cells_per_side)
    {
      make_periodic_unit_square(tria, cells_per_side);
      surface.setup();
      solver.setup();
      material.bending_rigidity      = make_linear_law(1, 1);
      material.gaussian_rigidity     = make_linear_law(0, 0);
      material.spontaneous_curvature = make_linear_law(0, 0);
      material.line_tension          = 1;
      material.transition_length     = 0.1;
      material.phase_mobility        = 1;
      geometry = compute_geometry(surface);
    }
    /// Recompute the geometry after the shape was changed.
    void update_geometry() { geometry = compute_geometry(surface); }
    void set_phase(const InitialPhaseOptions &initial)
    {
      phi = surface.scalar_space().ghosted_copy(make_initial_phase(surface, initial));
    }
    void step(double tau, const ThermalNoise &noise = {})
    {
      Vector next = surface.scalar_space().make_owned(), potential = surface.scalar_space().make_owned();
      solver.step(surface, geometry, material, options, LinearSolverOptions(), tau, phi, next, potential, nullptr,
                  noise);
      phi = next;
    }
    double energy() const { return compute_energy(surface, geometry, phi, material).total(); }
    double mass() const { return integrate(surface, phi); }
  };
} // namespace Membrane::Testing
