#pragma once
// Observables of a bud on the periodic patch, from the current cell vertices.
//
//  - direction s = +1 (bud along +z) or -1: the side on which the surface reaches
//    farther from its median height;
//  - apex: the point farthest along s; the bud axis is the vertical line through it;
//  - far-field level: mean height of the points horizontally farther than 1/2
//    from the axis (the corners of the patch around a centred bud);
//  - height: s (z_apex - z_far);
//  - cross-section radius R(h): the radius sqrt(area / pi) of the innermost closed
//    section of the surface around the axis at the level z_far + s h, on `levels`
//    levels (analysis/cross_sections.h);
//  - neck: the level j minimising R_j / max_{i > j} R_i (a constriction with a wider
//    bud above it); neck_ratio = that ratio, capped at 1 (1: no neck, a dome);
//    neck_radius = R_j, bud_radius = max_{i > j} R_i;
//  - domain_area: the area where phi > 0 (phase A);
//  - domain_protrusion: how far the phase-A domain stands out of the membrane
//    around it: s (z_top - z_rim) / (2 R_s), where z_top is the domain's extreme
//    point along s, z_rim the mean height of its boundary (phi = 0 on cell edges)
//    and R_s = sqrt(domain_area / 4 pi) the radius of a sphere of the domain's
//    area. 0: a flat domain; ~0.7: a hemispherical cap; 1: a complete sphere.
// Horizontal distances are taken modulo the unit period.

#include <membrane/surface/surface.h>

#include <string>

namespace Membrane
{
  struct BudShape
  {
    int    direction   = 1;
    double height      = 0;
    double neck_radius = 0;
    double bud_radius  = 0;
    double neck_ratio  = 1;
    double domain_area = 0;
    double domain_protrusion = 0;
  };

  BudShape measure_bud(const Surface &surface, const Vector &phi_ghosted, unsigned int levels = 64);

  struct OutcomeCriteria
  {
    double flat_protrusion     = 0.3; ///< domain_protrusion below: flat
    double complete_neck_ratio = 0.4; ///< neck_ratio below: complete bud
  };

  /// "flat", "incomplete bud" or "complete bud". A bud is complete only when a neck
  /// has formed: a section narrower than complete_neck_ratio times the bud above it
  /// (or a pinch-off stop). A domain that stands out, however far, without a neck is
  /// an incomplete bud; one that protrudes less than flat_protrusion is flat.
  std::string classify_outcome(const BudShape &shape, const OutcomeCriteria &criteria, bool pinch_off);
} // namespace Membrane
