// Stage 2 of a step: the shape step X^m -> X~ = X^m + W (ShapeSolver, MODEL.md section 4) at
// the frozen geometry of Gamma^m, with the pressure gamma of the local area constraint and the
// volume term of closed surfaces. Part of Simulator.
#include <membrane/simulator.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  bool Simulator::add_shape_increment(const ShapeUpdate &part)
  {
    if (!std::isfinite(part.increment.l2_norm()) || !std::isfinite(part.pressure.l2_norm()))
      return false;
    Vector moved = surface.vector_space().make_owned();
    moved        = surface.displacement();
    moved += part.increment;
    surface.set_displacement(moved);
    return true;
  }

  bool Simulator::shape_step(const double tau, const Vector &areas_before, const Vector &target, Vector &gamma)
  {
    // The linearized area row asks for the part of the defect a_target - a^m this step restores.
    Vector defect_of_step = target;
    defect_of_step -= areas_before;
    const ShapeUpdate update = shape_solver.step(surface, geometry, parameters.material, parameters.shape_options,
                                                 parameters.linear_solver, tau, defect_of_step, phi,
                                                 chemical_potential, &timer, volume_term(tau), noise_of_step());
    if (!add_shape_increment(update))
      return false;
    max_increment   = update.increment.linfty_norm();
    step_increment  = update.increment;
    gamma           = update.pressure;
    volume_pressure = update.volume_pressure;
    return true;
  }
} // namespace Membrane
