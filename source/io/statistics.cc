#include <membrane/io/atomic_file.h>
#include <membrane/io/statistics.h>

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace Membrane
{
  void Statistics::set(const std::string &column, const double value)
  {
    auto it = index.find(column);
    if (it == index.end())
      {
        it = index.emplace(column, columns.size()).first;
        columns.push_back(column);
      }
    if (current.size() < columns.size())
      current.resize(columns.size(), std::numeric_limits<double>::quiet_NaN());
    current[it->second] = value;
  }

  void Statistics::end_row()
  {
    rows.push_back(current);
    current.assign(columns.size(), std::numeric_limits<double>::quiet_NaN());
  }

  double Statistics::last(const std::string &column) const
  {
    const auto it = index.find(column);
    AssertThrow(it != index.end() && !rows.empty(), dealii::ExcMessage("No statistics column <" + column + ">"));
    return it->second < rows.back().size() ? rows.back()[it->second] : std::numeric_limits<double>::quiet_NaN();
  }

  std::string Statistics::to_text() const
  {
    std::ostringstream out;
    out << "#";
    for (const auto &c : columns)
      out << ' ' << c;
    out << '\n';
    out.precision(17);
    for (const auto &row : rows)
      {
        for (std::size_t c = 0; c < columns.size(); ++c)
          out << (c ? " " : "") << (c < row.size() ? row[c] : std::numeric_limits<double>::quiet_NaN());
        out << '\n';
      }
    return out.str();
  }

  Statistics Statistics::from_text(const std::string &text)
  {
    Statistics         table;
    std::istringstream in(text);
    std::string        line;
    AssertThrow(std::getline(in, line) && !line.empty() && line[0] == '#',
                dealii::ExcMessage("Statistics text without a '#' header line"));
    std::istringstream header(line.substr(1));
    for (std::string name; header >> name;)
      {
        table.index.emplace(name, table.columns.size());
        table.columns.push_back(name);
      }
    while (std::getline(in, line))
      {
        std::istringstream  values(line);
        std::vector<double> row;
        for (std::string word; values >> word;)
          row.push_back(std::strtod(word.c_str(), nullptr)); // also reads "nan"
        if (!row.empty())
          table.rows.push_back(row);
      }
    table.current.assign(table.columns.size(), std::numeric_limits<double>::quiet_NaN());
    return table;
  }

  void Statistics::write(const std::string &path) const
  {
    write_file_atomically(path, to_text());
  }
} // namespace Membrane
