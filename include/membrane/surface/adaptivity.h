#pragma once
// Local refinement and coarsening of the surface mesh (MODEL.md section 9).
//
// Indicators per cell, on the current surface (h: the cell's diameter on Gamma):
//  - interface: the cell, or a cell that shares a vertex with it, holds a sharpened
//    interface (phi varies across it by more than h times half the largest slope
//    3 / (4 xi) of the equilibrium profile tanh(3 s / (4 xi))), and
//    h > xi / (Interface cells per xi). A broad profile that has not sharpened yet
//    (the smooth bump start) is not refined for during the run, but (Refine broad profiles)
//    the initial mesh is refined to the same target wherever |phi0| < Interface phi at a
//    vertex, and such cells are not coarsened while phi there stays in that range, so that
//    a broad start sharpens on cells that are already fine;
//  - geometry: h |kappa| > Curvature resolution, with |kappa| the larger principal
//    curvature |H|/2 + sqrt(H^2/4 - K) of the mean H and K of the cell's vertices.
// A cell is refined if an indicator asks for it and its level is below Maximum
// refinement level; it is coarsened (down to the input mesh) if neither indicator
// would ask for it at twice its size, and if coarsening drops no more than the interpolation
// error Coarsening tolerance: the family's five inner vertices lie within that fraction of the
// parent's size, along their normals, from where refining it again would put them
// (refined_vertices). Adaptation happens every Interval steps.

#include <membrane/surface/geometry.h>

#include <deal.II/base/parameter_handler.h>

#include <array>

namespace Membrane
{
  struct AdaptivityOptions
  {
    unsigned int max_level             = 0;    ///< levels above the input mesh (0: uniform, no adaptation)
    unsigned int interval              = 10;   ///< accepted steps between adaptations
    double       interface_cells_per_xi = 1.5; ///< target h <= xi / this where the interface is
    double       interface_phi          = 0.9; ///< |phi| below this at a vertex marks the interface (resolution warning)
    double       curvature_resolution   = 0.3; ///< target h |kappa_max| <= this
    bool         smooth_new_vertices    = true; ///< new vertices on a smooth (Hermite) surface
    bool         refine_broad_profiles  = false; ///< refine |phi0| < interface_phi before the first step, keep it fine
    double       coarsening_tolerance   = 3e-3; ///< largest surface interpolation error (per parent size) a coarsening may drop
    double       memory_limit           = 0;    ///< bytes of all ranks after a refinement (0: 80 % of available)
    bool         measure_carried_energy = false; ///< also step the old mesh, for adaptation_energy_carried

    bool enabled() const { return max_level > 0; }
  };

  /// Entries of the subsection Mesh (the caller enters it).
  void declare_adaptivity_parameters(dealii::ParameterHandler &prm);
  /// Reads them (the caller enters Mesh); throws naming the entry on bad input.
  AdaptivityOptions parse_adaptivity_parameters(dealii::ParameterHandler &prm);
} // namespace Membrane

namespace Membrane
{
  /// Size of a cell on the current surface: its longest edge.
  double cell_size(const Surface &surface, const typename Triangulation::active_cell_iterator &cell);

  /// Largest size (cell_size) of the cells that hold the diffuse interface (a vertex
  /// with |phi| < `Interface phi`, or a sign change) once refined by the interface
  /// indicator: each is halved while it is larger than xi / Interface cells per xi and
  /// below the maximum level (on a uniform mesh: their present size). Over all ranks; 0 if
  /// there is no interface. With a broad initial profile the indicator refines these cells
  /// as the interface sharpens, so this, not their present size, is the resolution of a run.
  double interface_cell_size(const Surface &surface, const Vector &phi_ghosted, double transition_length,
                             const AdaptivityOptions &options, unsigned int base_level);

  /// Where refining a cell with these corners (deal.II order) and unit vertex normals puts its five
  /// new vertices on a smooth surface (Smooth new vertices): the edge midpoints 0-1, 0-2, 1-3, 2-3
  /// at the midpoints of the cubic Hermite curves whose end tangents are the edge projected on the
  /// corners' tangent planes, (A + B)/2 + (T_A - T_B)/8, and the centre by the bilinear (Coons)
  /// blend of these midpoints.
  std::array<dealii::Point<spacedim>, 5> refined_vertices(const std::array<dealii::Point<spacedim>, 4> &corner,
                                                          const std::array<dealii::Tensor<1, spacedim>, 4> &normal);

  /// Set refinement and coarsening flags on the locally owned cells of `triangulation`
  /// (the surface's) by the indicators above; `base_level` is the level of the input
  /// mesh. `initial_state`: the mesh of the initial state, where (with Refine broad
  /// profiles) a broad profile counts as interface. Returns the global numbers of cells
  /// flagged for refinement and coarsening.
  std::pair<unsigned int, unsigned int> mark_cells(Triangulation &triangulation, const Surface &surface,
                                                   const Geometry &geometry, const Vector &phi_ghosted,
                                                   double transition_length, const AdaptivityOptions &options,
                                                   unsigned int base_level, bool initial_state = false);

  /// The largest h kappa_max over the cells (h the cell size, kappa_max the larger principal
  /// curvature of the cell's mean H and K): the angle of arc, in radians, that the most bent
  /// cell spans.
  double largest_curvature_per_cell(const Triangulation &triangulation, const Surface &surface,
                                    const Geometry &geometry);

  /// The largest relative steepness of phi over the cells (over all ranks): the variation of phi
  /// across a cell divided by h and by half the largest slope 3 / (4 xi) of the equilibrium
  /// interface. Above 1 a cell holds a sharpened interface; about 0 where phi is uniform.
  double largest_relative_steepness(const Surface &surface, const Vector &phi_ghosted, double transition_length);

  /// True (on every rank) when the mesh no longer resolves what mark_cells() refines for,
  /// between two scheduled adaptations: a cell below the maximum level holds the
  /// interface and is coarser than the interface target, or bends by more than twice the
  /// curvature resolution (a neck or cap has moved into coarse cells). Cheap: one pass
  /// over the cells.
  bool leaves_resolved_band(const Triangulation &triangulation, const Surface &surface, const Geometry &geometry,
                            const Vector &phi_ghosted, double transition_length, const AdaptivityOptions &options,
                            unsigned int base_level);
} // namespace Membrane
