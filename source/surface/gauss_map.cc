#include <membrane/solvers/vector_access.h>
#include <membrane/surface/gauss_map.h>

#include <deal.II/base/mpi.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    /// Signed solid angle of the spherical triangle of unit vectors a, b, c.
    double solid_angle(const Tensor<1, spacedim> &a, const Tensor<1, spacedim> &b, const Tensor<1, spacedim> &c)
    {
      return 2 * std::atan2(a * cross_product_3d(b, c), 1 + a * b + b * c + c * a);
    }
  } // namespace

  double gauss_map_area(const Surface &surface, const Vector &normal)
  {
    double            local = 0;
    const LocalValues normals(normal);
    for (const auto &cell : surface.vector_space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          Tensor<1, spacedim> n[4];
          for (const unsigned int v : cell->vertex_indices())
            {
              for (unsigned int c = 0; c < spacedim; ++c)
                n[v][c] = normals[cell->vertex_dof_index(v, c)];
              n[v] /= n[v].norm();
            }
          // Positive order 0 -> 1 -> 3 -> 2 (the cell normal is a_1 x a_2).
          local += solid_angle(n[0], n[1], n[3]) + solid_angle(n[0], n[3], n[2]);
        }
    return Utilities::MPI::sum(local, surface.vector_space().communicator());
  }
} // namespace Membrane
