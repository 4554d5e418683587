// The coupled shape step: relaxation of a homogeneous membrane, the pressure
// stabilization against checkerboard modes, and the order of convergence of a
// short smooth evolution under mesh refinement.
#include "fixed_surface.h"
#include "parameter_text.h"

#include <membrane/analysis/bud_shape.h>
#include <membrane/parameters.h>
#include <membrane/shape_solver.h>
#include <membrane/simulator.h>
#include <membrane/surface/adaptivity.h>
#include <membrane/surface/grid_control.h>
#include <membrane/surface/tangential_area_correction.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

namespace
{
  using namespace Membrane;

  using Testing::make_parameters;

  const std::string homogeneous = R"(
subsection Initial phase
  set Type = uniform
  set Uniform value = -1
end
subsection Material
  set Line tension = 1
  set Transition length = 0.1
  set Shape mobility = 1
end
subsection Output
  set Write VTU = false
end
)";
  // The smooth initial shape of the single-phase relaxations: three cosine modes.
  const std::string cosine_shape = R"(
subsection Initial shape
  set Shape = cosine modes
  set Cosine modes = 0.06 1 1; 0.06 1 -1; 0.01 2 1
end
)";

  /// Column of the statistics as a vector.
  std::vector<double> column(const Statistics &stats, const std::string &name)
  {
    std::vector<double> values;
    std::istringstream  in(stats.to_text());
    std::string         line;
    std::getline(in, line);
    std::istringstream header(line.substr(1));
    std::vector<std::string> names;
    for (std::string n; header >> n;)
      names.push_back(n);
    const auto index = std::find(names.begin(), names.end(), name) - names.begin();
    while (std::getline(in, line))
      {
        std::istringstream row(line);
        std::string        word;
        for (long i = 0; i <= index; ++i)
          row >> word;
        values.push_back(std::strtod(word.c_str(), nullptr));
      }
    return values;
  }

  /// Nodal values of a field of `space` keyed by the vertex's grid indices (i, j) on an n x n mesh.
  std::map<std::pair<int, int>, double> nodal_values(const FieldSpace &space, const Vector &field, const int n,
                                                     const unsigned int component = 0)
  {
    std::map<std::pair<int, int>, double> values;
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        {
          const auto x = cell->vertex(v);
          values[{static_cast<int>(std::lround(x[0] * n)) % n, static_cast<int>(std::lround(x[1] * n)) % n}] =
            field[cell->vertex_dof_index(v, component)];
        }
    return values;
  }

  /// The bump of 7.3 (area 1.3) with its material and the bump profile of phi (with the
  /// experiment's mass -0.85 if `prescribe_mass`), on a fixed-surface fixture.
  void set_up_budding_bump(Testing::FixedSurface &setup, const bool prescribe_mass)
  {
    set_bump(setup.surface, 0.5, 1.3);
    setup.update_geometry();
    setup.material.line_tension      = 90;
    setup.material.transition_length = 0.06;
    setup.material.bending_rigidity  = make_linear_law(1.5, 1.5);
    setup.material.gaussian_rigidity = make_linear_law(-1, -1);
    setup.material.shape_mobility    = 5e-4;
    setup.material.phase_mobility    = 0.05;
    InitialPhaseOptions initial;
    initial.type           = "bump";
    initial.prescribe_mass = prescribe_mass;
    initial.mass           = -0.85;
    setup.set_phase(initial);
  }
} // namespace

// A homogeneous membrane (pure phase B, kappa = 1, H0 = 0) relaxes from a shape
// with a short-wavelength perturbation: the energy never increases, no step is
// rejected at the chosen tau bounds, area is kept, and the surface pressure
// ends uniform (at equilibrium grad gamma = 0 by the tangential law).
TEST(Shape, HomogeneousMembraneRelaxesWithMonotoneEnergyAndUniformPressure)
{
  const std::string dir = std::filesystem::temp_directory_path() / "membrane_relax";
  const Parameters  parameters = make_parameters(homogeneous + cosine_shape + R"(
subsection Mesh
  set Cells per side = 16
end
subsection Time stepping
  set End time = 0.2
  set Time step = 1e-4
  set Maximum time step = 0.02
end
subsection Output
  set Directory = )" + dir + "\nend\n");
  Simulator       simulator(parameters, RunOptions{true, "", "test"});
  const RunResult result = simulator.run();
  EXPECT_FALSE(result.failed) << result.stop_reason;

  const auto energy = column(simulator.statistics(), "energy");
  for (std::size_t i = 1; i < energy.size(); ++i)
    EXPECT_LE(energy[i], energy[i - 1] * (1 + 1e-10)) << "step " << i;
  EXPECT_LT(energy.back(), 0.7 * energy.front());
  EXPECT_EQ(simulator.statistics().last("rejected_steps"), 0);
  EXPECT_LT(std::abs(simulator.statistics().last("area_drift")), 1e-6);

  const double gamma_min = simulator.statistics().last("gamma_min");
  const double gamma_max = simulator.statistics().last("gamma_max");
  std::cout << "energy " << energy.front() << " -> " << energy.back() << ", gamma in [" << gamma_min << ", "
            << gamma_max << "]" << std::endl;
  EXPECT_LT(gamma_max - gamma_min, 1e-3 * std::max(std::abs(gamma_min), std::abs(gamma_max)));
}

// Descent on a coarse mesh near equilibrium: a single-phase membrane (phi = -1, no interface)
// at Shape mobility 1 on 16 x 16 cells relaxes with grid control on, with steps up to tau = 1
// (hundreds of bending relaxation times of the slowest mode), until the relative energy rate
// falls below 1e-9: it must get there without a rejected step or a stall. The grid control
// is at a rate per unit time (Grid control rate), so that long steps smooth the mesh as much
// as many short ones and the discrete equilibrium does not depend on the steps taken.
// The phase-force hint of a stalled run needs an interface: with phi uniform there is none.
TEST(Shape, SinglePhaseRelaxationReachesEquilibriumWithGridControl)
{
  const std::string dir      = std::filesystem::temp_directory_path() / "membrane_single_phase_equilibrium";
  const auto        relaxing = [&](const double equilibrium_time, const std::string &directory) {
    return make_parameters(homogeneous + cosine_shape + R"(
subsection Mesh
  set Cells per side = 16
end
subsection Shape
  set Grid control weight = 0.1
  set Grid control rate = 10
end
subsection Time stepping
  set End time = 100
  set Time step = 1e-4
  set Maximum time step = 1
  set Equilibrium rate = 1e-9
  set Equilibrium time = )" + std::to_string(equilibrium_time) + R"(
end
subsection Output
  set Directory = )" + directory + "\nend\n");
  };
  const Parameters parameters = relaxing(0, dir); // the Simulator keeps a reference
  Simulator        simulator(parameters, RunOptions{true, "", "test"});
  const RunResult result = simulator.run();
  EXPECT_FALSE(result.failed) << result.stop_reason;
  EXPECT_EQ(result.stop_reason.rfind("equilibrium", 0), 0u) << result.stop_reason;
  EXPECT_EQ(simulator.statistics().last("rejected_steps"), 0);
  const auto energy = column(simulator.statistics(), "energy");
  for (std::size_t i = 1; i < energy.size(); ++i)
    EXPECT_LE(energy[i], energy[i - 1] * (1 + 1e-10)) << "step " << i;
  std::ostringstream summary;
  summary << energy.size() - 1 << " steps to t = " << simulator.statistics().last("time") << ", energy "
          << energy.front() << " -> " << std::setprecision(12) << energy.back();
  std::cout << summary.str() << std::endl;
  EXPECT_LT(largest_relative_steepness(simulator.current_surface(), simulator.order_parameter(), 0.1), 1e-12);

  // With Equilibrium time = 5 the rate must stay below 1e-9 for 5 time units: the run goes on
  // past the first slow step, to a later stop whose window spans at least 5.
  const Parameters held = relaxing(5, dir + "_held");
  Simulator        held_simulator(held, RunOptions{true, "", "test"});
  const RunResult held_result = held_simulator.run();
  EXPECT_EQ(held_result.stop_reason.rfind("equilibrium", 0), 0u) << held_result.stop_reason;
  const double window = std::stod(held_result.stop_reason.substr(held_result.stop_reason.rfind(" for ") + 5));
  EXPECT_GE(window, 5 * (1 - 1e-12));
  EXPECT_GE(held_simulator.statistics().last("time"), simulator.statistics().last("time") + 4);
}

// The same relaxation with the ALE mesh motion and the default grid control (a fixed weight per
// step, no rate), on 16 x 16 and 32 x 32 cells from a first tau of 1e-5 and of 1e-4: each stops at
// equilibrium, the physical step's relative dissipation rate below 1e-9. The step control and the
// stop judge the physical step with the work of restoring the area that the smoothing cuts off;
// without that work the steps near equilibrium rose at any tau and the runs stalled by t = 7.
// Measured on the whole step, the rate on 32 x 32 stays at 1e-7 to t = 100: the smoothing keeps
// lowering the discrete energy while the mesh approaches its fixed point. The dissipation itself
// settles at 1e-8 to 6e-8 and the stop comes on a step where it dips below 1e-9 (docs/model.md,
// smooth relaxations), so a change of the trajectory can move the stop. The two first taus stop
// with the mesh at different points on its way: their energies differ by 1.8e-5 and 3.1e-5 of the
// energy, 0.7 % and 1.3 % of the mesh error |F_16 - F_32| (1.0e-2). On 8 x 8 the smoothing and the
// physical step cycle (docs/model.md): no stop is asserted there.
TEST(Shape, SinglePhaseRelaxationsReachEquilibriumWithTheAleMesh)
{
  const auto relax = [&](const int cells, const double first_tau) {
    const std::string dir = std::filesystem::temp_directory_path() /
                            ("membrane_single_phase_ale_" + std::to_string(cells) + "_" + std::to_string(first_tau));
    const Parameters parameters = make_parameters(homogeneous + cosine_shape + R"(
subsection Mesh
  set Cells per side = )" + std::to_string(cells) + R"(
end
subsection Shape
  set Mesh motion = ale
end
subsection Time stepping
  set End time = 100
  set Time step = )" + std::to_string(first_tau) + R"(
  set Maximum time step = 1
  set Equilibrium rate = 1e-9
end
subsection Output
  set Directory = )" + dir + "\nend\n");
    Simulator       simulator(parameters, RunOptions{true, "", "test"});
    const RunResult result = simulator.run();
    EXPECT_FALSE(result.failed) << result.stop_reason;
    EXPECT_EQ(result.stop_reason.rfind("equilibrium", 0), 0u) << cells << " cells, first tau " << first_tau << ": "
                                                              << result.stop_reason;
    EXPECT_GT(simulator.statistics().last("min_corner_sine"), 0.9);
    std::cout << cells << " x " << cells << " cells, first tau " << first_tau << ": " << result.stop_reason
              << ", energy " << std::setprecision(10) << simulator.statistics().last("energy") << std::endl;
    return simulator.statistics().last("energy");
  };
  const double coarse_small = relax(16, 1e-5), coarse_large = relax(16, 1e-4);
  const double fine_small = relax(32, 1e-5), fine_large = relax(32, 1e-4);
  const double mesh_error = std::abs(coarse_large - fine_large);
  EXPECT_LT(std::abs(coarse_small - coarse_large), 0.05 * mesh_error);
  EXPECT_LT(std::abs(fine_small - fine_large), 0.05 * mesh_error);
}

// Equal-order Q1 for (W, gamma): without stabilization the surface pressure of a
// single shape step on a uniform mesh carries a checkerboard (-1)^(i+j) mode;
// with the default stabilization its checkerboard content is small.
TEST(Shape, PressureStabilizationRemovesCheckerboard)
{
  constexpr int          n = 16;
  Testing::FixedSurface setup(n);
  set_up_budding_bump(setup, true);
  const double tau = 1e-3;
  Vector       next = setup.surface.scalar_space().make_owned(), potential = setup.surface.scalar_space().make_owned();
  setup.solver.step(setup.surface, setup.geometry, setup.material, setup.options, LinearSolverOptions(), tau,
                    setup.phi, next, potential);
  const Vector potential_ghosted = setup.surface.scalar_space().ghosted_copy(potential);

  const auto checkerboard = [&](const double delta) {
    ShapeSolver solver(setup.tria, true);
    solver.setup();
    ShapeOptions options;
    options.pressure_stabilization = delta;
    const ShapeUpdate update = solver.step(setup.surface, setup.geometry, setup.material, options,
                                           LinearSolverOptions(), tau, setup.surface.scalar_space().make_owned(), setup.phi,
                                           potential_ghosted);
    const auto gamma = nodal_values(setup.surface.scalar_space(), update.pressure, n);
    double     mean = 0, alternating = 0, variation = 0;
    for (const auto &[ij, g] : gamma)
      mean += g / gamma.size();
    for (const auto &[ij, g] : gamma)
      {
        alternating += ((ij.first + ij.second) % 2 ? -1 : 1) * g / gamma.size();
        variation += std::abs(g - mean) / gamma.size();
      }
    return std::abs(alternating) / variation;
  };
  const double stabilized = checkerboard(0.5), unstabilized = checkerboard(0.0);
  std::cout << "checkerboard content of gamma: " << unstabilized << " without, " << stabilized
            << " with stabilization" << std::endl;
  EXPECT_GT(unstabilized, 0.3);
  EXPECT_LT(stabilized, 0.02);
}

// The lumped curvature mass: eliminating the tangential parts B~ of the curvature vector
// (five fields, Shape/Curvature mass = lumped) gives the solution of the seven-field lumped
// system to round-off, and the lumped and consistent steps differ by a discretization
// error that falls at second order under refinement (one step of the bump with a phase
// domain, line tension and pressure stabilization on, at 16 and 32 cells per side).
TEST(Shape, LumpedCurvatureMassEliminatesTangentialPartsExactly)
{
  const auto step = [](const int n, const CurvatureMass mass) {
    Testing::FixedSurface setup(n);
    set_up_budding_bump(setup, false);
    ShapeSolver solver(setup.tria, true, mass);
    solver.setup();
    ShapeOptions options;
    options.curvature_mass = mass;
    const Vector potential = setup.surface.scalar_space().make_ghosted();
    const ShapeUpdate update = solver.step(setup.surface, setup.geometry, setup.material, options,
                                           LinearSolverOptions(), 1e-2, setup.surface.scalar_space().make_owned(),
                                           setup.phi, potential);
    std::array<std::map<std::pair<int, int>, double>, 5> fields;
    for (unsigned int c = 0; c < 3; ++c)
      fields[c] = nodal_values(setup.surface.vector_space(), update.increment, n, c);
    fields[3] = nodal_values(setup.surface.scalar_space(), update.pressure, n);
    fields[4] = nodal_values(setup.surface.scalar_space(), update.mean_curvature, n);
    return fields;
  };
  // Largest difference of field c at the vertices of the 16 x 16 mesh, relative to its size.
  const auto difference = [](const auto &a, const auto &b, const unsigned int c, const int stride_a, const int stride_b) {
    double worst = 0, size = 0;
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j)
        {
          const double x = a[c].at({i * stride_a, j * stride_a}), y = b[c].at({i * stride_b, j * stride_b});
          worst = std::max(worst, std::abs(x - y));
          size  = std::max(size, std::abs(y));
        }
    return worst / size;
  };
  const auto reduced = step(16, CurvatureMass::lumped), full = step(16, CurvatureMass::lumped_full);
  for (unsigned int c = 0; c < 5; ++c)
    EXPECT_LT(difference(reduced, full, c, 1, 1), 1e-9) << "field " << c;

  const auto consistent_16 = step(16, CurvatureMass::consistent), consistent_32 = step(32, CurvatureMass::consistent);
  const auto reduced_32    = step(32, CurvatureMass::lumped);
  for (const unsigned int c : {2u, 4u}) // height increment and H~
    {
      const double coarse = difference(reduced, consistent_16, c, 1, 1), fine = difference(reduced_32, consistent_32, c, 2, 2);
      std::cout << (c == 2 ? "height increment" : "mean curvature") << ": lumped vs consistent " << coarse
                << " (16), " << fine << " (32), observed order " << std::log2(coarse / fine) << std::endl;
      EXPECT_GT(coarse, 1e-6); // the two schemes differ
      // Measured 1.53 (height, not yet asymptotic on 16 cells) and 1.86 (H~); a lumping
      // error of first order would give about 1.
      EXPECT_GT(std::log2(coarse / fine), c == 2 ? 1.3 : 1.6);
    }
}

// MUMPS' block low-rank factorization and out-of-core factors (Linear solver/Low-rank
// tolerance, Out of core) on one shape step of the bump at 64 cells per side: the factors
// on disk give the in-memory solution to round-off. Compressed factors alone are off by
// about 100 x the dropping tolerance (7e-7 at 1e-8); the two steps of iterative refinement
// bring 1e-8 back to round-off, while at the largest accepted tolerance, 1e-4, a residue of
// the compression stays visible (measured 1.7e-8): the tolerance reaches MUMPS.
TEST(Shape, LowRankAndOutOfCoreFactorizationsKeepTheStep)
{
  Testing::FixedSurface setup(64);
  set_up_budding_bump(setup, false);
  const Vector potential = setup.surface.scalar_space().make_ghosted();
  const auto   step      = [&](const double low_rank, const bool out_of_core) {
    ShapeSolver solver(setup.tria, true);
    solver.setup();
    LinearSolverOptions linear;
    linear.low_rank_tolerance = low_rank;
    linear.out_of_core        = out_of_core;
    return solver
      .step(setup.surface, setup.geometry, setup.material, ShapeOptions(), linear, 1e-2,
            setup.surface.scalar_space().make_owned(), setup.phi, potential)
      .increment;
  };
  const Vector exact = step(0, false);
  const auto   difference = [&](Vector other) {
    other -= exact;
    return other.l2_norm() / exact.l2_norm();
  };
  const double on_disk = difference(step(0, true)), fine = difference(step(1e-8, false)),
               coarse = difference(step(1e-4, true));
  std::cout << "increment relative to the exact LU: out of core " << on_disk << ", low rank 1e-8 " << fine
            << ", low rank 1e-4 out of core " << coarse << std::endl;
  EXPECT_LT(on_disk, 1e-13);
  EXPECT_LT(fine, 1e-12);
  EXPECT_GT(coarse, 1e-11);
  EXPECT_LT(coarse, 1e-6);
}

// A short smooth coupled evolution (curved patch, smooth phi, phi-dependent
// kappa and H0) on 10, 20, 40 and 80 cells per side with the same time steps:
// the differences between successive meshes of the vertex positions and of phi
// at the coarse vertices fall by about 4 per refinement (observed order ~2).
TEST(Shape, SmoothEvolutionConvergesAtSecondOrder)
{
  const auto run = [](const int n, std::map<std::pair<int, int>, double> &phi_values,
                      std::array<std::map<std::pair<int, int>, double>, 3> &displacement_values) {
    const std::string dir        = std::filesystem::temp_directory_path() / ("membrane_eoc_" + std::to_string(n));
    const Parameters  parameters = make_parameters(R"(
subsection Mesh
  set Cells per side = )" + std::to_string(n) + R"(
end
subsection Initial shape
  set Shape = cosine modes
  set Cosine modes = 0.05 1 1; 0.05 1 -1
end
subsection Initial phase
  set Type = expression
  set Expression = 0.3 * cos(2 * pi * x) + 0.2 * sin(2 * pi * y)
end
subsection Material
  subsection Bending rigidity
    set Phase A value = 1
    set Phase B value = 2
  end
  subsection Spontaneous curvature
    set Phase A value = -2
    set Phase B value = 2
  end
  set Line tension = 1
  set Transition length = 0.2
  set Shape mobility = 1
  set Phase mobility = 0.01
end
subsection Time stepping
  set End time = 1e-3
  set Time step = 1e-4
  set Adaptive = false
  # The time error is held fixed while h -> 0, so on the 80 x 80 mesh a step moves
  # about one cell: no bound on the increment per step.
  set Maximum increment = 0
end
subsection Shape
  set Grid control weight = 0
end
subsection Output
  set Write VTU = false
  set Directory = )" + dir + "\nend\n");
    Simulator simulator(parameters, RunOptions{true, "", "test"});
    EXPECT_FALSE(simulator.run().failed);
    const Surface &surface = simulator.current_surface();
    phi_values             = nodal_values(surface.scalar_space(), simulator.order_parameter(), n);
    for (unsigned int c = 0; c < 3; ++c)
      displacement_values[c] = nodal_values(surface.vector_space(), surface.displacement(), n, c);
  };

  const std::vector<int> meshes = {10, 20, 40, 80};
  std::vector<std::map<std::pair<int, int>, double>>               phi(meshes.size());
  std::vector<std::array<std::map<std::pair<int, int>, double>, 3>> displacement(meshes.size());
  for (std::size_t k = 0; k < meshes.size(); ++k)
    run(meshes[k], phi[k], displacement[k]);

  // Max difference between meshes k and k+1 at the vertices of the coarsest mesh.
  const auto difference = [&](const std::size_t k, const auto &field) {
    double worst = 0;
    for (int i = 0; i < meshes[0]; ++i)
      for (int j = 0; j < meshes[0]; ++j)
        {
          const int r0 = meshes[k] / meshes[0], r1 = meshes[k + 1] / meshes[0];
          worst = std::max(worst, std::abs(field(k, i * r0, j * r0) - field(k + 1, i * r1, j * r1)));
        }
    return worst;
  };
  const auto phase = [&](const std::size_t k, const int i, const int j) { return phi[k].at({i, j}); };
  const auto height = [&](const std::size_t k, const int i, const int j) { return displacement[k][2].at({i, j}); };
  for (std::size_t k = 0; k + 2 < meshes.size(); ++k)
    {
      const double order_phi    = std::log2(difference(k, phase) / difference(k + 1, phase));
      const double order_height = std::log2(difference(k, height) / difference(k + 1, height));
      std::cout << "meshes " << meshes[k] << "/" << meshes[k + 1] << "/" << meshes[k + 2] << ": observed order phi "
                << order_phi << ", height " << order_height << std::endl;
      if (k + 3 == meshes.size())
        {
          EXPECT_NEAR(order_phi, 2.0, 0.3);
          EXPECT_NEAR(order_height, 2.0, 0.3);
        }
    }
}

// Bud observables on the bump z = a1 (1 + cos(pi rho / R0)): the height is the
// apex 2 a1 above the flat corners, a dome has no neck, and mirroring the shape
// turns the bud direction. The phase-A disc phi > 0 has the area of its disc
// on the surface.
TEST(Shape, BudObservablesOfTheBump)
{
  Testing::FixedSurface setup(32);
  const double          a1 = set_bump(setup.surface, 0.5, 1.3);
  InitialPhaseOptions   initial;
  initial.type        = "bump";
  initial.bump_height = 1.0; // phi = cos(pi rho / R0) > 0 for rho < R0 / 2
  setup.set_phase(initial);

  const BudShape up = measure_bud(setup.surface, setup.phi);
  EXPECT_EQ(up.direction, 1);
  EXPECT_NEAR(up.height, 2 * a1, 1e-12);
  EXPECT_EQ(up.neck_ratio, 1.0);
  // The disc rho < 1/4 on the surface: integral of 2 pi rho sqrt(1 + z'(rho)^2) (midpoint rule);
  // the indicator phi > 0 is sampled at quadrature points, hence the 3 % bound.
  double exact = 0;
  for (int k = 0; k < 10000; ++k)
    {
      const double rho = (k + 0.5) * 0.25 / 10000, slope = 2 * M_PI * a1 * std::sin(2 * M_PI * rho);
      exact += 2 * M_PI * rho * std::sqrt(1 + slope * slope) * 0.25 / 10000;
    }
  EXPECT_NEAR(up.domain_area / exact, 1.0, 0.03);
  EXPECT_EQ(classify_outcome(up, OutcomeCriteria(), false), "incomplete bud");
  EXPECT_EQ(classify_outcome(up, OutcomeCriteria(), true), "complete bud");

  Vector mirrored = setup.surface.vector_space().make_owned();
  mirrored        = setup.surface.displacement();
  mirrored *= -1.0;
  setup.surface.set_displacement(mirrored);
  const BudShape down = measure_bud(setup.surface, setup.phi);
  EXPECT_EQ(down.direction, -1);
  EXPECT_NEAR(down.height, 2 * a1, 1e-12);
  EXPECT_NEAR(down.domain_protrusion, up.domain_protrusion, 1e-12);
}

// Grid control on the bump: the vertex moves are tangential and the ALE remap keeps
// phi = f(position) in place. With f = 0.5 sin(2 pi x) cos(2 pi y) in the horizontal
// coordinates (the bump is a graph), the remapped nodal values match f at the moved
// vertices to a small fraction of the change they underwent, and integral phi ds is
// unchanged to round-off with a correction far below the 1e-6 bound.
TEST(Shape, GridControlIsTangentialAndRemapKeepsPhiInPlace)
{
  constexpr int          n = 32;
  Testing::FixedSurface setup(n);
  set_bump(setup.surface, 0.5, 1.3);
  setup.update_geometry();
  InitialPhaseOptions initial;
  initial.type       = "expression";
  initial.expression = "0.5 * sin(2 * pi * x) * cos(2 * pi * y)";
  setup.set_phase(initial);
  const auto f = [](const double x, const double y) {
    return 0.5 * std::sin(2 * M_PI * x) * std::cos(2 * M_PI * y);
  };

  const Vector shift = grid_control_displacement(setup.surface, setup.geometry.normal, 0.1);
  const auto   normal_part = [&]() {
    double worst = 0;
    const auto d = setup.surface.vector_space().ghosted_copy(shift);
    for (const auto &cell : setup.surface.vector_space().dof_handler().active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        {
          double dn = 0;
          for (unsigned int c = 0; c < 3; ++c)
            dn += d[cell->vertex_dof_index(v, c)] * setup.geometry.normal[cell->vertex_dof_index(v, c)];
          worst = std::max(worst, std::abs(dn));
        }
    return worst;
  }();
  EXPECT_LT(normal_part, 1e-14);
  EXPECT_GT(shift.linfty_norm(), 1e-4); // the bump's stretched cells do move

  const double mass_before = setup.mass();
  const auto   phi_before  = nodal_values(setup.surface.scalar_space(), setup.phi, n);
  const double correction  = move_tangentially_and_remap(setup.surface, shift, setup.phi);
  EXPECT_LT(std::abs(setup.mass() - mass_before), 1e-13 * setup.surface.area());
  EXPECT_LT(std::abs(correction), 1e-6);

  const auto phi_after = nodal_values(setup.surface.scalar_space(), setup.phi, n);
  std::array<std::map<std::pair<int, int>, double>, 3> D;
  for (unsigned int c = 0; c < 3; ++c)
    D[c] = nodal_values(setup.surface.vector_space(), setup.surface.displacement(), n, c);
  double error = 0, change = 0;
  for (const auto &[ij, value] : phi_after)
    {
      const double x = double(ij.first) / n + D[0].at(ij), y = double(ij.second) / n + D[1].at(ij);
      error  = std::max(error, std::abs(value - f(x, y)));
      change = std::max(change, std::abs(value - phi_before.at(ij)));
    }
  std::cout << "remap: largest change " << change << ", largest error against f(X_new) " << error
            << ", mass correction " << correction << std::endl;
  EXPECT_LT(error, 0.02 * change);
}

namespace
{
  /// The 7.3 setup (sigma = 630) on 16 x 16 cells with tau capped at `tau`, for the conservation tests.
  Parameters budding_with_capped_tau(const double tau, const double end_time, const std::string &dir)
  {
    return make_parameters(R"(
subsection Mesh
  set Cells per side = 16
end
subsection Initial shape
  set Shape = bump
  set Bump area = 1.3
end
subsection Initial phase
  set Type = bump
  set Prescribe mass = true
  set Mass = -0.85
end
subsection Material
  subsection Bending rigidity
    set Phase A value = 1.5
    set Phase B value = 1.5
  end
  subsection Gaussian rigidity
    set Phase A value = -1
    set Phase B value = -1
  end
  subsection Spontaneous curvature
    set Phase A value = 0
    set Phase B value = 0
  end
  set Line tension = 630
  set Transition length = 0.06
end
subsection Time stepping
  set Time step = 1e-4
  set Maximum time step = )" + std::to_string(tau) + R"(
  set End time = )" + std::to_string(end_time) + R"(
end
subsection Output
  set Write VTU = false
  set Directory = )" + dir + "\nend\n");
  }

  double column_max_abs(const Statistics &stats, const std::string &name)
  {
    double worst = 0;
    for (const double v : column(stats, name))
      worst = std::max(worst, std::abs(v));
    return worst;
  }
} // namespace

// Local area and mass do not degrade with the number of steps: 500 steps of a budding
// membrane keep the vertex area errors bounded (below 2e-4 at tau = 2e-3 on this coarse
// mesh, 1.3e-4 measured; the first steps of the bump leave 6e-4), the total area within
// 1e-8 and integral phi ds within 1e-6 (relative), although the surface moves and grid
// control redistributes the vertices.
TEST(Shape, AreaAndMassDoNotDriftOver500Steps)
{
  const Parameters parameters =
    budding_with_capped_tau(2e-3, 1.05, std::filesystem::temp_directory_path() / "membrane_conservation");
  Simulator       simulator(parameters, RunOptions{true, "", "test"});
  const RunResult result = simulator.run();
  ASSERT_FALSE(result.failed) << result.stop_reason;
  const Statistics &stats = simulator.statistics();
  ASSERT_GE(stats.last("step"), 500);
  // The first steps of the bump (tau = 1e-4 growing, the largest forces) leave the
  // largest errors; what matters is that they do not build up afterwards.
  const double area_error = std::abs(stats.last("area_error"));
  const double area_drift = std::abs(stats.last("area_drift"));
  const double mass_drift = column_max_abs(stats, "mass_drift");
  std::cout << "after " << stats.last("step") << " steps: vertex area error " << area_error << " (largest in the run "
            << column_max_abs(stats, "area_error") << "), area drift " << area_drift << ", largest mass drift "
            << mass_drift << ", bud height " << stats.last("bud_height") << std::endl;
  EXPECT_GT(stats.last("bud_height"), 0.5); // the surface did move
  EXPECT_LT(area_error, 2e-4);
  EXPECT_LT(area_error, 0.5 * column_max_abs(stats, "area_error"));
  EXPECT_LT(area_drift, 1e-8);
  EXPECT_LT(mass_drift, 1e-6);
}

// The tangential area correction restores the vertex areas of a curved, locally refined
// surface (hanging nodes) after a tangential reshuffle of its vertices: a grid-control
// move of weight 0.3 changes them by up to 1e-2; iterated least-squares tangential moves
// (refactorized whenever a move removes less than 90 % of the error, so that they converge
// like Newton's) bring them back to 1e-10 within 5 moves (4 measured), every move is
// tangential at its vertices, and the surface keeps its shape (total area to 1e-6).
TEST(Shape, TangentialAreaCorrectionRestoresVertexAreas)
{
  Testing::FixedSurface setup(16);
  for (const auto &cell : setup.tria.active_cell_iterators())
    if (cell->is_locally_owned() && cell->center().distance(dealii::Point<3>(0.5, 0.5, 0)) < 0.2)
      cell->set_refine_flag();
  setup.tria.execute_coarsening_and_refinement();
  setup.surface.setup();
  set_bump(setup.surface, 0.5, 1.3);
  setup.update_geometry();
  Surface     &surface = setup.surface;
  const Vector target  = vertex_areas(surface);
  const double area    = surface.area();

  Vector displaced = surface.vector_space().make_owned();
  displaced        = surface.displacement();
  displaced += grid_control_displacement(surface, setup.geometry.normal, 0.3);
  surface.set_displacement(displaced);
  const Vector normal = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
  Vector       before = surface.vector_space().make_owned();
  before              = surface.displacement();

  const auto result = correct_areas_tangentially(surface, normal, target, 1e-10, 8);
  std::cout << "vertex-area error " << result.initial_error << " -> " << result.final_error << " in "
            << result.iterations << " moves; total area " << area << " -> " << surface.area()
            << std::endl;
  EXPECT_GT(result.initial_error, 1e-3);
  EXPECT_LT(result.final_error, 1e-10);
  EXPECT_LE(result.iterations, 5u);
  EXPECT_NEAR(result.final_error, max_relative_difference(vertex_areas(surface), target), 1e-15);
  EXPECT_NEAR(surface.area(), area, 1e-6 * area);

  // The first move is tangential at every vertex (the later ones use the same
  // normals, taken before the first move, so the sum is too).
  Vector move = surface.vector_space().make_owned();
  move        = surface.displacement();
  move -= before;
  const Vector normal_part = nodal_dot_product(surface, surface.vector_space().ghosted_copy(move), normal);
  EXPECT_GT(move.linfty_norm(), 1e-4);
  EXPECT_LT(normal_part.linfty_norm(), 1e-12 * move.linfty_norm());
}

// The state at a fixed time converges as tau -> 0, and the vertex area error falls with
// tau. The grid-control weight of a step is proportional to tau (Shape/Grid control rate):
// with the paper's fixed weight per step the mesh is smoothed and phi remapped once per
// step, so the energy at t = 0.1 moves by 1.5e-3 (relative) from tau = 4e-3 to 1e-3
// (measured; it does not settle as tau shrinks), against 1.6e-4 with the rate.
TEST(Shape, StateAtFixedTimeConvergesWithTimeStep)
{
  const auto run = [](const double tau, const double rate) {
    Parameters parameters = budding_with_capped_tau(
      tau, 0.1,
      std::filesystem::temp_directory_path() / ("membrane_tau_" + std::to_string(tau) + "_" + std::to_string(rate)));
    parameters.grid_control_rate = rate;
    Simulator simulator(parameters, RunOptions{true, "", "test"});
    EXPECT_FALSE(simulator.run().failed);
    const Statistics &stats = simulator.statistics();
    EXPECT_NEAR(stats.last("time"), 0.1, 1e-12); // compared at the same time
    std::cout << "tau " << tau << ", grid control rate " << rate << ": energy at t = 0.1 " << stats.last("energy")
              << ", vertex area error " << std::abs(stats.last("area_error")) << std::endl;
    return std::make_pair(stats.last("energy"), std::abs(stats.last("area_error")));
  };
  const auto coarse = run(4e-3, 10), middle = run(2e-3, 10), fine = run(1e-3, 10);
  EXPECT_LT(std::abs(coarse.first - fine.first), 3e-4 * std::abs(fine.first));
  EXPECT_LT(middle.second, coarse.second);
  EXPECT_LT(fine.second, middle.second);
  // The paper's rule (a fixed weight per step) for contrast: the spread is many times larger.
  const double coarse_fixed = run(4e-3, 0).first, fine_fixed = run(1e-3, 0).first;
  EXPECT_GT(std::abs(coarse_fixed - fine_fixed), 5 * std::abs(coarse.first - fine.first));
}

// The bud observables do not depend on where the mesh is fine: the bump measured on a
// uniform 32 x 32 mesh and on the same mesh refined twice on the bump (where
// the samples then crowd) gives the same direction, height and domain protrusion.
TEST(Shape, BudObservablesIndependentOfLocalRefinement)
{
  InitialPhaseOptions initial;
  initial.type        = "bump";
  initial.bump_height = 1.0;
  const auto measure = [&](const unsigned int refinements) {
    Testing::FixedSurface setup(32);
    for (unsigned int r = 0; r < refinements; ++r)
      {
        for (const auto &cell : setup.tria.active_cell_iterators())
          {
            const double rho = cell->center().distance(dealii::Point<3>(0.5, 0.5, 0));
            if (cell->is_locally_owned() && rho < 0.3)
              cell->set_refine_flag();
          }
        setup.tria.execute_coarsening_and_refinement();
      }
    setup.surface.setup();
    set_bump(setup.surface, 0.5, 1.3);
    setup.set_phase(initial);
    std::cout << setup.tria.n_global_active_cells() << " cells: ";
    return measure_bud(setup.surface, setup.phi);
  };
  const BudShape uniform = measure(0);
  std::cout << "height " << uniform.height << ", protrusion " << uniform.domain_protrusion << std::endl;
  const BudShape refined = measure(2);
  std::cout << "height " << refined.height << ", protrusion " << refined.domain_protrusion << std::endl;
  EXPECT_EQ(refined.direction, 1);
  EXPECT_NEAR(refined.height / uniform.height, 1.0, 0.01);
  EXPECT_NEAR(refined.domain_protrusion / uniform.domain_protrusion, 1.0, 0.03);
}
