#pragma once
// Text fields shared by the CLI's CSV writers.
#include <cmath>
#include <cstdio>
#include <string>

namespace pierce::cli {

// A CSV field, quoted (RFC 4180) only when it holds a separator, quote or line break.
inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// `s` without leading and trailing spaces, tabs and carriage returns.
inline std::string trim_text(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// A double that reads back to the same value. Every CSV of the CLI writes a missing value (NaN)
// as `nan`, which Python, NumPy, pandas and ParaView's CSV reader all read back as NaN.
inline std::string exact_number(double v) {
  if (std::isnan(v)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace pierce::cli
