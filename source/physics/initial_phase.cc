#include <membrane/physics/counter_hash.h>
#include <membrane/physics/initial_phase.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/initial_shapes.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <cstring>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    /// Set each owned vertex value from a function of the reference vertex.
    template <typename Value>
    Vector vertex_field(const Surface &surface, const Value &value)
    {
      const FieldSpace &scalars = surface.scalar_space();
      Vector            field   = scalars.make_owned();
      for (const auto &cell : scalars.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            {
              const auto dof = cell->vertex_dof_index(v, 0);
              if (scalars.owned().is_element(dof))
                field[dof] = value(cell->vertex(v));
            }
      field.compress(VectorOperation::insert);
      scalars.constraints().distribute(field);
      return field;
    }

    double integral(const Surface &surface, const Vector &owned)
    {
      return integrate(surface, surface.scalar_space().ghosted_copy(owned));
    }
  } // namespace

  double hashed_uniform(const std::uint64_t seed, const Point<spacedim> &p)
  {
    // Quantise the reference position (exact on any mesh of the unit square up
    // to 2^20 cells per side) and hash it with the seed.
    std::uint64_t key = splitmix64(seed);
    for (unsigned int d = 0; d < spacedim; ++d)
      key = splitmix64(key ^ static_cast<std::uint64_t>(std::llround((p[d] + 8.0) * 1048576.0)));
    return (key >> 11) * 0x1.0p-53;
  }

  Vector make_initial_phase(const Surface &surface, const InitialPhaseOptions &options)
  {
    if (options.type == "bump")
      {
        const auto shape = vertex_field(surface, [&](const Point<spacedim> &p) { return bump_profile(p, options.bump_radius); });
        double height = options.bump_height;
        // integral (-1 + a3 shape) ds = M, and integral -1 ds = -area.
        if (options.prescribe_mass)
          height = (options.mass + surface.area()) / integral(surface, shape);
        Vector phi = vertex_field(surface, [](const Point<spacedim> &) { return -1.0; });
        phi.add(height, shape);
        return phi;
      }

    Vector phi;
    if (options.type == "random")
      phi = vertex_field(surface, [&](const Point<spacedim> &p) {
        return options.random_min + (options.random_max - options.random_min) * hashed_uniform(options.seed, p);
      });
    else if (options.type == "caps")
      phi = make_cap_phase(surface, options);
    else if (options.type == "uniform")
      phi = vertex_field(surface, [&](const Point<spacedim> &) { return options.uniform_value; });
    else
      {
        FunctionParser<2> parser(1);
        try
          {
            parser.initialize("x,y", options.expression, {{"pi", numbers::PI}});
          }
        catch (...)
          {
            AssertThrow(false, ExcMessage("Entry <Initial phase/Expression>: cannot parse <" + options.expression +
                                          "> as a function of x, y"));
          }
        phi = vertex_field(surface, [&](const Point<spacedim> &p) { return parser.value(Point<2>(p[0], p[1])); });
      }
    if (options.prescribe_mass)
      {
        // Adding a constant c changes integral phi ds by c * area.
        const double shift = (options.mass - integral(surface, phi)) / surface.area();
        phi.add(shift);
      }
    return phi;
  }

  void declare_initial_phase_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Initial phase");
    prm.declare_entry("Type", "random", Patterns::Selection("random|bump|uniform|expression|caps"),
                      "random: uniform in [Random min, Random max] per vertex (seeded, independent of the number "
                      "of MPI ranks); bump: -1 + a3 (1 + cos(pi rho/R0)) on the Initial shape's bump disc; "
                      "uniform: Uniform value; expression: phi0(x, y); caps: polar cap domains on a closed surface (Cap "
                      "axes, Cap area fraction, Cap profile).");
    prm.declare_entry("Random min", "-0.2", Patterns::Double(-1.5, 1.5), "b: lower bound of the random phi0.");
    prm.declare_entry("Random max", "0.2", Patterns::Double(-1.5, 1.5), "c: upper bound of the random phi0.");
    prm.declare_entry("Seed", "1", Patterns::Integer(0), "Seed of the random phi0.");
    prm.declare_entry("Uniform value", "0", Patterns::Double(-1.5, 1.5), "phi0 for Type = uniform.");
    prm.declare_entry("Expression", "0", Patterns::Anything(), "phi0(x, y) for Type = expression.");
    prm.declare_entry("Bump height", "0.5", Patterns::Double(0, 2),
                      "a3 for Type = bump when the mass is not prescribed.");
    prm.declare_entry("Prescribe mass", "false", Patterns::Bool(),
                      "Adjust phi0 so that integral phi0 ds equals Mass (bump: solve for a3; others: add a constant).");
    prm.declare_entry("Mass", "-0.85", Patterns::Double(), "Target integral phi0 ds on the initial surface.");
    prm.leave_subsection();
  }

  InitialPhaseOptions parse_initial_phase_parameters(ParameterHandler &prm)
  {
    InitialPhaseOptions options;
    prm.enter_subsection("Initial phase");
    options.type           = prm.get("Type");
    options.random_min     = prm.get_double("Random min");
    options.random_max     = prm.get_double("Random max");
    options.seed           = prm.get_integer("Seed");
    options.uniform_value  = prm.get_double("Uniform value");
    options.expression     = prm.get("Expression");
    options.bump_height    = prm.get_double("Bump height");
    options.prescribe_mass = prm.get_bool("Prescribe mass");
    options.mass           = prm.get_double("Mass");
    AssertThrow(options.random_min <= options.random_max,
                ExcMessage("Entries <Initial phase/Random min> and <Random max>: need min <= max (got " +
                           prm.get("Random min") + " > " + prm.get("Random max") + ")"));
    prm.leave_subsection();
    return options;
  }
} // namespace Membrane
