#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/initial_shapes.h>
#include <membrane/surface/surface.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    using SerialTriangulation = dealii::Triangulation<dim, spacedim>;

    /// Counter-clockwise ring of a cell's vertices in deal.II's lexicographic
    /// numbering: the cell normal a_1 x a_2 sees 0 -> 1 -> 3 -> 2 turning positively.
    constexpr unsigned int ring[4] = {0, 1, 3, 2};

    /// Signed volume 1/6 sum over the two triangles (0,1,3), (0,3,2) of each quad of
    /// x_a . (x_b x x_c): positive when the cells are oriented outward. Its sign is that
    /// of 1/3 integral X.n ds of the bilinear surface on any reasonable mesh.
    double signed_volume(const std::vector<Point<spacedim>> &vertices, const std::vector<CellData<dim>> &cells)
    {
      double volume = 0;
      for (const auto &cell : cells)
        {
          const auto &x = [&](const unsigned int v) { return vertices[cell.vertices[v]]; };
          volume += x(0) * cross_product_3d(x(1), x(3)) + x(0) * cross_product_3d(x(3), x(2));
        }
      return volume / 6;
    }

    /// Refuse anything but a closed, consistently oriented quadrilateral 2-manifold: every
    /// edge must be shared by exactly two cells that run through it in opposite directions.
    void check_closed(const SerialTriangulation &mesh, const std::vector<CellData<dim>> &cells,
                      const std::string &entry)
    {
      for (const auto &cell : mesh.active_cell_iterators())
        AssertThrow(cell->reference_cell() == ReferenceCells::Quadrilateral,
                    ExcMessage("Entry <" + entry + ">: the mesh has a cell that is not a quadrilateral (" +
                               cell->reference_cell().to_string() + "); only quadrilateral surface meshes are "
                               "supported (in Gmsh: Mesh.RecombineAll = 1, Mesh.SubdivisionAlgorithm = 1)"));
      std::map<std::pair<unsigned int, unsigned int>, unsigned int> directed;
      for (const auto &cell : cells)
        for (unsigned int k = 0; k < 4; ++k)
          ++directed[{cell.vertices[ring[k]], cell.vertices[ring[(k + 1) % 4]]}];
      unsigned int open = 0, inconsistent = 0, non_manifold = 0;
      for (const auto &[edge, count] : directed)
        {
          const auto reverse = directed.find({edge.second, edge.first});
          const unsigned int opposite = reverse == directed.end() ? 0 : reverse->second;
          if (count + opposite == 1)
            ++open;
          else if (count + opposite > 2)
            ++non_manifold;
          else if (count != 1 || opposite != 1)
            ++inconsistent;
        }
      AssertThrow(open == 0, ExcMessage("Entry <" + entry + ">: the surface mesh is open: " + std::to_string(open) +
                                        " cell edges lie on a boundary (a closed vesicle needs a closed surface; "
                                        "use Reference surface = periodic patch for a patch)"));
      AssertThrow(non_manifold == 0,
                  ExcMessage("Entry <" + entry + ">: the surface mesh is not a 2-manifold: " +
                             std::to_string(non_manifold) + " edges are shared by more than two cells"));
      AssertThrow(inconsistent == 0,
                  ExcMessage("Entry <" + entry + ">: the cells are not consistently oriented: " +
                             std::to_string(inconsistent / 2) + " edges are run through in the same direction by "
                             "both of their cells (reorient the mesh, e.g. in Gmsh with ReorientMesh)"));
    }

    unsigned int refinements_for(const unsigned int cells_per_side)
    {
      unsigned int k = 0;
      while ((1u << k) < cells_per_side)
        ++k;
      AssertThrow((1u << k) == cells_per_side,
                  ExcMessage("Entry <Mesh/Cells per side>: a sphere or ellipsoid has 2^k cells along each edge of "
                             "its six cube faces; got " + std::to_string(cells_per_side) + " (use e.g. 8, 16, 32)"));
      return k;
    }
  } // namespace

  double closed_surface_vertices(const ReferenceSurfaceOptions &options)
  {
    if (options.type == "sphere" || options.type == "ellipsoid")
      return 6.0 * options.cells_per_side * options.cells_per_side + 2;
    return 0;
  }

  void set_analytic_displacement(Surface &surface, const ReferenceSurfaceOptions &options,
                                 const std::string &expression, const std::string &entry)
  {
    const bool analytic = options.type == "sphere" || options.type == "ellipsoid";
    if (!analytic && expression.empty())
      return;
    FunctionParser<spacedim> perturbation(spacedim);
    if (!expression.empty())
      try
        {
          perturbation.initialize("x,y,z", expression, {{"pi", numbers::PI}});
        }
      catch (...)
        {
          AssertThrow(false, ExcMessage("Entry <" + entry + ">: cannot parse <" + expression +
                                        ">; expected three expressions 'Dx; Dy; Dz' in x, y, z"));
        }
    class Placement : public Function<spacedim>
    {
    public:
      Placement(const std::array<double, 3> &axes, const bool analytic, const FunctionParser<spacedim> *perturbation)
        : Function<spacedim>(spacedim)
        , axes(axes)
        , analytic(analytic)
        , perturbation(perturbation)
      {}
      double value(const Point<spacedim> &x, const unsigned int component) const override
      {
        // x / |x|_A with |x|_A^2 = sum (x_i / a_i)^2 lies on the ellipsoid (sphere: a_i = R).
        // Each coordinate divided by |x|_A, as before the perturbation existed (Point's /=
        // multiplies by the inverse, which rounds differently).
        double norm = 0;
        for (unsigned int i = 0; i < spacedim; ++i)
          norm += (x[i] / axes[i]) * (x[i] / axes[i]);
        Point<spacedim> on_surface = x;
        if (analytic)
          for (unsigned int i = 0; i < spacedim; ++i)
            on_surface[i] = x[i] / std::sqrt(norm);
        const double added = perturbation ? perturbation->value(on_surface, component) : 0.0;
        return on_surface[component] - x[component] + added;
      }
      const std::array<double, 3>     axes;
      const bool                      analytic;
      const FunctionParser<spacedim> *perturbation;
    };
    const std::array<double, 3> axes =
      options.type == "sphere" ? std::array<double, 3>{{options.radius, options.radius, options.radius}}
                               : options.semi_axes;
    set_displacement(surface, Placement(axes, analytic, expression.empty() ? nullptr : &perturbation));
  }


  void make_closed_surface(Triangulation &triangulation, const ReferenceSurfaceOptions &options)
  {
    SerialTriangulation refined;
    std::string         entry = "Mesh/Reference surface";
    if (options.type == "sphere" || options.type == "ellipsoid")
      {
        const unsigned int k = refinements_for(options.cells_per_side);
        GridGenerator::hyper_sphere(refined, Point<spacedim>(), options.type == "sphere" ? options.radius : 1.0);
        refined.refine_global(k); // on the spherical manifold
        if (options.type == "ellipsoid")
          GridTools::transform(
            [&](const Point<spacedim> &p) {
              return Point<spacedim>(options.semi_axes[0] * p[0], options.semi_axes[1] * p[1],
                                     options.semi_axes[2] * p[2]);
            },
            refined);
      }
    else
      {
        entry = "Mesh/Mesh file";
        AssertThrow(!options.file.empty(),
                    ExcMessage("Entry <Mesh/Mesh file>: Reference surface = file needs a mesh file (Gmsh .msh, "
                               "VTK .vtk or UCD .inp with quadrilateral cells)"));
        std::ifstream in(options.file);
        AssertThrow(in, ExcMessage("Entry <Mesh/Mesh file>: cannot open the mesh file <" + options.file + ">"));
        try
          {
            GridIn<dim, spacedim> reader;
            reader.attach_triangulation(refined);
            reader.read(options.file);
          }
        catch (const std::exception &e)
          {
            std::string what = e.what();
            const auto  text = what.find("Additional information:");
            if (text != std::string::npos)
              what = what.substr(text + 23);
            throw ExcMessage("Entry <Mesh/Mesh file>: cannot read <" + options.file +
                             "> as a quadrilateral surface mesh in 3D: " + Utilities::trim(what));
          }
        {
          const auto [vertices, coarse, subcells] = GridTools::get_coarse_mesh_description(refined);
          (void)subcells;
          check_closed(refined, coarse, entry);
        }
        refined.refine_global(options.file_refinements); // flat: no manifold is attached
      }

    SerialTriangulation flat;
    GridGenerator::flatten_triangulation(refined, flat);
    auto [vertices, cells, subcells] = GridTools::get_coarse_mesh_description(flat);
    check_closed(flat, cells, entry);
    if (signed_volume(vertices, cells) < 0)
      for (auto &cell : cells) // reverse the ring 0 -> 1 -> 3 -> 2 so that n points outward
        std::swap(cell.vertices[1], cell.vertices[2]);
    for (auto &cell : cells)
      cell.manifold_id = numbers::flat_manifold_id; // the reference is the flat Q1 surface
    triangulation.create_triangulation(vertices, cells, SubCellData());
  }
} // namespace Membrane
