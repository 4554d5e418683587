#pragma once
// The shape force of the energy terms that do not depend on the curvature (the line
// energy), as the exact derivative of their discrete energy with respect to the vertex
// positions, phi held at the vertices (Shape/Line force = stress).
//
// For such a term F = integral g(phi, grad_s phi) ds, a variation V of X at fixed nodal
// phi changes F by  dF[V] = integral T : grad_s V ds  with the stress T of the term
// (physics/free_energy.h, FreeEnergyTerm::add_stress). On the Q1 surface with the energy's
// own quadrature this is the exact derivative of the discrete F, so that a shape step along
// f = -M_L^-1 dF/dX lowers the discrete F to first order in tau. The potential form of the
// reference scheme (normal row: H G + sigma xi^2 b(grad phi, grad phi); tangential law:
// Y grad phi) equals it only in the continuum: near an equilibrium its difference is a
// force that moves the surface along a direction in which the discrete energy rises.

#include <membrane/physics/free_energy.h>
#include <membrane/surface/surface.h>

namespace Membrane
{
  /// f = -M_L^-1 dF_s/dX: the force density of the stress terms of `terms` at the vertices
  /// (vector space, ghosted), with the lumped mass M_L (the vertex areas). `terms` must have
  /// been prepared for `surface`.
  Vector stress_force(const Surface &surface, const Vector &phi_ghosted, const FreeEnergy &terms);
} // namespace Membrane
