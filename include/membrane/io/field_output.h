#pragma once
// PVD/VTU time series of the current surface in R^3 with its fields. Each
// snapshot is one VTU written collectively (MPI-IO), then renamed into place;
// the PVD index is rewritten atomically after every snapshot.

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

    /// Continue an existing series: keep the snapshots of surface.pvd up to `time`.
    void resume(double time);

  private:
    std::string                                directory;
    std::vector<std::pair<double, std::string>> snapshots;
  };
} // namespace Membrane
