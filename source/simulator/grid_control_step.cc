// Stage 4 of a step: the mesh. Lagrangian: grid control, the tangential smoothing of X~ with the
// ALE remap of phi (MODEL.md section 4), kept when the step as a whole descends (always at
// k_BT > 0). ALE: the mesh motion of surface/mesh_motion.h, at k_BT = 0 in two moves (the normal
// one, whose energy is the physical step's, then the smoothing).
// Then the geometry and energy F^{m+1}. Part of Simulator.
#include <membrane/simulator.h>
#include <membrane/solvers/vector_access.h>
#include <membrane/surface/grid_control.h>
#include <membrane/surface/mesh_motion.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  void Simulator::control_grid(const double energy_before, const double tau)
  {
    if (!(parameters.evolve_shape && parameters.grid_control_weight > 0))
      return update_geometry();

    // Grid control re-parametrizes the Lagrangian surface X~. The moved state is
    // kept when the step as a whole does not raise the energy; only otherwise is the
    // geometry of X~ itself needed (near equilibrium the move's O(h^2) energy change
    // would stall the energy-based step control at any tau).
    const State lagrangian = save_state();
    {
      TimerOutput::Scope scope(timer, "grid control");
      // With a grid-control rate, a long step is smoothed in several sweeps (each within
      // the stable weight), so the mesh moves at the same rate per unit time whatever tau.
      const unsigned int sweeps = parameters.grid_control_sweeps_of_step(tau);
      const double       weight = parameters.grid_control_weight_of_step(tau);
      // The tangential moves change the volume of the bilinear surface; a fixed volume is
      // restored after each sweep (unless the vertex areas hold it).
      const bool restore_moved_volume = volume_fixed() && !shape_solver.volume_held_by_areas();
      remap_correction = 0;
      for (unsigned int sweep = 0; sweep < sweeps; ++sweep)
        {
          const Vector normal = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
          const Vector shift  = grid_control_displacement(surface, normal, weight);
          const Vector ratio  = area_ratio();
          remap_correction += move_tangentially_and_remap(surface, shift, phi);
          // The reference area moves with the vertices, each keeping its relative error;
          // the total reference area is kept exactly.
          carry_reference_areas(ratio);
          if (restore_moved_volume)
            restore_volume();
        }
    }
    update_geometry();
    // At a temperature the energy of the step fluctuates by about k_BT per mode, far more than
    // the O(h^2) change of the re-parametrization: the move is always kept.
    if (std::isfinite(energy.total()) &&
        (parameters.thermal.active() ||
         energy.total() <= energy_before + parameters.energy_tolerance * std::abs(energy_before)))
      return;
    restore_state(lagrangian);
    remap_correction  = 0;
    grid_move_skipped = true;
    update_geometry();
  }

  void Simulator::update_geometry()
  {
    TimerOutput::Scope scope(timer, "geometry");
    geometry = compute_geometry(surface);
    energy   = compute_energy(surface, geometry, phi, parameters.material);
  }

  unsigned int Simulator::transport_substeps(const Vector &relative, const double solenoidal) const
  {
    const double cells = (relative.linfty_norm() + solenoidal) / reference_cell_size();
    return static_cast<unsigned int>(std::max(1.0, std::ceil(cells / max_transport_cells)));
  }

  void Simulator::carry_along(const Vector &mesh, const Vector &relative, const Vector &density,
                              const Vector *stream, const double stream_displacement)
  {
    // The explicit transport is accurate (and Lax-Wendroff stable) for relative moves below a cell;
    // at a temperature the lipids' random walk moves them further, so the move is split into
    // substeps of at most half a cell of the finest mesh, each from where the last one left.
    const unsigned int substeps = transport_substeps(relative, stream_displacement);
    Vector             mesh_substep = mesh, relative_substep = relative;
    mesh_substep *= 1.0 / substeps;
    relative_substep *= 1.0 / substeps;
    for (unsigned int k = 0; k < substeps; ++k)
      move_and_transport(surface, mesh_substep, relative_substep, {&phi}, stream, 1.0 / substeps);
    // The compression ratio a_ref / a stays with the vertex through the move.
    carry_reference_areas(density);
  }

  void Simulator::move_mesh(const double tau, const State &before)
  {
    {
      TimerOutput::Scope scope(timer, "mesh motion");
      const FieldSpace  &vectors  = surface.vector_space();
      Vector             material = vectors.make_owned(); // W
      material                    = surface.displacement();
      material -= before.displacement;
      // The lipids of vertex i cover its area on X~ = X^m + W after the physical step: their
      // compression a_ref,i / a_i(X~), taken while the surface is still at X~, where
      // restore_material_areas left it.
      const Vector density = area_ratio();
      // Back on Gamma^m: the mesh moves by the normal part of W plus the smoothing, at the
      // normals of Gamma^m that the shape step used (before.geometry).
      surface.set_displacement(before.displacement);
      // At a temperature the lipids also move by the solenoidal noise (split_noise).
      const Vector *stream              = split_noise ? &tangential_noise.stream : nullptr;
      const double  stream_displacement = stream ? tangential_noise.max_stream_displacement : 0;
      const unsigned int sweeps = parameters.grid_control_sweeps_of_step(tau);
      const double       weight = parameters.grid_control_weight_of_step(tau);
      if (parameters.thermal.active())
        {
          // At a temperature no energy test applies: one move by W^mesh, phi carried by d = W^mesh - W.
          const Vector mesh     = ale_mesh_increment(surface, vectors.ghosted_copy(material), before.geometry.normal,
                                                     sweeps, weight);
          Vector       relative = mesh;
          relative -= material;
          carry_along(mesh, relative, density, stream, stream_displacement);
        }
      else
        {
          // The physical step is judged on the shape it gives: Gamma^m moved by the normal part
          // of W, phi carried by the lipids' tangential motion (d = (W . nu) nu - W). Where the
          // vertices sit on that shape is the mesh motion's: judged on X^m + W, the step would
          // also count what moving the vertices along W's tangential part changes in the
          // discrete energy, an O(h^2) error that the smoothing then takes back, and which near
          // an equilibrium outweighs the step's descent at any tau (the step control stalled).
          const Vector normal   = normal_part(surface, vectors.ghosted_copy(material), before.geometry.normal);
          Vector       relative = normal;
          relative -= material;
          carry_along(normal, relative, density, nullptr, 0);
          {
            TimerOutput::Scope inner(timer, "geometry");
            physical_energy = compute_energy(surface, compute_geometry(surface), phi, parameters.material).total();
          }
          // The smoothing alone, measured where the normal motion put the vertices; phi stays
          // with the lipids (d = s).
          const Vector ratio     = area_ratio();
          const Vector smoothing = ale_mesh_increment(surface, vectors.ghosted_copy(vectors.make_owned()), vectors.ghosted_copy(
                                                        compute_vertex_normals(surface)), sweeps, weight);
          carry_along(smoothing, smoothing, ratio, nullptr, 0);
        }
      // What the step control bounds and compares is the motion of the shape, not of the lipids.
      step_increment = surface.displacement();
      step_increment -= before.displacement;
      max_increment = step_increment.linfty_norm();
      if (volume_fixed())
        restore_volume();
    }
    update_geometry();
    if (parameters.thermal.active())
      physical_energy = energy.total();
    mesh_motion_energy = energy.total() - physical_energy;
  }
} // namespace Membrane
