#pragma once
// Discrete differential geometry of the current surface (MODEL.md sections 1 and 4):
//  - vertex normals nu: area-weighted average of the cell normals around each
//    vertex (paper eq. 6.5), realised as sum_cells integral n phi_i ds, normalised;
//  - mean curvature H (sum of principal curvatures): the weak form of
//    lap_s X = H n, i.e. (Hvec, psi) = -(grad_s X, grad_s psi) for the Q1
//    mean-curvature vector, then H_i = Hvec_i . nu_i at each vertex;
//  - Gaussian curvature K: the L2 projection of ((tr grad_s nu)^2 - |grad_s nu|^2)/2.

#include <membrane/surface/surface.h>

#include <deal.II/base/derivative_form.h>
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

  /// Lengths of a cell's edges along the parameter directions u_1, u_2 in the reference
  /// (input) mesh, which turn the unit-cell Jacobian into a_k = dX/du_k.
  template <typename CellIterator>
  std::array<double, 2> reference_edge_lengths(const CellIterator &cell)
  {
    return {{cell->vertex(1).distance(cell->vertex(0)), cell->vertex(2).distance(cell->vertex(0))}};
  }

  /// a_k = dX/du_k at a point: the columns of the unit-cell Jacobian over the reference edge
  /// lengths (the parameter directions of the patch, the tangents of the tangential law).
  inline std::array<dealii::Tensor<1, spacedim>, 2>
  parameter_tangents(const dealii::DerivativeForm<1, dim, spacedim> &jacobian,
                     const std::array<double, 2>                    &reference_length)
  {
    std::array<dealii::Tensor<1, spacedim>, 2> a;
    for (unsigned int k = 0; k < 2; ++k)
      for (unsigned int c = 0; c < spacedim; ++c)
        a[k][c] = jacobian[c][k] / reference_length[k];
    return a;
  }

  /// The cell's unit normal a_1 x a_2 / |a_1 x a_2| from the Jacobian at a point, turned to the
  /// side of `nu` (the vertex normal field there): the cells of a closed mesh need not share an
  /// orientation.
  inline dealii::Tensor<1, spacedim> oriented_cell_normal(const dealii::DerivativeForm<1, dim, spacedim> &jacobian,
                                                          const dealii::Tensor<1, spacedim>             &nu)
  {
    dealii::Tensor<1, spacedim> a1, a2;
    for (unsigned int c = 0; c < spacedim; ++c)
      {
        a1[c] = jacobian[c][0];
        a2[c] = jacobian[c][1];
      }
    dealii::Tensor<1, spacedim> n = dealii::cross_product_3d(a1, a2);
    n /= n.norm();
    return n * nu < 0 ? -n : n;
  }

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
