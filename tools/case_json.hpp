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
// type or length, a non-finite number, an unknown field, joint or link (an empty
// `source`: the message names the field first). The wasm module parses its JS callers'
// cases here too, with their values JSON cannot hold marked (foreign_values.hpp).
Case parse_case(const std::string& text, const Model& model, const std::string& source);
Case case_from_json(const nlohmann::json& j, const Model& model, const std::string& source);

// The parts of a case, for inputs that take the case's forms outside a case (the wasm
// module's robot.forwardKinematics(q), rnea's f_ext, a solver's constraint blocks).
// Each throws achd::Error naming `field` and the index.
//
// n finite numbers ("gravity: expected 3 values, got 2", "gravity[1] is not finite").
Eigen::VectorXd numbers(const nlohmann::json& v, const std::string& field, int n);
// A per-joint vector: q (positions = true) or qd, ff_torques: an array in model order
// (num_positions() or num_rates() numbers), or an object keyed by joint name (joints not
// named: 0). A floating base's free joint, named after the root link, comes first with 7
// numbers in q ([x, y, z, qx, qy, qz, qw]) and 6 in the others; keyed by name it is an
// array of those, and when it is not named, the identity pose at the origin and rest.
Eigen::VectorXd joint_vector(const nlohmann::json& v, const std::string& field, const Model& model,
                             bool positions = false);
// "f_ext" and "f_virtual" (`field`): an array of one wrench per link after the root, or an
// object keyed by link name (links not named: no wrench); appended to `out`.
void link_wrenches(const nlohmann::json& f, const Model& model, const std::string& field, std::vector<Vector6>& out);
// "constraints": blocks {link, alpha, beta, point, w_fext, w_ff} on links named by the
// user, appended to c.constraints.
void constraint_blocks(const nlohmann::json& cs, const Model& model, Case& c);
// Why `name` is not a movable joint of the model, in the user's terms: a joint the loader
// locked (a side joint of a chain), or one that is not on the chain / not below the root.
std::string no_joint(const Model& model, const std::string& name);
// Why `name` names no link after the root (the links wrenches and constraint blocks act on).
std::string no_link(const Model& model, const std::string& name);

// How result_json writes numbers: with 17 significant digits (the CLI's output), or with
// the fewest that read back as the same double (the wasm module's results, which JS
// parses: printf's 17 digits cost more there than the solve).
enum class Digits { Seventeen, Shortest };

// The result of the last solve of `c` as JSON text, numbers as `digits` says (either
// reads back as the same doubles):
// the names ("joints" in the order of qdd, "links" in the order of link_accelerations,
// root link first), the outputs, "constraint_wrenches" (one per block of c.constraints);
// "loop_wrenches" (one per loop joint, after the blocks': alpha nu at Q, what link a exerts)
// and "nu_owners" (who owns each entry of nu) only when the model has loop joints or
// coupled joints;
// "prescribed_torques" (null where a joint is not prescribed) only when c prescribes a
// joint, "locked_joints" only when the model has any.
std::string result_json(const Model& model, const Data& data, const Case& c, Digits digits = Digits::Seventeen);

// Model::locked_joints as a JSON array [{"name", "value"}] (results and `achd info`).
std::string locked_joints_json(const Model& model, Digits digits = Digits::Seventeen);

}  // namespace achd::cli
