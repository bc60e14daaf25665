#pragma once
// Parsing the CLI's JSON inputs (cases, scenes) strictly: nlohmann::json keeps the last of
// two equal keys in an object, so {"q": [...], "q": [...]} would silently drop the first;
// here a repeated key is an error naming it (and the object it is in).
#include <string>

#include <nlohmann/json.hpp>

namespace achd::cli {

// The JSON value of `text`. Throws achd::Error "invalid JSON: ..." on a syntax error or a
// number out of range (1e999), "duplicate key 'q'" / "duplicate key 'x' in 'directions'"
// on a repeated key (names escaped by printable()).
nlohmann::json parse_json_text(const std::string& text);

}  // namespace achd::cli
