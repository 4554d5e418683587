#pragma once
// Spherical-harmonic amplitudes of a closed, star-shaped surface (MODEL.md section 10): the
// observables of a fluctuating quasi-spherical vesicle. About the centroid c of the enclosed
// volume, the surface is r(rhat) = R0 (1 + u(rhat)), and
//   u_lm = integral over the unit sphere of u Y_lm dOmega,
// Y_lm the real spherical harmonics, orthonormal on the unit sphere:
//   Y_l0 = N_l0 P_l^0(cos theta), Y_lm = sqrt 2 N_lm P_l^m(cos theta) cos(m varphi) (m > 0),
//   Y_l,-m = sqrt 2 N_lm P_l^m(cos theta) sin(m varphi), without the Condon-Shortley phase.
// Milner and Safran's <u_lm^2> = k_BT / (kappa (l - 1)(l + 2)(l (l + 1) + Sigma R^2 / kappa))
// holds for these amplitudes.
//
// Projection, not a least-squares fit: the radial projection from c maps the (star-shaped)
// surface one to one onto the unit sphere, so integral over Gamma of f (x - c).n / |x - c|^3 ds
// is integral of f dOmega exactly, and the orthonormality of Y_lm then separates the modes
// without truncating the expansion at l_max (a fit would alias the modes above l_max into the
// ones below). u is the Q1 interpolant of the vertex values |X_i - c| / R0 - 1, so that a mesh
// whose vertices lie on a sphere has u = 0 whatever the chordal sag of its bilinear cells.
// R0 is the mean radius, the solid-angle mean of that interpolant: u_00 = 0 exactly, and a
// sphere's R0 is its vertex radius (the radius of the sphere of the same volume differs from
// it by the O(h^2) sag and at second order in u, neither of which matters to the spectrum).
// u_1m (a translation) is of second order in u about the volume centroid.

#include <membrane/surface/surface.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <vector>

namespace Membrane
{
  /// The real spherical harmonic Y_lm (orthonormal on the unit sphere, convention above) at
  /// the unit vector `direction`; |m| <= l.
  double real_spherical_harmonic(unsigned int l, int m, const dealii::Tensor<1, spacedim> &direction);

  /// The amplitudes u_lm of a closed surface for l = 0 .. l_max.
  struct SphericalModes
  {
    dealii::Point<spacedim> centroid;       ///< c, the centroid of the enclosed volume
    double                  mean_radius = 0; ///< R0
    unsigned int            l_max       = 0;
    std::vector<double>     amplitudes;      ///< u_lm at index l (l + 1) + m

    double amplitude(unsigned int l, int m) const;
    /// sum over m of u_lm^2
    double power(unsigned int l) const;
  };

  /// The spherical-harmonic amplitudes of the current surface up to l_max; collective over
  /// the surface's ranks. The surface must be closed and star-shaped about its centroid.
  SphericalModes spherical_modes(const Surface &surface, unsigned int l_max);

  /// The centroid of the volume a closed surface encloses; collective.
  dealii::Point<spacedim> volume_centroid(const Surface &surface);

  /// integral f Y_lm dOmega of the ghosted scalar Q1 field f, by the radial projection of the
  /// surface from its volume centroid onto the unit sphere, at index l (l + 1) + m for l <= l_max;
  /// collective. The surface must be closed and star-shaped about its centroid.
  std::vector<double> field_spherical_amplitudes(const Surface &surface, const Vector &field_ghosted,
                                                 unsigned int l_max);

  /// sum over m of u_lm^2 for l = 0 .. l_max (entries 0 and 1 are fixed by the choice of R0
  /// and c, see above); collective.
  std::vector<double> spherical_mode_powers(const Surface &surface, unsigned int l_max);
} // namespace Membrane
