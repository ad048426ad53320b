#pragma once
// A small JSON writer for the --json outputs and summary files (no parsing needed).
// Doubles are written with the shortest representation that reads back to the same bits.
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tidalcrust {

class JsonWriter {
 public:
  JsonWriter& begin_object(std::string_view key = {}) { return open(key, '{'); }
  JsonWriter& end_object() { return close('}'); }
  JsonWriter& begin_array(std::string_view key = {}) { return open(key, '['); }
  JsonWriter& end_array() { return close(']'); }

  JsonWriter& value(std::string_view key, double v) { return raw(key, number(v)); }
  JsonWriter& value(std::string_view key, std::int64_t v) { return raw(key, fmt::format("{}", v)); }
  JsonWriter& value(std::string_view key, int v) { return value(key, static_cast<std::int64_t>(v)); }
  JsonWriter& value(std::string_view key, std::size_t v) { return raw(key, fmt::format("{}", v)); }
  JsonWriter& value(std::string_view key, bool v) { return raw(key, v ? "true" : "false"); }
  JsonWriter& value(std::string_view key, std::string_view v) { return raw(key, quote(v)); }
  JsonWriter& value(std::string_view key, const char* v) { return value(key, std::string_view(v)); }
  template <typename Range>
  JsonWriter& numbers(std::string_view key, const Range& values) {
    std::string text = "[";
    bool first = true;
    for (double v : values) {
      text += (first ? "" : ", ") + number(v);
      first = false;
    }
    return raw(key, text + "]");
  }
  /// Array element (inside begin_array): pass an empty key.
  JsonWriter& element(double v) { return value({}, v); }

  const std::string& str() const { return out_; }

  static std::string quote(std::string_view s) {
    std::string q = "\"";
    for (char c : s) {
      switch (c) {
        case '"': q += "\\\""; break;
        case '\\': q += "\\\\"; break;
        case '\n': q += "\\n"; break;
        case '\t': q += "\\t"; break;
        default:
          if (static_cast<unsigned char>(c) < 0x20) q += fmt::format("\\u{:04x}", static_cast<int>(c));
          else q += c;
      }
    }
    return q + "\"";
  }
  /// JSON has no NaN or infinity: they are written as null.
  static std::string number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

 private:
  JsonWriter& open(std::string_view key, char bracket) {
    prefix(key);
    out_ += bracket;
    first_.push_back(true);
    return *this;
  }
  JsonWriter& close(char bracket) {
    bool empty = first_.back();
    first_.pop_back();
    if (!empty) newline();
    out_ += bracket;
    if (first_.empty()) out_ += '\n';
    return *this;
  }
  JsonWriter& raw(std::string_view key, std::string_view text) {
    prefix(key);
    out_ += text;
    return *this;
  }
  void prefix(std::string_view key) {
    if (!first_.empty()) {
      if (!first_.back()) out_ += ',';
      first_.back() = false;
      newline();
    }
    if (!key.empty()) out_ += quote(key) + ": ";
  }
  void newline() { out_ += '\n' + std::string(2 * first_.size(), ' '); }

  std::string out_;
  std::vector<bool> first_;
};

}  // namespace tidalcrust
