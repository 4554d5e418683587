#pragma once
// The area of the discrete Gauss map: the sum over cells of the solid angle of the
// spherical quadrilateral spanned by the unit vertex normals of the cell (corners in
// the cell's positive order, split into two triangles; Van Oosterom-Strackee formula
// for each). The Q1 normal field, normalized, maps each cell onto that quadrilateral
// (its edges are straight in R^3, so great-circle arcs on the sphere); on a closed
// surface the arcs cancel pairwise and the sum is 4 pi times the degree of the map,
// 2 pi chi = 4 pi (1 - genus), to round-off on every mesh: the discrete Gauss-Bonnet
// theorem. The integral of the energy's K (a projection of
// ((tr grad_s nu)^2 - |grad_s nu|^2)/2) tends to the same value at second order.

#include <membrane/surface/surface.h>

namespace Membrane
{
  /// Sum over the cells of the solid angle of the vertex normals (ghosted vector field).
  double gauss_map_area(const Surface &surface, const Vector &normal_ghosted);
} // namespace Membrane
