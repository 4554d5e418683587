#pragma once
// The thermal force of the shape step at a quadrature point, and the split of its tangential part
// used by the ALE scheme (docs/model.md, "Mesh motion"; MODEL.md section 10).
//
// The shape step's thermal displacement density is tau L_X eta, white per quadrature point (its
// covariance is in shape_solver.h). Its tangential part eta_t splits, on the surface, into an
// irrotational and a solenoidal part (the discrete Helmholtz decomposition in Q1):
//     eta_t ~ grad_s chi + n x grad_s psi,
//     (grad_s chi, grad_s q) = (eta_t, grad_s q),   (grad_s psi, grad_s q) = (eta_t, n x grad_s q)
// for every Q1 q (n the cells' unit normal). The solenoidal part moves lipids without changing
// the shape or any area: (n x grad_s psi, grad_s q) = 0 exactly for Q1 psi and q (the integrand is
// d psi ^ d q, bilinear in the parameters: 2 x 2 Gauss integrates it exactly), so it is in the
// kernel of the local area constraint and the constraint passes it on unchanged. The equal-order
// stabilized constraint of the shape step cannot: the Q1 velocity of a grid-scale solenoidal field
// has a grid-scale discrete divergence, which the stabilization leaves as a local compression of
// the size of the noise. So the ALE scheme puts only grad_s chi into the shape step's tangential
// law (where it is exactly a shift of the pressure, gamma -> gamma - chi / (tau L_X), plus its
// normal force) and carries phi with n x grad_s psi in addition to the relative motion. What
// neither part holds (the noise that no Q1 gradient sees: the finest scales) and, on the
// periodic patch, the two uniform translations are left out.

#include <membrane/physics/thermal_noise.h>
#include <membrane/surface/surface.h>

#include <deal.II/base/tensor.h>

#include <cstdint>

namespace Membrane
{
  /// The shape noise's variates are components first_shape_noise_component + 3 q + c of the
  /// cell's key; the Cahn-Hilliard noise of the same step uses components 0 and 1.
  constexpr unsigned int first_shape_noise_component = 8;

  /// tau L_X eta at quadrature point q (weight `JxW`) of the cell with key `key`: three
  /// independent normals of variance 2 k_BT tau L_X / JxW.
  dealii::Tensor<1, spacedim> shape_noise(const ThermalNoise &noise, double tau_mobility, std::uint64_t key,
                                          unsigned int q, double JxW);

  struct TangentialNoise
  {
    Vector potential; ///< chi (ghosted, scalar space): grad_s chi enters the shape step
    Vector stream;    ///< psi (ghosted, scalar space): n x grad_s psi carries the lipids only
    double max_stream_displacement = 0; ///< max |grad_s psi| over the quadrature points
  };

  /// The split of this step's tangential noise on the current surface (see above). `normal`:
  /// the vertex normals (ghosted, vector space) that orient n. Two solves with the Q1
  /// stiffness matrix (plus 1e-6 / area times the mass, which fixes the constants of
  /// chi and psi; their gradients do not depend on it).
  TangentialNoise split_tangential_noise(const Surface &surface, const Vector &normal, const ThermalNoise &noise,
                                         double tau_mobility);
} // namespace Membrane
