#include <membrane/io/atomic_file.h>
#include <membrane/io/field_output.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <iomanip>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  FieldOutput::FieldOutput(std::string directory)
    : directory(std::move(directory))
  {}

  void FieldOutput::write(const Surface &surface, const Geometry &geometry,
                          const std::vector<std::pair<std::string, const Vector *>> &scalar_fields,
                          const double time, const unsigned int step)
  {
    DataOut<dim, spacedim> data_out;
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
