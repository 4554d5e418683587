#pragma once
// PVD/VTU time series of the current surface in R^3 with its fields. Each
// snapshot is one VTU with shared vertices: the points are the current surface
// X = X_ref + D (no displacement field, so nothing is warped twice), gathered on
// rank 0 and written under a temporary name, then renamed into place; the PVD
// index is rewritten atomically after every snapshot.

#include <membrane/surface/geometry.h>

#include <string>
#include <utility>
#include <vector>

namespace Membrane
{
  class FieldOutput
  {
  public:
    explicit FieldOutput(std::string directory);

    /// Scalar fields (scalar space, ghosted) by name, plus the geometry.
    void write(const Surface &surface, const Geometry &geometry,
               const std::vector<std::pair<std::string, const Vector *>> &scalar_fields, double time,
               unsigned int step);

    /// Continue the series of a resumed run up to `time`: the snapshots of this
    /// directory's surface.pvd, or, when the run resumes in another directory, those
    /// of the surface.pvd next to `checkpoint` (referred to by relative paths), so that
    /// the PVD spans the whole run.
    void resume(double time, const std::string &checkpoint);

  private:
    /// paraview_state.py: the series in ParaView's standard view (a Python state file).
    void write_paraview_state() const;

    /// Rank 0: merge the vertices gathered from all ranks and write the VTU and the PVD.
    void write_snapshot(const std::vector<std::vector<dealii::types::global_dof_index>> &keys,
                        const std::vector<std::vector<double>> &values,
                        const std::vector<std::vector<double>> &levels, unsigned int width,
                        const std::vector<std::pair<std::string, const Vector *>> &scalar_fields, double time,
                        unsigned int step);

    std::string                                directory;
    std::vector<std::pair<double, std::string>> snapshots;
  };
} // namespace Membrane
