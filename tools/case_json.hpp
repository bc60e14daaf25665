#pragma once
// The case and result JSON (docs/design.md section 5), shared by the CLI, the tests and
// the fuzz target.
#include <string>

#include <nlohmann/json.hpp>

#include "achd/achd.hpp"

namespace achd::cli {

// Parses a case for `model`. q, qd, ff_torques: an array in model order or an object
// keyed by joint name (joints not named: 0); f_ext: an array per link after the root or
// an object keyed by link name; "constraints": blocks {link (a name), alpha, beta, point}.
// Throws achd::Error naming `source`, the field and the index on invalid JSON, a wrong
// type or length, a non-finite number, an unknown field, joint or link.
Case parse_case(const std::string& text, const Model& model, const std::string& source);
Case case_from_json(const nlohmann::json& j, const Model& model, const std::string& source);

// The result of the last solve of `c` as JSON text, numbers with 17 significant digits:
// the names ("joints" in the order of qdd, "links" in the order of link_accelerations,
// root link first), the outputs, "constraint_wrenches" (one per block of c.constraints);
// "prescribed_torques" (null where a joint is not prescribed) only when c prescribes a
// joint, "locked_joints" only when the model has any.
std::string result_json(const Model& model, const Data& data, const Case& c);

// Model::locked_joints as a JSON array [{"name", "value"}] (results and `achd info`).
std::string locked_joints_json(const Model& model);

// Reads a case or scene file whole: a regular file of at most 16 MiB
// (kMaxJsonFileBytes), or stdin for "-" when `allow_stdin` (`--case -`). Throws
// achd::Error starting "PATH: " otherwise (read_text_file.hpp); `what` names the file's
// kind in the size message ("a case file").
std::string read_json_file(const std::string& path, const std::string& what, bool allow_stdin = false);

}  // namespace achd::cli
