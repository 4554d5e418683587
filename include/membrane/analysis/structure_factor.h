#pragma once
// The structure factor of the order parameter (MODEL.md section 10): the power
// of phi per shell of wave numbers, the observable of domain nucleation and
// coarsening and, in one phase, of the equipartition spectrum <|phi_q|^2> =
// k_BT / (A sigma (xi^2 q^2 + f''(phi_0))).
//
// Periodic patch: with the amplitudes phi_k = integral over [0,1)^2 of phi(u)
// exp(-2 pi i k.u) du (analysis/fourier_modes.h; here by the vertex
// (trapezoidal) rule of the reference mesh, which on a uniform mesh is the
// discrete Fourier transform of the vertex values and so has no attenuation
// from the bilinear interpolant), shell n >= 1 holds the wave vectors with n -
// 1/2 <= |k| < n + 1/2, and S_n is the mean of |phi_k|^2 over them. Closed
// surface: phi_lm = integral phi Y_lm dOmega over the unit sphere by the radial
// projection from the volume centroid (analysis/spherical_modes.h), and S_l is
// the mean of phi_lm^2 over m.
//
// The mean wave number q_1 = sum q |phi_q|^2 / sum |phi_q|^2 over all modes of
// the shells (q = 2 pi |k| on the patch of side 1, l on a closed surface) gives
// the domain size 2 pi / q_1 of a coarsening pattern.

#include <membrane/surface/surface.h>

#include <vector>

namespace Membrane
{
  struct StructureFactor
  {
    std::vector<double>       power;        ///< S_n at index n - 1 (patch) or S_l at index l - 1 (closed)
    std::vector<unsigned int> multiplicity; ///< number of modes in each shell
    std::vector<double>       wavenumber;   ///< mean |q| of each shell's modes
    /// q_1 = sum q |phi_q|^2 / sum |phi_q|^2 over every mode of the shells (0 if phi is uniform).
    double mean_wavenumber = 0;
  };

  /// Shells 1 .. n_shells of phi on the periodic unit-square patch; collective.
  StructureFactor patch_structure_factor(const FieldSpace &scalars, const Vector &phi_ghosted, unsigned int n_shells);

  /// Degrees l = 1 .. l_max of phi on a closed, star-shaped surface; collective.
  StructureFactor sphere_structure_factor(const Surface &surface, const Vector &phi_ghosted, unsigned int l_max);
} // namespace Membrane
