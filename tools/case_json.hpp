#pragma once
// The case and result JSON (docs/design.md section 5), shared by the CLI, the tests and
// the fuzz target.
#include <string>

#include <nlohmann/json.hpp>

#include "achd/achd.hpp"

namespace achd::cli {

// Parses a case for `model`. Throws achd::Error naming `source`, the field and the index
// on invalid JSON, a wrong type or length, a non-finite number or an unknown field.
Case parse_case(const std::string& text, const Model& model, const std::string& source);
Case case_from_json(const nlohmann::json& j, const Model& model, const std::string& source);

// The result of the last solve of `c` as JSON text, numbers with 17 significant digits;
// "prescribed_torques" (null where a joint is not prescribed) only when c prescribes a joint.
std::string result_json(const Model& model, const Data& data, const Case& c);

// Reads a whole file; throws achd::Error("PATH: cannot open file").
std::string read_file(const std::string& path);

}  // namespace achd::cli
