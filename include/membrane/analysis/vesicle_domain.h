#pragma once
// How far the phase-A domain of a closed vesicle stands out of the vesicle: the closed-surface
// counterpart of the patch's domain_protrusion (bud_shape.h), measured along the direction
// from the vesicle's centroid to the domain's:
//   protrusion = (z_top - z_rim) / (2 R_s),  z = (X - centroid) . axis,
// z_top the domain's farthest vertex, z_rim the mean height of its boundary (phi = 0 on
// cell edges), R_s = sqrt(domain_area / 4 pi). A cap of 10 % of a sphere, lying in the
// sphere, gives 0.32; a hemispherical bud about 0.7; a complete spherical bud 1. With
// several domains the value is that of their union. The neck is sought on the planes normal
// to the same axis.

#include <membrane/surface/surface.h>

namespace Membrane
{
  struct VesicleDomain
  {
    double domain_area = 0; ///< area where phi > 0
    double protrusion  = 0;
    /// The neck along the domain axis (analysis/cross_sections.h, find_neck_along): the
    /// narrowest section normal to the axis, between the vesicle's centroid and the
    /// domain's farthest point, below a wider one. ratio 1: no neck.
    double neck_radius = 0;
    double bud_radius  = 0;
    double neck_ratio  = 1;
  };

  VesicleDomain measure_vesicle_domain(const Surface &surface, const Vector &phi_ghosted);
} // namespace Membrane
