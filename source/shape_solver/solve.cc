// Shape step, solve: set-up of the system's space, one step (assembly, area defect, volume
// coupling, then the LU or the block-preconditioned FGMRES) and the copy of the solution into
// the increment, pressure and curvature fields. Part of ShapeSolver.
#include <membrane/shape_solver.h>
#include <membrane/solvers/vector_access.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <optional>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    constexpr unsigned int pressure_component = ShapeComponents::pressure, curvature_component = ShapeComponents::curvature;
  } // namespace

  ShapeSolver::ShapeSolver(const Triangulation &triangulation, const bool periodic, const CurvatureMass curvature_mass)
    : periodic(periodic)
    , curvature_mass(curvature_mass)
    , space(triangulation, curvature_mass == CurvatureMass::lumped ? 5 : 7)
  {}

  void ShapeSolver::setup()
  {
    space.setup(periodic);
    space.reinit_matrix(matrix);
    rhs = space.make_owned();
    if (solver)
      earlier_factorizations += solver->n_factorizations();
    solver.reset(); // the mesh (and so the pattern) changed
    block_preconditioner.reset();
  }
  ShapeUpdate ShapeSolver::step(const Surface &surface, const Geometry &geometry, const Material &material,
                                const ShapeOptions &options, const LinearSolverOptions &solver_options,
                                const double tau, const Vector &area_defect, const Vector &phi,
                                const Vector &potential, TimerOutput *timer, const VolumeCoupling &volume_term,
                                const ThermalNoise &noise)
  {
    Assert(options.curvature_mass == curvature_mass,
           ExcMessage("the curvature mass of the options must be that of the solver's layout"));
    volume = volume_term;
    {
      std::optional<TimerOutput::Scope> scope;
      if (timer)
        scope.emplace(*timer, "shape assembly");
      assemble(surface, geometry, material, options, tau, phi, potential, noise);
      add_area_defect(surface, area_defect);
      if (volume.active)
        assemble_volume_coupling(surface, geometry, tau * material.shape_mobility);
    }
    this->solver_options = solver_options;
    if (solver_options.type == "block")
      {
        AssertThrow(curvature_mass == CurvatureMass::consistent,
                    ExcMessage("<Linear solver/Type> = block needs <Shape/Curvature mass> = consistent"));
        std::optional<TimerOutput::Scope> scope;
        if (timer)
          scope.emplace(*timer, "shape solve");
        if (!block_preconditioner)
          block_preconditioner = std::make_unique<ShapePreconditioner>();
        block_preconditioner->build(space, matrix, surface, geometry, material, options, tau, phi, periodic);
      }
    else if (!solver)
      solver = std::make_unique<LinearSolver>(solver_options, "shape_");
    return solve(surface, timer);
  }
  void ShapeSolver::linear_solve(Vector &solution, const Vector &right_hand_side, const bool same_matrix)
  {
    if (solver_options.type != "block")
      {
        if (same_matrix)
          solver->solve_again(solution, right_hand_side);
        else
          solver->solve(matrix, solution, right_hand_side);
        return;
      }
    // FGMRES: the preconditioner's inner mass solves are iterations (to 1e-8), not a fixed operator.
    SolverControl        control(solver_options.max_iterations,
                                 solver_options.relative_tolerance * right_hand_side.l2_norm());
    SolverFGMRES<Vector> fgmres(control, SolverFGMRES<Vector>::AdditionalData(krylov_restart));
    solution = 0;
    ++krylov_solves;
    if (right_hand_side.l2_norm() == 0)
      return;
    try
      {
        fgmres.solve(matrix, solution, right_hand_side, *block_preconditioner);
      }
    catch (const SolverControl::NoConvergence &failure)
      {
        AssertThrow(false, ExcMessage("the linear solver (block) did not reach the relative residual " +
                                      std::to_string(solver_options.relative_tolerance) + " in " +
                                      std::to_string(failure.last_step) + " iterations (<Linear solver/Maximum "
                                      "iterations>); it reached " +
                                      std::to_string(failure.last_residual / right_hand_side.l2_norm())));
      }
    krylov_iterations += control.last_step();
  }

  ShapeUpdate ShapeSolver::solve(const Surface &surface, TimerOutput *timer, const bool same_matrix)
  {
    Vector solution = space.make_owned();
    {
      std::optional<TimerOutput::Scope> scope;
      if (timer)
        scope.emplace(*timer, "shape solve");
      linear_solve(solution, rhs, same_matrix);
    }
    const double volume_pressure = volume.active ? apply_volume_coupling(solution, same_matrix) : 0.0;
    space.constraints().distribute(solution);
    const Vector ghosted = space.ghosted_copy(solution);

    ShapeUpdate update{surface.vector_space().make_owned(), surface.scalar_space().make_owned(),
                       surface.scalar_space().make_owned()};
    for (unsigned int c = 0; c < spacedim; ++c)
      copy_component(space, ghosted, c, surface.vector_space(), update.increment, c);
    copy_component(space, ghosted, pressure_component, surface.scalar_space(), update.pressure);
    copy_component(space, ghosted, curvature_component, surface.scalar_space(), update.mean_curvature);
    update.volume_pressure = volume_pressure;
    return update;
  }} // namespace Membrane
