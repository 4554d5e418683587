#pragma once
// The per-step statistics table: named columns in order of first use, one row
// per step, written as a whitespace-separated text file with a '#' header.

#include <map>
#include <string>
#include <vector>

namespace Membrane
{
  class Statistics
  {
  public:
    /// Set a value in the current row (creates the column on first use).
    void set(const std::string &column, double value);
    /// Close the current row.
    void end_row();

    std::size_t n_rows() const { return rows.size(); }
    const std::vector<std::string> &column_names() const { return columns; }
    /// The rows in order; a row shorter than column_names() lacks the later columns.
    const std::vector<std::vector<double>> &row_values() const { return rows; }
    double      last(const std::string &column) const;
    std::string to_text() const;
    /// The inverse of to_text() (for resuming a run from a checkpoint).
    static Statistics from_text(const std::string &text);
    /// Written on rank 0 only, atomically.
    void write(const std::string &path) const;

  private:
    std::vector<std::string>            columns;
    std::map<std::string, std::size_t>  index;
    std::vector<std::vector<double>>    rows;
    std::vector<double>                 current;
  };
} // namespace Membrane
