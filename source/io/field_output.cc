#include <membrane/io/atomic_file.h>
#include <membrane/io/field_output.h>
#include <membrane/io/vtu_writer.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    /// The PVD entries with t <= time of `pvd`, file names prefixed by `prefix`.
    std::vector<std::pair<double, std::string>> read_pvd(const std::string &pvd, const double time,
                                                         const std::string &prefix)
    {
      // write_pvd_record writes one line per snapshot: <DataSet timestep="t" group="" part="0" file="name"/>
      std::ifstream                               in(pvd);
      std::vector<std::pair<double, std::string>> entries;
      for (std::string line; std::getline(in, line);)
        {
          const auto t = line.find("timestep=\""), f = line.find("file=\"");
          if (t == std::string::npos || f == std::string::npos)
            continue;
          const double      when = std::stod(line.substr(t + 10));
          const std::string name = line.substr(f + 6, line.find('"', f + 6) - f - 6);
          if (when <= time * (1 + 1e-12))
            entries.emplace_back(when, prefix + name);
        }
      return entries;
    }

    /// deal.II numbers the vertices of a quadrilateral lexicographically; VTK goes around it.
    constexpr std::array<unsigned int, 4> vtk_vertex_order = {{0, 1, 3, 2}};
  } // namespace

  FieldOutput::FieldOutput(std::string directory)
    : directory(std::move(directory))
  {}

  void FieldOutput::write_paraview_state() const
  {
    // A ParaView Python state: File > Load State (or paraview --state=paraview_state.py)
    // opens the series with the standard view. The PVD is looked up next to the script
    // first, so a moved run directory still opens.
    const std::string pvd = std::filesystem::absolute(directory + "/surface.pvd").lexically_normal().string();
    write_file_atomically(directory + "/paraview_state.py", R"(# ParaView state of a membrane-flow run: File > Load State, or paraview --state=paraview_state.py.
# The surface coloured by phi (phase A red, B blue), smooth-shaded, at the last time; the
# points are the current surface already (no Warp By Vector).
import os
from paraview.simple import *

pvd = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'surface.pvd') if '__file__' in globals() else ''
if not os.path.exists(pvd):
    pvd = r')" + pvd + R"('
reader = PVDReader(registrationName='surface.pvd', FileName=pvd)
surface = ExtractSurface(registrationName='surface', Input=reader)
smooth = GenerateSurfaceNormals(registrationName='smooth shading', Input=surface)
smooth.FeatureAngle = 80.0
view = GetActiveViewOrCreate('RenderView')
view.Background = [1, 1, 1]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
display = Show(smooth, view)
ColorBy(display, ('POINTS', 'phi'))
lut = GetColorTransferFunction('phi')
lut.ApplyPreset('Cool to Warm', True)
lut.AutomaticRescaleRangeMode = 'Never'
lut.RescaleTransferFunction(-1.0, 1.0)
display.SetScalarBarVisibility(view, True)
bar = GetScalarBar(lut, view)
bar.TitleColor = bar.LabelColor = [0, 0, 0]
bar.RangeLabelFormat = bar.LabelFormat = '%.1f'
clock = AnnotateTime(registrationName='time')
clock.Format = 't = {time:.4g}'
clock_display = Show(clock, view)
clock_display.Color = [0, 0, 0]
clock_display.WindowLocation = 'Upper Left Corner'
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
if reader.TimestepValues:
    scene.AnimationTime = list(reader.TimestepValues)[-1]
# An oblique view from the side of -y, z up, framing the surface at the last time.
view.OrientationAxesVisibility = 0
smooth.UpdatePipeline(scene.AnimationTime)
x0, x1, y0, y1, z0, z1 = smooth.GetDataInformation().GetBounds()
centre = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
view.CameraFocalPoint = centre
view.CameraPosition = [centre[0] + 1.2, centre[1] - 2.2, centre[2] + 1.5]
view.CameraViewUp = [0, 0, 1]
view.ResetCamera(False)
Render(view)
)");
  }

  void FieldOutput::resume(const double time, const std::string &checkpoint)
  {
    namespace fs = std::filesystem;
    snapshots.clear();
    if (fs::exists(directory + "/surface.pvd"))
      snapshots = read_pvd(directory + "/surface.pvd", time, "");
    if (!snapshots.empty())
      return;
    const fs::path earlier = fs::path(checkpoint).parent_path();
    if (fs::exists(earlier / "surface.pvd") && !fs::equivalent(earlier, directory))
      {
        const std::string prefix = fs::relative(earlier, directory).generic_string() + "/";
        snapshots = read_pvd((earlier / "surface.pvd").string(), time, prefix);
      }
  }

  void FieldOutput::write(const Surface &surface, const Geometry &geometry,
                          const std::vector<std::pair<std::string, const Vector *>> &scalar_fields,
                          const double time, const unsigned int step)
  {
    const FieldSpace &scalars = surface.scalar_space(), &vectors = surface.vector_space();
    const auto       &triangulation = scalars.dof_handler().get_triangulation();
    const MPI_Comm    communicator  = scalars.communicator();

    // Each rank lists the vertices of its cells as (scalar DoF index, values): the
    // position X_ref + D, the normal, H, K and the scalar fields. A vertex is one
    // scalar DoF; the two copies of a periodic vertex are distinct DoFs (tied by a
    // constraint), so the patch is not closed up, and a hanging vertex sits on its
    // coarse edge because its values are constrained.
    const unsigned int                   width = 3 + 3 + 2 + scalar_fields.size();
    std::vector<types::global_dof_index> keys;
    std::vector<double>                  values, levels;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto scalar_cell = scalars.cell(cell), vector_cell = vectors.cell(cell);
          levels.push_back(cell->level());
          for (const unsigned int v : vtk_vertex_order)
            {
              const auto key = scalar_cell->vertex_dof_index(v, 0);
              keys.push_back(key);
              for (unsigned int c = 0; c < spacedim; ++c)
                values.push_back(cell->vertex(v)[c] + surface.displacement()(vector_cell->vertex_dof_index(v, c)));
              for (unsigned int c = 0; c < spacedim; ++c)
                values.push_back(geometry.normal(vector_cell->vertex_dof_index(v, c)));
              values.push_back(geometry.mean_curvature(key));
              values.push_back(geometry.gauss_curvature(key));
              for (const auto &field : scalar_fields)
                values.push_back((*field.second)(key));
            }
        }
    const auto all_keys   = Utilities::MPI::gather(communicator, keys, 0);
    const auto all_values = Utilities::MPI::gather(communicator, values, 0);
    const auto all_levels = Utilities::MPI::gather(communicator, levels, 0);
    // Rank 0 writes; a failure (a full disk, say) is raised on every rank so that
    // all of them stop together.
    std::string failure;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      try
        {
          write_snapshot(all_keys, all_values, all_levels, width, scalar_fields, time, step);
        }
      catch (const ExceptionBase &e)
        {
          // The message itself, without deal.II's frame (it is raised again below).
          std::ostringstream message;
          e.print_info(message);
          failure = Utilities::trim(message.str());
        }
      catch (const std::exception &e)
        {
          failure = e.what();
        }
    failure = Utilities::MPI::broadcast(communicator, failure, 0);
    AssertThrow(failure.empty(), ExcMessage(failure));
  }

  void FieldOutput::write_snapshot(const std::vector<std::vector<types::global_dof_index>> &all_keys,
                                   const std::vector<std::vector<double>> &all_values,
                                   const std::vector<std::vector<double>> &all_levels, const unsigned int width,
                                   const std::vector<std::pair<std::string, const Vector *>> &scalar_fields,
                                   const double time, const unsigned int step)
  {
    QuadMesh mesh;
    mesh.time  = time;
    mesh.cycle = step;
    std::vector<VtuArray> point_arrays = {{"normal", 3, {}}, {"H", 1, {}}, {"K", 1, {}}};
    for (const auto &field : scalar_fields)
      point_arrays.push_back({field.first, 1, {}});
    VtuArray                                     level{"level", 1, {}};
    std::map<types::global_dof_index, std::int64_t> point_of_key;
    for (unsigned int rank = 0; rank < all_keys.size(); ++rank)
      {
        level.values.insert(level.values.end(), all_levels[rank].begin(), all_levels[rank].end());
        for (std::size_t i = 0; i < all_keys[rank].size(); ++i)
          {
            const auto [entry, inserted] = point_of_key.emplace(all_keys[rank][i], mesh.n_points());
            mesh.connectivity.push_back(entry->second);
            if (!inserted)
              continue;
            const double *vertex = &all_values[rank][i * width];
            mesh.points.insert(mesh.points.end(), vertex, vertex + 3);
            unsigned int column = 3;
            for (auto &array : point_arrays)
              for (unsigned int c = 0; c < array.components; ++c)
                array.values.push_back(vertex[column++]);
          }
      }
    mesh.point_data = std::move(point_arrays);
    mesh.cell_data  = {std::move(level)};

    std::ostringstream name;
    name << "surface-" << std::setw(6) << std::setfill('0') << step << ".vtu";
    write_file_atomically(directory + "/" + name.str(), vtu_content(mesh));
    snapshots.emplace_back(time, name.str());
    std::ostringstream pvd;
    DataOutBase::write_pvd_record(pvd, snapshots);
    write_file_atomically(directory + "/surface.pvd", pvd.str());
    if (snapshots.size() == 1 || !std::filesystem::exists(directory + "/paraview_state.py"))
      write_paraview_state();
  }
} // namespace Membrane
