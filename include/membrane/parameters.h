#pragma once
// Every input of a run, declared with a default, a pattern and documentation
// (meaning, scale, the paper's symbol) in a deal.II ParameterHandler.

#include <membrane/analysis/bud_shape.h>
#include <membrane/cahn_hilliard.h>
#include <membrane/physics/initial_phase.h>
#include <membrane/physics/material.h>
#include <membrane/shape_solver.h>
#include <membrane/solvers/linear_solver.h>
#include <membrane/surface/adaptivity.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <utility>
#include <vector>

namespace Membrane
{
  struct Parameters
  {
    // Mesh
    unsigned int      cells_per_side = 32;
    AdaptivityOptions adaptivity;
    // Initial shape
    std::string shape = "flat";
    double      bump_radius = 0.5, bump_area = 1.3;
    std::string cosine_modes, displacement_expression;
    // Physics
    Material            material;
    InitialPhaseOptions initial_phase;
    // Time stepping
    double       end_time = 0.01, time_step = 1e-4;
    unsigned int max_steps = 1000000;
    bool         adaptive = true;
    double       min_time_step = 1e-9, max_time_step = 1e-2, growth_factor = 1.25, accuracy_tolerance = 0;
    double       energy_tolerance = 1e-10, equilibrium_rate = 0, min_cell_quality = 0.1;
    // Shape
    bool         evolve_shape = true;
    ShapeOptions shape_options;
    double       grid_control_weight = 0.1;
    // Outcome
    OutcomeCriteria outcome;
    double          pinch_off_radius = 0.03;
    // Checkpoints
    unsigned int checkpoint_interval = 0;
    std::string  resume_from;
    // Solvers
    CahnHilliardOptions cahn_hilliard;
    LinearSolverOptions linear_solver;
    // Output
    std::string output_directory = "results";
    double      output_interval  = 0;
    bool        write_vtu        = true;

    static void declare(dealii::ParameterHandler &prm);
    /// Reads every entry and checks the combinations; throws with a message
    /// naming the entry and the accepted values.
    void parse(dealii::ParameterHandler &prm);
  };

  /// Read a .prm file into `prm` (declared) and `parameters`, then apply the
  /// overrides ("Section/Subsection/Entry", value) in order; a clean message for
  /// unknown entries and values out of range.
  void read_parameter_file(const std::string &filename, dealii::ParameterHandler &prm, Parameters &parameters,
                           const std::vector<std::pair<std::string, std::string>> &overrides = {});
} // namespace Membrane
