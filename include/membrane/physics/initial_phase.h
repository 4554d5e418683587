#pragma once
// Initial order parameter phi0 on the reference vertices.
//  random:     independent uniform values in [min, max] per vertex. The value at
//              a vertex is a counter-based hash of (seed, vertex position), so a
//              run is reproducible and independent of the number of MPI ranks
//              and of the DoF numbering;
//  bump:       -1 + a3 (1 + cos(pi rho / R0)) for rho < R0 (MODEL.md section 5);
//  uniform:    a constant;
//  expression: a function of the reference point (x, y);
//  caps:       polar cap domains of phase A on a closed surface (cap_phase.cc): each
//              cap is the set of points whose direction from the centroid lies within
//              the angle theta_c of its axis, theta_c chosen so that the cap covers
//              the given fraction of the area; sharp (+-1) or tanh(3 d / (4 xi)) with
//              d = R (theta_c - theta), R = sqrt(A / 4 pi); several caps are joined
//              (phi is the largest of their profiles).
// With a prescribed mass M = integral phi0 ds (on the initial surface), bump
// solves for a3 (phi0 is affine in a3); the other types add a constant.

#include <membrane/surface/surface.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace Membrane
{
  struct InitialPhaseOptions
  {
    std::string   type       = "random";
    double        random_min = -0.1;
    double        random_max = 0.1;
    std::uint64_t seed       = 1;
    double        uniform_value = 0;
    std::string   expression    = "0";
    double        bump_radius   = 0.5;
    double        bump_height   = 0.5; ///< a3 when the mass is not prescribed
    bool          prescribe_mass = false;
    double        mass           = 0;
    std::vector<dealii::Tensor<1, spacedim>> cap_axes; ///< caps: unit axes, one per cap
    double        cap_area_fraction = 0.1;  ///< caps: area fraction of each cap
    bool          cap_sharp         = false; ///< caps: +-1 instead of the tanh profile
    double        transition_length = 0.03;  ///< xi of the tanh profile
  };

  /// Parse "x y z; x y z; ..." into unit vectors; throws naming `entry`.
  std::vector<dealii::Tensor<1, spacedim>> parse_cap_axes(const std::string &text, const std::string &entry);

  /// phi0 of Type = caps (owned, constraints applied; no mass prescription).
  Vector make_cap_phase(const Surface &surface, const InitialPhaseOptions &options);

  /// A uniform number in [0, 1) determined by (seed, point) alone.
  double hashed_uniform(std::uint64_t seed, const dealii::Point<spacedim> &reference_point);

  /// phi0 as an owned scalar-space vector (constraints applied).
  Vector make_initial_phase(const Surface &surface, const InitialPhaseOptions &options);

  /// The section Initial phase of the input (without the caps' entries, vesicle_parameters.cc):
  /// declared with defaults and documentation, and read; the bump radius is the Initial shape's.
  void                declare_initial_phase_parameters(dealii::ParameterHandler &prm);
  InitialPhaseOptions parse_initial_phase_parameters(dealii::ParameterHandler &prm);
} // namespace Membrane
