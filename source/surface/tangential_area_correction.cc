#include <membrane/surface/geometry.h>
#include <membrane/surface/tangential_area_correction.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>

#include <petscksp.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    void check(const PetscErrorCode code, const char *what)
    {
      AssertThrow(code == 0, ExcMessage(std::string("PETSc error in ") + what + " (code " + std::to_string(code) + ")"));
    }

    /// B: (B w)_i = integral psi_i div_s w ds, rows of the scalar space, columns of the
    /// vector space, both with their constraints (div_s of psi_j e_c is (grad_s psi_j)_c).
    void assemble_area_change(const Surface &surface, SparseMatrix &B)
    {
      const FieldSpace &scalars = surface.scalar_space(), &vectors = surface.vector_space();
      const auto       &fe      = vectors.fe();
      const unsigned int n_vertices = GeometryInfo<dim>::vertices_per_cell, n_vector = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> scalar_dofs(n_vertices), vector_dofs(n_vector);

      DynamicSparsityPattern pattern(scalars.dof_handler().n_dofs(), vectors.dof_handler().n_dofs(), scalars.relevant());
      for (const auto &cell : vectors.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(vector_dofs);
            scalars.cell(cell)->get_dof_indices(scalar_dofs);
            scalars.constraints().add_entries_local_to_global(scalar_dofs, vectors.constraints(), vector_dofs, pattern,
                                                              false);
          }
      SparsityTools::distribute_sparsity_pattern(pattern, scalars.owned(), scalars.communicator(), scalars.relevant());
      B.reinit(scalars.owned(), vectors.owned(), pattern, scalars.communicator());

      const QGauss<dim>       quadrature(2);
      FEValues<dim, spacedim> fe_values(surface.mapping(), fe, quadrature,
                                        update_values | update_gradients | update_JxW_values);
      FullMatrix<double>      local(n_vertices, n_vector);
      for (const auto &cell : vectors.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            cell->get_dof_indices(vector_dofs);
            scalars.cell(cell)->get_dof_indices(scalar_dofs);
            local = 0;
            for (const unsigned int q : fe_values.quadrature_point_indices())
              for (unsigned int i = 0; i < n_vertices; ++i)
                {
                  const double psi = fe_values.shape_value(fe.component_to_system_index(0, i), q) * fe_values.JxW(q);
                  for (unsigned int k = 0; k < n_vector; ++k)
                    local(i, k) += psi * fe_values.shape_grad(k, q)[fe.system_to_component_index(k).first];
                }
            scalars.constraints().distribute_local_to_global(local, scalar_dofs, vectors.constraints(), vector_dofs, B);
          }
      B.compress(VectorOperation::add);
    }

    /// D^(1/2) = blockdiag(P_j / sqrt(a_j)) on the vector space: the tangent projector of
    /// each unconstrained vertex over the square root of its area (zero rows elsewhere).
    void assemble_tangent_scaling(const Surface &surface, const Vector &normal, const Vector &areas_ghosted,
                                  SparseMatrix &D)
    {
      const FieldSpace &scalars = surface.scalar_space(), &vectors = surface.vector_space();
      std::vector<std::pair<std::array<types::global_dof_index, spacedim>, Tensor<2, spacedim>>> blocks;
      for (const auto &cell : vectors.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            {
              const auto first = cell->vertex_dof_index(v, 0);
              if (!vectors.owned().is_element(first) || vectors.constraints().is_constrained(first))
                continue;
              std::array<types::global_dof_index, spacedim> dofs;
              Tensor<1, spacedim>                           nu;
              for (unsigned int c = 0; c < spacedim; ++c)
                {
                  dofs[c] = cell->vertex_dof_index(v, c);
                  nu[c]   = normal[dofs[c]];
                }
              const double area = areas_ghosted[scalars.cell(cell)->vertex_dof_index(v, 0)];
              blocks.emplace_back(dofs, (unit_symmetric_tensor<spacedim>() - outer_product(nu, nu)) /
                                          std::sqrt(std::max(area, 1e-300)));
            }
      DynamicSparsityPattern pattern(vectors.relevant());
      for (const auto &[dofs, block] : blocks)
        for (const auto row : dofs)
          for (const auto column : dofs)
            pattern.add(row, column);
      D.reinit(vectors.owned(), vectors.owned(), pattern, vectors.communicator());
      for (const auto &[dofs, block] : blocks)
        for (unsigned int r = 0; r < spacedim; ++r)
          for (unsigned int c = 0; c < spacedim; ++c)
            D.set(dofs[r], dofs[c], block[r][c]);
      D.compress(VectorOperation::insert);
    }

    /// The least-squares tangential move that changes the vertex areas by `defect`
    /// (linearized): w = D B^T q with (B D B^T + epsilon) q = defect.
    Vector tangential_move(const Surface &surface, const Vector &normal, const Vector &areas, const Vector &defect)
    {
      const FieldSpace &scalars = surface.scalar_space(), &vectors = surface.vector_space();

      SparseMatrix B, D;
      assemble_area_change(surface, B);
      assemble_tangent_scaling(surface, normal, scalars.ghosted_copy(areas), D);
      Mat BD = nullptr, S = nullptr;
      check(MatMatMult(B, D, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &BD), "MatMatMult");
      check(MatMatTransposeMult(BD, BD, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &S), "MatMatTransposeMult");
      // S = B D B^T is a surface Laplacian (wide stencil): the rows of constrained vertices
      // are empty, and the checkerboard of a uniform mesh is a near-kernel. A shift of 1e-10
      // of its largest diagonal entry makes it regular without damping the smooth modes;
      // a move that does not lower the measured error is not kept.
      Vec diagonal = nullptr;
      check(MatCreateVecs(S, &diagonal, nullptr), "MatCreateVecs");
      check(MatGetDiagonal(S, diagonal), "MatGetDiagonal");
      PetscReal largest = 0;
      check(VecMax(diagonal, nullptr, &largest), "VecMax");
      check(VecDestroy(&diagonal), "VecDestroy");
      check(MatSetOption(S, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption"); // empty rows
      check(MatShift(S, 1e-10 * largest), "MatShift");

      Vector q = scalars.make_owned();
      KSP    ksp = nullptr;
      PC     pc  = nullptr;
      check(KSPCreate(scalars.communicator(), &ksp), "KSPCreate");
      check(KSPSetOperators(ksp, S, S), "KSPSetOperators");
      check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
      check(KSPGetPC(ksp, &pc), "KSPGetPC");
      check(PCSetType(pc, PCLU), "PCSetType");
      check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
      check(KSPSolve(ksp, defect, q), "KSPSolve");
      check(KSPDestroy(&ksp), "KSPDestroy");

      // w = D^(1/2) (B D^(1/2))^T q
      Vector product = vectors.make_owned(), move = vectors.make_owned();
      check(MatMultTranspose(BD, q, product), "MatMultTranspose");
      check(MatMult(D, product, move), "MatMult");
      check(MatDestroy(&S), "MatDestroy");
      check(MatDestroy(&BD), "MatDestroy");
      vectors.constraints().distribute(move);
      return move;
    }
  } // namespace

  TangentialAreaCorrection correct_areas_tangentially(Surface &surface, const Vector &normal_ghosted,
                                                      const Vector &target, const double tolerance,
                                                      const unsigned int max_iterations)
  {
    TangentialAreaCorrection result;
    Vector                   areas = vertex_areas(surface);
    result.initial_error = result.final_error = max_relative_difference(areas, target);
    for (unsigned int it = 0; it < max_iterations && result.final_error > tolerance; ++it)
      {
        Vector defect = target;
        defect -= areas;
        const Vector move = tangential_move(surface, normal_ghosted, areas, defect);
        if (!std::isfinite(move.l2_norm()))
          break;
        Vector before = surface.vector_space().make_owned();
        before        = surface.displacement();
        Vector moved  = before;
        moved += move;
        surface.set_displacement(moved);
        const Vector new_areas = vertex_areas(surface);
        const double error     = max_relative_difference(new_areas, target);
        if (!(error < result.final_error))
          {
            surface.set_displacement(before);
            break;
          }
        areas              = new_areas;
        result.final_error = error;
        ++result.iterations;
      }
    return result;
  }
} // namespace Membrane
