#pragma once
// CSV cells (RFC 4180) for the tables the commands write (report's sweep.csv, compare
// --resolution's convergence.csv): one writer, so every table quotes and leaves out values alike.
#include <fmt/format.h>

#include <cmath>
#include <string>

namespace tidalcrust {

/// A number in its shortest round-trip form ("{}"); empty for NaN and infinities (no value).
inline std::string csv_number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : ""; }

/// A text cell, quoted (with its quotes doubled) when it holds a comma, quote or line break.
inline std::string csv_text(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + "\"";
}

}  // namespace tidalcrust
