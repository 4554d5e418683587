#pragma once
// Reference surfaces of closed vesicles (MODEL.md section 8): the reference
// mesh U is a closed quadrilateral surface in R^3 and X = X_ref + D.
//  sphere:    the cube-sphere of GridGenerator::hyper_sphere, each cube face
//             refined to n x n cells on the spherical manifold;
//  ellipsoid: the same sphere (unit radius) scaled by the semi-axes;
//  file:      a closed quadrilateral surface mesh read by deal.II's GridIn
//             (Gmsh .msh, VTK .vtk, UCD .inp), optionally refined (flat).
// The refined mesh is then flattened into the coarse mesh of the distributed
// triangulation, so that the reference is the flat Q1 surface through these
// vertices at every level: later refinement (mesh adaptation) places new
// reference vertices on the bilinear cells, where the transferred Q1
// displacement reproduces the current surface exactly. Cells are oriented so
// that the cell normal a_1 x a_2 points outward (positive enclosed volume).

#include <membrane/core/types.h>

#include <deal.II/base/point.h>

#include <array>
#include <string>

namespace Membrane
{
  class Surface;

  struct ReferenceSurfaceOptions
  {
    std::string             type           = "periodic patch"; ///< periodic patch|sphere|ellipsoid|file
    unsigned int            cells_per_side = 32; ///< sphere, ellipsoid: cells along each cube-face edge (2^k)
    double                  radius         = 1;  ///< sphere
    std::array<double, 3>   semi_axes{{1, 1, 1}}; ///< ellipsoid
    std::string             file;                 ///< file
    unsigned int            file_refinements = 0; ///< file: uniform refinements of the file's cells

    bool closed() const { return type != "periodic patch"; }
  };

  /// Build the closed reference surface into the (empty) distributed triangulation.
  /// Throws dealii::ExcMessage naming the entry for an unreadable file, a mesh that is
  /// not a closed, consistently oriented quadrilateral 2-manifold, or a cell count
  /// that is not a power of 2.
  void make_closed_surface(Triangulation &triangulation, const ReferenceSurfaceOptions &options);

  /// Sphere and ellipsoid: the displacement that moves every reference vertex radially onto
  /// the analytic surface (zero on the input mesh, whose vertices lie on it; after the
  /// initial refinement it puts the new vertices there instead of on the bilinear cells).
  /// Nothing for the other types. A non-empty `expression` 'Dx; Dy; Dz' in x, y, z (and pi)
  /// is evaluated at that point of the surface and added (a perturbed initial vesicle; errors
  /// name `entry`).
  void set_analytic_displacement(Surface &surface, const ReferenceSurfaceOptions &options,
                                 const std::string &expression = "", const std::string &entry = "");

  /// Number of reference vertices before the mesh is built (for the memory estimate);
  /// 0 if unknown (file).
  double closed_surface_vertices(const ReferenceSurfaceOptions &options);
} // namespace Membrane
