#include <membrane/surface/initial_shapes.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    class NormalDisplacement : public Function<spacedim>
    {
    public:
      explicit NormalDisplacement(std::function<double(const Point<spacedim> &)> height)
        : Function<spacedim>(spacedim)
        , height(std::move(height))
      {}
      double value(const Point<spacedim> &p, const unsigned int component) const override
      {
        return component == 2 ? height(p) : 0.0;
      }

    private:
      std::function<double(const Point<spacedim> &)> height;
    };
  } // namespace

  std::vector<CosineMode> parse_cosine_modes(const std::string &text, const std::string &entry)
  {
    std::vector<CosineMode> modes;
    for (const std::string &item : Utilities::split_string_list(text, ';'))
      {
        if (item.empty())
          continue;
        std::istringstream in(item);
        CosineMode         mode{0, 0, 0, 0};
        in >> mode.amplitude >> mode.k1 >> mode.k2;
        AssertThrow(!in.fail(), ExcMessage("Entry <" + entry + ">: cannot read the mode <" + item +
                                           ">; expected 'amplitude k1 k2 [phase]' with integer k1, k2"));
        if (!(in >> mode.phase))
          mode.phase = 0;
        modes.push_back(mode);
      }
    return modes;
  }

  void set_displacement(Surface &surface, const Function<spacedim> &displacement)
  {
    Vector d = surface.vector_space().make_owned();
    VectorTools::interpolate(surface.reference_mapping(), surface.vector_space().dof_handler(), displacement, d);
    surface.set_displacement(d);
  }

  double bump_profile(const Point<spacedim> &p, const double radius)
  {
    const double rho = std::hypot(p[0] - 0.5, p[1] - 0.5);
    return rho < radius ? 1.0 + std::cos(numbers::PI * rho / radius) : 0.0;
  }

  double set_bump(Surface &surface, const double radius, const double target_area)
  {
    const auto area_for = [&](const double amplitude) {
      set_displacement(surface, NormalDisplacement([=](const Point<spacedim> &p) {
                         return amplitude * bump_profile(p, radius);
                       }));
      return surface.area();
    };
    const double flat_area = area_for(0.0);
    AssertThrow(target_area >= flat_area,
                ExcMessage("Entry <Bump area>: the target area " + std::to_string(target_area) +
                           " is below the flat patch area " + std::to_string(flat_area)));
    if (target_area == flat_area)
      return 0;
    double low = 0, high = 0.1, f_low = flat_area - target_area, f_high = area_for(high) - target_area;
    while (f_high < 0)
      {
        low = high, f_low = f_high;
        high *= 2;
        AssertThrow(high < 1e3, ExcMessage("Entry <Bump area>: target area not reachable"));
        f_high = area_for(high) - target_area;
      }
    AssertThrow(std::isfinite(f_high), ExcMessage("Entry <Bump area>: the area of the bump is not finite"));
    // The area is increasing and convex in the amplitude (sqrt(1 + a^2 |grad b|^2) at every
    // quadrature point): regula falsi with the Illinois modification keeps the bracket and
    // converges superlinearly, about 10 area evaluations to round-off where bisection needs
    // 55 (each one interpolates the displacement and integrates the area).
    double amplitude = high;
    int    last_side = 0; // -1: the last update moved low, +1: high
    for (unsigned int it = 0; it < 200 && f_high != 0 && high - low > 1e-15 * high; ++it)
      {
        amplitude = (low * f_high - high * f_low) / (f_high - f_low);
        if (!(amplitude > low && amplitude < high))
          amplitude = 0.5 * (low + high);
        const double f = area_for(amplitude) - target_area;
        if (std::abs(f) <= 1e-14 * target_area)
          return amplitude; // the surface is at this amplitude
        if (f < 0)
          {
            low = amplitude, f_low = f;
            if (last_side == -1)
              f_high *= 0.5;
            last_side = -1;
          }
        else
          {
            high = amplitude, f_high = f;
            if (last_side == +1)
              f_low *= 0.5;
            last_side = +1;
          }
        amplitude = 0.5 * (low + high);
      }
    area_for(amplitude);
    return amplitude;
  }

  void set_cosine_modes(Surface &surface, const std::vector<CosineMode> &modes)
  {
    set_displacement(surface, NormalDisplacement([&](const Point<spacedim> &p) {
                       double z = 0;
                       for (const auto &m : modes)
                         z += m.amplitude * std::cos(2 * numbers::PI * (m.k1 * p[0] + m.k2 * p[1]) + m.phase);
                       return z;
                     }));
  }

  void set_displacement_expression(Surface &surface, const std::string &expression, const std::string &entry)
  {
    FunctionParser<2> parser(spacedim);
    try
      {
        parser.initialize("x,y", expression, {{"pi", numbers::PI}});
      }
    catch (...)
      {
        AssertThrow(false, ExcMessage("Entry <" + entry + ">: cannot parse <" + expression +
                                      ">; expected three expressions 'Dx; Dy; Dz' in x, y"));
      }
    // The displacement must be periodic on the unit square.
    for (unsigned int i = 0; i <= 16; ++i)
      for (unsigned int c = 0; c < spacedim; ++c)
        {
          const double s = i / 16.0;
          const double jump = std::max(std::abs(parser.value(Point<2>(0, s), c) - parser.value(Point<2>(1, s), c)),
                                       std::abs(parser.value(Point<2>(s, 0), c) - parser.value(Point<2>(s, 1), c)));
          AssertThrow(jump < 1e-10, ExcMessage("Entry <" + entry + ">: the displacement is not periodic on the "
                                               "unit square (component " + std::to_string(c) +
                                               " jumps by " + std::to_string(jump) + ")"));
        }
    class Lifted : public Function<spacedim>
    {
    public:
      explicit Lifted(const FunctionParser<2> &f) : Function<spacedim>(spacedim), f(f) {}
      double value(const Point<spacedim> &p, const unsigned int c) const override
      {
        return f.value(Point<2>(p[0], p[1]), c);
      }
      const FunctionParser<2> &f;
    };
    set_displacement(surface, Lifted(parser));
  }
} // namespace Membrane
