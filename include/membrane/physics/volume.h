#pragma once
// The enclosed volume of a closed surface and its constraint (MODEL.md section 8).
//
//   V = 1/3 integral over Gamma of X.n ds,   delta V = integral delta X . n ds,
//   reduced volume v = 6 sqrt(pi) V / A^(3/2)   (1 for a sphere).
//
// Modes (Volume/Constraint):
//  free:     no volume term; V evolves with the shape;
//  fixed:    a global multiplier p (pressure inside minus outside) for V = V_target(t);
//            the energy gains -p (V - V_target), the shape step is bordered by the
//            linearized constraint integral over Gamma^m of W.n^m ds = V_target - V(X^m)
//            (ShapeSolver::VolumeCoupling) and each step's result is projected back
//            onto it, so that errors do not accumulate;
//  pressure: the same force p n with p given; positive p inflates.
// V_target moves linearly from the initial volume V_0 to v* A_0^(3/2) / (6 sqrt(pi))
// over the ramp time, where v* is the reduced volume target and A_0 the initial area
// (which the local area constraint keeps); without a target it stays V_0.

#include <membrane/surface/surface.h>

#include <string>

namespace Membrane
{
  struct VolumeOptions
  {
    std::string constraint            = "free"; ///< free|fixed|pressure
    double      pressure              = 0;      ///< p for constraint = pressure (energy/length^3)
    double      reduced_volume_target = 0;      ///< v* (0: keep the initial volume)
    double      ramp_time             = 0;      ///< time over which V_target moves to v* (0: at once)
  };

  /// V = 1/3 integral X.n ds of the current (bilinear) surface; exact with 2x2 Gauss points.
  double enclosed_volume(const Surface &surface);

  /// v = 6 sqrt(pi) V / A^(3/2).
  double reduced_volume(double volume, double area);

  /// The volume that v* stands for on a surface of area A: v* A^(3/2) / (6 sqrt(pi)).
  double volume_of_reduced_volume(double reduced, double area);

  /// V_target(t) (see above).
  double target_volume(const VolumeOptions &options, double initial_volume, double initial_area, double time);
} // namespace Membrane
