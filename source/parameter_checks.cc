// The checks of parameter combinations that no single entry's pattern can express (each names
// the entries involved and the accepted range), and the area bound they use. Part of Parameters.
#include <membrane/parameters.h>
#include <membrane/physics/terms/area_difference.h>
#include <membrane/surface/initial_shapes.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    std::string number(const double value)
    {
      std::ostringstream out;
      out << std::setprecision(6) << value;
      return out.str();
    }

    std::string where(const double phi)
    {
      return "phi = " + number(phi) + (phi == 1 ? " (phase A)" : phi == -1 ? " (phase B)" : "");
    }
  } // namespace

  double initial_area_bound(const Parameters &parameters, bool *exact)
  {
    if (parameters.reference.closed())
      {
        // A sphere's area is known; an ellipsoid's or a file's only after the mesh is built.
        if (exact)
          *exact = parameters.reference.type == "sphere";
        return parameters.reference.type == "sphere"
                 ? 4 * M_PI * parameters.reference.radius * parameters.reference.radius
                 : 0.0;
      }
    if (exact)
      *exact = parameters.shape == "flat" || parameters.shape == "bump";
    if (parameters.shape == "flat")
      return 1;
    if (parameters.shape == "bump")
      return parameters.bump_area;
    if (parameters.shape == "cosine modes")
      {
        // |grad z| <= G = sum 2 pi |A| |k|, so the area integral of sqrt(1 + |grad z|^2) <= sqrt(1 + G^2).
        double gradient = 0;
        for (const auto &mode : parse_cosine_modes(parameters.cosine_modes, "Initial shape/Cosine modes"))
          gradient += 2 * M_PI * std::abs(mode.amplitude) * std::hypot(double(mode.k1), double(mode.k2));
        return std::sqrt(1 + gradient * gradient);
      }
    return 0;
  }

  void check_parameter_combinations(const Parameters &parameters)
  {
    const Material &material = parameters.material;
    // phi on [-1, 1] at 201 points, +-1 and 0 exactly.
    // phi = +1, -1 (the pure phases, first, so that a bad Phase A / B value is named as
    // such), then the 199 points strictly between: 201 samples of [-1, 1].
    constexpr int samples = 200;
    const auto    phi_at  = [](const int k) {
      return k == 0 ? 1.0 : k == 1 ? -1.0 : -1.0 + 2.0 * (k - 1) / samples;
    };

    if (material.bending_rigidity)
      for (int k = 0; k <= samples; ++k)
        {
          const double phi   = phi_at(k);
          const double kappa = material.bending_rigidity->value(phi);
          AssertThrow(std::isfinite(kappa) && kappa > 0,
                      ExcMessage("Entry <Material/Bending rigidity>: kappa must be > 0 in both phases and everywhere "
                                 "between them (phi in [-1, 1]); got kappa = " + number(kappa) + " at " + where(phi) +
                                 ". Accepted: Phase A value > 0 and Phase B value > 0 (linear, tanh), or an "
                                 "Expression that is positive on [-1, 1]"));
        }

    if (material.bending_rigidity && material.gaussian_rigidity)
      for (int k = 0; k <= samples; ++k)
        {
          const double phi     = phi_at(k);
          const double kappa   = material.bending_rigidity->value(phi);
          const double kappa_g = material.gaussian_rigidity->value(phi);
          AssertThrow(std::isfinite(kappa_g) && -2 * kappa < kappa_g && kappa_g <= 0,
                      ExcMessage("Entries <Material/Gaussian rigidity> and <Material/Bending rigidity>: the bending "
                                 "energy 1/2 kappa (H - H0)^2 + kappa_G K is bounded below only for -2 kappa < kappa_G "
                                 "<= 0; at " + where(phi) + " kappa = " + number(kappa) + " and kappa_G = " +
                                 number(kappa_g) + ", outside the accepted range (" + number(-2 * kappa) +
                                 ", 0]. Choose the Gaussian rigidity's Phase A / Phase B values (or Expression) "
                                 "inside (-2 kappa, 0] for every phi in [-1, 1]"));
        }

    const InitialPhaseOptions &phase = parameters.initial_phase;
    if (phase.prescribe_mass)
      {
        bool         exact = false;
        const double area  = initial_area_bound(parameters, &exact);
        if (area > 0)
          AssertThrow(std::isfinite(phase.mass) && std::abs(phase.mass) < area,
                      ExcMessage("Entries <Initial phase/Mass> and <Initial phase/Prescribe mass>: a prescribed mass "
                                 "(integral of phi0 over the initial surface) must lie strictly between -A and A, "
                                 "where A is the initial area (phi = -1 and +1 are the pure phases); " +
                                 std::string(exact ? "A = " + number(area) +
                                                       (parameters.reference.closed() ? " (the sphere)" :
                                                        parameters.shape == "bump" ? " (<Initial shape/Bump area>)"
                                                                                   : " (flat patch)")
                                                   : "A <= " + number(area) + " (upper bound for these <Initial "
                                                                              "shape/Cosine modes>)") +
                                 ", so the accepted range is (" + number(-area) + ", " + number(area) + "); got Mass = " +
                                 number(phase.mass)));
      }

    const LinearSolverOptions &solver = parameters.linear_solver;
    AssertThrow(solver.type == "direct" || (solver.low_rank_tolerance == 0 && !solver.out_of_core),
                ExcMessage("Entries <Linear solver/Low-rank tolerance> and <Linear solver/Out of core> control the "
                           "MUMPS factorization and apply only to <Linear solver/Type> = direct; with Type = " +
                           solver.type + " set Low-rank tolerance = 0 and Out of core = false"));

    AssertThrow(solver.type != "block" || parameters.shape_options.curvature_mass == CurvatureMass::consistent,
                ExcMessage("Entry <Linear solver/Type> = block preconditions the seven-field shape system: it needs "
                           "<Shape/Curvature mass> = consistent (got lumped; use Type = direct with it)"));

    AssertThrow(!parameters.material.area_difference.active() || parameters.reference.closed(),
                ExcMessage("Entry <Material/Area difference/Stiffness> = " +
                           number(parameters.material.area_difference.stiffness) +
                           " > 0 needs a closed vesicle (<Mesh/Reference surface> = sphere, ellipsoid or a mesh "
                           "file): the area difference of the monolayers of an open patch is not defined; or set "
                           "Stiffness = 0"));
    AssertThrow(!parameters.thermal.active() || !parameters.adaptive,
                ExcMessage("Entry <Material/Temperature> = " + number(parameters.thermal.temperature) +
                           " > 0 needs <Time stepping/Adaptive> = false (a fixed tau: the energy fluctuates, so the "
                           "energy-descent control does not apply); or set Temperature = 0"));

    AssertThrow(!parameters.output_directory.empty(),
                ExcMessage("Entry <Output/Directory>: must not be empty; name a directory for the run's files "
                           "(e.g. results/run1)"));
  }
} // namespace Membrane
