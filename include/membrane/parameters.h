#pragma once
// Every input of a run, declared with a default, a pattern and documentation
// (meaning, scale, the paper's symbol) in a deal.II ParameterHandler.

#include <membrane/analysis/bud_shape.h>
#include <membrane/cahn_hilliard_options.h>
#include <membrane/physics/initial_phase.h>
#include <membrane/physics/material.h>
#include <membrane/physics/thermal_noise.h>
#include <membrane/physics/volume.h>
#include <membrane/shape_options.h>
#include <membrane/solvers/linear_solver_options.h>
#include <membrane/surface/adaptivity.h>
#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/mesh_motion.h>

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cmath>
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
    ReferenceSurfaceOptions reference; ///< periodic patch or a closed surface (vesicle_parameters.cc)
    VolumeOptions           volume;    ///< the enclosed volume of a closed surface
    // Initial shape
    std::string shape = "flat";
    double      bump_radius = 0.5, bump_area = 1.3;
    std::string cosine_modes, displacement_expression;
    // Physics
    Material            material;
    ThermalNoise        thermal; ///< k_BT and seed (its step is set by each step)
    InitialPhaseOptions initial_phase;
    // Time stepping
    double       end_time = 0.01, time_step = 1e-4;
    unsigned int max_steps = 1000000;
    bool         adaptive = true;
    double       min_time_step = 1e-9, max_time_step = 1e-2, growth_factor = 1.25, accuracy_tolerance = 0;
    double       energy_tolerance = 1e-10, equilibrium_rate = 0, min_cell_quality = 0.1;
    double       equilibrium_time = 0; // how long the rate must stay below equilibrium_rate
    double       max_increment_cells = 1; // largest vertex move in one step, in cell sizes (0: no bound)
    // Shape
    bool         evolve_shape = true;
    ShapeOptions shape_options;
    double       grid_control_weight = 0.1; ///< per step; with a rate, the largest per step
    double       grid_control_rate   = 0;   ///< per unit time (0: the weight per step, whatever tau)
    MeshMotion   mesh_motion         = MeshMotion::lagrangian; ///< what the vertices follow (surface/mesh_motion.h)

    /// Grid-control sweeps of a step of length tau (docs/model.md, grid control): with a
    /// rate r, a step whose weight r tau exceeds Grid control weight is split into sweeps of
    /// at most that weight, so that the mesh is smoothed at the rate r whatever tau.
    unsigned int grid_control_sweeps_of_step(const double tau) const
    {
      if (grid_control_rate <= 0 || grid_control_weight <= 0)
        return 1;
      return static_cast<unsigned int>(std::max(1.0, std::ceil(grid_control_rate * tau / grid_control_weight - 1e-12)));
    }

    /// The weight of each grid-control sweep of a step of length tau.
    double grid_control_weight_of_step(const double tau) const
    {
      return grid_control_rate > 0 ?
               std::min(grid_control_weight, grid_control_rate * tau / grid_control_sweeps_of_step(tau)) :
               grid_control_weight;
    }
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
    unsigned int structure_factor_shells = 0; ///< phase_shell_n columns (analysis/structure_factor.h)

    static void declare(dealii::ParameterHandler &prm);
    /// Reads every entry and checks the combinations; throws with a message
    /// naming the entry and the accepted values.
    void parse(dealii::ParameterHandler &prm);
  };

  /// Read a .prm file into `prm` (declared) and `parameters`, then apply the
  /// overrides ("Section/Subsection/Entry", value) in order; a clean message for
  /// unknown entries and values out of range.
  /// The input file must be a readable regular file, an override's entry path
  /// "Section/.../Entry" must have no empty part. An empty `filename` means no file (the
  /// defaults and the overrides only). Messages about an override start with
  /// `override_prefix` (the command line's "--set ").
  void read_parameter_file(const std::string &filename, dealii::ParameterHandler &prm, Parameters &parameters,
                           const std::vector<std::pair<std::string, std::string>> &overrides = {},
                           const std::string &override_prefix = "--set ");

  // ---- validation helpers (docs/reliability.md) ----------------------------------------

  /// Throws dealii::ExcMessage unless `filename` names a readable regular file (the
  /// message says what it is instead: missing, a directory, unreadable, ...).
  void check_input_file(const std::string &filename, const std::string &what = "parameter file");

  /// Splits an override "Section/Subsection/Entry" into its parts (each trimmed);
  /// throws dealii::ExcMessage naming the override if the path or any part is empty.
  std::vector<std::string> split_entry_path(const std::string &path, const std::string &override_text);

  /// Combinations that pass each entry's pattern but make no sense together; called at
  /// the end of Parameters::parse. Throws dealii::ExcMessage naming the entries and the
  /// accepted range:
  ///  - a phase-dependent bending rigidity kappa(phi) <= 0 (or not finite) anywhere on
  ///    phi in [-1, 1] (sampled at 201 points, any law);
  ///  - a Gaussian rigidity outside -2 kappa(phi) < kappa_G(phi) <= 0 anywhere on [-1, 1]
  ///    (the bending energy 1/2 kappa (H - H0)^2 + kappa_G K is bounded below only there);
  ///  - a prescribed initial mass (Prescribe mass = true) with |Mass| >= the initial area
  ///    (exact for flat and bump; for cosine modes the upper bound sqrt(1 + G^2) with
  ///    G = sum 2 pi |A| |k|; not checked for Shape = expression);
  ///  - an empty Output/Directory.
  void check_parameter_combinations(const Parameters &parameters);

  /// Largest |Mass| that the initial shape can carry, if known before the mesh is built:
  /// the area of the initial surface (flat: 1, bump: Bump area) or an upper bound of it
  /// (cosine modes); 0 when unknown (expression).
  double initial_area_bound(const Parameters &parameters, bool *exact = nullptr);

  /// Memory a run needs, estimated before the mesh is built (docs/reliability.md):
  /// V = (Cells per side + 1)^2 vertices. With the direct solver the LU factors dominate:
  /// 400 factor entries per unknown at 32 x 32 cells (measured: 3.05e6 entries for the
  /// 7 unknowns per vertex of the shape system), growing like log2(V) (nested dissection:
  /// fill ~ N log N), 12 bytes each, for the shape system (7 unknowns per vertex, when
  /// the shape evolves) and the Cahn-Hilliard system (2 per vertex):
  ///   bytes = 1.5 * 12 * 400 * log2(V) / log2(1089) * V * (7 + 2) + 200 MB per MPI rank.
  /// With GMRES: 1.5 * 24 kB per vertex (8 kB without the shape system) + 200 MB per rank.
  /// The factor 1.5 is the safety factor; measured peaks are 77-90 % of the estimate
  /// (32 to 256 cells per side, one rank). The estimate is for the input mesh: local
  /// refinement (Maximum refinement level > 0) adds to it; Simulator::refinement_fits()
  /// checks each refinement against the memory the run uses.
  struct MemoryEstimate
  {
    double vertices = 0;
    double bytes    = 0;
  };
  /// `cells_per_side` > 0 replaces Mesh/Cells per side (to find the largest mesh that fits).
  MemoryEstimate estimate_memory(const Parameters &parameters, unsigned int mpi_ranks = 1,
                                 unsigned int cells_per_side = 0);
} // namespace Membrane
