// Cost of one Cahn-Hilliard step (assembly + direct solve) and of the geometry
// update on the periodic patch, per mesh size. Reports time per step and the
// ratio to the 32 x 32 paper resolution. A benchmark, not a test: it never fails
// on time. Run: build/benchmarks/bench_cahn_hilliard
#include "fixed_surface.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <benchmark/benchmark.h>

using namespace Membrane;

namespace
{
  /// The fixed bump of experiment 7.3 with the paper's material constants.
  struct Patch : Testing::FixedSurface
  {
    explicit Patch(unsigned int n)
      : FixedSurface(n)
    {
      set_bump(surface, 0.5, 1.3);
      update_geometry();
      material.bending_rigidity      = make_linear_law(1.5, 1.5);
      material.gaussian_rigidity     = make_linear_law(-1, -1);
      material.spontaneous_curvature = make_linear_law(-10, 5);
      material.line_tension          = 450;
      material.transition_length     = 0.03;
      material.phase_mobility        = 0.05;
      set_phase(InitialPhaseOptions());
    }
  };

  void cahn_hilliard_step(benchmark::State &state)
  {
    Patch  p(state.range(0));
    Vector next = p.surface.scalar_space().make_owned(), potential = next;
    for (auto _ : state)
      p.solver.step(p.surface, p.geometry, p.material, p.options, LinearSolverOptions(), 1e-4, p.phi, next,
                    potential);
    state.counters["vertices"] = p.surface.scalar_space().dof_handler().n_dofs();
  }

  void geometry_update(benchmark::State &state)
  {
    Patch p(state.range(0));
    for (auto _ : state)
      benchmark::DoNotOptimize(compute_geometry(p.surface));
  }
} // namespace

BENCHMARK(cahn_hilliard_step)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);
BENCHMARK(geometry_update)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
