#pragma once
// The options of the shape step (shape_solver.h): what the parameters configure, without the
// solver itself, so that the parameters and the block preconditioner need not include it.

namespace dealii
{
  class ParameterHandler;
}

namespace Membrane
{
  /// Mass of the curvature rows (shape_solver.h); fixed when the ShapeSolver is built.
  enum class CurvatureMass
  {
    consistent,  ///< seven fields, the reference discretization
    lumped,      ///< five fields: B~ eliminated, the curvature row projected on nu_i
    lumped_full  ///< seven fields of the lumped scheme (verification of `lumped`)
  };

  /// How the shape step takes the force of the terms that have a stress (the line energy).
  enum class LineForce
  {
    potential, ///< normal row H G + sigma xi^2 b(grad phi, grad phi), tangential law Y grad phi (reference)
    stress     ///< the exact derivative of the discrete energy (physics/stress_force.h)
  };

  struct ShapeOptions
  {
    CurvatureMass curvature_mass  = CurvatureMass::consistent;
    double pressure_stabilization = 0.5; ///< delta (0: none)
    double line_stiffness         = 0;   ///< weight of the implicit line-energy stiffness in the tangential law (0: explicit)
    LineForce line_force          = LineForce::potential;
    bool   correct_area           = true;  ///< feed back the defect of the vertex areas
    unsigned int area_corrections = 1;     ///< projections per step onto the area constraint
    double area_tolerance         = 1e-12; ///< no projection below this relative defect
    double area_relaxation_time   = 1e-4;  ///< T_a: a step restores min(1, tau / T_a) of the area defect (0: all)
    unsigned int tangential_area_iterations = 0; ///< largest number of tangential area-correction moves per step (0: none)
    double tangential_area_tolerance = 1e-9;  ///< its target: the largest relative vertex-area error
    bool   correct_mass           = true;  ///< restore integral phi ds after the shape step
  };

  /// The entries of the section Shape that ShapeOptions holds: declared with defaults and
  /// documentation, and read.
  void         declare_shape_parameters(dealii::ParameterHandler &prm);
  ShapeOptions parse_shape_parameters(dealii::ParameterHandler &prm);
} // namespace Membrane
