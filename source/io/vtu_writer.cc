#include <membrane/io/vtu_writer.h>

#include <deal.II/base/exceptions.h>

#include <cstring>
#include <sstream>

namespace Membrane
{
  namespace
  {
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the VTU header declares LittleEndian");

    /// The appended-data section: each array is a UInt64 byte count followed by its bytes;
    /// the XML refers to an array by the offset of its byte count.
    class AppendedData
    {
    public:
      template <typename T>
      std::size_t add(const std::vector<T> &values)
      {
        const std::size_t   offset = bytes.size();
        const std::uint64_t size   = values.size() * sizeof(T);
        append(&size, sizeof(size));
        append(values.data(), size);
        return offset;
      }
      const std::string &data() const { return bytes; }

    private:
      void append(const void *source, const std::size_t size)
      {
        bytes.append(static_cast<const char *>(source), size);
      }
      std::string bytes;
    };

    void write_array(std::ostream &xml, AppendedData &appended, const VtuArray &array, const std::size_t n,
                     const std::string &where)
    {
      AssertThrow(array.components > 0 && array.values.size() == n * array.components,
                  dealii::ExcMessage("VTU " + where + " array <" + array.name + "> has " +
                                     std::to_string(array.values.size()) + " values for " + std::to_string(n) +
                                     " entries of " + std::to_string(array.components) + " components"));
      xml << "      <DataArray type=\"Float64\" Name=\"" << array.name << "\" NumberOfComponents=\""
          << array.components << "\" format=\"appended\" offset=\"" << appended.add(array.values) << "\"/>\n";
    }
  } // namespace

  std::string vtu_content(const QuadMesh &mesh)
  {
    const std::size_t n_points = mesh.n_points(), n_cells = mesh.n_cells();
    AssertThrow(mesh.points.size() == 3 * n_points && mesh.connectivity.size() == 4 * n_cells,
                dealii::ExcMessage("VTU mesh: points must have 3 and cells 4 entries each"));
    for (const auto index : mesh.connectivity)
      AssertThrow(index >= 0 && static_cast<std::size_t>(index) < n_points,
                  dealii::ExcMessage("VTU mesh: a cell refers to point " + std::to_string(index) + " of " +
                                     std::to_string(n_points)));

    AppendedData       appended;
    std::ostringstream xml;
    xml << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <FieldData>\n"
        << "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"appended\" offset=\""
        << appended.add(std::vector<double>{mesh.time}) << "\"/>\n"
        << "      <DataArray type=\"Int64\" Name=\"CYCLE\" NumberOfTuples=\"1\" format=\"appended\" offset=\""
        << appended.add(std::vector<std::int64_t>{mesh.cycle}) << "\"/>\n"
        << "    </FieldData>\n"
        << "    <Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\"" << n_cells << "\">\n";

    xml << "    <PointData>\n";
    for (const auto &array : mesh.point_data)
      write_array(xml, appended, array, n_points, "point");
    xml << "    </PointData>\n    <CellData>\n";
    for (const auto &array : mesh.cell_data)
      write_array(xml, appended, array, n_cells, "cell");
    xml << "    </CellData>\n";

    xml << "    <Points>\n"
        << "      <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\""
        << appended.add(mesh.points) << "\"/>\n"
        << "    </Points>\n";

    std::vector<std::int64_t> offsets(n_cells);
    for (std::size_t c = 0; c < n_cells; ++c)
      offsets[c] = static_cast<std::int64_t>(4 * (c + 1));
    const std::vector<std::uint8_t> types(n_cells, 9); // VTK_QUAD
    xml << "    <Cells>\n"
        << "      <DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\""
        << appended.add(mesh.connectivity) << "\"/>\n"
        << "      <DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"" << appended.add(offsets)
        << "\"/>\n"
        << "      <DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"" << appended.add(types)
        << "\"/>\n"
        << "    </Cells>\n"
        << "    </Piece>\n"
        << "  </UnstructuredGrid>\n"
        << "  <AppendedData encoding=\"raw\">\n_";
    std::string content = xml.str();
    content += appended.data();
    content += "\n  </AppendedData>\n</VTKFile>\n";
    return content;
  }
} // namespace Membrane
