// Cost of one Cahn-Hilliard step (assembly + direct solve) and of the geometry
// update on the periodic patch, per mesh size. Reports time per step and the
// ratio to the 32 x 32 paper resolution. A benchmark, not a test: it never fails
// on time. Run: build/benchmarks/bench_cahn_hilliard
#include <membrane/cahn_hilliard.h>
#include <membrane/physics/initial_phase.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/initial_shapes.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <benchmark/benchmark.h>

using namespace Membrane;

namespace
{
  struct Patch
  {
    Triangulation      tria{MPI_COMM_WORLD};
    Surface            surface{tria, true};
    CahnHilliardSolver solver{tria, true};
    Material           material;
    Geometry           geometry;
    Vector             phi;
    explicit Patch(unsigned int n)
    {
      make_periodic_unit_square(tria, n);
      surface.setup();
      solver.setup();
      set_bump(surface, 0.5, 1.3);
      material.bending_rigidity      = make_linear_law(1.5, 1.5);
      material.gaussian_rigidity     = make_linear_law(-1, -1);
      material.spontaneous_curvature = make_linear_law(-10, 5);
      material.line_tension = 450, material.transition_length = 0.03, material.phase_mobility = 0.05;
      geometry = compute_geometry(surface);
      phi      = surface.scalar_space().ghosted_copy(make_initial_phase(surface, InitialPhaseOptions()));
    }
  };

  void cahn_hilliard_step(benchmark::State &state)
  {
    Patch  p(state.range(0));
    Vector next = p.surface.scalar_space().make_owned(), potential = next;
    for (auto _ : state)
      p.solver.step(p.surface, p.geometry, p.material, CahnHilliardOptions(), LinearSolverOptions(), 1e-4, p.phi,
                    next, potential);
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
