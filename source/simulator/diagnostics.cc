// What a run says when it is in trouble or set up badly: the resolution warning at the start
// and the notes a failed or stalled run adds to its stop reason. Part of Simulator.
#include <membrane/simulator.h>
#include <membrane/surface/adaptivity.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace Membrane
{
  using namespace dealii;

  std::string Simulator::format(const double value)
  {
    std::ostringstream out;
    out << std::setprecision(4) << value;
    return out.str();
  }

  void Simulator::warn_if_unresolved() const
  {
    // The diffuse interface phi = tanh(3 s / (4 xi)) spans about 3.9 xi between
    // phi = -0.9 and 0.9; h <= 1.25 xi puts about 3 cells across it. h is
    // measured on the current surface, where the interface is (everywhere if none).
    // With local refinement, the size the interface cells reach as the interface sharpens
    // (the smooth bump start is refined only then).
    const AdaptivityOptions &adaptivity = parameters.adaptivity;
    const double             xi         = parameters.material.transition_length;
    const double             interface  = interface_cell_size(surface, phi, xi, adaptivity, base_level);
    // A phi that is uniform stays uniform in the deterministic flow: no interface will need the mesh.
    const auto [phi_min, phi_max] = global_range(phi);
    if (interface == 0 && !parameters.thermal.active() && phi_max == phi_min)
      return;
    const double h = interface > 0 ? interface : surface.max_cell_diameter() / std::sqrt(2.0);
    if (h <= 1.25 * xi)
      return;
    pcout << "Warning: cell size h = " << h
          << (interface > 0 ? (adaptivity.enabled() ? " at the interface once refined" : " at the interface") : "")
          << " exceeds 1.25 x the transition length xi = " << xi << " (h/xi = " << h / xi
          << "); the diffuse interface (width ~3.9 xi between phi = -0.9 and 0.9) is under-resolved. ";
    const double factor = h / (1.25 * xi);
    if (adaptivity.enabled() && xi / adaptivity.interface_cells_per_xi > 1.25 * xi)
      pcout << "Raise <Mesh/Interface cells per xi> to at least 0.8.\n";
    else if (parameters.adaptivity.enabled())
      pcout << "Raise <Mesh/Maximum refinement level> above " << parameters.adaptivity.max_level
            << " or <Mesh/Cells per side> to at least " << std::ceil(parameters.cells_per_side * factor) << ".\n";
    else
      pcout << "Increase <Mesh/Cells per side> to at least " << std::ceil(parameters.cells_per_side * factor)
            << ", or refine locally with <Mesh/Maximum refinement level>.\n";
  }

  std::string Simulator::curvature_resolution_note() const
  {
    // Energy rises that do not shrink with tau: on a mesh too coarse for the curvature
    // the discrete shape velocity is no longer a descent direction of the discrete
    // energy (docs/reliability.md). Say so when the mesh is that coarse.
    const double arc   = largest_curvature_per_cell(triangulation, surface, geometry);
    const double bound = 2 * parameters.adaptivity.curvature_resolution;
    if (arc <= bound)
      return "";
    return "; the mesh does not resolve the curvature (the most bent cell spans " + format(arc) +
           " rad of arc, more than 2 x <Mesh/Curvature resolution> = " + format(bound) +
           "), where the discrete shape step stops being a descent step of the discrete energy: refine with "
           "<Mesh/Maximum refinement level> or <Mesh/Cells per side>";
  }

  std::string Simulator::line_stiffness_note(const Rejection &last, const double tau) const
  {
    // The explicit phase force Y grad phi overshoots on interface-scale tangential modes once
    // tau L_X sigma / h^2 is O(1) (docs/model.md); the implicit line stiffness removes that limit.
    const Material &material = parameters.material;
    if (!parameters.evolve_shape || last.kind != "energy_rise" || parameters.shape_options.line_stiffness > 0 ||
        material.line_tension <= 0)
      return "";
    const double h     = reference_cell_size();
    const double limit = h * h / (material.shape_mobility * material.line_tension);
    if (tau > 10 * limit)
      return "";
    // The stiffness is sigma xi^2 |grad_s phi|^2: without an interface (phi uniform, or a
    // broad profile that has not sharpened) there is none, and the rise has another cause.
    if (largest_relative_steepness(surface, phi, material.transition_length) < 0.5)
      return "";
    return "; tau is within 10x of the explicit limit of the phase force, h^2 / (L_X sigma) = " + format(limit) +
           " for the finest cells: if the energy rises at the phase interface, <Shape/Line stiffness> = 1 lifts "
           "that limit (docs/model.md)";
  }
} // namespace Membrane
