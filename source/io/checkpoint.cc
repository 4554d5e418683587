#include <membrane/io/atomic_file.h>
#include <membrane/io/checkpoint.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <tuple>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    constexpr const char *magic    = "membrane-checkpoint 4";
    constexpr const char *magic_v3 = "membrane-checkpoint 3";
    constexpr const char *magic_v2 = "membrane-checkpoint 2";
    constexpr const char *magic_v1 = "membrane-checkpoint 1";
    /// x, y, z, D (3), phi, reference area, increment of X (3) and of phi. z tells
    /// apart the vertices of a closed surface that share x and y (formats 1 and 2, of
    /// the patch, have no z; formats 1-3 have no increments, format 1 no area).
    constexpr std::size_t fields = 12;
    using Key = std::tuple<double, double, double>;

    /// Calls f(reference vertex, vector dofs[3], scalar dof) for every owned,
    /// unconstrained vertex of the scalar space.
    template <typename F>
    void for_each_owned_vertex(const Surface &surface, const F &f)
    {
      const FieldSpace &scalars = surface.scalar_space();
      for (const auto &cell : surface.vector_space().dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto scalar_cell = scalars.cell(cell);
            for (const unsigned int v : cell->vertex_indices())
              {
                const auto dof = scalar_cell->vertex_dof_index(v, 0);
                if (!scalars.owned().is_element(dof) || scalars.constraints().is_constrained(dof))
                  continue;
                const std::array<types::global_dof_index, 3> vector_dofs{
                  {cell->vertex_dof_index(v, 0), cell->vertex_dof_index(v, 1), cell->vertex_dof_index(v, 2)}};
                f(cell->vertex(v), vector_dofs, dof);
              }
          }
    }
  } // namespace

  namespace
  {
    using CellKey = std::tuple<int, double, double, double>; ///< level and reference centre of a cell

    /// Every cell with children (level and reference centre), over all ranks.
    std::set<CellKey> refined_cells(const dealii::Triangulation<dim, spacedim> &triangulation)
    {
      std::vector<double> local;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (typename dealii::Triangulation<dim, spacedim>::cell_iterator parent = cell; parent->level() > 0;)
            {
              parent = parent->parent();
              const auto c = parent->center();
              local.insert(local.end(), {double(parent->level()), c[0], c[1], c[2]});
            }
      std::set<CellKey> cells;
      for (const auto &part : Utilities::MPI::all_gather(triangulation.get_communicator(), local))
        for (std::size_t i = 0; i < part.size(); i += 4)
          cells.emplace(int(part[i]), part[i + 1], part[i + 2], part[i + 3]);
      return cells;
    }
  } // namespace

  void refine_like_checkpoint(const std::string &path, Triangulation &triangulation, const unsigned int cells_per_side,
                              const unsigned int finest_level)
  {
    std::ifstream in(path);
    AssertThrow(in, ExcMessage("Entry <Checkpoint/Resume from>: cannot open the checkpoint <" + path + ">"));
    std::set<CellKey> refined;
    for (std::string line; std::getline(in, line);)
      {
        std::istringstream words(line);
        std::string        name;
        words >> name;
        if (name == "vertices")
          break;
        if (name == "cells_per_side")
          {
            double written = 0;
            words >> written;
            AssertThrow(written == cells_per_side,
                        ExcMessage("Entry <Checkpoint/Resume from>: <" + path + "> was written on a mesh with " +
                                   std::to_string(int(written)) + " cells per side; this run has <Mesh/Cells per "
                                   "side> = " + std::to_string(cells_per_side)));
          }
        if (name == "parameters")
          {
            std::size_t n = 0;
            words >> n;
            for (std::size_t i = 0; i < n && std::getline(in, line); ++i)
              ;
            continue;
          }
        if (name != "refined")
          continue;
        std::size_t n = 0;
        words >> n;
        for (std::size_t i = 0; i < n && std::getline(in, line); ++i)
          {
            std::istringstream cell(line);
            int                level;
            double             x, y, z = 0; // no z: a checkpoint of the patch in format 2
            cell >> level >> x >> y;
            if (!(cell >> z))
              z = 0;
            AssertThrow(level >= 0 && unsigned(level) < finest_level,
                        ExcMessage("Entry <Checkpoint/Resume from>: <" + path + "> was written on a mesh refined "
                                   "beyond what this run allows (check <Mesh/Cells per side> and <Mesh/Maximum "
                                   "refinement level>)"));
            refined.emplace(level, x, y, z);
          }
      }
    // Refine level by level; p4est's 2:1 balance adds nothing, the saved mesh was balanced.
    for (bool changed = true; changed;)
      {
        unsigned int flagged = 0;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const auto c = cell->center();
              if (refined.count({cell->level(), c[0], c[1], c[2]}))
                {
                  cell->set_refine_flag();
                  ++flagged;
                }
            }
        changed = Utilities::MPI::sum(flagged, triangulation.get_communicator()) > 0;
        if (changed)
          triangulation.execute_coarsening_and_refinement();
      }
  }

  std::string checkpoint_parameters(const std::string &path)
  {
    std::ifstream in(path);
    std::string   text;
    for (std::string line; std::getline(in, line);)
      {
        std::istringstream words(line);
        std::string        name;
        std::size_t        n = 0;
        words >> name >> n;
        if (name == "vertices")
          break;
        if (name != "parameters")
          continue;
        for (std::size_t i = 0; i < n && std::getline(in, line); ++i)
          text += line + '\n';
        break;
      }
    return text;
  }

  std::vector<std::string> changed_parameters(const std::string &before, const std::string &now)
  {
    // ShortPRM: "subsection Name" / "end" around "set Entry = value" lines.
    const auto entries = [](const std::string &text) {
      std::map<std::string, std::string> values;
      std::vector<std::string>           sections;
      std::istringstream                 in(text);
      for (std::string line; std::getline(in, line);)
        {
          line = Utilities::trim(line);
          if (line.rfind("subsection ", 0) == 0)
            sections.push_back(Utilities::trim(line.substr(11)));
          else if (line == "end" && !sections.empty())
            sections.pop_back();
          else if (line.rfind("set ", 0) == 0 && line.find('=') != std::string::npos)
            {
              std::string path;
              for (const auto &section : sections)
                path += section + "/";
              const auto eq = line.find('=');
              values[path + Utilities::trim(line.substr(4, eq - 4))] = Utilities::trim(line.substr(eq + 1));
            }
        }
      return values;
    };
    const auto               old_values = entries(before), new_values = entries(now);
    std::vector<std::string> changes;
    for (const auto &[path, value] : new_values)
      if (const auto it = old_values.find(path); it != old_values.end() && it->second != value)
        changes.push_back(path + ": " + it->second + " -> " + value);
    return changes;
  }

  void save_checkpoint(const std::string &path, const Surface &surface, const Vector &phi,
                       const Vector &reference_areas, const std::map<std::string, double> &scalars,
                       const std::string &statistics_text, const std::string &parameter_text,
                       const StepIncrements *increments)
  {
    const Vector &D     = surface.displacement();
    const Vector  areas = surface.scalar_space().ghosted_copy(reference_areas);
    const Vector  dX    = increments ? surface.vector_space().ghosted_copy(increments->shape) :
                                       surface.vector_space().make_ghosted();
    const Vector  dphi  = increments ? surface.scalar_space().ghosted_copy(increments->phi) :
                                       surface.scalar_space().make_ghosted();
    std::vector<double> local;
    std::set<types::global_dof_index> seen;
    for_each_owned_vertex(surface, [&](const Point<spacedim> &x, const auto &vector_dofs, const auto dof) {
      if (!seen.insert(dof).second)
        return;
      local.insert(local.end(), {x[0], x[1], x[2], D[vector_dofs[0]], D[vector_dofs[1]], D[vector_dofs[2]], phi[dof],
                                 areas[dof], dX[vector_dofs[0]], dX[vector_dofs[1]], dX[vector_dofs[2]], dphi[dof]});
    });
    const MPI_Comm comm  = surface.scalar_space().communicator();
    const auto     parts = Utilities::MPI::gather(comm, local, 0);
    // Collective: every rank takes part before the others return.
    const auto refined = refined_cells(surface.scalar_space().dof_handler().get_triangulation());
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return;
    std::ostringstream out;
    out << magic << '\n' << std::setprecision(17);
    for (const auto &[name, value] : scalars)
      out << name << ' ' << value << '\n';
    {
      const auto lines = Utilities::split_string_list(parameter_text, '\n');
      out << "parameters " << lines.size() << '\n';
      for (const auto &line : lines)
        out << line << '\n';
    }
    out << "refined " << refined.size() << '\n';
    for (const auto &[level, x, y, z] : refined)
      out << level << ' ' << x << ' ' << y << ' ' << z << '\n';
    std::size_t n = 0;
    for (const auto &part : parts)
      n += part.size() / fields;
    out << "vertices " << n << '\n';
    for (const auto &part : parts)
      for (std::size_t i = 0; i < part.size(); i += fields)
        for (std::size_t k = 0; k < fields; ++k)
          out << part[i + k] << (k + 1 < fields ? ' ' : '\n');
    out << "statistics\n" << statistics_text;
    write_file_atomically(path, out.str());
  }

  std::map<std::string, double> load_checkpoint(const std::string &path, const Surface &surface,
                                                Vector &displacement, Vector &phi, Vector &reference_areas,
                                                std::string &statistics_text, StepIncrements *increments)
  {
    std::ifstream in(path);
    AssertThrow(in, ExcMessage("Entry <Checkpoint/Resume from>: cannot open the checkpoint <" + path + ">"));
    std::string line;
    AssertThrow(std::getline(in, line) &&
                  (line == magic || line == magic_v3 || line == magic_v2 || line == magic_v1),
                ExcMessage("Entry <Checkpoint/Resume from>: <" + path + "> is not a membrane checkpoint"));
    const bool                    has_areas      = line != magic_v1;
    const bool                    has_z          = line == magic || line == magic_v3;
    const bool                    has_increments = line == magic;
    std::map<std::string, double> scalars;
    std::size_t                   n = 0;
    while (std::getline(in, line))
      {
        std::istringstream words(line);
        std::string        name;
        words >> name;
        if (name == "vertices")
          {
            words >> n;
            break;
          }
        if (name == "refined" || name == "parameters") // read by refine_like_checkpoint(), checkpoint_parameters()
          {
            std::size_t cells = 0;
            words >> cells;
            for (std::size_t i = 0; i < cells && std::getline(in, line); ++i)
              ;
            continue;
          }
        words >> scalars[name];
      }
    const std::string name = "Entry <Checkpoint/Resume from>: <" + path + ">";
    // On the periodic patch a vertex on the edges u_k = 0 and 1 exists twice; the file holds the copy
    // that carried the dofs when it was written, and after a mesh that refined and coarsened that can be
    // the other one than in the mesh rebuilt from the checkpoint. Both copies get the key of u_k = 0.
    const auto key = [periodic = surface.periodic()](const double x, const double y, const double z) -> Key {
      return periodic ? Key{x == 1.0 ? 0.0 : x, y == 1.0 ? 0.0 : y, z} : Key{x, y, z};
    };
    std::map<Key, std::array<double, 9>> values;
    for (std::size_t i = 0; i < n; ++i)
      {
        AssertThrow(std::getline(in, line), ExcMessage(name + " is truncated (vertex " + std::to_string(i) + " of " +
                                                       std::to_string(n) + ")"));
        std::istringstream    words(line);
        double                x, y, z = 0;
        std::array<double, 9> v{};
        words >> x >> y;
        if (has_z)
          words >> z;
        words >> v[0] >> v[1] >> v[2] >> v[3];
        if (has_areas)
          words >> v[4];
        if (has_increments)
          words >> v[5] >> v[6] >> v[7] >> v[8];
        bool finite = !words.fail() && std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
        for (const double value : v)
          finite = finite && std::isfinite(value);
        AssertThrow(finite, ExcMessage(name + " is corrupt: vertex line " + std::to_string(i + 1) +
                                         " is not finite numbers: <" + line + ">"));
        values[key(x, y, z)] = v;
      }
    AssertThrow(std::getline(in, line) && line == "statistics", ExcMessage(name + " is truncated"));
    statistics_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    // The statistics must hold one complete, finite row per accepted step (0 included).
    {
      std::istringstream rows(statistics_text);
      std::string        header, row;
      std::getline(rows, header);
      std::size_t n_columns = 0, n_rows = 0;
      for (std::istringstream names(header.substr(header.empty() ? 0 : 1)); names >> row;)
        ++n_columns;
      while (std::getline(rows, row))
        {
          if (row.empty())
            continue;
          std::istringstream words(row);
          std::size_t        count = 0;
          for (std::string word; words >> word; ++count)
            ;
          AssertThrow(count == n_columns, ExcMessage(name + " is corrupt: statistics row " + std::to_string(n_rows + 1) +
                                                      " has " + std::to_string(count) + " of " +
                                                      std::to_string(n_columns) + " values"));
          ++n_rows;
        }
      const auto step = scalars.find("step");
      AssertThrow(header.rfind("#", 0) == 0 && step != scalars.end() && n_rows == std::size_t(step->second) + 1,
                  ExcMessage(name + " is truncated: its statistics have " + std::to_string(n_rows) +
                             " rows for step " + (step != scalars.end() ? std::to_string(int(step->second)) : "?")));
    }
    for (const auto &[scalar, value] : scalars)
      AssertThrow(std::isfinite(value), ExcMessage(name + " is corrupt: <" + scalar + "> is not finite"));

    bool        all_found = true;
    std::string missing; // the first vertex of this mesh the file does not hold, for the message
    for_each_owned_vertex(surface, [&](const Point<spacedim> &x, const auto &vector_dofs, const auto dof) {
      const auto it = values.find(key(x[0], x[1], x[2]));
      if (it == values.end())
        {
          if (all_found)
            {
              std::ostringstream where;
              where << std::setprecision(17) << "; the vertex (" << x[0] << ", " << x[1] << ", " << x[2]
                    << ") is not in the file";
              missing = where.str();
            }
          all_found = false;
          return;
        }
      for (unsigned int c = 0; c < spacedim; ++c)
        displacement[vector_dofs[c]] = it->second[c];
      phi[dof]             = it->second[3];
      reference_areas[dof] = it->second[4];
      if (increments)
        {
          for (unsigned int c = 0; c < spacedim; ++c)
            increments->shape[vector_dofs[c]] = it->second[5 + c];
          increments->phi[dof] = it->second[8];
        }
    });
    // Every vertex of this mesh in the file, and no other: a finer mesh's file holds
    // all vertices of a coarser one.
    std::size_t local_vertices = 0;
    std::set<types::global_dof_index> counted;
    for_each_owned_vertex(surface, [&](const auto &, const auto &, const auto dof) {
      local_vertices += counted.insert(dof).second;
    });
    const MPI_Comm comm = surface.scalar_space().communicator();
    AssertThrow(Utilities::MPI::min(all_found ? 1 : 0, comm) == 1 &&
                  Utilities::MPI::sum(local_vertices, comm) == values.size(),
                ExcMessage(name + " was written on another mesh (" + std::to_string(values.size()) +
                           " vertices; this run has " + std::to_string(Utilities::MPI::sum(local_vertices, comm)) +
                           missing + "): check <Mesh/Cells per side> and the refinement entries"));
    displacement.compress(VectorOperation::insert);
    phi.compress(VectorOperation::insert);
    reference_areas.compress(VectorOperation::insert);
    if (increments)
      {
        increments->shape.compress(VectorOperation::insert);
        increments->phi.compress(VectorOperation::insert);
        surface.vector_space().constraints().distribute(increments->shape);
        surface.scalar_space().constraints().distribute(increments->phi);
      }
    surface.vector_space().constraints().distribute(displacement);
    surface.scalar_space().constraints().distribute(phi);
    return scalars;
  }
} // namespace Membrane
