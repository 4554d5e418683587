#pragma once
// Horizontal cross-sections of a surface around a vertical axis, and the neck of a
// bud found from them.
//
// The section at height z is read along rays: from the axis, 90 horizontal rays
// are followed to the nearest point where the surface crosses the plane. If every
// ray meets the surface within half a period, the nearest crossings bound a closed
// section around the axis: the innermost one (an overhanging bud cap or the
// membrane around the bud, farther out, does not count). Its radius is that of the
// circle of the same area, sqrt(area / pi). Otherwise the plane has no closed
// section around the axis at that height (radius 0).
//
// The neck is the narrowest closed section below a wider one: over sampled heights
// z_j between the far-field level and the apex, the j minimising
// R_j / max_{i above j} R_i. neck_ratio is that ratio (1 if no section is narrower
// than one above it: a dome without a neck), bud_radius the widest section above.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <vector>

namespace Membrane
{
  /// A quadrilateral of the surface: its four vertices in deal.II's order (lexicographic).
  using SurfaceQuad = std::array<dealii::Point<3>, 4>;

  struct Neck
  {
    double radius     = 0; ///< of the narrowest closed section below a wider one
    double height     = 0; ///< z of that section
    double bud_radius = 0; ///< of the widest closed section above it
    double ratio      = 1; ///< radius / bud_radius, capped at 1 (1: no neck)
  };

  /// Radius sqrt(area / pi) of the innermost closed section around the vertical axis
  /// through `axis` (x, y) at height `level`; 0 if there is none. Horizontal distances
  /// are taken modulo `period` (0: not periodic).
  double section_radius(const std::vector<SurfaceQuad> &quads, const dealii::Point<2> &axis, double level,
                        double period, unsigned int rays = 90);

  /// The neck between the heights `base` and `apex` (either order: the bud points
  /// from base to apex), sampled on `levels` heights.
  Neck find_neck(const std::vector<SurfaceQuad> &quads, const dealii::Point<2> &axis, double base, double apex,
                 double period, unsigned int levels = 64);

  /// The same along an arbitrary axis (a closed vesicle): the sections are the planes
  /// normal to the unit vector `axis` at the heights h = (x - origin) . axis between
  /// `base` and `apex`, each read around the line through `origin` along `axis`. Not
  /// periodic; Neck::height is such an h. The narrowest level is refined on `levels`
  /// more levels within one level spacing either side.
  Neck find_neck_along(const std::vector<SurfaceQuad> &quads, const dealii::Point<3> &origin,
                       const dealii::Tensor<1, 3> &axis, double base, double apex, unsigned int levels = 64);
} // namespace Membrane
