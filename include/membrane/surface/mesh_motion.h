#pragma once
// Mesh motion of the ALE scheme (docs/model.md, "Mesh motion").
//
// The shape step gives the material displacement W = tau v on Gamma^m (normal and tangential:
// the dissipation, the local area constraint and the thermal noise act on v). With Shape/Mesh
// motion = ale the vertices are not material points: the mesh keeps only the normal part of that
// motion, and its tangential motion serves mesh quality only (grid control's smoothing, no
// physics, no noise):
//     X^{m+1}_i = X^m_i + W^mesh_i,   W^mesh_i = (W_i . nu_i) nu_i + s_i,
// with nu the vertex normals of Gamma^m and s the smoothing measured at X^m + (W . nu) nu. The
// material configuration X^m + W is never built as a mesh (at a temperature its cells fold: the
// lipids' random walk moves each vertex by a good part of a cell per step). The lipids do not
// move with the mesh: phi is carried by the relative displacement d = W^mesh - W = -tau (v - w)
// in the conservative ALE form, on Gamma^m,
//     (phi^{m+1}, chi_i)_{m+1} = (phi~, chi_i)_m - (phi~ d, grad_s chi_i)_m - 1/2 (d . grad_s phi~, d . grad_s chi_i)_m
// with lumped masses on both sides, so that integral phi ds is conserved exactly (sum_i
// grad chi_i = 0) and a profile translated by d is carried to second order in d (the last
// term, Lax-Wendroff's, keeps the explicit transport stable for |d| below a cell; for a random
// d it is the diffusion <d d>/2 of the lipids' random walk).

#include <membrane/surface/surface.h>

#include <string>
#include <vector>

namespace Membrane
{
  /// How the vertices move (Shape/Mesh motion).
  enum class MeshMotion
  {
    lagrangian, ///< material points, repaired by grid control under the energy test (the paper)
    ale         ///< the normal velocity of the membrane plus grid control; phi carried by v - w
  };

  MeshMotion parse_mesh_motion(const std::string &name);

  /// (W_i . nu_i) nu_i at every free vertex: the normal part of the material displacement
  /// (owned, vector space). `increment` and `normal` ghosted, vector space.
  Vector normal_part(const Surface &surface, const Vector &increment, const Vector &normal);

  /// The mesh displacement W^mesh of the ALE step from the current surface Gamma^m (owned, vector
  /// space): the normal part of `increment`, then `sweeps` sweeps of grid control's smoothing of
  /// weight `weight` (grid_control_displacement), each measured where the previous ones put the
  /// vertices. The surface is left where it was.
  Vector ale_mesh_increment(Surface &surface, const Vector &increment, const Vector &normal, unsigned int sweeps,
                            double weight);

  /// The ALE transport flux F_i = (f d, grad_s chi_i) + 1/2 (d . grad_s f, d . grad_s chi_i) on
  /// the current surface (owned, scalar space; sums to zero). `relative` and `f` ghosted. A
  /// `stream` psi (ghosted, scalar space) adds the lipids' solenoidal displacement
  /// stream_scale n x grad_s psi to their motion: d gains its negative (physics/tangential_noise.h).
  Vector transport_flux(const Surface &surface, const Vector &relative, const Vector &f,
                        const Vector *stream = nullptr, double stream_scale = 1);

  /// Moves the surface by `mesh_increment` (owned, vector space) and carries each nodal field
  /// of `fields` (ghosted, scalar space, updated in place) conservatively along the relative
  /// displacement `relative` (owned): m_i^{new} f_i^{new} = m_i f_i - F_i with the lumped vertex
  /// areas m of the surface before and after the move; `stream` and `stream_scale` as in
  /// transport_flux.
  void move_and_transport(Surface &surface, const Vector &mesh_increment, const Vector &relative,
                          const std::vector<Vector *> &fields, const Vector *stream = nullptr,
                          double stream_scale = 1);
} // namespace Membrane
