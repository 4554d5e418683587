#pragma once
// Fourier amplitudes of fields on the periodic patch (MODEL.md section 10): the observables
// of thermal fluctuations. With u the parameter coordinates of the unit square (the
// reference mesh), a field f has the amplitudes
//   f_k = integral over [0,1)^2 of f(u) exp(-2 pi i k.u) du,   q = 2 pi k,
// so that f = sum_k f_k exp(i q.u) and, for a field of small amplitude on a patch of area
// A = 1, the equipartition spectra of MODEL.md section 10 hold for <|f_k|^2> as written there.
// The height is the z component of X (the patch lies in the plane z = 0); to leading order
// in the amplitude, the parameter u of a point is its position (x, y).

#include <membrane/surface/surface.h>

#include <array>
#include <complex>
#include <vector>

namespace Membrane
{
  /// The amplitudes f_k of component `component` of the ghosted Q1 field `field` of `space`,
  /// for each wave vector k of `modes` (integers); collective.
  std::vector<std::complex<double>> fourier_amplitudes(const FieldSpace &space, const Vector &field,
                                                       unsigned int component,
                                                       const std::vector<std::array<int, 2>> &modes);

  /// The mean of |f_k|^2 over the lowest two shells of wave vectors, |k|^2 = 1 ((1,0), (0,1))
  /// and |k|^2 = 2 ((1,1), (1,-1)): the statistics columns of the spectra.
  struct LowestModes
  {
    double shell_1 = 0, shell_2 = 0;
  };
  LowestModes lowest_mode_powers(const FieldSpace &space, const Vector &field, unsigned int component);
} // namespace Membrane
