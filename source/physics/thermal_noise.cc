#include <membrane/physics/counter_hash.h>
#include <membrane/physics/thermal_noise.h>

#include <cmath>
#include <string>

namespace Membrane
{
  namespace
  {
    /// A uniform variate in (0, 1] from the 53 high bits of a word.
    double uniform(const std::uint64_t word)
    {
      return (static_cast<double>(word >> 11) + 1.0) * 0x1.0p-53;
    }
  } // namespace

  void declare_thermal_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Temperature", "0", dealii::Patterns::Double(0, 1e6),
                      "k_BT, in the energy unit of the moduli (kappa = 20 k_BT means Temperature = kappa / 20; "
                      "docs/units.md): the thermal noise of the fluctuating gradient flow (MODEL.md section 10). "
                      "The Cahn-Hilliard step gains a conserved random flux of covariance 2 k_BT L_phi / tau per "
                      "cell, the shape step a random force of covariance 2 k_BT / (tau L_X) times the mass matrix, "
                      "projected by the area and volume constraints like the deterministic force (with <Shape/Mesh motion> = ale "
                      "its solenoidal tangential part moves only the lipids, physics/tangential_noise.h). 0: the "
                      "deterministic flow. Needs <Time stepping/Adaptive> = false (a fixed tau: the energy "
                      "fluctuates, so energy-descent control does not apply).");
    prm.declare_entry("Noise seed", "1", dealii::Patterns::Integer(0),
                      "Seed of the thermal noise. Each variate is a function of (seed, step, cell, component): a "
                      "run gives the same trajectory on any number of ranks and after a resume.");
  }

  ThermalNoise parse_thermal_parameters(dealii::ParameterHandler &prm)
  {
    ThermalNoise noise;
    noise.temperature = prm.get_double("Temperature");
    noise.seed        = static_cast<std::uint64_t>(prm.get_integer("Noise seed"));
    return noise;
  }

  double standard_normal(const std::uint64_t seed, const std::uint64_t step, const std::uint64_t id,
                         const unsigned int component)
  {
    const std::uint64_t key = splitmix64(splitmix64(splitmix64(splitmix64(seed) ^ step) ^ id) ^ component);
    const double        u1 = uniform(splitmix64(key)), u2 = uniform(splitmix64(key ^ 0x5851f42d4c957f2dULL));
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
  }

  std::uint64_t cell_key(const dealii::CellId &id)
  {
    std::uint64_t hash = 0xcbf29ce484222325ULL; // FNV-1a over the id's text, then mixed
    for (const char c : id.to_string())
      hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
    return splitmix64(hash);
  }
} // namespace Membrane
