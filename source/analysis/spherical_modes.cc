#include <membrane/analysis/spherical_modes.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <cmath>
#include <complex>
#include <cstdlib>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    /// Y_lm for all l <= l_max at `direction` (a unit vector), at index l (l + 1) + m. The
    /// orthonormal associated Legendre functions divided by sin^m theta, pbar_lm(cos theta),
    /// follow the standard three-term recursion in l; sin^m theta e^{i m varphi} is (x + i y)^m,
    /// so nothing is singular at the poles.
    void harmonics(const unsigned int l_max, const Tensor<1, spacedim> &direction, std::vector<double> &Y)
    {
      const int                  L = l_max;
      const double               z = direction[2];
      const std::complex<double> xy(direction[0], direction[1]);
      Y.assign((l_max + 1) * (l_max + 1), 0.0);
      std::vector<double>  pbar((l_max + 1) * (l_max + 1), 0.0); // pbar_lm at index l (l + 1) + m, m >= 0
      const auto           at = [](const int l, const int m) { return l * (l + 1) + m; };
      std::complex<double> power_m(1, 0);                          // (x + i y)^m
      double               diagonal = 1 / std::sqrt(4 * M_PI);    // pbar_mm
      for (int m = 0; m <= L; ++m)
        {
          if (m > 0)
            {
              diagonal *= std::sqrt((2 * m + 1) / (2.0 * m));
              power_m *= xy;
            }
          pbar[at(m, m)] = diagonal;
          if (m + 1 <= L)
            pbar[at(m + 1, m)] = std::sqrt(2 * m + 3.0) * z * diagonal;
          for (int l = m + 2; l <= L; ++l)
            {
              const double a = std::sqrt((4.0 * l * l - 1) / (l * l - m * m));
              const double b = std::sqrt(((l - 1.0) * (l - 1) - m * m) / (4.0 * (l - 1) * (l - 1) - 1));
              pbar[at(l, m)] = a * (z * pbar[at(l - 1, m)] - b * pbar[at(l - 2, m)]);
            }
          for (int l = m; l <= L; ++l)
            if (m == 0)
              Y[at(l, 0)] = pbar[at(l, 0)];
            else
              {
                Y[at(l, m)]  = std::sqrt(2.0) * pbar[at(l, m)] * power_m.real();
                Y[at(l, -m)] = std::sqrt(2.0) * pbar[at(l, m)] * power_m.imag();
              }
        }
    }
  } // namespace

  double real_spherical_harmonic(const unsigned int l, const int m, const Tensor<1, spacedim> &direction)
  {
    Assert(static_cast<unsigned int>(std::abs(m)) <= l, ExcIndexRange(std::abs(m), 0, l + 1));
    std::vector<double> Y;
    harmonics(l, direction, Y);
    return Y[l * (l + 1) + m];
  }

  double SphericalModes::amplitude(const unsigned int l, const int m) const
  {
    Assert(l <= l_max && static_cast<unsigned int>(std::abs(m)) <= l, ExcIndexRange(l, 0, l_max + 1));
    return amplitudes[l * (l + 1) + m];
  }

  double SphericalModes::power(const unsigned int l) const
  {
    double sum = 0;
    for (int m = -static_cast<int>(l); m <= static_cast<int>(l); ++m)
      sum += amplitude(l, m) * amplitude(l, m);
    return sum;
  }

  Point<spacedim> volume_centroid(const Surface &surface)
  {
    // integral over Omega of x_i dV = integral over Gamma of x_i^2 / 2 n_i ds, V = integral x.n ds / 3.
    const QGauss<dim>       quadrature(3);
    FEValues<dim, spacedim> fe_values(surface.mapping(), surface.vector_space().fe(), quadrature,
                                      update_quadrature_points | update_normal_vectors | update_JxW_values);
    std::vector<double>     moments(spacedim + 1, 0.0);
    for (const auto &cell : surface.vector_space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Point<spacedim>     &x = fe_values.quadrature_point(q);
              const Tensor<1, spacedim> &n = fe_values.normal_vector(q);
              for (unsigned int i = 0; i < spacedim; ++i)
                moments[i] += x[i] * x[i] / 2 * n[i] * fe_values.JxW(q);
              moments[spacedim] += x * n * fe_values.JxW(q) / 3;
            }
        }
    Utilities::MPI::sum(moments, surface.vector_space().communicator(), moments);
    Point<spacedim> centroid;
    for (unsigned int i = 0; i < spacedim; ++i)
      centroid[i] = moments[i] / moments[spacedim];
    return centroid;
  }

  std::vector<double> field_spherical_amplitudes(const Surface &surface, const Vector &field_ghosted,
                                                 const unsigned int l_max)
  {
    const Point<spacedim>   centroid = volume_centroid(surface);
    const FieldSpace       &scalars  = surface.scalar_space();
    const QGauss<dim>       quadrature(3);
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature,
                                      update_values | update_quadrature_points | update_normal_vectors |
                                        update_JxW_values);
    const unsigned int      n_harmonics = (l_max + 1) * (l_max + 1);
    std::vector<double>     sums(n_harmonics, 0.0), Y, f(quadrature.size());
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(field_ghosted, f);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              // dOmega = (x - c).n / |x - c|^3 ds: the radial projection onto the unit sphere.
              const Tensor<1, spacedim> x        = fe_values.quadrature_point(q) - centroid;
              const double              distance = x.norm();
              const double solid_angle = x * fe_values.normal_vector(q) / (distance * distance * distance) *
                                         fe_values.JxW(q);
              harmonics(l_max, x / distance, Y);
              for (unsigned int k = 0; k < n_harmonics; ++k)
                sums[k] += f[q] * Y[k] * solid_angle;
            }
        }
    Utilities::MPI::sum(sums, scalars.communicator(), sums);
    return sums;
  }

  SphericalModes spherical_modes(const Surface &surface, const unsigned int l_max)
  {
    const FieldSpace &vectors = surface.vector_space();
    const MPI_Comm    comm    = vectors.communicator();
    // Three Gauss points per direction: the integrands (a bilinear interpolant times Y_lm of
    // low l times the solid-angle density) are smooth on each cell, and their quadrature
    // error is far below the interpolation error of u.
    const QGauss<dim>       quadrature(3);
    FEValues<dim, spacedim> fe_values(surface.mapping(), vectors.fe(), quadrature,
                                      update_quadrature_points | update_normal_vectors | update_JxW_values);
    // The vertices of a cell in deal.II's order, which is QTrapezoid's: the reference
    // vertex positions (the reference mapping is Q1) and the displacement there.
    const QTrapezoid<dim>   vertex_rule;
    FEValues<dim, spacedim> vertex_values(surface.reference_mapping(), vectors.fe(), vertex_rule,
                                          update_values | update_quadrature_points);
    const unsigned int      n_vertices = vertex_rule.size();
    std::vector<dealii::Vector<double>> D(n_vertices, dealii::Vector<double>(spacedim));

    SphericalModes modes;
    modes.l_max    = l_max;
    modes.centroid = volume_centroid(surface);

    // One pass for integral r Y_lm dOmega, integral Y_lm dOmega, integral r dOmega and the
    // total solid angle; then R0 = <r> and u_lm = integral r Y_lm dOmega / R0 - integral Y_lm dOmega.
    const unsigned int  n_harmonics = (l_max + 1) * (l_max + 1);
    std::vector<double> sums(2 * n_harmonics + 2, 0.0), Y, radius(n_vertices);
    for (const auto &cell : vectors.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          vertex_values.reinit(cell);
          vertex_values.get_function_values(surface.displacement(), D);
          for (unsigned int v = 0; v < n_vertices; ++v)
            {
              Tensor<1, spacedim> x = vertex_values.quadrature_point(v) - modes.centroid;
              for (unsigned int i = 0; i < spacedim; ++i)
                x[i] += D[v][i];
              radius[v] = x.norm();
            }
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Tensor<1, spacedim> x        = fe_values.quadrature_point(q) - modes.centroid;
              const double              distance = x.norm();
              const double solid_angle = x * fe_values.normal_vector(q) / (distance * distance * distance) *
                                         fe_values.JxW(q);
              // The bilinear interpolant of the vertex radii at this point.
              const Point<dim> &p = quadrature.point(q);
              double            r = 0;
              for (unsigned int v = 0; v < n_vertices; ++v)
                r += radius[v] * ((v & 1) ? p[0] : 1 - p[0]) * ((v & 2) ? p[1] : 1 - p[1]);
              harmonics(l_max, x / distance, Y);
              for (unsigned int k = 0; k < n_harmonics; ++k)
                {
                  sums[k] += r * Y[k] * solid_angle;
                  sums[n_harmonics + k] += Y[k] * solid_angle;
                }
              sums[2 * n_harmonics] += r * solid_angle;
              sums[2 * n_harmonics + 1] += solid_angle;
            }
        }
    Utilities::MPI::sum(sums, comm, sums);
    modes.mean_radius = sums[2 * n_harmonics] / sums[2 * n_harmonics + 1];
    modes.amplitudes.resize(n_harmonics);
    for (unsigned int k = 0; k < n_harmonics; ++k)
      modes.amplitudes[k] = sums[k] / modes.mean_radius - sums[n_harmonics + k];
    return modes;
  }

  std::vector<double> spherical_mode_powers(const Surface &surface, const unsigned int l_max)
  {
    const SphericalModes modes = spherical_modes(surface, l_max);
    std::vector<double>  powers(l_max + 1);
    for (unsigned int l = 0; l <= l_max; ++l)
      powers[l] = modes.power(l);
    return powers;
  }
} // namespace Membrane
