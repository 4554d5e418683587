#pragma once
// A small JSON object writer for the run's records (run_info.json, summary.json):
// whatever a string holds (quotes, backslashes, control characters, bytes that are
// not UTF-8), the result is valid JSON (RFC 8259).
//
//   JsonObject info;
//   info.add("code_version", code_version());
//   info.add("command", command_line);      // escaped
//   info.add("mpi_ranks", n_ranks);          // integer
//   info.add("energy", 1.2345678901234567); // 17 significant digits: reads back to the same double
//   info.add("failed", false);
//   write_file_atomically(dir + "/run_info.json", info.str());
//
// Numbers that JSON cannot hold (NaN, +-inf) are written as null. Adding a key that is
// already there replaces its value in place (JSON objects must not repeat keys).
// Nested objects and arrays are not supported (add the JSON text of the value with
// add_raw when needed; it is not checked).

#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Membrane
{
  /// `text` as the inside of a JSON string (without the surrounding quotes): `"` and
  /// `\` are escaped, control characters (< 0x20, and 0x7f) become \n, \t, ... or \u00XX,
  /// and bytes that do not form valid UTF-8 become U+FFFD (the replacement character).
  std::string json_escape(const std::string &text);

  /// `text` as a JSON string literal, quotes included.
  std::string json_string(const std::string &text);

  /// A double as a JSON number with 17 significant digits ("null" if not finite).
  std::string json_number(double value);

  class JsonObject
  {
  public:
    JsonObject &add(const std::string &key, const std::string &value);
    JsonObject &add(const std::string &key, const char *value);
    JsonObject &add(const std::string &key, double value);
    JsonObject &add(const std::string &key, bool value);
    /// Every integer type (int, unsigned int, long, std::size_t, ...), written exactly.
    template <typename Integer,
              typename = std::enable_if_t<std::is_integral_v<Integer> && !std::is_same_v<Integer, bool>>>
    JsonObject &add(const std::string &key, const Integer value)
    {
      if constexpr (std::is_signed_v<Integer>)
        return add_raw(key, std::to_string(static_cast<long long>(value)));
      else
        return add_raw(key, std::to_string(static_cast<unsigned long long>(value)));
    }
    /// A value that is JSON text already (not checked).
    JsonObject &add_raw(const std::string &key, const std::string &json_value);

    bool        empty() const { return members.empty(); }
    std::size_t size() const { return members.size(); }

    /// The object, one member per line with two spaces of indent, and a final newline:
    /// {
    ///   "key": value,
    ///   ...
    /// }
    std::string str() const;

  private:
    std::vector<std::pair<std::string, std::string>> members; ///< escaped key, JSON text of the value
  };
} // namespace Membrane
