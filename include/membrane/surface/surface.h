#pragma once
// The membrane surface: a reference mesh (the periodic unit square in the plane
// z = 0, or any closed surface mesh) and a Q1 displacement D, so that
// X = X_ref + D. The current surface is seen through a bilinear mapping (MappingQCache
// of degree 1 through the displaced vertices, like MappingQEulerian), which
// makes FEValues<2,3> compute surface gradients, normals and ds on Gamma = X(U).

#include <membrane/surface/field_space.h>
#include <membrane/core/types.h>

#include <deal.II/fe/mapping_q_cache.h>

#include <memory>

namespace Membrane
{
  /// The bilinear map through the displaced vertices, cached per cell (MappingQCache of
  /// degree 1). FEValues would otherwise take a cell that is a translation of the previous
  /// one in the reference mesh as congruent on the surface too and reuse its Jacobians;
  /// like MappingQEulerian, this mapping never reports cell similarity.
  class DisplacedMapping : public dealii::MappingQCache<dim, spacedim>
  {
  public:
    DisplacedMapping()
      : dealii::MappingQCache<dim, spacedim>(1)
    {}
    std::unique_ptr<dealii::Mapping<dim, spacedim>> clone() const override
    {
      return std::make_unique<DisplacedMapping>(*this);
    }

  protected:
    dealii::CellSimilarity::Similarity
    fill_fe_values(const typename dealii::Triangulation<dim, spacedim>::cell_iterator &cell,
                   const dealii::CellSimilarity::Similarity, const dealii::Quadrature<dim> &quadrature,
                   const typename dealii::Mapping<dim, spacedim>::InternalDataBase &internal_data,
                   dealii::internal::FEValuesImplementation::MappingRelatedData<dim, spacedim> &output_data)
      const override
    {
      dealii::MappingQCache<dim, spacedim>::fill_fe_values(cell, dealii::CellSimilarity::invalid_next_cell,
                                                           quadrature, internal_data, output_data);
      return dealii::CellSimilarity::invalid_next_cell;
    }
  };

  /// Split n cells per side into n = coarse * 2^refinements with coarse odd, so
  /// that p4est works on the fewest trees.
  std::pair<unsigned int, unsigned int> factor_cells_per_side(unsigned int cells_per_side);

  /// The periodic unit square [0,1]^2 x {0} with colorized boundary ids
  /// (0|1 at u1 = 0|1, 2|3 at u2 = 0|1) and periodicity registered with p4est.
  void make_periodic_unit_square(Triangulation &triangulation, unsigned int cells_per_side);

  class Surface
  {
  public:
    /// `triangulation` must outlive the surface; `periodic` says whether the
    /// unit-square identification applies (false for closed surfaces).
    Surface(const Triangulation &triangulation, bool periodic);

    /// Rebuild spaces after a mesh change; the displacement is reset to zero.
    void setup();

    const FieldSpace &vector_space() const { return vectors; }
    const FieldSpace &scalar_space() const { return scalars; }
    bool              periodic() const { return is_periodic; }

    /// Replace the displacement (owned vector; constraints are applied here).
    void set_displacement(const Vector &displacement_owned);
    const Vector &displacement() const { return displacement_ghosted; }

    /// The map U -> Gamma through which every integral on the surface is taken.
    const dealii::Mapping<dim, spacedim> &mapping() const { return *eulerian; }
    const dealii::Mapping<dim, spacedim> &reference_mapping() const;

    /// Consistent mass matrix of the scalar or the vector space on the current
    /// surface. Assembled on first use after each change of the displacement into
    /// a matrix whose sparsity is built once per mesh.
    const SparseMatrix &mass_matrix(const FieldSpace &space) const;

    /// Total area of the current surface.
    double area() const;
    /// Largest cell diameter on the current surface (global).
    double max_cell_diameter() const;
    /// Euler characteristic of the surface: 0 for the periodic patch (a torus), V - E + F
    /// of the coarse mesh for a closed surface (2 for a sphere). Gauss-Bonnet:
    /// integral K ds = 2 pi chi.
    int euler_characteristic() const;

  private:
    const Triangulation &triangulation;
    const bool           is_periodic;
    FieldSpace           vectors;
    FieldSpace           scalars;
    Vector               displacement_ghosted;
    struct CachedMass
    {
      SparseMatrix matrix;
      bool         current = false;
    };
    mutable CachedMass scalar_mass, vector_mass;
    /// The current surface's vertex positions, cached per cell: FEValues on it costs no
    /// reads of the (PETSc) displacement vector. Refilled by every set_displacement().
    std::unique_ptr<DisplacedMapping> eulerian;
    void update_mapping();
  };
} // namespace Membrane
