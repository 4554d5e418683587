#include <membrane/analysis/surface_quads.h>
#include <membrane/solvers/vector_access.h>

#include <deal.II/base/mpi.h>

#include <optional>

namespace Membrane
{
  using namespace dealii;

  std::vector<SurfaceQuad> gather_surface_quads(const Surface &surface, const Vector *phi,
                                                std::vector<double> *vertex_phi)
  {
    std::vector<double>        local, local_phi;
    std::optional<LocalValues> phi_values;
    if (phi != nullptr)
      phi_values.emplace(*phi);
    for (const auto &cell : surface.vector_space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto X           = surface.mapping().get_vertices(cell);
          const auto scalar_cell = surface.scalar_space().cell(cell);
          for (const unsigned int v : cell->vertex_indices())
            {
              local.insert(local.end(), {X[v][0], X[v][1], X[v][2]});
              if (phi != nullptr)
                local_phi.push_back((*phi_values)[scalar_cell->vertex_dof_index(v, 0)]);
            }
        }
    const MPI_Comm           comm = surface.vector_space().communicator();
    std::vector<SurfaceQuad> quads;
    for (const auto &part : Utilities::MPI::all_gather(comm, local))
      for (std::size_t i = 0; i + 12 <= part.size(); i += 12)
        quads.push_back({{Point<spacedim>(part[i], part[i + 1], part[i + 2]),
                          Point<spacedim>(part[i + 3], part[i + 4], part[i + 5]),
                          Point<spacedim>(part[i + 6], part[i + 7], part[i + 8]),
                          Point<spacedim>(part[i + 9], part[i + 10], part[i + 11])}});
    if (phi != nullptr && vertex_phi != nullptr)
      {
        vertex_phi->clear();
        for (const auto &part : Utilities::MPI::all_gather(comm, local_phi))
          vertex_phi->insert(vertex_phi->end(), part.begin(), part.end());
      }
    return quads;
  }
} // namespace Membrane
