// Stage: mesh adaptation (MODEL.md section 9), between accepted steps. Marking, transfer of the
// state to the new mesh, the placement of new vertices and the memory guard. Part of Simulator.
#include <membrane/io/memory.h>
#include <membrane/simulator.h>
#include <membrane/solvers/vector_access.h>
#include <membrane/surface/adaptivity.h>
#include <membrane/surface/grid_control.h>

#include <deal.II/distributed/solution_transfer.h>

#include <set>
#include <tuple>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    using CellKey = std::tuple<int, double, double, double>; ///< level and reference centre (x, y, z: closed surfaces)

    CellKey key(const typename Triangulation::cell_iterator &cell)
    {
      const auto c = cell->center();
      return {cell->level(), c[0], c[1], c[2]};
    }

    /// Place the vertices created by refining the cells in `split` on a smooth surface
    /// instead of on the bilinear one (refined_vertices). On a bilinear surface the kinks
    /// along the old edges would show up in the weak mean curvature of the finer mesh as
    /// spurious bending energy.
    void place_new_vertices(const FieldSpace &vectors, const std::set<CellKey> &split, const Vector &normal_ghosted,
                            Vector &displacement_owned)
    {
      const Vector D = vectors.ghosted_copy(displacement_owned);
      std::set<CellKey> done;
      for (const auto &cell : vectors.dof_handler().active_cell_iterators())
        {
          if (!cell->is_locally_owned() || cell->level() == 0 || !split.count(key(cell->parent())) ||
              !done.insert(key(cell->parent())).second)
            continue;
          const auto parent = cell->parent();
          // Position and normal of vertex v of child c, and a setter for new vertices.
          const auto position = [&](const unsigned int c, const unsigned int v) {
            Point<spacedim> x = parent->child(c)->vertex(v);
            for (unsigned int d = 0; d < spacedim; ++d)
              x[d] += D[parent->child(c)->vertex_dof_index(v, d)];
            return x;
          };
          const auto normal = [&](const unsigned int c, const unsigned int v) {
            Tensor<1, spacedim> n;
            for (unsigned int d = 0; d < spacedim; ++d)
              n[d] = normal_ghosted[parent->child(c)->vertex_dof_index(v, d)];
            return n;
          };
          const auto set = [&](const unsigned int c, const unsigned int v, const Point<spacedim> &x) {
            for (unsigned int d = 0; d < spacedim; ++d)
              {
                const auto dof = parent->child(c)->vertex_dof_index(v, d);
                if (vectors.owned().is_element(dof) && !vectors.constraints().is_constrained(dof))
                  displacement_owned[dof] = x[d] - parent->child(c)->vertex(v)[d];
              }
          };
          // Parent corner i is vertex i of child i. Edge midpoints: 0-1 is vertex 1 of child 0,
          // 0-2 vertex 2 of child 0, 1-3 vertex 1 of child 3, 2-3 vertex 2 of child 3; the centre
          // is vertex 3 of child 0.
          const auto placed = refined_vertices({{position(0, 0), position(1, 1), position(2, 2), position(3, 3)}},
                                               {{normal(0, 0), normal(1, 1), normal(2, 2), normal(3, 3)}});
          set(0, 1, placed[0]);
          set(0, 2, placed[1]);
          set(3, 1, placed[2]);
          set(3, 2, placed[3]);
          set(0, 3, placed[4]);
        }
      displacement_owned.compress(VectorOperation::insert);
      vectors.constraints().distribute(displacement_owned);
    }
  } // namespace

  bool Simulator::adaptation_due() const
  {
    const AdaptivityOptions &adaptivity = parameters.adaptivity;
    if (!adaptivity.enabled())
      return false;
    if (step % adaptivity.interval == 0)
      return true;
    // Between the scheduled adaptations: as soon as the interface or a strongly curved
    // region (a neck, a bud cap) moves into cells coarser than the indicators ask for.
    // Not while refinement is held back for lack of memory (it would retry every step).
    TimerOutput::Scope scope(timer, "mesh adaptation");
    return !memory_warning_given && leaves_resolved_band(triangulation, surface, geometry, phi,
                                                         parameters.material.transition_length, adaptivity, base_level);
  }

  bool Simulator::adapt_mesh()
  {
    TimerOutput::Scope scope(timer, "mesh adaptation");
    auto [n_refine, n_coarsen] = mark_cells(triangulation, surface, geometry, phi,
                                            parameters.material.transition_length, parameters.adaptivity, base_level);
    if (!refinement_fits(n_refine))
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          cell->clear_refine_flag();
        n_refine = 0;
      }
    if (n_refine + n_coarsen == 0)
      return false;
    if (parameters.adaptivity.measure_carried_energy && !end_time_reached())
      step_old_mesh(std::min(step_control.tau(), parameters.end_time - time));
    const unsigned int cells_before  = triangulation.n_global_active_cells();
    const EnergyTerms  terms_before  = energy;
    const double       energy_before = energy.total();

    // Everything the next step needs: D, phi, the reference areas (as the ratio
    // a_ref / a, which refined cells split and coarsened cells sum in proportion to
    // their areas) and gamma (for the output).
    const Vector displacement = surface.displacement();
    const Vector ratio        = area_ratio();
    const Vector normal       = geometry.normal;
    using Transfer            = parallel::distributed::SolutionTransfer<dim, Vector, spacedim>;
    Transfer                   vector_transfer(surface.vector_space().dof_handler());
    Transfer                   scalar_transfer(surface.scalar_space().dof_handler());
    const std::vector<const Vector *> scalars_in = {&phi, &ratio, &pressure};
    triangulation.prepare_coarsening_and_refinement();
    std::set<CellKey> split;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && cell->refine_flag_set())
        split.insert(key(cell));
    const std::vector<const Vector *> vectors_in = {&displacement, &normal};
    vector_transfer.prepare_for_coarsening_and_refinement(vectors_in);
    scalar_transfer.prepare_for_coarsening_and_refinement(scalars_in);
    triangulation.execute_coarsening_and_refinement();

    setup_spaces_and_solvers();
    const FieldSpace &scalars = surface.scalar_space();
    Vector                moved = surface.vector_space().make_owned(), normal_new = moved;
    std::vector<Vector *> vectors_out = {&moved, &normal_new};
    vector_transfer.interpolate(vectors_out);
    surface.vector_space().constraints().distribute(moved);
    surface.vector_space().constraints().distribute(normal_new);
    if (parameters.adaptivity.smooth_new_vertices)
      place_new_vertices(surface.vector_space(), split, surface.vector_space().ghosted_copy(normal_new), moved);
    surface.set_displacement(moved);
    Vector              phi_new = scalars.make_owned(), ratio_new = scalars.make_owned(),
           pressure_new = scalars.make_owned();
    std::vector<Vector *> scalars_out = {&phi_new, &ratio_new, &pressure_new};
    scalar_transfer.interpolate(scalars_out);
    for (Vector *v : scalars_out)
      scalars.constraints().distribute(*v);

    // Refinement reproduces the Q1 surface and phi exactly; coarsening drops vertices.
    // A constant restores integral phi ds to round-off (as after the ALE remap).
    phi                 = scalars.ghosted_copy(phi_new);
    const double shift  = (initial_mass - integrate(surface, phi)) / surface.area();
    phi_new.add(shift);
    scalars.constraints().distribute(phi_new);
    phi                = scalars.ghosted_copy(phi_new);
    pressure           = scalars.ghosted_copy(pressure_new);
    chemical_potential = scalars.make_ghosted();
    carry_reference_areas(ratio_new);

    geometry     = compute_geometry(surface);
    energy       = compute_energy(surface, geometry, phi, parameters.material);
    cell_quality = min_corner_sine(surface, geometry.normal);
    adaptation_energy_jump += energy.total() - energy_before;
    ++adaptations;
    if (!options.quiet)
      pcout << "Mesh adapted at t = " << time << ": " << cells_before << " -> " << triangulation.n_global_active_cells()
            << " cells (" << n_refine << " flagged for refinement, " << n_coarsen << " for coarsening), energy jump "
            << energy.total() - energy_before << " (bending " << energy.bending - terms_before.bending << ", Gaussian "
            << energy.gaussian - terms_before.gaussian << ", line "
            << energy.gradient + energy.well - terms_before.gradient - terms_before.well << "), mass shift " << shift
            << '\n';
    return true;
  }

  void Simulator::step_old_mesh(const double tau)
  {
    // The trial leaves the refinement and coarsening flags alone; what else it sets (the step's
    // increments, error estimate and solver counts) the next trial sets again.
    const State  before          = save_state();
    const double pressure_before = volume_pressure, quality_before = cell_quality;
    twin_pending                 = try_step(tau).empty(); // a rejected trial has restored the state itself
    twin_tau                     = tau;
    twin_energy                  = energy.total();
    restore_state(before);
    volume_pressure = pressure_before;
    cell_quality    = quality_before;
  }

  void Simulator::compare_with_old_mesh(const double tau)
  {
    if (!twin_pending)
      return;
    twin_pending = false;
    if (tau != twin_tau) // the first trial on the new mesh was rejected: not the same step
      return;
    const double carried = energy.total() - twin_energy;
    adaptation_energy_carried += carried;
    ++carried_measured;
    if (!options.quiet)
      pcout << "Adaptation at t = " << time - tau << ": energy carried after one step " << carried << '\n';
  }

  void Simulator::adapt_initial_mesh()
  {
    if (!parameters.adaptivity.enabled())
      return;
    for (unsigned int round = 0; round < parameters.adaptivity.max_level; ++round)
      {
        const auto [n_refine, n_coarsen] = mark_cells(triangulation, surface, geometry, phi,
                                                      parameters.material.transition_length,
                                                      parameters.adaptivity, base_level, true);
        (void)n_coarsen;
        if (n_refine == 0 || !refinement_fits(n_refine))
          break;
        for (const auto &cell : triangulation.active_cell_iterators())
          cell->clear_coarsen_flag(); // the initial mesh only grows
        triangulation.execute_coarsening_and_refinement();
        setup_spaces_and_solvers();
        set_initial_state(); // from the formulas on the finer mesh, not interpolated
      }
    pcout << "Initial mesh: " << triangulation.n_global_active_cells() << " cells, finest level "
          << finest_level() << " above the input mesh\n";
  }

  bool Simulator::refinement_fits(const unsigned int n_refine)
  {
    if (n_refine == 0 || (!options.check_memory && parameters.adaptivity.memory_limit <= 0))
      return true;
    // The memory of a run grows about in proportion to its cells (matrices, LU factors,
    // vectors); a refined cell becomes four. Scale what the ranks use now, less a
    // process's own fixed part (libraries, MPI; as in estimate_memory()).
    const double fixed_part = 200e6;
    const double resident   = Utilities::MPI::sum(std::max(resident_memory(), 0.0), communicator);
    const double variable   = Utilities::MPI::sum(std::max(resident_memory() - fixed_part, 0.0), communicator);
    const double growth     = variable * 3.0 * n_refine / triangulation.n_global_active_cells();
    const double limit      = parameters.adaptivity.memory_limit;
    const double available  = limit > 0 ? limit - resident : available_memory(communicator);
    if ((limit <= 0 && available < 0) || growth <= (limit > 0 ? 1.0 : 0.8) * available)
      return true;
    if (!memory_warning_given)
      pcout << "Warning: at t = " << time << " refining " << n_refine << " cells would need about "
            << format_bytes(growth) << " more memory, and only " << format_bytes(std::max(available, 0.0))
            << (limit > 0 ? " is left below <Mesh/Refinement memory limit>" : " is available (MemAvailable in /proc/meminfo)")
            << ". The mesh is not refined further while that holds "
            << "(coarsening goes on); the results are those of a coarser mesh than <Mesh/Maximum refinement level> "
            << "asks for. Run on more machines with mpirun, lower the level, raise the limit, or skip this check with "
            << "--no-memory-check.\n";
    memory_warning_given = true;
    return false;
  }

  unsigned int Simulator::finest_level() const
  {
    unsigned int local = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        local = std::max(local, static_cast<unsigned int>(cell->level()));
    return Utilities::MPI::max(local, communicator) - base_level;
  }
} // namespace Membrane
