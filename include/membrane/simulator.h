#pragma once
// A run: builds the periodic patch or a closed vesicle and its initial state from the
// parameters, advances the time loop, and writes fields, statistics, the parameters used,
// the code version, checkpoints and a summary into the output directory.
//
// One time step m -> m+1 (MODEL.md section 4), one file per stage under source/simulator/:
//   1. phase step: Cahn-Hilliard on Gamma^m, phi^m -> (phi~, Y)          phase_step.cc
//   2. shape step: (X^m, phi^m, Y) -> X~ = X^m + W (ShapeSolver)           shape_step.cc
//   3. area and volume restoration: projections of X~ back onto the local
//      area constraint and a fixed volume (same operator); phi~ rides on
//      the vertices and integral phi ds is restored                        constraint_restoration.cc
//   4. grid control: tangential vertex smoothing with the ALE remap of phi~
//      -> phi^{m+1} (the reference vertex areas follow the vertices), then
//      geometry and energy F^{m+1}. If the moved state would raise the energy
//      above F^m, the move is discarded and X^{m+1} = X~, phi^{m+1} = phi~    grid_control_step.cc
//   5. acceptance: with adaptive stepping a step is rejected (state restored,
//      tau reduced) when F would rise, a cell would fold, a vertex move too far,
//      the local error exceed its tolerance, or a solve fail                step_acceptance.cc
// The time loop and the sequence of the stages are in time_loop.cc; between accepted steps
// come mesh adaptation (adaptation.cc) and output (output.cc); set-up and resume are in
// setup.cc, the messages of a run in trouble in diagnostics.cc.

#include <membrane/analysis/bud_shape.h>
#include <membrane/cahn_hilliard.h>
#include <membrane/membrane_topology.h>
#include <membrane/io/statistics.h>
#include <membrane/parameters.h>
#include <membrane/physics/energy.h>
#include <membrane/physics/tangential_noise.h>
#include <membrane/shape_solver.h>
#include <membrane/surface/tangential_area_correction.h>
#include <membrane/surface/geometry.h>
#include <membrane/time_step_control.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace Membrane
{
  struct RunOptions
  {
    bool        quiet = false;
    std::string parameter_text; ///< the full parameter set, written next to the results
    std::string command_line;
    bool        check_memory = true; ///< refuse a local refinement that would not fit in the available memory
  };

  struct RunResult
  {
    std::string stop_reason; ///< "end time", "maximum steps", "equilibrium", "pinch-off approach: ..." or a failure
    bool        failed = false; ///< stopped because the scheme could not continue (not a physical stop)
    std::string outcome;        ///< "flat", "incomplete bud" or "complete bud"
  };

  /// The reasons a trial step is rejected, as the keys of summary.json's "rejections".
  inline constexpr std::array<const char *, 6> rejection_kinds = {
    {"energy_rise", "local_error", "large_move", "degenerate_cell", "solver_failure", "non_finite"}};

  class Simulator
  {
  public:
    Simulator(const Parameters &parameters, RunOptions options, MPI_Comm communicator = MPI_COMM_WORLD);
    ~Simulator();

    /// The whole run: initialize(), advance() until it returns false, finish().
    RunResult run();

    /// The pieces of run(), for driving the time loop from elsewhere (the Python module).
    /// Sets up the mesh and the initial state (or resumes), writes run_info.json, the
    /// parameters and the first statistics row and snapshot.
    void      initialize();
    /// One trial step of the time loop (accepted or rejected) with the output that is due;
    /// false once the run has stopped (end time, maximum steps, a stop rule, a signal or a
    /// failure), and then without doing anything: result() says why.
    bool      advance();
    /// Writes the last snapshot, checkpoint, statistics and summary.json; once only.
    RunResult finish();
    const RunResult &result() const { return run_result; }
    bool             stopped() const { return loop_stopped; }

    const Statistics &statistics() const { return stats; }
    /// The current state (for tests and post-processing in C++).
    const Surface &current_surface() const { return surface; }
    const Vector  &order_parameter() const { return phi; }
    const Vector  &chemical_potential_field() const { return chemical_potential; } ///< Y, ghosted
    const Vector  &pressure_field() const { return pressure; }                     ///< gamma, ghosted
    const Geometry    &current_geometry() const { return geometry; }
    const EnergyTerms &energy_terms() const { return energy; }
    double             current_time() const { return time; }
    unsigned int       current_step() const { return step; }
    double             next_time_step() const { return step_control.tau(); }
    const Triangulation &mesh() const { return triangulation; }

  private:
    /// Why a trial step was rejected (empty: accepted).
    struct Rejection
    {
      std::string kind;    ///< one of rejection_kinds
      std::string message; ///< for the log and the stop reason
      bool        empty() const { return kind.empty(); }
    };
    /// What a rejected step (or a discarded grid move) restores.
    struct State
    {
      Vector      displacement; ///< owned
      Vector      phi, pressure; ///< ghosted
      Vector      reference_areas; ///< owned
      Geometry    geometry;
      EnergyTerms energy;
    };
    // The time loop (time_loop.cc): run(), initialize(), advance(), finish() above, and one
    // trial step as the sequence of its stages; a rejected trial restores the State.
    State     save_state() const;
    void      restore_state(const State &state);
    Rejection try_step(double tau);
    bool      end_time_reached() const;

    // Set-up (setup.cc): the input mesh (from the topology), the spaces and solvers, the
    // initial state or the state of a checkpoint.
    void setup();
    /// The finite element spaces, the solvers and their matrices on the current mesh (at the
    /// start and after every change of the mesh).
    void setup_spaces_and_solvers();
    void set_initial_state();
    void resume();

    // Stage 1, the phase step (phase_step.cc): Cahn-Hilliard phi^m -> (phi~, Y) into phi_new
    // and chemical_potential; false if phi~ is not finite or |phi~| > 10.
    bool phase_step(double tau, Vector &phi_new);
    /// The thermal noise of the step being taken (keyed by the step index, so that a
    /// retried or resumed step draws the same variates). With Mesh motion = ale its tangential
    /// part in the shape step is the irrotational part of tangential_noise.
    ThermalNoise noise_of_step() const;

    // Stage 2, the shape step (shape_step.cc): X~ = X^m + W aiming at the vertex areas
    // `target`; gamma receives the pressure. false if the solve gave non-finite values.
    bool shape_step(double tau, const Vector &areas_before, const Vector &target, Vector &gamma);
    /// Adds a shape increment to the surface; false (and nothing added) if it is not finite.
    bool add_shape_increment(const ShapeUpdate &part);

    // Stage 3, area and volume restoration (constraint_restoration.cc).
    /// The vertex areas a step of length tau aims at from the current ones a^m:
    /// a^m + theta (a_ref - a^m), theta = min(1, tau / <Shape/Area relaxation time>)
    /// (a^m itself if the area is not corrected).
    Vector area_target(double tau, const Vector &areas) const;
    /// Projections of X~ back onto the area target and a fixed volume (same operator), the
    /// tangential area correction; gamma gains their pressures and becomes `pressure`.
    bool   restore_areas_and_volume(double tau, const Vector &target, Vector &gamma);
    /// Mesh motion = ale: the same projections onto the area target, with the operator of
    /// Gamma^m and the vertex areas of the material configuration X~ = X^m + W (which the
    /// mesh does not follow), then the tangential area correction on X~. The volume is
    /// restored after the mesh motion instead. `displacement_before` is X^m's; the surface is
    /// left at X~.
    bool   restore_material_areas(double tau, const Vector &target, Vector &gamma, const Vector &displacement_before);
    /// phi = phi~ riding on the moved vertices, with integral phi ds restored by a constant.
    void   restore_mass(const Vector &phi_new);
    /// a_ref,i / a_i as a ghosted nodal field; carry_reference_areas() is its inverse
    /// on another mesh or surface (the total reference area kept exactly). Used by
    /// grid control and mesh adaptation alike.
    Vector area_ratio() const;
    void   carry_reference_areas(const Vector &ratio_owned);
    /// A closed surface whose volume is fixed or under a prescribed pressure (volume_term()
    /// is active) / fixed; unlike volume_term() these do not measure the volume.
    bool           volume_constrained() const;
    bool           volume_fixed() const;
    /// The volume term of a shape step or of its projection (target at t_{m+1} = time + tau).
    VolumeCoupling volume_term(double tau) const;
    /// The work integral p dV done on the membrane by the shape step just made (from
    /// the volume before it and the pressure of the previous step); 0 without a volume term.
    double         pressure_work_of_step(double volume_before, double pressure_before) const;
    /// After grid control: a uniform normal shift alpha nu (Newton on alpha) puts V back on
    /// V_target(t_{m+1}); a constant restores integral phi ds.
    void           restore_volume();

    // Stage 4, grid control (grid_control_step.cc): tangential smoothing of X~ with the ALE
    // remap of phi, kept if F^{m+1} <= F^m (always at k_BT > 0); then geometry and energy.
    void control_grid(double energy_before, double tau);
    /// Mesh motion = ale (grid_control_step.cc): the mesh moves from Gamma^m (`before`) by the
    /// normal part of the material displacement plus grid control's smoothing, with phi and the
    /// lipid area density carried by the relative motion (surface/mesh_motion.h); a fixed volume
    /// restored; F^{m+1}. At k_BT = 0 in two moves, the normal one first: its energy is the
    /// physical step's (physical_energy), the smoothing's change is mesh_motion_energy.
    void move_mesh(double tau, const State &before);
    /// -sum_i gamma_i (target_i - a_i): the energy the step's restoration of the vertex-area
    /// defect costs against the surface pressure (the current `pressure`), to first order.
    double area_work_of_step(const Vector &target, const Vector &areas_before) const;
    /// Moves the surface by `mesh` and carries phi along the lipids' relative displacement
    /// `relative` (and the solenoidal `stream`, of largest displacement `stream_displacement`),
    /// in substeps below max_transport_cells; the reference areas keep the compression `density`.
    void carry_along(const Vector &mesh, const Vector &relative, const Vector &density, const Vector *stream,
                     double stream_displacement);
    /// The geometry and the energy of the current surface and phi.
    void update_geometry();
    /// Substeps of the transport of a step whose lipids move by `relative` (and the solenoidal
    /// noise, `solenoidal` at most) against the mesh: each at most max_transport_cells cells of the
    /// finest mesh.
    unsigned int           transport_substeps(const Vector &relative, double solenoidal) const;
    /// The vertex areas of X~ = X^m + `increment` (owned vector space; `displacement_before`
    /// is X^m's). Evaluated on the displaced mesh, which is left at X^m again.
    Vector                 material_areas(const Vector &displacement_before, const Vector &increment);
    static constexpr double max_transport_cells = 0.5;

    // Stage 5, acceptance and step control (step_acceptance.cc).
    /// Why the trial step just made is rejected (empty: accepted).
    Rejection judge_step(double tau, double energy_before);
    /// What the stop message of a failed fixed step suggests: only remedies the run accepts
    /// (Adaptive = true is refused at k_BT > 0; a degenerate cell of a Lagrangian mesh asks for
    /// Mesh motion = ale).
    std::string fixed_step_remedy(const Rejection &why) const;
    /// The local error estimate of the trial step: half the change of its increment
    /// against the previous step's velocity, in cells for the shape and absolute for phi.
    double    local_error(double tau) const;
    /// Size of the finest cells of the input mesh (the patch: 1 / (Cells per side 2^level)),
    /// the scale of shape increments for step control.
    double    reference_cell_size() const;

    // Mesh adaptation between accepted steps (adaptation.cc): mark, transfer the state, set
    // up the solvers on the new mesh.
    /// Every Adaptivity interval accepted steps, and whenever the interface or the
    /// curvature leaves the refined band (leaves_resolved_band()); collective.
    bool         adaptation_due() const;
    /// false if no cell was flagged.
    bool         adapt_mesh();
    /// Measure carried energy: take the next step (of length `tau`) on the current mesh as a trial,
    /// keep its energy for the comparison after the first step on the new mesh, and restore the
    /// state, as after a rejected trial.
    void         step_old_mesh(double tau);
    /// After an accepted step of length `tau`: add F - twin_energy to adaptation_energy_carried
    /// if it is the step that follows an adaptation with the tau of its twin.
    void         compare_with_old_mesh(double tau);
    /// Refine the initial mesh where the initial state asks for it (up to the maximum
    /// level), setting the initial state anew on each mesh.
    void         adapt_initial_mesh();
    /// false (and a warning, once) when refining n_refine cells would not fit in the
    /// available memory; collective.
    bool         refinement_fits(unsigned int n_refine);
    /// Refinement level of the finest cell above the input mesh.
    unsigned int finest_level() const;

    // Output (output.cc): statistics, progress, snapshots, checkpoints and run records.
    void     record_statistics(double tau);
    /// The columns of an enclosed volume: V, its drift, v, the pressure and its work, the
    /// Laplace pressure, the volume compliance.
    void     record_volume_statistics();
    void     report_progress(bool force);
    /// A snapshot of the fields (once per step at most).
    void     write_fields();
    void     write_checkpoint() const;
    void     write_run_info() const;
    void     write_summary(const RunResult &result, double wall_seconds) const;

    // Diagnostics (diagnostics.cc).
    /// A number with 4 significant digits, for messages.
    static std::string format(double value);
    void               warn_if_unresolved() const;
    /// For a failed or stalled run: a note when the mesh does not resolve the curvature.
    std::string        curvature_resolution_note() const;
    /// For a failed or stalled run whose steps raise the energy: a note when tau is near the
    /// explicit limit h^2 / (L_X sigma) of the phase force and Shape/Line stiffness is off.
    std::string        line_stiffness_note(const Rejection &last, double tau) const;

    const Parameters &parameters;
    const RunOptions  options;
    MPI_Comm          communicator;
    dealii::ConditionalOStream pcout;
    mutable dealii::TimerOutput timer;

    /// The periodic patch or a closed vesicle: what differs between them.
    std::unique_ptr<MembraneTopology> topology;
    Triangulation      triangulation;
    Surface            surface;
    CahnHilliardSolver cahn_hilliard;
    ShapeSolver        shape_solver;
    TangentialAreaCorrector tangential_corrector; ///< keeps its matrices while the mesh is unchanged
    Geometry           geometry;
    EnergyTerms        energy;
    Vector             phi, chemical_potential, pressure; ///< ghosted
    /// Reference area a_ref,i of the membrane carried by each vertex (owned,
    /// assembled): the local area constraint's target. Set at the start; grid
    /// control carries it with the vertices (keeping each vertex's relative error).
    Vector             reference_areas;
    BudShape           bud;

    TimeStepController step_control;
    double       time = 0, initial_mass = 0, initial_area = 0, next_output_time = 0;
    unsigned int step = 0, rejected_steps = 0, solver_iterations = 0, grid_control_skipped = 0;
    /// Rejected steps by kind (rejection_kinds), over the whole run (restored on resume).
    std::map<std::string, unsigned int> rejections;
    /// Observables of the last accepted step, for the statistics.
    double max_increment = 0, remap_correction = 0, cell_quality = 1, area_error = 0, shape_mass_correction = 0;
    /// The energy the step control judges: F^{m+1}, or with Mesh motion = ale F(X~, phi~) of the
    /// physical step; mesh_motion_energy = F^{m+1} - F(X~, phi~) (0 for the Lagrangian mesh).
    double physical_energy = 0, mesh_motion_energy = 0;
    /// What the last judged step dissipated, F^m + p dV + area work - physical_energy (>= 0 at
    /// k_BT = 0 up to Time stepping/Energy tolerance; set by judge_step): its rate is what the
    /// equilibrium stop judges.
    double dissipation = 0;
    /// Mesh motion = ale at k_BT > 0: the Helmholtz split of the trial step's tangential noise
    /// (physics/tangential_noise.h): chi for the shape step, psi for the lipids' transport.
    TangentialNoise tangential_noise;
    bool            split_noise = false; ///< the trial step uses tangential_noise
    /// Closed surfaces: V_0 and the volume pressure p of the last step (step and projections).
    double initial_volume = 0, volume_pressure = 0;
    /// The work integral p dV done on the membrane by the volume term: in the trial step,
    /// and summed over the run (F - pressure_work never increases).
    double step_pressure_work = 0, pressure_work = 0;
    /// Mesh motion = ale: the work of the surface pressure restoring the area defect (area_work_of_step).
    double step_area_work = 0;
    double trial_end_time = 0; ///< t_{m+1} of the trial step
    unsigned int area_projections = 0, tangential_area_moves = 0; ///< of the last step
    /// Accuracy control: the physical increments of the trial step and of the last
    /// accepted one (owned), the tau of that one (0: none, e.g. after an adaptation),
    /// the trial's error estimate relative to the tolerance, and the factor for tau
    /// after a rejection.
    Vector step_increment, step_phi_change, previous_increment, previous_phi_change;
    double previous_tau = 0, error_estimate = -1, step_error = -1, rejection_factor = 0.5;
    bool         local_error_irreducible = false; ///< this trial's estimate did not fall with tau
    unsigned int irreducible_error_steps = 0;     ///< accepted steps with such an estimate
    /// Mesh adaptation: the level of the input mesh, the number of adaptations and the
    /// sum of their energy changes (not steps of the gradient flow).
    unsigned int base_level = 0, adaptations = 0;
    double       plateau_since = -1; ///< time since which the energy rate is below Equilibrium rate (-1: not)
    double       adaptation_energy_jump = 0;
    /// Measure carried energy: the sum over adaptations of F after the first step on the new mesh
    /// minus F after the same step on the old one, the adaptations it covers, and the pending
    /// comparison of the last adaptation (tau and F of its step on the old mesh).
    double       adaptation_energy_carried = 0;
    unsigned int carried_measured          = 0;
    double       twin_tau = 0, twin_energy = 0;
    bool         twin_pending = false;
    bool         memory_warning_given   = false; ///< refinement_fits() warns once per run
    bool   grid_move_skipped = false; ///< in the current trial step

    Statistics                         stats;
    std::unique_ptr<class FieldOutput> output;
    dealii::Timer                      wall;
    double                             last_progress = -1e9;
    double earlier_wall_seconds = 0; ///< wall time of the segments before a resume
    double segment_start_time   = 0; ///< t at the start of this segment (for the ETA)
    std::unique_ptr<class LogFile> log; ///< rank 0: log.txt in the output directory
    std::vector<std::string> changed_on_resume; ///< "Section/Entry: old -> new" against the checkpoint's run
    /// The time loop's state between initialize(), advance() and finish().
    RunResult    run_result{"end time", false, ""};
    bool         loop_stopped = false, interrupted = false, finished_run = false;
    unsigned int last_written = std::numeric_limits<unsigned int>::max(); ///< step of the last snapshot
  };
} // namespace Membrane
