#pragma once
// A run: builds the periodic patch and its initial state from the parameters,
// advances the time loop, and writes fields, statistics, the parameters used,
// the code version and a summary into the output directory.
//
// One time step on a fixed surface (MODEL.md section 4):
//   1. geometry of Gamma^m: vertex normals, H^m (weak lap_s X = H n), K^m (projection);
//   2. Cahn-Hilliard: (phi^m) -> (phi^{m+1}, Y) by one linear solve;
//   3. energy terms, area and integral phi ds into the statistics.

#include <membrane/cahn_hilliard.h>
#include <membrane/io/statistics.h>
#include <membrane/parameters.h>
#include <membrane/surface/geometry.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <memory>
#include <string>

namespace Membrane
{
  struct RunOptions
  {
    bool        quiet = false;
    std::string parameter_text; ///< the full parameter set, written next to the results
    std::string command_line;
  };

  class Simulator
  {
  public:
    Simulator(const Parameters &parameters, RunOptions options, MPI_Comm communicator = MPI_COMM_WORLD);
    ~Simulator();

    /// Runs to the end time; returns the reason it stopped ("end time",
    /// "maximum steps", or a divergence message).
    std::string run();

    const Statistics &statistics() const { return stats; }

  private:
    void setup();
    void set_initial_state();
    void warn_if_unresolved() const;
    bool advance(double tau);
    void record_statistics(double tau, unsigned int iterations, double solve_seconds);
    void write_run_info() const;
    void write_summary(const std::string &stop_reason, double wall_seconds) const;
    void report_progress(bool force);

    const Parameters &parameters;
    const RunOptions  options;
    MPI_Comm          communicator;
    dealii::ConditionalOStream pcout;
    dealii::TimerOutput        timer;

    Triangulation      triangulation;
    Surface            surface;
    CahnHilliardSolver cahn_hilliard;
    Geometry           geometry;
    Vector             phi, chemical_potential; ///< ghosted
    double             time = 0, initial_mass = 0, initial_area = 0;
    unsigned int       step = 0;
    Statistics         stats;
    std::unique_ptr<class FieldOutput> output;
    dealii::Timer      wall;
    double             last_progress = -1e9, next_output_time = 0;
  };
} // namespace Membrane
