#include <membrane/analysis/spherical_modes.h>
#include <membrane/analysis/structure_factor.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>

#include <cmath>
#include <complex>

namespace Membrane
{
  using namespace dealii;

  StructureFactor patch_structure_factor(const FieldSpace &scalars, const Vector &phi_ghosted,
                                         const unsigned int n_shells)
  {
    // The wave vectors of one half plane (k1 > 0, or k1 = 0 < k2): phi is real,
    // so |phi_-k| = |phi_k|, and each shell's mean is the same over the half
    // plane as over all.
    const int                       K = n_shells;
    std::vector<std::array<int, 2>> modes;
    std::vector<unsigned int>       shell_of;
    for (int k1 = 0; k1 <= K; ++k1)
      for (int k2 = -K; k2 <= K; ++k2)
        {
          if (k1 == 0 && k2 <= 0)
            continue;
          const unsigned int shell = static_cast<unsigned int>(std::lround(std::sqrt(double(k1 * k1 + k2 * k2))));
          if (shell >= 1 && shell <= n_shells)
            {
              modes.push_back({{k1, k2}});
              shell_of.push_back(shell);
            }
        }
    // The vertex rule on the reference mesh: on a uniform periodic mesh, the sum
    // over vertices of phi_i exp(-2 pi i k.u_i) h^2 (each periodic vertex once:
    // its copies share the weight). exp(-2 pi i k.u) = e1(k1) e2(k2), tabulated
    // per point.
    const MappingQ<dim, spacedim>     reference_mapping(1);
    const QTrapezoid<dim>             quadrature;
    FEValues<dim, spacedim>           fe_values(reference_mapping, scalars.fe(), quadrature,
                                                update_values | update_quadrature_points | update_JxW_values);
    std::vector<double>               phi(quadrature.size());
    std::vector<std::complex<double>> e1(K + 1), e2(2 * K + 1);
    std::vector<double>               parts(2 * modes.size(), 0.0);
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(phi_ghosted, phi);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Point<spacedim>     &u     = fe_values.quadrature_point(q);
              const std::complex<double> step1 = std::polar(1.0, -2 * M_PI * u[0]);
              const std::complex<double> step2 = std::polar(1.0, -2 * M_PI * u[1]);
              e1[0]                            = 1;
              for (int k = 1; k <= K; ++k)
                e1[k] = e1[k - 1] * step1;
              e2[K] = 1;
              for (int k = 1; k <= K; ++k)
                {
                  e2[K + k] = e2[K + k - 1] * step2;
                  e2[K - k] = std::conj(e2[K + k]);
                }
              const double f = phi[q] * fe_values.JxW(q);
              for (std::size_t m = 0; m < modes.size(); ++m)
                {
                  const std::complex<double> e = e1[modes[m][0]] * e2[K + modes[m][1]];
                  parts[2 * m] += f * e.real();
                  parts[2 * m + 1] += f * e.imag();
                }
            }
        }
    Utilities::MPI::sum(parts, scalars.communicator(), parts);
    StructureFactor result;
    result.power.assign(n_shells, 0.0);
    result.multiplicity.assign(n_shells, 0);
    result.wavenumber.assign(n_shells, 0.0);
    double weighted = 0, total = 0;
    for (std::size_t m = 0; m < modes.size(); ++m)
      {
        const unsigned int s     = shell_of[m] - 1;
        const double       power = parts[2 * m] * parts[2 * m] + parts[2 * m + 1] * parts[2 * m + 1];
        const double       q     = 2 * M_PI * std::hypot(modes[m][0], modes[m][1]);
        result.power[s] += power;
        result.wavenumber[s] += q;
        ++result.multiplicity[s];
        weighted += q * power;
        total += power;
      }
    result.mean_wavenumber = total > 0 ? weighted / total : 0.0;
    for (unsigned int s = 0; s < n_shells; ++s)
      {
        result.power[s] /= result.multiplicity[s];
        result.wavenumber[s] /= result.multiplicity[s];
      }
    return result;
  }

  StructureFactor sphere_structure_factor(const Surface &surface, const Vector &phi_ghosted, const unsigned int l_max)
  {
    const std::vector<double> amplitudes = field_spherical_amplitudes(surface, phi_ghosted, l_max);
    StructureFactor           result;
    double                    weighted = 0, total = 0;
    for (unsigned int l = 1; l <= l_max; ++l)
      {
        double sum = 0;
        for (unsigned int k = l * l; k < (l + 1) * (l + 1); ++k)
          sum += amplitudes[k] * amplitudes[k];
        result.power.push_back(sum / (2 * l + 1));
        result.multiplicity.push_back(2 * l + 1);
        result.wavenumber.push_back(l);
        weighted += l * sum;
        total += sum;
      }
    result.mean_wavenumber = total > 0 ? weighted / total : 0.0;
    return result;
  }
} // namespace Membrane
