#include <membrane/io/json.h>

#include <cmath>
#include <cstdio>

namespace Membrane
{
  namespace
  {
    /// Length of the valid UTF-8 sequence starting at text[i] (0: not valid), by RFC 3629:
    /// no overlong forms, no surrogates, nothing above U+10FFFF.
    std::size_t utf8_sequence_length(const std::string &text, const std::size_t i)
    {
      const auto byte = [&](const std::size_t k) { return static_cast<unsigned char>(text[k]); };
      const unsigned char c = byte(i);
      std::size_t         n;
      unsigned char       lo = 0x80, hi = 0xbf; // range of the second byte
      if (c >= 0xc2 && c <= 0xdf)
        n = 2;
      else if (c >= 0xe0 && c <= 0xef)
        {
          n = 3;
          if (c == 0xe0)
            lo = 0xa0; // no overlong forms
          else if (c == 0xed)
            hi = 0x9f; // no surrogates
        }
      else if (c >= 0xf0 && c <= 0xf4)
        {
          n = 4;
          if (c == 0xf0)
            lo = 0x90;
          else if (c == 0xf4)
            hi = 0x8f; // <= U+10FFFF
        }
      else
        return 0;
      if (i + n > text.size())
        return 0;
      if (byte(i + 1) < lo || byte(i + 1) > hi)
        return 0;
      for (std::size_t k = 2; k < n; ++k)
        if (byte(i + k) < 0x80 || byte(i + k) > 0xbf)
          return 0;
      return n;
    }
  } // namespace

  std::string json_escape(const std::string &text)
  {
    std::string out;
    out.reserve(text.size() + 8);
    for (std::size_t i = 0; i < text.size();)
      {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c < 0x80)
          {
            switch (c)
              {
                case '"': out += "\\\""; break;
                case '\\': out += "\\\\"; break;
                case '\b': out += "\\b"; break;
                case '\f': out += "\\f"; break;
                case '\n': out += "\\n"; break;
                case '\r': out += "\\r"; break;
                case '\t': out += "\\t"; break;
                default:
                  if (c < 0x20 || c == 0x7f)
                    {
                      char buffer[8];
                      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned int>(c));
                      out += buffer;
                    }
                  else
                    out += static_cast<char>(c);
              }
            ++i;
          }
        else if (const std::size_t n = utf8_sequence_length(text, i); n > 0)
          {
            out.append(text, i, n);
            i += n;
          }
        else
          {
            out += "\\ufffd";
            ++i;
          }
      }
    return out;
  }

  std::string json_string(const std::string &text)
  {
    return '"' + json_escape(text) + '"';
  }

  std::string json_number(const double value)
  {
    if (!std::isfinite(value))
      return "null";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return buffer;
  }

  JsonObject &JsonObject::add_raw(const std::string &key, const std::string &json_value)
  {
    const std::string escaped = json_escape(key);
    for (auto &[k, v] : members)
      if (k == escaped)
        {
          v = json_value;
          return *this;
        }
    members.emplace_back(escaped, json_value);
    return *this;
  }

  JsonObject &JsonObject::add(const std::string &key, const std::string &value)
  {
    return add_raw(key, json_string(value));
  }

  JsonObject &JsonObject::add(const std::string &key, const char *value)
  {
    return add_raw(key, value ? json_string(value) : std::string("null"));
  }

  JsonObject &JsonObject::add(const std::string &key, const double value)
  {
    return add_raw(key, json_number(value));
  }

  JsonObject &JsonObject::add(const std::string &key, const bool value)
  {
    return add_raw(key, value ? "true" : "false");
  }

  std::string JsonObject::str() const
  {
    if (members.empty())
      return "{}\n";
    std::string out = "{\n";
    for (std::size_t i = 0; i < members.size(); ++i)
      out += "  \"" + members[i].first + "\": " + members[i].second + (i + 1 < members.size() ? ",\n" : "\n");
    return out + "}\n";
  }
} // namespace Membrane
