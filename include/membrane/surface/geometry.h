#pragma once
// Discrete differential geometry of the current surface (MODEL.md sections 1 and 4):
//  - vertex normals nu: area-weighted average of the cell normals around each
//    vertex (paper eq. 6.5), realised as sum_cells integral n phi_i ds, normalised;
//  - mean curvature H (sum of principal curvatures): the weak form of
//    lap_s X = H n, i.e. (Hvec, psi) = -(grad_s X, grad_s psi) for the Q1
//    mean-curvature vector, then H_i = Hvec_i . nu_i at each vertex;
//  - Gaussian curvature K: the L2 projection of ((tr grad_s nu)^2 - |grad_s nu|^2)/2.

#include <membrane/surface/surface.h>

#include <deal.II/base/tensor.h>

#include <array>

namespace Membrane
{
  struct Geometry
  {
    Vector normal;          ///< unit vertex normals (vector space, ghosted)
    Vector mean_curvature;  ///< H (scalar space, ghosted)
    Vector gauss_curvature; ///< K (scalar space, ghosted)
  };

  /// Vertex normals of the current surface (owned vector of the vector space).
  Vector compute_vertex_normals(const Surface &surface);

  /// Mean curvature from the weak Laplace-Beltrami of X, projected on `normal`.
  Vector compute_mean_curvature(const Surface &surface, const Vector &normal_ghosted);

  /// L2 projection of K = ((tr grad_s nu)^2 - |grad_s nu|^2)/2.
  Vector compute_gauss_curvature(const Surface &surface, const Vector &normal_ghosted);

  /// An orthonormal basis of the plane normal to nu (a vertex normal), a function of nu
  /// alone, so that every cell at a vertex uses the same one. It follows the projection
  /// of the z axis, which turns smoothly from vertex to vertex (a hanging vertex and its
  /// parents get nearly the same frame), and that of the x axis near the poles.
  std::array<dealii::Tensor<1, spacedim>, 2> tangent_frame(const dealii::Tensor<1, spacedim> &nu);

  /// All three, ghosted.
  Geometry compute_geometry(const Surface &surface);

  /// The vertex-wise dot product a_i . b_i of two vector-space fields (ghosted),
  /// as an owned scalar-space vector with constraints applied.
  Vector nodal_dot_product(const Surface &surface, const Vector &a_ghosted, const Vector &b_ghosted);

  /// The area carried by each vertex, a_i = integral psi_i ds over the current surface
  /// (owned scalar-space vector, assembled: constrained vertices hold 0, their share
  /// is in their masters). Their sum is the total area, and integral phi ds = sum phi_i a_i.
  Vector vertex_areas(const Surface &surface);

  /// Largest |a_i - b_i| / b_i over the vertices with b_i > 0 (global).
  double max_relative_difference(const Vector &a, const Vector &b);

  /// Integral of a scalar-space field over the current surface.
  double integrate(const Surface &surface, const Vector &scalar_ghosted);
} // namespace Membrane
