#include <membrane/surface/projection.h>
#include <membrane/surface/surface.h>

#include <set>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

namespace Membrane
{
  using namespace dealii;

  std::pair<unsigned int, unsigned int> factor_cells_per_side(unsigned int cells_per_side)
  {
    AssertThrow(cells_per_side >= 1, ExcMessage("cells per side must be at least 1"));
    unsigned int refinements = 0;
    while (cells_per_side % 2 == 0)
      {
        cells_per_side /= 2;
        ++refinements;
      }
    return {cells_per_side, refinements};
  }

  void make_periodic_unit_square(Triangulation &triangulation, const unsigned int cells_per_side)
  {
    const auto [coarse, refinements] = factor_cells_per_side(cells_per_side);
    GridGenerator::subdivided_hyper_cube(triangulation, coarse, 0.0, 1.0, /*colorize=*/true);

    std::vector<GridTools::PeriodicFacePair<typename Triangulation::cell_iterator>> pairs;
    GridTools::collect_periodic_faces(triangulation, 0, 1, 0, pairs);
    GridTools::collect_periodic_faces(triangulation, 2, 3, 1, pairs);
    triangulation.add_periodicity(pairs);
    triangulation.refine_global(refinements);
  }

  Surface::Surface(const Triangulation &triangulation, const bool periodic)
    : triangulation(triangulation)
    , is_periodic(periodic)
    , vectors(triangulation, spacedim)
    , scalars(triangulation, 1)
  {}

  void Surface::setup()
  {
    vectors.setup(is_periodic);
    scalars.setup(is_periodic);
    displacement_ghosted = vectors.make_ghosted();
    eulerian             = std::make_unique<DisplacedMapping>();
    update_mapping();
    scalars.reinit_matrix(scalar_mass.matrix);
    vectors.reinit_matrix(vector_mass.matrix, /*couple_components=*/false);
    scalar_mass.current = vector_mass.current = false;
  }

  const SparseMatrix &Surface::mass_matrix(const FieldSpace &space) const
  {
    Assert(&space == &scalars || &space == &vectors, ExcMessage("not a space of this surface"));
    CachedMass &cache = &space == &scalars ? scalar_mass : vector_mass;
    if (!cache.current)
      {
        assemble_mass_matrix(*this, space, cache.matrix);
        cache.current = true;
      }
    return cache.matrix;
  }

  const Mapping<dim, spacedim> &Surface::reference_mapping() const
  {
    return StaticMappingQ1<dim, spacedim>::mapping;
  }

  void Surface::set_displacement(const Vector &displacement_owned)
  {
    Vector constrained = displacement_owned;
    vectors.constraints().distribute(constrained);
    displacement_ghosted = constrained;
    scalar_mass.current = vector_mass.current = false;
    update_mapping();
  }

  void Surface::update_mapping()
  {
    // X = X_ref + D at every vertex of a locally relevant cell (read once from the ghosted
    // vector), then the bilinear map of every cell through its four vertices: the same
    // map as MappingQEulerian of degree 1, without per-cell vector reads in FEValues.
    // Vertices of artificial cells keep their reference position (never integrated over).
    std::vector<Point<spacedim>> position = triangulation.get_vertices();
    for (const auto &cell : vectors.dof_handler().active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int c = 0; c < spacedim; ++c)
            position[cell->vertex_index(v)][c] = cell->vertex(v)[c] + displacement_ghosted(cell->vertex_dof_index(v, c));
    eulerian->initialize(triangulation, [&position](const typename Triangulation::cell_iterator &cell) {
      std::vector<Point<spacedim>> points(GeometryInfo<dim>::vertices_per_cell);
      for (const unsigned int v : cell->vertex_indices())
        points[v] = position[cell->vertex_index(v)];
      return points;
    });
  }

  int Surface::euler_characteristic() const
  {
    if (is_periodic)
      return 0;
    // The coarse mesh is known to every rank (p4est replicates level 0).
    std::set<unsigned int> vertices, lines;
    int                    faces = 0;
    for (const auto &cell : triangulation.cell_iterators_on_level(0))
      {
        ++faces;
        for (const unsigned int v : cell->vertex_indices())
          vertices.insert(cell->vertex_index(v));
        for (const unsigned int l : cell->line_indices())
          lines.insert(cell->line_index(l));
      }
    return static_cast<int>(vertices.size()) - static_cast<int>(lines.size()) + faces;
  }

  double Surface::area() const
  {
    const QGauss<dim>          quadrature(2);
    FEValues<dim, spacedim>    fe_values(mapping(), scalars.fe(), quadrature, update_JxW_values);
    double                     local = 0;
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            local += fe_values.JxW(q);
        }
    return Utilities::MPI::sum(local, triangulation.get_communicator());
  }

  double Surface::max_cell_diameter() const
  {
    double local = 0;
    for (const auto &cell : vectors.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto vertices = eulerian->get_vertices(cell);
          local = std::max({local, vertices[0].distance(vertices[3]), vertices[1].distance(vertices[2])});
        }
    return Utilities::MPI::max(local, triangulation.get_communicator());
  }
} // namespace Membrane
