// The entries of the section Shape that configure the shape step and its constraint
// restoration (ShapeOptions), declared and read here. Evolve shape and the grid-control
// entries of the same section belong to the run (parameters.cc).
#include <membrane/shape_options.h>

#include <deal.II/base/parameter_handler.h>

#include <limits>

namespace Membrane
{
  using namespace dealii;

  void declare_shape_parameters(ParameterHandler &prm)
  {
    const double max_double = std::numeric_limits<double>::max();
    prm.enter_subsection("Shape");
    prm.declare_entry("Pressure stabilization", "0.5", Patterns::Double(0, 1),
                      "delta: weight of the residual of the tangential law in the area equation, which removes "
                      "checkerboard modes of the Q1 surface pressure gamma (0: none).");
    prm.declare_entry("Line stiffness", "0", Patterns::Double(0, 10),
                      "Weight s of the linearly implicit line-energy force in the tangential law. The force "
                      "Y grad phi is taken at Gamma^m; a tangential move W stretches the frozen phi profile and "
                      "changes the gradient energy by sigma xi^2 ((grad_s W)^T grad phi, (grad_s V)^T grad phi) to "
                      "second order, which s = 1 adds implicitly (an O(tau^2) change of the step). Without it the "
                      "explicit force limits tau to about h^2 / (L_X sigma) at a sharp interface. 0: explicit "
                      "(the reference scheme).");
    prm.declare_entry("Line force", "potential", Patterns::Selection("potential|stress"),
                      "How the shape step takes the force of the line energy. potential: the reference scheme, "
                      "H G + sigma xi^2 b^ij d_i phi d_j phi in the normal row and Y grad phi in the tangential law "
                      "(MODEL.md section 4), equal to the variation of F only in the continuum. stress: the exact "
                      "derivative of the discrete line energy with respect to the vertex positions (phi carried by "
                      "the vertices), f = -M_L^-1 dF_l/dX with the vertex areas M_L, in both rows; the tangential "
                      "law keeps Y grad phi of the other terms only. With it a shape step lowers the discrete "
                      "energy to first order in tau, also near an equilibrium (docs/model.md).");
    prm.declare_entry("Curvature mass", "consistent", Patterns::Selection("consistent|lumped"),
                      "Mass matrix of the mean-curvature equation of the shape step. consistent: the reference "
                      "discretization, seven coupled fields per vertex (W, gamma, H, and the two tangential parts "
                      "of the curvature vector). lumped: the mass lumped to the vertices, which lets the "
                      "tangential parts be eliminated exactly: five fields per vertex, and a factorization of the "
                      "shape system about half as expensive (docs/model.md: accuracy against the consistent mass).");
    prm.declare_entry("Correct area", "true", Patterns::Bool(),
                      "Local area conservation against a reference: each step's area equation targets the "
                      "reference area of every vertex (set at the start, carried by grid control), so area errors "
                      "do not accumulate. false: the linearized constraint keeps the current areas (errors drift).");
    prm.declare_entry("Area relaxation time", "1e-4", Patterns::Double(0, max_double),
                      "T_a: a step of length tau restores the fraction min(1, tau / T_a) of the vertex area defect "
                      "a_ref - a (the constraint drift relaxes at the rate 1/T_a). Steps longer than T_a restore it "
                      "whole; shorter ones (a step cut short to land on the end time, a retried step) only in "
                      "proportion, so that their energy change shrinks with tau. At Material/Temperature > 0 the uniform "
                      "part of the defect (the relative defect of the total area) is restored whole in every step, "
                      "its variation in proportion. 0: every step restores it whole.");
    prm.declare_entry("Area projections", "1", Patterns::Integer(0, 5),
                      "Projections of each step's result back onto the local area constraint (same operator, one "
                      "back-substitution each); they remove the O(|grad W|^2) error of the linearized constraint "
                      "within the step. Needs Correct area = true.");
    prm.declare_entry("Tangential area correction", "0", Patterns::Integer(0, 10),
                      "Largest number of tangential vertex moves per step that bring the vertex areas to their "
                      "targets after the area projections (the damped least-squares tangential move of the "
                      "linearized constraint, from a sparse direct solve of a surface Laplacian, factorized once "
                      "per step and reused by the further moves; each kept only if it lowers the largest "
                      "vertex-area error, else retried with more damping; they stop at 1e-9). It removes the "
                      "defects that the pressure-stabilized area row cannot, inside locally refined patches and "
                      "on curved vesicles (7.3: area_error below 1e-6, about 11 % more run time; phase-field "
                      "vesicles: about 1e-5 instead of 1e-3 to 8e-2). With Mesh motion = ale the moves act on the material "
                      "configuration X^m + W, which the mesh does not follow: a tangential flow of the lipids that "
                      "carries phi. 0: none. Needs Correct area = true.");
    prm.declare_entry("Correct mass", "true", Patterns::Bool(),
                      "Restore integral phi ds after each shape step by a constant shift of phi (reported as "
                      "shape_mass_correction). phi rides on the vertices, and the local area error left by the "
                      "pressure stabilization (O(tau) per step) would otherwise change the mass.");
    prm.leave_subsection();
  }

  ShapeOptions parse_shape_parameters(ParameterHandler &prm)
  {
    ShapeOptions options;
    prm.enter_subsection("Shape");
    options.pressure_stabilization = prm.get_double("Pressure stabilization");
    options.line_stiffness         = prm.get_double("Line stiffness");
    options.line_force = prm.get("Line force") == "stress" ? LineForce::stress : LineForce::potential;
    options.curvature_mass = prm.get("Curvature mass") == "lumped" ? CurvatureMass::lumped : CurvatureMass::consistent;
    options.correct_area               = prm.get_bool("Correct area");
    options.area_corrections           = prm.get_integer("Area projections");
    options.area_relaxation_time       = prm.get_double("Area relaxation time");
    options.tangential_area_iterations = prm.get_integer("Tangential area correction");
    options.correct_mass               = prm.get_bool("Correct mass");
    prm.leave_subsection();
    return options;
  }
} // namespace Membrane
