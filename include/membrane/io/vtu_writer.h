#pragma once
// A VTK XML unstructured grid of quadrilaterals with shared vertices, written as
// one self-contained file (raw appended binary data). ParaView and VTK read it
// directly; smooth shading needs no "Clean to Grid" because each vertex is one point.

#include <cstdint>
#include <string>
#include <vector>

namespace Membrane
{
  struct VtuArray
  {
    std::string         name;
    unsigned int        components = 1;
    std::vector<double> values; ///< components per point (or cell), interleaved
  };

  struct QuadMesh
  {
    std::vector<double>       points;       ///< x, y, z per point
    std::vector<std::int64_t> connectivity; ///< 4 point indices per cell, counterclockwise
    std::vector<VtuArray>     point_data;
    std::vector<VtuArray>     cell_data;
    double                    time  = 0; ///< written as the TIME field data
    unsigned int              cycle = 0; ///< written as the CYCLE field data

    std::size_t n_points() const { return points.size() / 3; }
    std::size_t n_cells() const { return connectivity.size() / 4; }
  };

  /// The complete file content. Throws if an array's size does not match the mesh.
  std::string vtu_content(const QuadMesh &mesh);
} // namespace Membrane
