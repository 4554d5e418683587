#include <membrane/solvers/petsc_check.h>
#include <membrane/solvers/vector_access.h>
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
    /// Damping of the least-squares move (Levenberg-Marquardt): B D B^T is shifted by a
    /// fraction of its largest diagonal entry. A mode q of eigenvalue lambda moves the
    /// vertices by about (defect . q) sqrt(lambda) / (lambda + shift), so the modes that
    /// barely change the areas (checkerboards of the wide-stencil Laplacian, and on curved
    /// surfaces nearly constant q, since tangential moves keep the total area to first
    /// order) get moves of up to 1 / (2 sqrt(shift)) per unit defect, whose second-order
    /// area changes can exceed what they remove. Each correction starts with the smallest
    /// shift; a move that does not lower the error is retried with the shift multiplied by
    /// 100, up to the largest. On the patch the first suffices; on the phase-field vesicles
    /// a shift of 1e-10 (then the only one) kept no move after the first, while 1e-6 takes
    /// the vertex areas from 8e-3 to 1e-6 in three moves (vesicle-sorting, first steps).
    constexpr double smallest_shift = 1e-8, largest_shift = 1e-4, shift_increase = 100;

    /// B: (B w)_i = integral psi_i div_s w ds, rows of the scalar space, columns of the
    /// vector space, both with their constraints (div_s of psi_j e_c is (grad_s psi_j)_c).
    /// The pattern is made only when `new_pattern` (first use on a mesh).
    void assemble_area_change(const Surface &surface, SparseMatrix &B, const bool new_pattern)
    {
      const FieldSpace &scalars = surface.scalar_space(), &vectors = surface.vector_space();
      const auto       &fe      = vectors.fe();
      const unsigned int n_vertices = GeometryInfo<dim>::vertices_per_cell, n_vector = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> scalar_dofs(n_vertices), vector_dofs(n_vector);

      if (new_pattern)
        {
          DynamicSparsityPattern pattern(scalars.dof_handler().n_dofs(), vectors.dof_handler().n_dofs(),
                                         scalars.relevant());
          for (const auto &cell : vectors.dof_handler().active_cell_iterators())
            if (cell->is_locally_owned())
              {
                cell->get_dof_indices(vector_dofs);
                scalars.cell(cell)->get_dof_indices(scalar_dofs);
                scalars.constraints().add_entries_local_to_global(scalar_dofs, vectors.constraints(), vector_dofs,
                                                                  pattern, false);
              }
          SparsityTools::distribute_sparsity_pattern(pattern, scalars.owned(), scalars.communicator(),
                                                     scalars.relevant());
          B.reinit(scalars.owned(), vectors.owned(), pattern, scalars.communicator());
        }
      else
        B = 0;

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
    /// The pattern (3 x 3 blocks) is made only when `new_pattern`.
    void assemble_tangent_scaling(const Surface &surface, const Vector &normal, const Vector &areas_ghosted,
                                  SparseMatrix &D, const bool new_pattern)
    {
      const FieldSpace &scalars = surface.scalar_space(), &vectors = surface.vector_space();
      std::vector<std::pair<std::array<types::global_dof_index, spacedim>, Tensor<2, spacedim>>> blocks;
      const LocalValues normals(normal), areas(areas_ghosted);
      for_each_free_vertex(vectors, [&](const auto &cell, const unsigned int v, const auto &dofs) {
        Tensor<1, spacedim> nu;
        for (unsigned int c = 0; c < spacedim; ++c)
          nu[c] = normals[dofs[c]];
        const double area = areas[scalars.cell(cell)->vertex_dof_index(v, 0)];
        blocks.emplace_back(dofs, (unit_symmetric_tensor<spacedim>() - outer_product(nu, nu)) /
                                    std::sqrt(std::max(area, 1e-300)));
      });
      if (new_pattern)
        {
          DynamicSparsityPattern pattern(vectors.relevant());
          for (const auto &[dofs, block] : blocks)
            for (const auto row : dofs)
              for (const auto column : dofs)
                pattern.add(row, column);
          D.reinit(vectors.owned(), vectors.owned(), pattern, vectors.communicator());
        }
      for (const auto &[dofs, block] : blocks)
        for (unsigned int r = 0; r < spacedim; ++r)
          for (unsigned int c = 0; c < spacedim; ++c)
            D.set(dofs[r], dofs[c], block[r][c]);
      D.compress(VectorOperation::insert);
    }

  } // namespace

  struct TangentialAreaCorrector::Petsc
  {
    Mat BD = nullptr, S = nullptr, regularized = nullptr;
    KSP ksp = nullptr;

    ~Petsc()
    {
      // Destruction must not throw; the error codes are not checked here.
      KSPDestroy(&ksp);
      MatDestroy(&regularized);
      MatDestroy(&S);
      MatDestroy(&BD);
    }
  };

  // Defined here, where Petsc is a complete type (std::unique_ptr needs it).
  TangentialAreaCorrector::TangentialAreaCorrector()  = default;
  TangentialAreaCorrector::~TangentialAreaCorrector() = default;

  void TangentialAreaCorrector::reset()
  {
    petsc.reset();
  }

  void TangentialAreaCorrector::factorize(const Surface &surface, const Vector &normal_ghosted, const Vector &areas,
                                          const double shift)
  {
    const bool first = petsc == nullptr;
    if (first)
      petsc = std::make_unique<Petsc>();
    assemble_area_change(surface, B, first);
    assemble_tangent_scaling(surface, normal_ghosted, surface.scalar_space().ghosted_copy(areas), D, first);
    const MatReuse reuse = first ? MAT_INITIAL_MATRIX : MAT_REUSE_MATRIX;
    check_petsc(MatMatMult(B, D, reuse, PETSC_DEFAULT, &petsc->BD), "MatMatMult");
    // (PETSc 3.18 refuses MAT_REUSE_MATRIX for A A^T; its symbolic product is cheap.)
    check_petsc(MatDestroy(&petsc->S), "MatDestroy");
    check_petsc(MatMatTransposeMult(petsc->BD, petsc->BD, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &petsc->S),
          "MatMatTransposeMult");
    // S = B D B^T is a surface Laplacian (wide stencil): the rows of constrained vertices
    // are empty, and the checkerboard of a uniform mesh is a near-kernel. The shift (see
    // smallest_shift) makes it regular and damps the near-kernel. It goes into a copy
    // that keeps the added diagonal entries, so that its pattern, and with it the
    // solver's analysis, stays the same from step to step.
    Vec diagonal = nullptr;
    check_petsc(MatCreateVecs(petsc->S, &diagonal, nullptr), "MatCreateVecs");
    check_petsc(MatGetDiagonal(petsc->S, diagonal), "MatGetDiagonal");
    PetscReal largest = 0;
    check_petsc(VecMax(diagonal, nullptr, &largest), "VecMax");
    check_petsc(VecDestroy(&diagonal), "VecDestroy");
    if (first)
      {
        check_petsc(MatDuplicate(petsc->S, MAT_COPY_VALUES, &petsc->regularized), "MatDuplicate");
        check_petsc(MatSetOption(petsc->regularized, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
      }
    else
      check_petsc(MatCopy(petsc->S, petsc->regularized, SUBSET_NONZERO_PATTERN), "MatCopy");
    check_petsc(MatShift(petsc->regularized, shift * largest), "MatShift");
    if (first)
      {
        PC pc = nullptr;
        check_petsc(KSPCreate(surface.scalar_space().communicator(), &petsc->ksp), "KSPCreate");
        check_petsc(KSPSetType(petsc->ksp, KSPPREONLY), "KSPSetType");
        check_petsc(KSPGetPC(petsc->ksp, &pc), "KSPGetPC");
        check_petsc(PCSetType(pc, PCLU), "PCSetType");
        check_petsc(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
      }
    // Same matrix object, new values: PETSc refactorizes numerically at the next solve.
    check_petsc(KSPSetOperators(petsc->ksp, petsc->regularized, petsc->regularized), "KSPSetOperators");
    check_petsc(KSPSetUp(petsc->ksp), "KSPSetUp");
  }

  Vector TangentialAreaCorrector::move(const Surface &surface, const Vector &defect) const
  {
    const FieldSpace &vectors = surface.vector_space();
    Vector            q       = surface.scalar_space().make_owned();
    check_petsc(KSPSolve(petsc->ksp, defect, q), "KSPSolve");
    // w = D^(1/2) (B D^(1/2))^T q
    Vector product = vectors.make_owned(), result = vectors.make_owned();
    check_petsc(MatMultTranspose(petsc->BD, q, product), "MatMultTranspose");
    check_petsc(MatMult(D, product, result), "MatMult");
    vectors.constraints().distribute(result);
    return result;
  }

  TangentialAreaCorrection TangentialAreaCorrector::correct(Surface &surface, const Vector &normal_ghosted,
                                                            const Vector &target, const double tolerance,
                                                            const unsigned int max_iterations)
  {
    TangentialAreaCorrection result;
    double                   shift = smallest_shift; // of the current factorization
    Vector                   areas = vertex_areas(surface);
    result.initial_error = result.final_error = max_relative_difference(areas, target);
    bool factorized_here = false; // at the current surface
    for (unsigned int it = 0; it < max_iterations && result.final_error > tolerance; ++it)
      {
        const bool fresh = !factorized_here;
        if (fresh)
          try
            {
              factorize(surface, normal_ghosted, areas, shift);
            }
          catch (...)
            {
              reset(); // half-built products must not be reused by the next step
              throw;
            }
        factorized_here = true;
        Vector defect   = target;
        defect -= areas;
        const Vector step = move(surface, defect);
        if (!std::isfinite(step.l2_norm()))
          break;
        Vector before = surface.vector_space().make_owned();
        before        = surface.displacement();
        Vector moved  = before;
        moved += step;
        surface.set_displacement(moved);
        const Vector new_areas = vertex_areas(surface);
        const double error     = max_relative_difference(new_areas, target);
        if (!(error < result.final_error))
          {
            surface.set_displacement(before);
            if (fresh)
              {
                if (shift * shift_increase > largest_shift)
                  break;
                shift *= shift_increase; // damp the move more
              }
            factorized_here = false; // an older Jacobian, or too little damping: retry
            continue;
          }
        // A move that removed less than 90 % of the error: the next one needs the
        // Jacobian of the moved surface.
        if (error > 0.1 * result.final_error)
          factorized_here = false;
        areas              = new_areas;
        result.final_error = error;
        ++result.iterations;
      }
    return result;
  }

  TangentialAreaCorrection correct_areas_tangentially(Surface &surface, const Vector &normal_ghosted,
                                                      const Vector &target, const double tolerance,
                                                      const unsigned int max_iterations)
  {
    TangentialAreaCorrector corrector;
    return corrector.correct(surface, normal_ghosted, target, tolerance, max_iterations);
  }
} // namespace Membrane
