#pragma once
// Checkpoints: the state a run needs to continue exactly as if uninterrupted.
// A text file (written atomically by rank 0) with named scalars (time, tau,
// step, ...), the vertex values of the displacement D, of phi and of the reference
// vertex areas of the local area constraint, keyed by the
// reference position of the vertex (so the file does not depend on the number
// of MPI ranks or the DoF numbering), and the statistics so far. Format 4 adds the
// increments of the last accepted step (of X and of phi), against which the accuracy
// control estimates the error of the next one. Values are written with 17 significant
// digits, which round-trips doubles exactly.

#include <membrane/surface/surface.h>

#include <map>
#include <string>
#include <vector>

namespace Membrane
{
  /// The increments of the last accepted step: of X (the vector space) and of phi
  /// (the scalar space), owned vectors.
  struct StepIncrements
  {
    Vector shape, phi;
  };

  /// Writes the checkpoint; `increments` nullptr: zeros (no step to compare with).
  void save_checkpoint(const std::string &path, const Surface &surface, const Vector &phi_ghosted,
                       const Vector &reference_areas, const std::map<std::string, double> &scalars,
                       const std::string &statistics_text, const std::string &parameter_text = "",
                       const StepIncrements *increments = nullptr);

  /// The parameters (ShortPRM text) a checkpoint's run used ("" for older checkpoints).
  std::string checkpoint_parameters(const std::string &path);

  /// Entries whose values differ between two ShortPRM texts, as "Section/Entry: old -> new".
  std::vector<std::string> changed_parameters(const std::string &before, const std::string &now);

  /// Refine the input mesh `triangulation` until it is the (adapted) mesh the
  /// checkpoint `path` was written on; call before the spaces are set up. Throws
  /// if the checkpoint's mesh had another number of cells per side, or cells finer
  /// than `finest_level` (the level of the input mesh plus the refinement allowed).
  void refine_like_checkpoint(const std::string &path, Triangulation &triangulation, unsigned int cells_per_side,
                              unsigned int finest_level);

  /// Reads `path` into the displacement, phi and the reference vertex areas (owned
  /// vectors of the surface's spaces, constraints applied) and the statistics text;
  /// returns the scalars. A checkpoint of format 1 (without reference areas) gets
  /// the areas of its surface. `increments` (owned vectors of the surface's spaces), if
  /// given, get the last step's increments (zero from checkpoints before format 4).
  /// Throws with a clear message if the file is missing, truncated or belongs
  /// to another mesh.
  std::map<std::string, double> load_checkpoint(const std::string &path, const Surface &surface,
                                                Vector &displacement_owned, Vector &phi_owned,
                                                Vector &reference_areas_owned, std::string &statistics_text,
                                                StepIncrements *increments = nullptr);
} // namespace Membrane
