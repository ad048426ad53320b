#pragma once
// JSON outputs (inspect/compare/estimate/bench --json, status.json, summary.json) are built as
// nlohmann::json values (https://json.nlohmann.me) and turned into text here, in one way.
#include <nlohmann/json.hpp>
#include <string>

namespace tidalcrust {

/// A JSON value whose objects keep their keys in insertion order, so outputs read like their code.
using Json = nlohmann::ordered_json;

/// `json` as text, indented by two spaces, ending in a newline. Doubles are written with the
/// shortest text that reads back to the same bits; NaN and infinities (which JSON lacks) as null;
/// bytes that are not UTF-8 (e.g. in a file name) as U+FFFD instead of throwing.
inline std::string json_text(const Json& json) {
  return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace tidalcrust
