#include <membrane/parameters.h>
#include <membrane/physics/volume.h>
#include <membrane/vesicle_parameters.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <limits>

namespace Membrane
{
  using namespace dealii;

  void declare_vesicle_parameters(ParameterHandler &prm)
  {
    const double max_double = std::numeric_limits<double>::max();
    prm.enter_subsection("Mesh");
    prm.declare_entry("Reference surface", "periodic patch", Patterns::Selection("periodic patch|sphere|ellipsoid|file"),
                      "periodic patch: the unit square with periodic edges (Cells per side along each edge); sphere: "
                      "a cube-sphere of Sphere radius with Cells per side (2^k) cells along each edge of its six "
                      "faces; ellipsoid: that sphere of radius 1 scaled by Semi-axes; file: a closed quadrilateral "
                      "surface mesh from Mesh file. Closed surfaces are oriented with the outward normal.");
    prm.declare_entry("Sphere radius", "1", Patterns::Double(1e-6, max_double), "R of Reference surface = sphere (length).");
    prm.declare_entry("Semi-axes", "1.2, 0.9, 0.9", Patterns::List(Patterns::Double(1e-6, max_double), 3, 3),
                      "a, b, c of Reference surface = ellipsoid along x, y, z (length); a > b = c is prolate.");
    prm.declare_entry("Mesh file", "", Patterns::Anything(),
                      "Reference surface = file: a closed, consistently oriented quadrilateral surface mesh in 3D "
                      "read by deal.II's GridIn (Gmsh .msh, VTK .vtk, UCD .inp).");
    prm.declare_entry("File refinements", "0", Patterns::Integer(0, 8),
                      "Reference surface = file: uniform refinements of the file's cells (new vertices on the "
                      "bilinear cells).");
    prm.leave_subsection();

    prm.enter_subsection("Volume");
    prm.declare_entry("Constraint", "free", Patterns::Selection("free|fixed|pressure"),
                      "Enclosed volume V = 1/3 integral X.n ds of a closed surface. free: no volume term; fixed: V "
                      "= V_target through a global pressure p (Lagrange multiplier); pressure: a prescribed pressure "
                      "difference p (inside minus outside; positive inflates).");
    prm.declare_entry("Pressure", "0", Patterns::Double(-max_double, max_double),
                      "p for Constraint = pressure (energy/length^3).");
    prm.declare_entry("Reduced volume target", "0", Patterns::Double(0, max_double),
                      "Constraint = fixed: v* in (0, 1], the reduced volume v = 6 sqrt(pi) V / A^(3/2) to reach; "
                      "V_target moves linearly from the initial volume to v* A0^(3/2) / (6 sqrt(pi)) over Ramp time "
                      "(A0: the initial area). 0: keep the initial volume.");
    prm.declare_entry("Ramp time", "0", Patterns::Double(0, max_double),
                      "Time over which V_target moves to the Reduced volume target (0: at once).");
    prm.leave_subsection();

    prm.enter_subsection("Initial phase");
    prm.declare_entry("Cap axes", "0 0 1", Patterns::Anything(),
                      "Type = caps: 'x y z; x y z; ...', one direction per cap domain of phase A (phi = +1) on a "
                      "closed surface; each cap is the set of points whose direction from the centroid makes the "
                      "smallest angles with its axis.");
    prm.declare_entry("Cap area fraction", "0.1", Patterns::Double(0, 1),
                      "Type = caps: the fraction of the initial area that each cap covers.");
    prm.declare_entry("Cap profile", "tanh", Patterns::Selection("sharp|tanh"),
                      "Type = caps: sharp: phi = +1 in a cap and -1 outside; tanh: phi = tanh(3 d / (4 xi)) with d "
                      "the signed distance to the cap's edge along the surface (estimated as R (theta_c - theta) "
                      "with R = sqrt(A / 4 pi)).");
    prm.leave_subsection();
  }

  namespace
  {
    std::array<double, 3> parse_semi_axes(const std::string &text)
    {
      const auto            parts = Utilities::split_string_list(text, ',');
      std::array<double, 3> axes{};
      for (unsigned int i = 0; i < 3; ++i)
        axes[i] = Utilities::string_to_double(parts[i]);
      return axes;
    }
  } // namespace

  void parse_vesicle_parameters(ParameterHandler &prm, Parameters &parameters)
  {
    ReferenceSurfaceOptions &reference = parameters.reference;
    prm.enter_subsection("Mesh");
    reference.type             = prm.get("Reference surface");
    reference.cells_per_side   = parameters.cells_per_side;
    reference.radius           = prm.get_double("Sphere radius");
    reference.semi_axes        = parse_semi_axes(prm.get("Semi-axes"));
    reference.file             = prm.get("Mesh file");
    reference.file_refinements = prm.get_integer("File refinements");
    prm.leave_subsection();

    VolumeOptions &volume = parameters.volume;
    prm.enter_subsection("Volume");
    volume.constraint            = prm.get("Constraint");
    volume.pressure              = prm.get_double("Pressure");
    volume.reduced_volume_target = prm.get_double("Reduced volume target");
    volume.ramp_time             = prm.get_double("Ramp time");
    prm.leave_subsection();

    InitialPhaseOptions &phase = parameters.initial_phase;
    prm.enter_subsection("Initial phase");
    phase.cap_axes          = parse_cap_axes(prm.get("Cap axes"), "Initial phase/Cap axes");
    phase.cap_area_fraction = prm.get_double("Cap area fraction");
    phase.cap_sharp         = prm.get("Cap profile") == "sharp";
    phase.transition_length = parameters.material.transition_length;
    prm.leave_subsection();

    const bool closed = reference.closed();
    if (reference.type == "sphere" || reference.type == "ellipsoid")
      {
        const unsigned int n = parameters.cells_per_side;
        AssertThrow((n & (n - 1)) == 0,
                    ExcMessage("Entry <Mesh/Cells per side>: a sphere or ellipsoid has 2^k cells along each edge of "
                               "its six cube faces; got " + std::to_string(n) + " (use e.g. 8, 16, 32)"));
      }
    if (reference.type == "file")
      AssertThrow(!reference.file.empty(),
                  ExcMessage("Entry <Mesh/Mesh file>: Reference surface = file needs a mesh file (Gmsh .msh, VTK "
                             ".vtk or UCD .inp with quadrilateral cells)"));
    AssertThrow(!closed || parameters.shape == "flat" || parameters.shape == "expression",
                ExcMessage("Entry <Initial shape/Shape> = " + parameters.shape + ": bump and cosine modes are shapes of "
                           "the periodic patch; a closed surface starts as its <Mesh/Reference surface> (flat), "
                           "perturbed by a Displacement expression in x, y, z (expression)"));
    AssertThrow(!closed || (phase.type != "bump" && phase.type != "expression"),
                ExcMessage("Entry <Initial phase/Type> = " + phase.type + ": defined on the periodic patch; on a "
                           "closed surface use caps, random or uniform"));
    AssertThrow(closed || phase.type != "caps",
                ExcMessage("Entry <Initial phase/Type> = caps: needs a closed <Mesh/Reference surface>"));
    AssertThrow(closed || volume.constraint == "free",
                ExcMessage("Entry <Volume/Constraint> = " + volume.constraint + ": a volume needs a closed <Mesh/"
                           "Reference surface> (sphere, ellipsoid or file)"));
    AssertThrow(volume.reduced_volume_target <= 1,
                ExcMessage("Entry <Volume/Reduced volume target> = " + std::to_string(volume.reduced_volume_target) +
                           ": exceeds 1; no closed surface of area A encloses more than the sphere of that area "
                           "(v = 6 sqrt(pi) V / A^(3/2) <= 1). Accepted: (0, 1], or 0 to keep the initial volume"));
    AssertThrow(volume.reduced_volume_target == 0 || volume.constraint == "fixed",
                ExcMessage("Entry <Volume/Reduced volume target>: needs <Volume/Constraint> = fixed (got " +
                           volume.constraint + ")"));
  }
} // namespace Membrane
