#pragma once
// The cells of the current surface as quadrilaterals of points, gathered from every rank:
// the cross-sections and the neck (analysis/cross_sections.h) need whole cells on every rank.

#include <membrane/analysis/cross_sections.h>
#include <membrane/surface/surface.h>

#include <vector>

namespace Membrane
{
  /// Every active cell's four current vertex positions (deal.II's order), on every rank;
  /// with `vertex_phi`, also phi at those vertices (4 per quad, same order). Collective.
  std::vector<SurfaceQuad> gather_surface_quads(const Surface &surface, const Vector *phi_ghosted = nullptr,
                                                std::vector<double> *vertex_phi = nullptr);
} // namespace Membrane
