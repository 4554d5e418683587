#include <membrane/parameters.h>
#include <membrane/physics/terms/area_difference.h>
#include <membrane/surface/initial_shapes.h>
#include <membrane/vesicle_parameters.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    const double max_double = std::numeric_limits<double>::max();

    void declare_initial_state(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      prm.declare_entry("Cells per side", "32", Patterns::Integer(2, 4096),
                        "Cells along each side of the periodic unit square (the paper: 32, i.e. 1024 vertices).");
      prm.leave_subsection();

      prm.enter_subsection("Initial shape");
      prm.declare_entry("Shape", "flat", Patterns::Selection("flat|bump|cosine modes|expression"),
                        "flat: the unit square; bump: z = a1 (1 + cos(pi rho/R0)) for rho = |u - (1/2,1/2)| < R0 "
                        "with a1 solved for Bump area; cosine modes: a sum of periodic modes; expression: a "
                        "displacement 'Dx; Dy; Dz' of the reference point (x, y). A closed surface: flat (its "
                        "Reference surface) or expression (added to it).");
      prm.declare_entry("Bump radius", "0.5", Patterns::Double(1e-3, 0.5), "R0: radius of the bump (<= 1/2).");
      prm.declare_entry("Bump area", "1.3", Patterns::Double(1, max_double),
                        "Total surface area the bump amplitude a1 is solved for (the patch projects to area 1).");
      prm.declare_entry("Cosine modes", "0.05 1 1; 0.05 1 -1", Patterns::Anything(),
                        "'A k1 k2 [phase]; ...': z = sum A cos(2 pi (k1 u1 + k2 u2) + phase), integer k1, k2.");
      prm.declare_entry("Displacement expression", "0; 0; 0", Patterns::Anything(),
                        "'Dx; Dy; Dz' in x, y (and pi); must be periodic on the unit square. On a closed surface: "
                        "in x, y, z (and pi) of the point of the Reference surface, added to it (e.g. to break "
                        "the symmetry of an ellipsoid).");
      prm.leave_subsection();
    }

    void declare_numerics(ParameterHandler &prm)
    {
      prm.enter_subsection("Time stepping");
      prm.declare_entry("End time", "0.01", Patterns::Double(0, max_double), "T: the run stops at t = T.");
      prm.declare_entry("Time step", "1e-4", Patterns::Double(1e-14, max_double), "tau: the time step.");
      prm.declare_entry("Maximum steps", "1000000", Patterns::Integer(1), "Stop after this many accepted steps.");
      prm.declare_entry("Adaptive", "true", Patterns::Bool(),
                        "Adapt tau: a step is rejected and retried with tau/2 when the energy would rise (beyond "
                        "Energy tolerance), a cell would fold or invert (Minimum cell quality) or a solve fails; "
                        "after an easy step (vertices moved < 0.2 cells, energy changed < 1 %) tau grows by Growth "
                        "factor. Time step is the first tau. false: fixed tau, and any such failure stops the run.");
      prm.declare_entry("Minimum time step", "1e-9", Patterns::Double(1e-300, max_double),
                        "The run stops (keeping its last good state) when tau would fall below this.");
      prm.declare_entry("Maximum time step", "1e-2", Patterns::Double(1e-300, max_double), "Upper bound of tau.");
      prm.declare_entry("Growth factor", "1.25", Patterns::Double(1, 10), "tau <- factor tau after an easy step.");
      prm.declare_entry("Accuracy tolerance", "0", Patterns::Double(0, 1),
                        "Accuracy-based control of tau (0: off). Each step's local error is estimated from the "
                        "change of the velocities: 1/2 max |W - (tau/tau_prev) W_prev| in cell sizes for the shape "
                        "and 1/2 max |dphi - (tau/tau_prev) dphi_prev| for phi. A step whose estimate exceeds this "
                        "tolerance is rejected; otherwise tau <- tau min(Growth factor, 0.9 sqrt(tolerance / "
                        "estimate)), within the other rules and bounds. An estimate that has not fallen in "
                        "proportion to tau since its last rejection (a stiff mode, not a time-discretization "
                        "error) is accepted and tau held. Use with a Shape/Grid control rate.");
      prm.declare_entry("Energy tolerance", "1e-10", Patterns::Double(0, 1),
                        "Largest accepted relative rise of the free energy in one step (round-off allowance).");
      prm.declare_entry("Equilibrium rate", "0", Patterns::Double(0, max_double),
                        "Stop at equilibrium when the physical step's relative energy rate |F^{m+1} - F^m - W| / (tau |F^m|) "
                        "falls below this (1/time; 0: never); W the work of the volume and area constraints. With "
                        "Shape/Mesh motion = ale, F^{m+1} is the energy before the smoothing (docs/model.md).");
      prm.declare_entry("Equilibrium time", "0", Patterns::Double(0, max_double),
                        "The equilibrium stop needs the energy rate below Equilibrium rate in every accepted step "
                        "for at least this much time (0: one step suffices). After a parameter change on resume, "
                        "or near a turning point, the first steps can be slow before the state starts to move.");
      prm.declare_entry("Minimum cell quality", "0.1", Patterns::Double(-1, 1),
                        "Smallest accepted sine of a cell's corner angle (1: rectangle; 0: degenerate).");
      prm.declare_entry("Maximum increment", "1", Patterns::Double(0, max_double),
                        "Largest displacement of a vertex in one step, in cell sizes of the input mesh (0: no "
                        "bound). A step that moves the surface further is rejected: with Adaptive = true it is "
                        "retried with a smaller tau; with a fixed tau the run stops, keeping its last good state, "
                        "because the time step is too large for the dynamics (the adaptive control keeps moves "
                        "below half a cell).");
      prm.leave_subsection();

      prm.enter_subsection("Shape");
      prm.declare_entry("Evolve shape", "true", Patterns::Bool(),
                        "false: the surface is held fixed and only phi evolves (Cahn-Hilliard on a curved surface).");
      prm.declare_entry("Grid control weight", "0.1", Patterns::Double(0, 0.5),
                        "w: after each step every vertex moves by w times the tangential part of (mean of its edge "
                        "neighbours - itself), and phi is remapped (the paper's alpha = delta = 0.1; 0: no grid "
                        "control, a purely Lagrangian mesh). With a Grid control rate, the largest weight of a sweep.");
      prm.declare_entry("Grid control rate", "0", Patterns::Double(0, max_double),
                        "r, per unit time: a step of length tau moves the grid by the weight r tau, in "
                        "ceil(r tau / Grid control weight) sweeps of equal weight, so that the mesh is smoothed (and "
                        "phi remapped) at a rate that does not depend on the number or length of the steps, and the "
                        "state at a fixed time converges as tau -> 0 (10: the paper's 0.1 per step at "
                        "tau = 1e-2; use it for time-step studies and with Accuracy tolerance). 0: the weight of every "
                        "step is Grid control weight, whatever tau (the paper's rule; the state then depends on the "
                        "number of steps, see docs/time-step-accuracy.md).");
      prm.declare_entry("Mesh motion", "lagrangian", Patterns::Selection("lagrangian|ale"),
                        "What the vertices follow. lagrangian: the lipids (the paper's scheme): the vertices are "
                        "material points, grid control smooths the mesh after each step and is kept only where the "
                        "energy does not rise (always at a temperature). ale: the shape of the membrane, not its "
                        "lipids: the mesh moves with the normal velocity plus grid control's smoothing, and phi and "
                        "the reference areas are carried by the lipids' velocity relative to the mesh (conserving "
                        "integral phi ds exactly); the energy test judges the physical step, and the mesh motion's "
                        "change of the discrete energy is recorded as mesh_motion_energy (docs/model.md, mesh "
                        "motion). Use ale at a temperature and with Line force = stress.");
      prm.leave_subsection();

      prm.enter_subsection("Outcome");
      prm.declare_entry("Flat protrusion", "0.3", Patterns::Double(0, max_double),
                        "The outcome is flat when the phase-A domain protrudes less than this: (domain top - mean "
                        "height of its rim) / (diameter of a sphere of the domain's area); a hemispherical cap is 0.71.");
      prm.declare_entry("Complete neck ratio", "0.4", Patterns::Double(0, 1),
                        "The outcome is a complete bud when a neck has formed: the narrowest closed cross-section "
                        "around the bud axis is narrower than this fraction of the widest section above it "
                        "(radii of circles of equal area). A domain that stands out without such a neck is an "
                        "incomplete bud.");
      prm.declare_entry("Pinch-off radius", "0.03", Patterns::Double(0, max_double),
                        "The run stops (approach to pinch-off) when a complete bud's neck radius falls below this.");
      prm.leave_subsection();

      prm.enter_subsection("Checkpoint");
      prm.declare_entry("Interval", "0", Patterns::Integer(0),
                        "Write checkpoint.txt (atomically) every this many accepted steps and at the end (0: never).");
      prm.declare_entry("Resume from", "", Patterns::Anything(),
                        "A checkpoint file to continue from (same mesh; the statistics continue too). Empty: start at t = 0.");
      prm.leave_subsection();

      prm.enter_subsection("Output");
      prm.declare_entry("Directory", "results", Patterns::DirectoryName(),
                        "Where the run writes its fields, statistics, parameters and summary.");
      prm.declare_entry("Interval", "0", Patterns::Double(0, max_double),
                        "Time between VTU snapshots (0: every step). The first and last states are always written.");
      prm.declare_entry("Write VTU", "true", Patterns::Bool(), "Write the PVD/VTU time series of the surface.");
      prm.declare_entry("Structure factor shells", "0", Patterns::Integer(0, 64),
                        "n > 0: statistics columns phase_shell_1 .. phase_shell_n, the structure factor of phi (the "
                        "mean of |phi_k|^2 over the Fourier shell |k| = n on the patch, over m of phi_lm^2 at degree l "
                        "= n on a closed surface), and phase_wavenumber, its mean wave number (2 pi |k| on the patch, "
                        "l on a closed surface; docs/fluctuations.md). 0: none.");
      prm.leave_subsection();
    }
  } // namespace

  void Parameters::declare(ParameterHandler &prm)
  {
    declare_initial_state(prm);
    prm.enter_subsection("Mesh");
    declare_adaptivity_parameters(prm);
    prm.leave_subsection();
    declare_initial_phase_parameters(prm);
    declare_material_parameters(prm);
    declare_numerics(prm);
    declare_shape_parameters(prm);
    declare_cahn_hilliard_parameters(prm);
    declare_linear_solver_parameters(prm);
    declare_vesicle_parameters(prm);
  }

  void Parameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    cells_per_side = prm.get_integer("Cells per side");
    adaptivity     = parse_adaptivity_parameters(prm);
    prm.leave_subsection();

    prm.enter_subsection("Initial shape");
    shape                   = prm.get("Shape");
    bump_radius             = prm.get_double("Bump radius");
    bump_area               = prm.get_double("Bump area");
    cosine_modes            = prm.get("Cosine modes");
    displacement_expression = prm.get("Displacement expression");
    if (shape == "cosine modes")
      AssertThrow(!parse_cosine_modes(cosine_modes, "Initial shape/Cosine modes").empty(),
                  ExcMessage("Entry <Initial shape/Cosine modes>: Shape = cosine modes needs at least one mode"));
    prm.leave_subsection();

    initial_phase             = parse_initial_phase_parameters(prm);
    initial_phase.bump_radius = bump_radius; // the bump of Type = bump is the Initial shape's

    material = parse_material_parameters(prm);
    prm.enter_subsection("Material");
    thermal = parse_thermal_parameters(prm);
    prm.leave_subsection();

    prm.enter_subsection("Time stepping");
    end_time  = prm.get_double("End time");
    time_step = prm.get_double("Time step");
    max_steps = prm.get_integer("Maximum steps");
    adaptive         = prm.get_bool("Adaptive");
    min_time_step    = prm.get_double("Minimum time step");
    max_time_step    = prm.get_double("Maximum time step");
    growth_factor    = prm.get_double("Growth factor");
    accuracy_tolerance = prm.get_double("Accuracy tolerance");
    energy_tolerance = prm.get_double("Energy tolerance");
    equilibrium_rate = prm.get_double("Equilibrium rate");
    equilibrium_time = prm.get_double("Equilibrium time");
    min_cell_quality = prm.get_double("Minimum cell quality");
    max_increment_cells = prm.get_double("Maximum increment");
    AssertThrow(min_time_step <= time_step && time_step <= max_time_step,
                ExcMessage("Entries <Time stepping/Time step>: need Minimum time step <= Time step <= Maximum time "
                           "step (got " + prm.get("Minimum time step") + ", " + prm.get("Time step") + ", " +
                           prm.get("Maximum time step") + ")"));
    prm.leave_subsection();

    shape_options = parse_shape_parameters(prm);
    prm.enter_subsection("Shape");
    evolve_shape        = prm.get_bool("Evolve shape");
    grid_control_weight = prm.get_double("Grid control weight");
    grid_control_rate   = prm.get_double("Grid control rate");
    mesh_motion         = parse_mesh_motion(prm.get("Mesh motion"));
    prm.leave_subsection();

    prm.enter_subsection("Outcome");
    outcome.flat_protrusion     = prm.get_double("Flat protrusion");
    outcome.complete_neck_ratio = prm.get_double("Complete neck ratio");
    pinch_off_radius            = prm.get_double("Pinch-off radius");
    prm.leave_subsection();

    prm.enter_subsection("Checkpoint");
    checkpoint_interval = prm.get_integer("Interval");
    resume_from         = prm.get("Resume from");
    prm.leave_subsection();

    cahn_hilliard = parse_cahn_hilliard_parameters(prm);
    linear_solver = parse_linear_solver_parameters(prm);

    prm.enter_subsection("Output");
    output_directory = prm.get("Directory");
    output_interval  = prm.get_double("Interval");
    write_vtu        = prm.get_bool("Write VTU");
    structure_factor_shells = prm.get_integer("Structure factor shells");
    prm.leave_subsection();

    parse_vesicle_parameters(prm, *this);
    check_parameter_combinations(*this);
  }

  void read_parameter_file(const std::string &filename, ParameterHandler &prm, Parameters &parameters,
                           const std::vector<std::pair<std::string, std::string>> &overrides,
                           const std::string &override_prefix)
  {
    Parameters::declare(prm);
    if (!filename.empty())
      {
        check_input_file(filename);
        prm.parse_input(filename, "", /*skip_undefined=*/false, /*assert_mandatory_entries_are_found=*/false);
      }
    for (const auto &[path, value] : overrides)
      {
        std::vector<std::string> parts = split_entry_path(path, override_prefix + path + "=" + value);
        const std::string        entry = parts.back();
        parts.pop_back();
        for (const auto &section : parts)
          prm.enter_subsection(section);
        try
          {
            prm.set(entry, value);
          }
        catch (const std::exception &e)
          {
            // deal.II names the accepted pattern in its message ("... the given pattern <[Double 0...]>").
            const std::string text    = e.what();
            const auto        pattern = text.find("pattern <");
            throw ExcMessage(override_prefix + path + "=" + value + ": " +
                             (pattern == std::string::npos ? std::string("no such entry (see --print-parameters)")
                                                           : "the value does not match the accepted " +
                                                               text.substr(pattern, text.find('>', pattern) - pattern + 1)));
          }
        for (std::size_t i = 0; i < parts.size(); ++i)
          prm.leave_subsection();
      }
    parameters.parse(prm);
  }

  void check_input_file(const std::string &filename, const std::string &what)
  {
    namespace fs = std::filesystem;
    const std::string prefix = "Cannot open the " + what + " <" + filename + ">: ";
    AssertThrow(!filename.empty(), ExcMessage("Cannot open the " + what + ": the file name is empty"));
    std::error_code ec;
    const auto      status = fs::status(filename, ec);
    AssertThrow(fs::exists(status), ExcMessage(prefix + "no such file"));
    AssertThrow(!fs::is_directory(status), ExcMessage(prefix + "it is a directory, not a file"));
    AssertThrow(fs::is_regular_file(status),
                ExcMessage(prefix + "it is not a regular file (a device, pipe or socket)"));
    std::ifstream in(filename);
    const int     error = errno;
    AssertThrow(in, ExcMessage(prefix + (error ? std::strerror(error) : "cannot read it")));
  }

  std::vector<std::string> split_entry_path(const std::string &path, const std::string &override_text)
  {
    const auto trim = [](const std::string &text) {
      const auto begin = text.find_first_not_of(" \t");
      if (begin == std::string::npos)
        return std::string();
      return text.substr(begin, text.find_last_not_of(" \t") - begin + 1);
    };
    std::vector<std::string> parts;
    std::size_t              start = 0;
    while (true)
      {
        const auto slash = path.find('/', start);
        parts.push_back(trim(path.substr(start, slash == std::string::npos ? std::string::npos : slash - start)));
        if (slash == std::string::npos)
          break;
        start = slash + 1;
      }
    AssertThrow(!trim(path).empty(),
                ExcMessage(override_text + ": the entry path is empty; write --set 'Section/Entry=value', e.g. "
                                           "--set 'Material/Line tension=630'"));
    AssertThrow(std::none_of(parts.begin(), parts.end(), [](const std::string &p) { return p.empty(); }),
                ExcMessage(override_text + ": the entry path <" + path +
                           "> has an empty part (a leading, trailing or doubled '/'); write --set "
                           "'Section/Entry=value', e.g. --set 'Material/Line tension=630'"));
    return parts;
  }

  MemoryEstimate estimate_memory(const Parameters &parameters, const unsigned int mpi_ranks,
                                 const unsigned int cells_per_side)
  {
    MemoryEstimate estimate;
    const double   n       = cells_per_side > 0 ? cells_per_side : parameters.cells_per_side;
    // A cube-sphere has 6 n^2 + 2 vertices (a file mesh is counted as a patch).
    const bool     cube    = closed_surface_vertices(parameters.reference) > 0;
    const double   v       = cube ? 6 * n * n + 2 : (n + 1) * (n + 1);
    const double   safety  = 1.5;
    const double   per_rank = 200e6;
    estimate.vertices      = v;
    // The shape system has 7 fields per vertex, 5 with the lumped curvature mass.
    const bool   lumped              = parameters.shape_options.curvature_mass == CurvatureMass::lumped;
    const double unknowns_per_vertex = (parameters.evolve_shape ? (lumped ? 5 : 7) : 0) + 2;
    const LinearSolverOptions &solver = parameters.linear_solver;
    if (solver.type == "direct")
      {
        const double fill = 400 * std::log2(std::max(v, 2.0)) / std::log2(1089.0); // factor entries per unknown
        // Measured peaks of a whole run at 256 x 256 (benchmarks/README.md): 0.86x of the
        // exact in-core run with low-rank factors, 0.57x with them out of core. Scaling the
        // factor term by 0.8 and 0.6 keeps the estimate above them (measured/estimate 0.60, 0.64).
        const double share = (solver.low_rank_tolerance > 0 ? 0.8 : 1.0) * (solver.out_of_core ? 0.6 : 1.0);
        estimate.bytes     = safety * 12 * fill * v * unknowns_per_vertex * share;
      }
    else
      estimate.bytes = safety * (parameters.evolve_shape ? 24e3 : 8e3) * v;
    estimate.bytes += per_rank * std::max(1u, mpi_ranks);
    return estimate;
  }
} // namespace Membrane
