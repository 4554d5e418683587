#include <membrane/analysis/cross_sections.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace Membrane
{
  using dealii::Point;
  using dealii::Tensor;

  namespace
  {
    struct Segment
    {
      Point<2> a, b;
    };

    /// Where the plane z = level cuts the surface: one segment per triangle that it
    /// crosses (each quad split along its 0-3 diagonal), in coordinates relative to
    /// the axis (wrapped into the period around it).
    std::vector<Segment> plane_cut(const std::vector<SurfaceQuad> &quads, const Point<2> &axis, const double level,
                                   const double period)
    {
      const auto relative = [&](const Point<3> &p) {
        Point<2> r(p[0] - axis[0], p[1] - axis[1]);
        if (period > 0)
          for (unsigned int d = 0; d < 2; ++d)
            r[d] -= period * std::round(r[d] / period);
        return r;
      };
      static constexpr unsigned int triangles[2][3] = {{0, 1, 3}, {0, 3, 2}};
      std::vector<Segment>          cut;
      for (const auto &quad : quads)
        for (const auto &triangle : triangles)
          {
            Point<2>     ends[2];
            unsigned int n = 0;
            for (unsigned int e = 0; e < 3; ++e)
              {
                const Point<3> &p = quad[triangle[e]], &q = quad[triangle[(e + 1) % 3]];
                // Half-open in z, so that a vertex exactly at the level is counted once.
                if ((p[2] <= level) == (q[2] <= level) || n == 2)
                  continue;
                const double s = (level - p[2]) / (q[2] - p[2]);
                ends[n++]      = relative(p + s * (q - p));
              }
            // A segment that straddles the periodic seam is not part of a section around the axis.
            if (n == 2 && (period <= 0 || (ends[1] - ends[0]).norm() < 0.5 * period))
              cut.push_back({ends[0], ends[1]});
          }
      return cut;
    }
  } // namespace

  double section_radius(const std::vector<SurfaceQuad> &quads, const Point<2> &axis, const double level,
                        const double period, const unsigned int rays)
  {
    const std::vector<Segment> cut   = plane_cut(quads, axis, level, period);
    const double               reach = period > 0 ? 0.5 * period : std::numeric_limits<double>::max();
    std::vector<double>        dx(rays), dy(rays), nearest(rays, reach);
    for (unsigned int k = 0; k < rays; ++k)
      {
        const double theta = 2 * M_PI * (k + 0.5) / rays;
        dx[k]              = std::cos(theta);
        dy[k]              = std::sin(theta);
      }
    // A segment can only meet the rays whose angles lie in its angular span seen from the
    // axis; those (with one ray to spare either side) are tested, the others cannot hit it.
    // A segment that passes close to the axis spans nearly pi and is tested against all.
    const double rays_per_radian = rays / (2 * M_PI);
    for (const auto &[a, b] : cut)
      {
        const double angle_a = std::atan2(a[1], a[0]);
        double       span    = std::atan2(b[1], b[0]) - angle_a;
        if (span > M_PI)
          span -= 2 * M_PI;
        else if (span < -M_PI)
          span += 2 * M_PI;
        int first = 0, last = static_cast<int>(rays) - 1;
        if (std::abs(span) < 3)
          {
            const double low = std::min(angle_a, angle_a + span);
            first = static_cast<int>(std::floor(low * rays_per_radian - 0.5)) - 1;
            last  = static_cast<int>(std::ceil((low + std::abs(span)) * rays_per_radian - 0.5)) + 1;
          }
        for (int ray = first; ray <= last; ++ray)
          {
            const unsigned int k = ((ray % static_cast<int>(rays)) + rays) % rays;
            // Solve t d = a + s (b - a) for t > 0, s in [0, 1].
            const double ex = b[0] - a[0], ey = b[1] - a[1];
            const double det = ex * dy[k] - ey * dx[k];
            if (det == 0)
              continue;
            const double s = (a[1] * dx[k] - a[0] * dy[k]) / det;
            const double t = (a[1] * ex - a[0] * ey) / det;
            if (s >= 0 && s <= 1 && t > 0)
              nearest[k] = std::min(nearest[k], t);
          }
      }
    double sum_r2 = 0;
    for (unsigned int k = 0; k < rays; ++k)
      {
        if (nearest[k] >= reach)
          return 0; // a ray leaves without meeting the surface: no closed section around the axis
        sum_r2 += nearest[k] * nearest[k];
      }
    // The star-shaped region bounded by the nearest crossings has area pi * mean(r^2).
    return std::sqrt(sum_r2 / rays);
  }

  Neck find_neck(const std::vector<SurfaceQuad> &quads, const Point<2> &axis, const double base, const double apex,
                 const double period, const unsigned int levels)
  {
    std::vector<double> R(levels), z(levels);
    for (unsigned int j = 0; j < levels; ++j)
      {
        z[j] = base + (apex - base) * (j + 0.5) / levels;
        R[j] = section_radius(quads, axis, z[j], period);
      }
    Neck   neck;
    double above = 0, widest = 0;
    for (const double r : R)
      widest = std::max(widest, r);
    neck.bud_radius = widest;
    for (int j = static_cast<int>(levels) - 2; j >= 0; --j)
      {
        above = std::max(above, R[j + 1]);
        if (R[j] > 0 && above > 0 && R[j] / above < neck.ratio)
          {
            neck.ratio      = R[j] / above;
            neck.radius     = R[j];
            neck.height     = z[j];
            neck.bud_radius = above;
          }
      }
    if (neck.ratio == 1)
      {
        // No neck: report the section nearest the base that is closed.
        for (unsigned int j = 0; j < levels; ++j)
          if (R[j] > 0)
            {
              neck.radius = R[j];
              neck.height = z[j];
              break;
            }
      }
    return neck;
  }

  Neck find_neck_along(const std::vector<SurfaceQuad> &quads, const Point<3> &origin, const Tensor<1, 3> &axis,
                       const double base, const double apex, const unsigned int levels)
  {
    // Coordinates in an orthonormal frame (e1, e2, axis): the planes become horizontal and
    // the axis the vertical line through (0, 0).
    const Tensor<1, 3> helper = std::abs(axis[0]) < 0.9 ? Tensor<1, 3>({1., 0., 0.}) : Tensor<1, 3>({0., 1., 0.});
    Tensor<1, 3>       e1     = helper - (helper * axis) * axis;
    e1 /= e1.norm();
    const Tensor<1, 3>       e2 = cross_product_3d(axis, e1);
    std::vector<SurfaceQuad> turned(quads.size());
    for (std::size_t c = 0; c < quads.size(); ++c)
      for (unsigned int v = 0; v < 4; ++v)
        {
          const Tensor<1, 3> r = quads[c][v] - origin;
          turned[c][v]         = Point<3>(r * e1, r * e2, r * axis);
        }
    // A vesicle's sections span the whole vesicle, so the levels lie farther apart than
    // on the patch: the narrowest one is sought again on as many levels within one
    // spacing either side of it.
    Neck         neck    = find_neck(turned, Point<2>(0, 0), base, apex, 0.0, levels);
    const double spacing = (apex - base) / levels;
    if (neck.ratio < 1)
      for (unsigned int j = 0; j <= levels; ++j)
        {
          const double h = neck.height + spacing * (2.0 * j / levels - 1);
          const double r = section_radius(turned, Point<2>(0, 0), h, 0.0);
          if (r > 0 && r < neck.radius)
            {
              neck.radius = r;
              neck.height = h;
              neck.ratio  = r / neck.bud_radius;
            }
        }
    return neck;
  }
} // namespace Membrane
