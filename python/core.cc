// membrane_flow._core: a run of the simulator driven from Python (docs/python.md).
// The time loop is Simulator's own (initialize / advance / finish, the same code the
// program runs); the state is copied into numpy arrays indexed by the vertices
// (the degrees of freedom of the scalar Q1 space).
#include <membrane/app.h>
#include <membrane/io/run_directory.h>
#include <membrane/parameters.h>
#include <membrane/simulator.h>
#include <membrane/solvers/blas_threads.h>

#include <deal.II/base/mpi.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <iostream>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace
{
  using namespace Membrane;

  /// The exception raised for bad input and failed runs (membrane_flow.Error).
  struct Error : std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  class Simulation;
  std::set<Simulation *> open_simulations;

  /// MPI (and with it PETSc and p4est) is started by the first Simulation and ended
  /// at interpreter exit, after the simulations still open are closed.
  std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;

  void start_mpi()
  {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (initialized)
      return;
    static int   argc    = 1;
    static char  name[]  = "membrane_flow";
    static char *args[]  = {name, nullptr};
    static char **argv   = args;
    mpi = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(argc, argv, 1);
    use_single_threaded_blas();
  }

  class Simulation
  {
  public:
    Simulation(const std::string &input, const std::vector<std::pair<std::string, std::string>> &entries,
               const bool overwrite, const bool quiet)
    {
      start_mpi();
      guarded([&]() {
        dealii::ParameterHandler prm;
        read_parameter_file(input, prm, parameters, entries, "");
        std::ostringstream text;
        prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
        options.parameter_text = text.str();
        options.quiet          = quiet;
        options.command_line   = "python: membrane_flow.Simulation(" + (input.empty() ? "" : "'" + input + "', ") +
                               std::to_string(entries.size()) + " entries)";
        std::vector<std::string> keep;
        if (!input.empty())
          keep.push_back(input);
        directory = claim_run_directory({parameters.output_directory, overwrite, parameters.resume_from, keep},
                                        MPI_COMM_WORLD);
        simulator = std::make_unique<Simulator>(parameters, options);
        open_simulations.insert(this);
        py::gil_scoped_release release; // other Python threads run meanwhile
        simulator->initialize();
      });
    }

    ~Simulation()
    {
      try
        {
          close();
        }
      catch (...) // nothing may escape a destructor; close() has freed the simulator
        {}
    }

    /// Ends the run (summary.json) and frees the simulator; the object is unusable after.
    void close()
    {
      if (!simulator)
        return;
      guarded([&]() { simulator->finish(); });
      simulator.reset();
      directory = RunDirectory();
      open_simulations.erase(this);
    }

    /// Trial steps until one is accepted; false (nothing done) when the run has stopped.
    bool step()
    {
      const unsigned int before = sim().current_step();
      while (sim().current_step() == before)
        {
          bool more = false;
          guarded([&]() {
            Simulator          &simulator = sim();
            py::gil_scoped_release release; // other Python threads run meanwhile
            more = simulator.advance();
          });
          if (!more)
            return false;
          if (PyErr_CheckSignals() != 0) // Ctrl-C between trial steps: KeyboardInterrupt
            throw py::error_already_set();
        }
      return true;
    }

    unsigned int advance(const unsigned int n)
    {
      unsigned int taken = 0;
      while (taken < n && step())
        ++taken;
      return taken;
    }

    unsigned int run_until(const double t)
    {
      unsigned int taken = 0;
      while (sim().current_time() < t && step())
        ++taken;
      return taken;
    }

    py::dict finish()
    {
      guarded([&]() { sim().finish(); });
      return result();
    }

    py::dict run()
    {
      while (step())
        ;
      return finish();
    }

    py::dict result()
    {
      const RunResult &r = sim().result();
      py::dict         out;
      out["stop_reason"] = sim().stopped() ? r.stop_reason : std::string();
      out["failed"]      = r.failed;
      out["outcome"]     = r.outcome;
      return out;
    }

    bool   stopped() { return sim().stopped(); }
    double time() { return sim().current_time(); }
    unsigned int steps() { return sim().current_step(); }
    double tau() { return sim().next_time_step(); }
    std::string output_directory() const { return parameters.output_directory; }
    std::string parameter_text() const { return options.parameter_text; }
    bool        is_open() const { return simulator != nullptr; }

    py::dict energies()
    {
      const EnergyTerms &e = sim().energy_terms();
      py::dict           out;
      out["energy"]          = e.total();
      out["bending_energy"]  = e.bending;
      out["gaussian_energy"] = e.gaussian;
      out["gradient_energy"] = e.gradient;
      out["well_energy"]     = e.well;
      return out;
    }

    py::dict statistics()
    {
      const Statistics &stats = sim().statistics();
      const auto       &names = stats.column_names();
      const auto       &rows  = stats.row_values();
      py::dict          out;
      for (std::size_t c = 0; c < names.size(); ++c)
        {
          py::array_t<double> column(rows.size());
          auto                values = column.mutable_unchecked<1>();
          for (std::size_t r = 0; r < rows.size(); ++r)
            values(r) = c < rows[r].size() ? rows[r][c] : std::numeric_limits<double>::quiet_NaN();
          out[py::str(names[c])] = column;
        }
      return out;
    }

    /// X = X_ref + D at every vertex (n_vertices x 3).
    py::array_t<double> positions()
    {
      single_rank();
      return vertex_vectors(sim().current_surface().displacement(), true);
    }

    /// A vector field (vector space) at every vertex (n_vertices x 3), plus the
    /// reference position of the vertex if `add_reference`.
    py::array_t<double> vertex_vectors(const Vector &v, const bool add_reference)
    {
      const Surface      &surface = sim().current_surface();
      const FieldSpace   &vectors = surface.vector_space();
      py::array_t<double> out({n_vertices(), std::size_t(spacedim)});
      auto                x = out.mutable_unchecked<2>();
      std::vector<dealii::types::global_dof_index> dofs(vectors.fe().n_dofs_per_cell());
      for (const auto &cell : sim().mesh().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto scalar_cell = surface.scalar_space().cell(cell);
            vectors.cell(cell)->get_dof_indices(dofs);
            for (unsigned int k = 0; k < dofs.size(); ++k)
              {
                const auto [component, vertex] = vectors.fe().system_to_component_index(k);
                x(scalar_cell->vertex_dof_index(vertex, 0), component) =
                  (add_reference ? cell->vertex(vertex)[component] : 0.0) + v(dofs[k]);
              }
          }
      return out;
    }

    /// The four vertices of each cell, counter-clockwise in the parameter plane (VTK_QUAD order).
    py::array_t<long> cells()
    {
      single_rank();
      const auto       &mesh = sim().mesh();
      py::array_t<long> out({std::size_t(mesh.n_global_active_cells()), std::size_t(4)});
      auto              c = out.mutable_unchecked<2>();
      std::size_t       n = 0;
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto scalar_cell = sim().current_surface().scalar_space().cell(cell);
            const unsigned int order[4] = {0, 1, 3, 2};
            for (unsigned int v = 0; v < 4; ++v)
              c(n, v) = scalar_cell->vertex_dof_index(order[v], 0);
            ++n;
          }
      return out;
    }

    /// A vertex field: phi, Y, gamma, H, K, vertex_area (n_vertices), normal, displacement (n_vertices x 3).
    py::array_t<double> field(const std::string &name)
    {
      single_rank();
      const Surface &surface = sim().current_surface();
      if (name == "normal" || name == "displacement")
        return vertex_vectors(name == "normal" ? sim().current_geometry().normal : surface.displacement(), false);
      Vector areas;
      const Vector *v = nullptr;
      if (name == "phi")
        v = &sim().order_parameter();
      else if (name == "Y")
        v = &sim().chemical_potential_field();
      else if (name == "gamma")
        v = &sim().pressure_field();
      else if (name == "H")
        v = &sim().current_geometry().mean_curvature;
      else if (name == "K")
        v = &sim().current_geometry().gauss_curvature;
      else if (name == "vertex_area")
        {
          areas = vertex_areas(surface);
          v     = &areas;
        }
      else
        throw py::key_error("no field <" + name + ">; the fields are phi, Y, gamma, H, K, vertex_area, normal, "
                            "displacement");
      py::array_t<double> out(n_vertices());
      auto                x = out.mutable_unchecked<1>();
      for (std::size_t i = 0; i < n_vertices(); ++i)
        x(i) = (*v)(i);
      return out;
    }

  private:
    Parameters                 parameters; // the simulator keeps a reference
    RunOptions                 options;
    RunDirectory               directory;
    std::unique_ptr<Simulator> simulator;
    bool                       failed_with_error = false;

    Simulator &sim()
    {
      if (!simulator)
        throw Error(failed_with_error ? "the simulation stopped with an error and cannot continue"
                                      : "the simulation is closed");
      return *simulator;
    }

    std::size_t n_vertices() { return sim().current_surface().scalar_space().dof_handler().n_dofs(); }

    void single_rank()
    {
      if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        throw Error("the state arrays are available on a single MPI rank only");
    }

    /// C++ exceptions become membrane_flow.Error with the message the program prints.
    template <typename F>
    void guarded(F &&f)
    {
      try
        {
          f();
        }
      catch (const py::error_already_set &)
        {
          throw;
        }
      catch (const std::exception &e)
        {
          const std::string message = error_message(e);
          failed_with_error         = simulator != nullptr;
          simulator.reset();
          directory = RunDirectory();
          open_simulations.erase(this);
          throw Error(message);
        }
    }
  };

  /// At interpreter exit: close the simulations still open, then end PETSc and MPI.
  void shut_down()
  {
    while (!open_simulations.empty())
      {
        Simulation *simulation = *open_simulations.begin();
        try
          {
            simulation->close();
          }
        catch (const std::exception &e) // the simulation is freed and unregistered all the same
          {
            std::cerr << "membrane_flow: closing a simulation at exit: " << e.what() << std::endl;
          }
      }
    mpi.reset();
  }
} // namespace

PYBIND11_MODULE(_core, m)
{
  m.doc() = "The compiled part of membrane_flow: a run of membrane-flow driven from Python.";
  py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
  m.def("code_version", []() { return std::string(Membrane::code_version()); });
  m.def("mpi_ranks", []() {
    start_mpi();
    return dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  });
  py::module_::import("atexit").attr("register")(py::cpp_function(&shut_down));

  py::class_<Simulation>(m, "Simulation")
    .def(py::init<const std::string &, const std::vector<std::pair<std::string, std::string>> &, bool, bool>(),
         py::arg("input"), py::arg("entries"), py::arg("overwrite"), py::arg("quiet"))
    .def("step", &Simulation::step)
    .def("advance", &Simulation::advance, py::arg("n"))
    .def("run_until", &Simulation::run_until, py::arg("t"))
    .def("run", &Simulation::run)
    .def("finish", &Simulation::finish)
    .def("close", &Simulation::close)
    .def("result", &Simulation::result)
    .def("stopped", &Simulation::stopped)
    .def("time", &Simulation::time)
    .def("steps", &Simulation::steps)
    .def("tau", &Simulation::tau)
    .def("output_directory", &Simulation::output_directory)
    .def("parameter_text", &Simulation::parameter_text)
    .def("is_open", &Simulation::is_open)
    .def("energies", &Simulation::energies)
    .def("statistics", &Simulation::statistics)
    .def("positions", &Simulation::positions)
    .def("cells", &Simulation::cells)
    .def("field", &Simulation::field, py::arg("name"));
}
