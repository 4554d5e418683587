#pragma once
// What differs between the periodic membrane patch and a closed vesicle in a run: the input
// mesh and the size of its cells, where the initial surface lies, the volume it encloses, how
// a phase domain and its bud are measured, and the shape observables of the statistics.
// The Simulator asks this object instead of branching on the kind of surface.

#include <membrane/analysis/bud_shape.h>
#include <membrane/analysis/structure_factor.h>
#include <membrane/io/statistics.h>
#include <membrane/physics/energy.h>
#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/surface.h>

#include <memory>
#include <string>
#include <vector>

namespace Membrane
{
  class MembraneTopology
  {
  public:
    virtual ~MembraneTopology() = default;

    /// The patch for `Mesh/Reference surface = periodic patch`, a closed vesicle otherwise.
    static std::unique_ptr<MembraneTopology> create(const ReferenceSurfaceOptions &reference,
                                                    unsigned int                  cells_per_side);

    /// "Membrane patch" or "Vesicle (<reference surface>)", for the start-up line.
    virtual std::string name() const = 0;
    /// Whether the spaces are periodic (the patch) or the surface is closed.
    virtual bool periodic() const = 0;
    /// Whether the membrane encloses a volume (and the volume columns are recorded).
    virtual bool encloses_volume() const = 0;
    /// Builds the input mesh into the empty triangulation.
    virtual void make_mesh(Triangulation &triangulation) = 0;
    /// Refinement level of the input mesh's cells in the triangulation (the patch's unit
    /// square is built from a coarser one).
    unsigned int base_level() const { return input_level; }
    /// Size of the finest cells `level` refinements above the input mesh: the scale of the
    /// shape increments in step control.
    virtual double finest_cell_size(unsigned int level) const = 0;
    /// The entries of Initial shape.
    struct InitialShape
    {
      std::string shape; ///< flat, bump, cosine modes or expression
      double      bump_radius = 0.5, bump_area = 1.3;
      std::string cosine_modes, displacement_expression;
    };
    /// The initial surface. The patch: the unit square, flat, with the bump, the cosine modes
    /// or the displacement expression 'Dx; Dy; Dz' in x, y (periodic). A closed mesh: on its
    /// analytic surface, plus the expression in x, y, z of that surface (the input checks refuse
    /// the patch's other shapes). Returns a line for the log ("" if none).
    virtual std::string place_initial_surface(Surface &surface, const InitialShape &shape) const = 0;
    /// The enclosed volume V (0 for the patch).
    virtual double enclosed_volume(const Surface &surface) const = 0;
    /// The phase domain and its bud, for the statistics and the outcome classification.
    virtual BudShape measure_domain(const Surface &surface, const Vector &phi_ghosted) const = 0;
    /// The shape observables of a statistics row: the patch's Fourier spectra, the vesicle's
    /// area difference, integral K, Gauss-map area and spherical-harmonic spectrum.
    virtual void record_shape_statistics(const Surface &surface, const Geometry &geometry, const Vector &phi_ghosted,
                                         const EnergyTerms &energy, Statistics &stats) const = 0;
    /// The structure factor of phi over shells 1 .. n (analysis/structure_factor.h): Fourier
    /// shells |k| on the patch, degrees l on a closed surface.
    virtual StructureFactor phase_structure_factor(const Surface &surface, const Vector &phi_ghosted,
                                                   unsigned int n) const = 0;
    /// The shape columns summary.json repeats.
    virtual std::vector<std::string> summary_columns() const = 0;

  protected:
    unsigned int input_level = 0;
  };
} // namespace Membrane
