#include <membrane/solvers/vector_access.h>
#include <membrane/surface/adaptivity.h>

#include <deal.II/base/geometry_info.h>

#include <algorithm>
#include <cmath>

namespace Membrane
{
  using namespace dealii;

  void declare_adaptivity_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Maximum refinement level", "0", Patterns::Integer(0, 6),
                      "Local refinement: levels of refinement allowed above the input mesh (Cells per side) where "
                      "the interface or the curvature need them; cells are coarsened back to the input mesh "
                      "where neither does. 0: a uniform mesh that never changes.");
    prm.declare_entry("Adaptivity interval", "10", Patterns::Integer(1, 100000),
                      "Accepted steps between scheduled mesh adaptations (with Maximum refinement level > 0); the mesh "
                      "also adapts after any step at which the interface or a strongly curved region has moved into "
                      "cells coarser than the indicators ask for.");
    prm.declare_entry("Interface cells per xi", "1.5", Patterns::Double(0.25, 16),
                      "Cells that hold a sharpened interface (phi varies across them with more than half the "
                      "largest slope 3 / (4 xi) of the equilibrium profile tanh(3 s / (4 xi))) and their "
                      "neighbours are refined until their size on the surface is at most xi / this (the "
                      "interface's 10-90 % width is 2.9 xi). A broad profile that has not sharpened yet is not "
                      "refined for.");
    prm.declare_entry("Interface phi", "0.9", Patterns::Double(0.1, 0.999),
                      "A vertex with |phi| below this belongs to the diffuse interface (for the start-up "
                      "resolution warning, which measures the cells there).");
    prm.declare_entry("Curvature resolution", "0.3", Patterns::Double(0.01, 10),
                      "Cells are refined until h |kappa_max| <= this (h: cell size on the surface, kappa_max: the "
                      "larger principal curvature of the mean H and K of the cell's vertices), so that bud caps "
                      "and necks are resolved.");
    prm.declare_entry("Refinement memory limit", "0", Patterns::Double(0, 1e9),
                      "GB: local refinement stops (the mesh is not refined further, with a warning) when the "
                      "memory of all ranks would exceed this after refining. 0: 80 % of the memory available at "
                      "the time (MemAvailable of /proc/meminfo, summed over the hosts of the ranks).");
    prm.declare_entry("Coarsening tolerance", "3e-3", Patterns::Double(0, 1),
                      "Cells are coarsened (where the indicators allow it) only where that drops no more than this "
                      "interpolation error of the surface: the inner vertices of the four cells lie within this "
                      "fraction of the parent cell's size, along their normals, from where refining the parent again "
                      "would place them (Smooth new vertices). Coarsening changes the bending energy at second order "
                      "in this error (about kappa times its square per parent cell); without the bound the coarsenings "
                      "of a budding run raise the energy by a few percent. 1: no bound (every cell the indicators "
                      "allow is coarsened); 0: never coarsen.");
    prm.declare_entry("Refine broad profiles", "false", Patterns::Bool(),
                      "Before the first step, refine the cells where the initial phi lies in the diffuse range "
                      "(|phi0| < Interface phi at a vertex) to the interface target, with the initial state set from "
                      "its formulas on the finer mesh, and do not coarsen cells while phi there stays in that range. "
                      "A broad start (the bump profile, a random mixture) then sharpens on cells that are already "
                      "fine. Without it the refinements that follow the sharpening each raise the bending energy by "
                      "0.2-0.4 (7.3 at sigma = 1000 to t = 0.05: +0.51, +0.66, +0.97 with 1, 2, 3 levels; with it "
                      "+0.05, +0.22, +0.21, all in coarsenings), at the price of 1.2-1.5 times the cells (cells of the "
                      "curved bump, once refined, stay refined). For convergence studies.");
    prm.declare_entry("Measure carried energy", "false", Patterns::Bool(),
                      "Before each mesh change, also take the next step on the old mesh (a trial that is then "
                      "discarded) and compare its energy with that of the same step on the new mesh: the statistic "
                      "adaptation_energy_carried sums these differences, the energy an adaptation leaves in the state "
                      "once the step has relaxed the mesh-scale modes. adaptation_energy_jump, F right after the "
                      "transfer minus F before, is mostly the bending energy of the new vertices' small offsets from "
                      "the smooth surface, modes of wavelength h that the next implicit step removes (their relaxation "
                      "time (h / pi)^4 / (Shape mobility kappa) is far below tau). Costs one step per adaptation. For "
                      "convergence studies.");
    prm.declare_entry("Smooth new vertices", "true", Patterns::Bool(),
                      "Place the vertices created by refinement on a smooth surface through the old vertices and "
                      "their normals (cubic Hermite edges) instead of on the bilinear surface, whose kinks along the "
                      "old edges the finer mesh would see as bending energy.");
  }

  AdaptivityOptions parse_adaptivity_parameters(ParameterHandler &prm)
  {
    AdaptivityOptions options;
    options.max_level              = prm.get_integer("Maximum refinement level");
    options.interval               = prm.get_integer("Adaptivity interval");
    options.interface_cells_per_xi = prm.get_double("Interface cells per xi");
    options.interface_phi          = prm.get_double("Interface phi");
    options.curvature_resolution   = prm.get_double("Curvature resolution");
    options.smooth_new_vertices    = prm.get_bool("Smooth new vertices");
    options.refine_broad_profiles  = prm.get_bool("Refine broad profiles");
    options.coarsening_tolerance   = prm.get_double("Coarsening tolerance");
    options.memory_limit           = prm.get_double("Refinement memory limit") * 1e9;
    options.measure_carried_energy = prm.get_bool("Measure carried energy");
    return options;
  }
} // namespace Membrane

namespace Membrane
{
  double cell_size(const Surface &surface, const typename Triangulation::active_cell_iterator &cell)
  {
    const auto X = surface.mapping().get_vertices(cell);
    return std::max({X[0].distance(X[1]), X[0].distance(X[2]), X[1].distance(X[3]), X[2].distance(X[3])});
  }

  namespace
  {
    /// Smallest and largest phi over the vertices of a cell.
    std::pair<double, double> phi_bounds(const FieldSpace &scalars,
                                         const typename Triangulation::active_cell_iterator &cell, const LocalValues &phi)
    {
      const auto scalar_cell = scalars.cell(cell);
      double     low = 1e300, high = -1e300;
      for (const unsigned int v : cell->vertex_indices())
        {
          const double value = phi[scalar_cell->vertex_dof_index(v, 0)];
          low                = std::min(low, value);
          high               = std::max(high, value);
        }
      return {low, high};
    }

    /// A vertex with |phi| < interface_phi, or a sign change (a sharp interface inside the cell).
    bool holds_interface(const FieldSpace &scalars, const typename Triangulation::active_cell_iterator &cell,
                         const LocalValues &phi, const double interface_phi)
    {
      const auto [low, high] = phi_bounds(scalars, cell, phi);
      return low < interface_phi && high > -interface_phi;
    }

    double phi_range(const FieldSpace &scalars, const typename Triangulation::active_cell_iterator &cell,
                     const LocalValues &phi)
    {
      const auto [low, high] = phi_bounds(scalars, cell, phi);
      return high - low;
    }

    /// The equilibrium interface phi = tanh(3 s / (4 xi)) has |grad_s phi| = 3 (1 - phi^2) / (4 xi),
    /// at most 3 / (4 xi). A cell across which phi varies by more than half that slope
    /// (range / h > 3 / (8 xi)) holds a sharpened interface: at equilibrium these are the
    /// cells with |phi| < 0.7 on a resolved mesh, and every cell that a sharp interface crosses
    /// on a coarse one; a broad profile that has not sharpened yet (the smooth bump start)
    /// is not steep, and needs no fine cells.
    double relative_steepness(const FieldSpace &scalars, const typename Triangulation::active_cell_iterator &cell,
                              const LocalValues &phi, const double h, const double xi)
    {
      return phi_range(scalars, cell, phi) / h / (3 / (8 * xi));
    }

    /// The larger principal curvature of a cell, |H|/2 + sqrt(H^2/4 - K) of the mean H and K of
    /// its vertices. The mean, not the largest value at a vertex: the projected H and K are
    /// noisy at single vertices (where refinement left a slight kink, next to a coarse-fine
    /// border), and the pointwise maximum flagged a ring of cells around every refined region at
    /// each adaptation, even on a frozen surface, each refinement raising the energy and the
    /// noise for the next one.
    double largest_principal_curvature(const FieldSpace &scalars, const typename Triangulation::active_cell_iterator &cell,
                                       const LocalValues &mean_curvature, const LocalValues &gauss_curvature)
    {
      const auto scalar_cell = scalars.cell(cell);
      double     H = 0, K = 0;
      for (const unsigned int v : cell->vertex_indices())
        {
          const auto dof = scalar_cell->vertex_dof_index(v, 0);
          H += mean_curvature[dof] / cell->n_vertices();
          K += gauss_curvature[dof] / cell->n_vertices();
        }
      return 0.5 * std::abs(H) + std::sqrt(std::max(0.0, 0.25 * H * H - K));
    }
  } // namespace

  bool leaves_resolved_band(const Triangulation &triangulation, const Surface &surface, const Geometry &geometry,
                            const Vector &phi, const double xi, const AdaptivityOptions &options,
                            const unsigned int base_level)
  {
    const FieldSpace &scalars = surface.scalar_space();
    const double      target  = xi / options.interface_cells_per_xi;
    bool              leaves  = false;
    const LocalValues phi_values(phi), H(geometry.mean_curvature), K(geometry.gauss_curvature);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && cell->level() - base_level < options.max_level)
        {
          // A margin of 1.5 on the steepness, so that a sharpening interface does not
          // trigger an adaptation every step.
          const double h = cell_size(surface, cell);
          if ((h > target && relative_steepness(scalars, cell, phi_values, h, xi) > 1.5) ||
              h * largest_principal_curvature(scalars, cell, H, K) > 2 * options.curvature_resolution)
            {
              leaves = true;
              break;
            }
        }
    return Utilities::MPI::logical_or(leaves, triangulation.get_communicator());
  }

  std::array<Point<spacedim>, 5> refined_vertices(const std::array<Point<spacedim>, 4>     &corner,
                                                  const std::array<Tensor<1, spacedim>, 4> &normal)
  {
    const auto midpoint = [&](const unsigned int a, const unsigned int b) {
      const Tensor<1, spacedim> chord = corner[b] - corner[a];
      return Point<spacedim>(0.5 * (corner[a] + corner[b]) +
                             ((normal[b] * chord) * normal[b] - (normal[a] * chord) * normal[a]) / 8);
    };
    const Point<spacedim> m01 = midpoint(0, 1), m02 = midpoint(0, 2), m13 = midpoint(1, 3), m23 = midpoint(2, 3);
    Point<spacedim>       centre;
    for (unsigned int i = 0; i < 4; ++i)
      centre -= 0.25 * corner[i];
    centre += 0.5 * (m01 + m02 + m13 + m23);
    return {{m01, m02, m13, m23, centre}};
  }

  namespace
  {
    /// The geometric interpolation error that coarsening the children of `parent` (all active)
    /// would drop: the largest distance of the five inner vertices from where refining the
    /// parent again would place them (refined_vertices), along the vertex's normal, relative
    /// to the parent's size. Only the normal part changes the surface: a tangential offset is a
    /// different parametrization of the same surface. Graph-like placement (the initial shapes'
    /// formulas) and grid control move vertices tangentially by about h^2 kappa |slope| / 8 from
    /// the Hermite points, which is above the tolerance on a sloped bump and held every family
    /// of an initial refinement from coarsening.
    double coarsening_error(const Surface &surface, const typename Triangulation::cell_iterator &parent,
                            const LocalValues &normals)
    {
      const FieldSpace &vectors = surface.vector_space();
      // Parent corner i is vertex i of child i; the edge midpoints 0-1, 0-2 are vertices 1, 2 of
      // child 0, the midpoints 1-3, 2-3 vertices 1, 2 of child 3, the centre vertex 3 of child 0.
      const auto position = [&](const unsigned int c, const unsigned int v) {
        return surface.mapping().get_vertices(parent->child(c))[v];
      };
      const auto normal = [&](const unsigned int c, const unsigned int v) {
        const auto cell = vectors.cell(typename Triangulation::active_cell_iterator(parent->child(c)));
        Tensor<1, spacedim> n;
        for (unsigned int d = 0; d < spacedim; ++d)
          n[d] = normals[cell->vertex_dof_index(v, d)];
        return n;
      };
      const std::array<Point<spacedim>, 4> corner = {{position(0, 0), position(1, 1), position(2, 2), position(3, 3)}};
      const auto predicted = refined_vertices(corner, {{normal(0, 0), normal(1, 1), normal(2, 2), normal(3, 3)}});
      const double size = std::max({corner[0].distance(corner[1]), corner[0].distance(corner[2]),
                                    corner[1].distance(corner[3]), corner[2].distance(corner[3])});
      const auto offset = [&](const unsigned int c, const unsigned int v, const Point<spacedim> &p) {
        return std::abs((position(c, v) - p) * normal(c, v));
      };
      return std::max({offset(0, 1, predicted[0]), offset(0, 2, predicted[1]), offset(3, 1, predicted[2]),
                       offset(3, 2, predicted[3]), offset(0, 3, predicted[4])}) /
             size;
    }

    /// Clears the coarsening flags of every family whose coarsening would drop more than the
    /// tolerance (coarsening_error), and of families that would not coarsen as a whole. The
    /// surface only: the energy jumps of coarsening in budding runs were 95 % bending.
    void limit_coarsening(Triangulation &triangulation, const Surface &surface, const Geometry &geometry,
                          const double tolerance)
    {
      if (tolerance >= 1)
        return;
      if (tolerance <= 0)
        {
          for (const auto &cell : triangulation.active_cell_iterators())
            cell->clear_coarsen_flag();
          return;
        }
      const LocalValues normals(geometry.normal);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned() && cell->coarsen_flag_set() && cell->level() > 0 && cell->parent()->child(0) == cell)
          {
            const auto parent = cell->parent();
            bool       family = true;
            for (unsigned int c = 0; c < parent->n_children(); ++c)
              family = family && parent->child(c)->is_active() && parent->child(c)->is_locally_owned() &&
                       parent->child(c)->coarsen_flag_set();
            if (!family || coarsening_error(surface, parent, normals) > tolerance)
              for (unsigned int c = 0; c < parent->n_children(); ++c)
                if (parent->child(c)->is_active())
                  parent->child(c)->clear_coarsen_flag();
          }
    }
  } // namespace

  double largest_relative_steepness(const Surface &surface, const Vector &phi, const double xi)
  {
    double            local = 0;
    const LocalValues phi_values(phi);
    for (const auto &cell : surface.scalar_space().dof_handler().get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        local = std::max(local, relative_steepness(surface.scalar_space(), cell, phi_values, cell_size(surface, cell), xi));
    return Utilities::MPI::max(local, surface.scalar_space().communicator());
  }

  double largest_curvature_per_cell(const Triangulation &triangulation, const Surface &surface, const Geometry &geometry)
  {
    double            local = 0;
    const LocalValues H(geometry.mean_curvature), K(geometry.gauss_curvature);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        local = std::max(local, cell_size(surface, cell) * largest_principal_curvature(surface.scalar_space(), cell, H, K));
    return Utilities::MPI::max(local, triangulation.get_communicator());
  }

  double interface_cell_size(const Surface &surface, const Vector &phi, const double xi,
                             const AdaptivityOptions &options, const unsigned int base_level)
  {
    const double      target = xi / options.interface_cells_per_xi;
    double            local  = 0;
    const LocalValues phi_values(phi);
    for (const auto &cell : surface.scalar_space().dof_handler().get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned() && holds_interface(surface.scalar_space(), cell, phi_values, options.interface_phi))
        {
          double       h     = cell_size(surface, cell);
          unsigned int level = cell->level() - base_level;
          for (; h > target && level < options.max_level; ++level)
            h /= 2;
          local = std::max(local, h);
        }
    return Utilities::MPI::max(local, surface.scalar_space().communicator());
  }

  std::pair<unsigned int, unsigned int> mark_cells(Triangulation &triangulation, const Surface &surface,
                                                   const Geometry &geometry, const Vector &phi,
                                                   const double xi, const AdaptivityOptions &options,
                                                   const unsigned int base_level, const bool initial_state)
  {
    const FieldSpace &scalars = surface.scalar_space();
    // The band: cells that hold a sharpened interface (relative_steepness > 1) and their
    // vertex neighbours, so that the interface stays inside refined cells between
    // adaptations. Steepness rather than |phi| < Interface phi: a broad profile (the smooth
    // bump start, before the interface has sharpened) needs no fine cells, and refining it
    // to the interface target at every adaptation cost most of an adaptive run's time in its
    // first steps. On the initial mesh, with Refine broad profiles, the diffuse range counts
    // too: refining there while the interface sharpens raised the bending energy at each
    // refinement (new vertices placed from the normals of a mesh that is still coarse).
    const bool broad = options.refine_broad_profiles;
    Vector                 band = scalars.make_owned();
    dealii::Vector<double> ones(GeometryInfo<dim>::vertices_per_cell);
    ones = 1;
    std::vector<types::global_dof_index> dofs(GeometryInfo<dim>::vertices_per_cell);
    const LocalValues                    phi_values(phi);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() &&
          (relative_steepness(scalars, cell, phi_values, cell_size(surface, cell), xi) > 1 ||
           (broad && initial_state && holds_interface(scalars, cell, phi_values, options.interface_phi))))
        {
          scalars.cell(cell)->get_dof_indices(dofs);
          scalars.constraints().distribute_local_to_global(ones, dofs, band);
        }
    band.compress(VectorOperation::add);
    scalars.constraints().distribute(band);
    const Vector      band_ghosted = scalars.ghosted_copy(band);
    const LocalValues in_band_values(band_ghosted), H(geometry.mean_curvature), K(geometry.gauss_curvature);

    const double target = xi / options.interface_cells_per_xi;
    unsigned int refine = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto scalar_cell = scalars.cell(cell);
          bool       in_band     = false;
          for (const unsigned int v : cell->vertex_indices())
            in_band = in_band || in_band_values[scalar_cell->vertex_dof_index(v, 0)] > 0;
          const double kappa_max = largest_principal_curvature(scalars, cell, H, K);
          const double       h     = cell_size(surface, cell);
          const unsigned int level = cell->level() - base_level;
          const bool refine_here = (in_band && h > target) || h * kappa_max > options.curvature_resolution;
          // Coarsen only where neither indicator would ask for the cell at twice its size,
          // with a margin of 2 so that cells do not flip back and forth.
          const bool coarse_enough = !in_band && relative_steepness(scalars, cell, phi_values, h, xi) < 0.5 &&
                                     2 * h * kappa_max < 0.5 * options.curvature_resolution &&
                                     !(broad && holds_interface(scalars, cell, phi_values, options.interface_phi));
          if (refine_here && level < options.max_level)
            {
              cell->set_refine_flag();
              ++refine;
            }
          else if (!refine_here && coarse_enough && level > 0)
            cell->set_coarsen_flag();
        }
    // Counted after the bound: the flags that remain.
    limit_coarsening(triangulation, surface, geometry, options.coarsening_tolerance);
    unsigned int coarsen = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      coarsen += cell->is_locally_owned() && cell->coarsen_flag_set();
    const MPI_Comm comm = triangulation.get_communicator();
    return {Utilities::MPI::sum(refine, comm), Utilities::MPI::sum(coarsen, comm)};
  }
} // namespace Membrane
