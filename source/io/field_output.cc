#include <membrane/io/atomic_file.h>
#include <membrane/io/field_output.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <fstream>
#include <iomanip>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  FieldOutput::FieldOutput(std::string directory)
    : directory(std::move(directory))
  {}

  void FieldOutput::resume(const double time)
  {
    // write_pvd_record writes one line per snapshot: <DataSet timestep="t" group="" part="0" file="name"/>
    std::ifstream in(directory + "/surface.pvd");
    snapshots.clear();
    for (std::string line; std::getline(in, line);)
      {
        const auto t = line.find("timestep=\""), f = line.find("file=\"");
        if (t == std::string::npos || f == std::string::npos)
          continue;
        const double      when = std::stod(line.substr(t + 10));
        const std::string name = line.substr(f + 6, line.find('"', f + 6) - f - 6);
        if (when <= time * (1 + 1e-12))
          snapshots.emplace_back(when, name);
      }
  }

  void FieldOutput::write(const Surface &surface, const Geometry &geometry,
                          const std::vector<std::pair<std::string, const Vector *>> &scalar_fields,
                          const double time, const unsigned int step)
  {
    DataOut<dim, spacedim> data_out;
    // The scalar space's DoFHandler carries the cell data (attached before any vector).
    data_out.attach_dof_handler(surface.scalar_space().dof_handler());
    const auto             vector_kind = std::vector<DataComponentInterpretation::DataComponentInterpretation>(
      spacedim, DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(surface.vector_space().dof_handler(), surface.displacement(),
                             std::vector<std::string>(spacedim, "displacement"), vector_kind);
    data_out.add_data_vector(surface.vector_space().dof_handler(), geometry.normal,
                             std::vector<std::string>(spacedim, "normal"), vector_kind);
    data_out.add_data_vector(surface.scalar_space().dof_handler(), geometry.mean_curvature, "H");
    data_out.add_data_vector(surface.scalar_space().dof_handler(), geometry.gauss_curvature, "K");
    for (const auto &[name, field] : scalar_fields)
      data_out.add_data_vector(surface.scalar_space().dof_handler(), *field, name);
    // Refinement level of each cell (cell data; levels count from the coarse mesh).
    const auto            &triangulation = surface.scalar_space().dof_handler().get_triangulation();
    dealii::Vector<float>  levels(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        levels[cell->active_cell_index()] = cell->level();
    data_out.add_data_vector(levels, "level", DataOut<dim, spacedim>::type_cell_data);
    data_out.build_patches(surface.mapping());

    std::ostringstream name;
    name << "surface-" << std::setw(6) << std::setfill('0') << step << ".vtu";
    const std::string path = directory + "/" + name.str();
    DataOutBase::VtkFlags flags(time, step);
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out.set_flags(flags);
    data_out.write_vtu_in_parallel(temporary_name(path), surface.scalar_space().communicator());

    if (Utilities::MPI::this_mpi_process(surface.scalar_space().communicator()) == 0)
      {
        commit_temporary(path);
        snapshots.emplace_back(time, name.str());
        std::ostringstream pvd;
        DataOutBase::write_pvd_record(pvd, snapshots);
        write_file_atomically(directory + "/surface.pvd", pvd.str());
      }
  }
} // namespace Membrane
