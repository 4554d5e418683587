// The periodic patch and the closed vesicle as MembraneTopology (membrane_topology.h).
#include <membrane/analysis/fourier_modes.h>
#include <membrane/analysis/spherical_modes.h>
#include <membrane/analysis/vesicle_domain.h>
#include <membrane/membrane_topology.h>
#include <membrane/physics/terms/area_difference.h>
#include <membrane/physics/volume.h>
#include <membrane/surface/gauss_map.h>
#include <membrane/surface/initial_shapes.h>

#include <deal.II/grid/grid_tools.h>

#include <cmath>
#include <sstream>

namespace Membrane
{
  namespace
  {
    /// The unit square with periodic identification in x and y (MODEL.md section 5).
    class PeriodicPatch : public MembraneTopology
    {
    public:
      explicit PeriodicPatch(const unsigned int cells_per_side)
        : cells_per_side(cells_per_side)
      {}

      std::string name() const override { return "Membrane patch"; }
      bool        periodic() const override { return true; }
      bool        encloses_volume() const override { return false; }

      void make_mesh(Triangulation &triangulation) override
      {
        make_periodic_unit_square(triangulation, cells_per_side);
        input_level = factor_cells_per_side(cells_per_side).second;
      }

      double finest_cell_size(const unsigned int level) const override
      {
        return 1.0 / (cells_per_side << level);
      }

      std::string place_initial_surface(Surface &surface, const InitialShape &shape) const override
      {
        if (shape.shape == "bump")
          {
            const double a1 = set_bump(surface, shape.bump_radius, shape.bump_area);
            std::ostringstream line;
            line << "Bump amplitude a1 = " << a1 << " for area " << shape.bump_area;
            return line.str();
          }
        if (shape.shape == "cosine modes")
          set_cosine_modes(surface, parse_cosine_modes(shape.cosine_modes, "Initial shape/Cosine modes"));
        else if (shape.shape == "expression")
          set_displacement_expression(surface, shape.displacement_expression, "Initial shape/Displacement expression");
        return "";
      }

      double enclosed_volume(const Surface &) const override { return 0.0; }

      BudShape measure_domain(const Surface &surface, const Vector &phi_ghosted) const override
      {
        return measure_bud(surface, phi_ghosted);
      }

      void record_shape_statistics(const Surface &surface, const Geometry &, const Vector &phi_ghosted,
                                   const EnergyTerms &, Statistics &stats) const override
      {
        // Spectra of the patch (analysis/fourier_modes.h): <|h_k|^2> and <|phi_k|^2> over the
        // shells |k|^2 = 1 and 2.
        const LowestModes height = lowest_mode_powers(surface.vector_space(), surface.displacement(), 2);
        const LowestModes phase  = lowest_mode_powers(surface.scalar_space(), phi_ghosted, 0);
        stats.set("height_mode_1", height.shell_1);
        stats.set("height_mode_2", height.shell_2);
        stats.set("phase_mode_1", phase.shell_1);
        stats.set("phase_mode_2", phase.shell_2);
      }

      StructureFactor phase_structure_factor(const Surface &surface, const Vector &phi_ghosted,
                                             const unsigned int n) const override
      {
        return patch_structure_factor(surface.scalar_space(), phi_ghosted, n);
      }

      std::vector<std::string> summary_columns() const override { return {}; }

    private:
      const unsigned int cells_per_side;
    };

    /// A closed surface (MODEL.md section 8): sphere, ellipsoid or a mesh file.
    class ClosedVesicle : public MembraneTopology
    {
    public:
      explicit ClosedVesicle(const ReferenceSurfaceOptions &reference)
        : reference(reference)
      {}

      std::string name() const override { return "Vesicle (" + reference.type + ")"; }
      bool        periodic() const override { return false; }
      bool        encloses_volume() const override { return true; }

      void make_mesh(Triangulation &triangulation) override
      {
        make_closed_surface(triangulation, reference);
        input_level     = 0; // the input mesh is the coarse mesh
        input_cell_size = std::sqrt(dealii::GridTools::volume(triangulation) / triangulation.n_global_active_cells());
      }

      double finest_cell_size(const unsigned int level) const override
      {
        return input_cell_size / (1u << level);
      }

      std::string place_initial_surface(Surface &surface, const InitialShape &shape) const override
      {
        // Refined initial meshes: onto the sphere/ellipsoid, not on the bilinear cells.
        set_analytic_displacement(surface, reference,
                                  shape.shape == "expression" ? shape.displacement_expression : "",
                                  "Initial shape/Displacement expression");
        return "";
      }

      double enclosed_volume(const Surface &surface) const override { return Membrane::enclosed_volume(surface); }

      BudShape measure_domain(const Surface &surface, const Vector &phi_ghosted) const override
      {
        // The patch's height has no meaning on a vesicle; the domain protrusion and the neck,
        // measured along the vesicle's domain axis, feed the outcome classification.
        const VesicleDomain domain = measure_vesicle_domain(surface, phi_ghosted);
        BudShape            shape;
        shape.domain_area       = domain.domain_area;
        shape.domain_protrusion = domain.protrusion;
        shape.neck_radius       = domain.neck_radius;
        shape.bud_radius        = domain.bud_radius;
        shape.neck_ratio        = domain.neck_ratio;
        return shape;
      }

      void record_shape_statistics(const Surface &surface, const Geometry &geometry, const Vector &,
                                   const EnergyTerms &energy, Statistics &stats) const override
      {
        // m = -M / (8 pi R_0), M = integral H ds: 1 on a sphere (physics/terms/area_difference.h).
        const auto [M, A] = total_mean_curvature_and_area(surface, geometry);
        stats.set("reduced_area_difference", -M / (8 * M_PI * std::sqrt(A / (4 * M_PI))));
        stats.set("area_difference_energy", energy.area_difference);
        stats.set("integral_K", integrate(surface, geometry.gauss_curvature));
        stats.set("gauss_map_area", gauss_map_area(surface, geometry.normal));
        // The shape spectrum (analysis/spherical_modes.h): the mean of u_lm^2 over m, which
        // Milner and Safran predict as k_BT / (kappa (l - 1)(l + 2)(l (l + 1) + Sigma R^2 / kappa)).
        // l <= 6: the two-parameter fit of (kappa, Sigma) needs the modes where bending dominates.
        const std::vector<double> shape_power = spherical_mode_powers(surface, 6);
        for (unsigned int l = 2; l <= 6; ++l)
          stats.set("shape_mode_" + std::to_string(l), shape_power[l] / (2 * l + 1));
      }

      StructureFactor phase_structure_factor(const Surface &surface, const Vector &phi_ghosted,
                                             const unsigned int n) const override
      {
        return sphere_structure_factor(surface, phi_ghosted, n);
      }

      std::vector<std::string> summary_columns() const override { return {"integral_K", "gauss_map_area"}; }

    private:
      const ReferenceSurfaceOptions reference;
      double                        input_cell_size = 0;
    };
  } // namespace

  std::unique_ptr<MembraneTopology> MembraneTopology::create(const ReferenceSurfaceOptions &reference,
                                                             const unsigned int             cells_per_side)
  {
    if (reference.closed())
      return std::make_unique<ClosedVesicle>(reference);
    return std::make_unique<PeriodicPatch>(cells_per_side);
  }
} // namespace Membrane
