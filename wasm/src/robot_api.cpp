// Robots: URDF loading, the description the wrapper reads once, and the copying
// computations (forward kinematics, tip Jacobian, mass matrix, RNEA). Inputs and outputs
// are wasm-memory arrays the wrapper owns; lengths are checked by the wrapper.
#include <cstdio>

#include "achd/achd.hpp"
#include "c_api.hpp"
#include "json_out.hpp"
#include "loops_json.hpp"
#include "robot_links.hpp"

namespace achd::wasm {
namespace {

// {"root", "tip" (null for a tree), "floating", "num_rates" (joint rates: qd's length),
// "num_positions" (q's), "joints": [{name, type, lower, upper, velocity, effort, damping,
// friction, rate_index, rate_count, position_index, position_count}] (a floating base's
// free joint once, type "floating", 6 rates and 7 positions from 0; every other joint one
// of each), "links": [names after the root], "link_details": describe_links(),
// "locked_joints": [{name, value}], "couplings": [{joint, leader, multiplier, offset}]
// (Model::couplings), "warnings": [the loader's, Model::warnings]}
std::string describe(const Model& m, const std::string& urdf_text) {
  std::string s = "{\"root\":" + quoted(m.root_name) + ",\"tip\":" + (m.has_tip() ? quoted(m.tip_name) : "null") +
                  ",\"floating\":" + (m.floating ? "true" : "false") +
                  ",\"num_rates\":" + std::to_string(m.num_rates()) +
                  ",\"num_positions\":" + std::to_string(m.num_positions()) + ",\"joints\":[";
  if (m.floating)
    s += "{\"name\":" + quoted(m.root_name) + ",\"type\":\"floating\",\"lower\":-1e300,\"upper\":1e300,"
         "\"velocity\":0,\"effort\":0,\"damping\":0,\"friction\":0,\"rate_index\":0,\"rate_count\":6,"
         "\"position_index\":0,\"position_count\":7}";
  for (int j = m.free_joint_rates(); j < m.num_rates(); ++j) {
    const Body& b = m.bodies[j];
    s += std::string(s.back() == '[' ? "" : ",") + "{\"name\":" + quoted(b.joint_name) + ",\"type\":" +
         quoted(joint_type_name(b.type)) + ",\"lower\":" + number(b.limits.lower) +
         ",\"upper\":" + number(b.limits.upper) + ",\"velocity\":" + number(b.limits.velocity) +
         ",\"effort\":" + number(b.limits.effort) + ",\"damping\":" + number(b.damping) +
         ",\"friction\":" + number(b.friction) + ",\"rate_index\":" + std::to_string(j) +
         ",\"rate_count\":1,\"position_index\":" + std::to_string(m.position_index(j)) + ",\"position_count\":1}";
  }
  s += "],\"links\":[";
  for (int l = 0; l < m.num_links(); ++l) s += (l ? "," : "") + quoted(m.links[l].name);
  s += "],\"link_details\":" + describe_links(m, urdf_text) + ",\"locked_joints\":[";
  for (size_t k = 0; k < m.locked_joints.size(); ++k)
    s += std::string(k ? "," : "") + "{\"name\":" + quoted(m.locked_joints[k].name) +
         ",\"value\":" + number(m.locked_joints[k].value) + "}";
  s += "],\"couplings\":[";
  for (size_t k = 0; k < m.couplings.size(); ++k) {
    const JointCoupling& c = m.couplings[k];
    s += std::string(k ? "," : "") + "{\"joint\":" + quoted(m.bodies[c.follower].joint_name) +
         ",\"leader\":" + quoted(m.bodies[c.leader].joint_name) + ",\"multiplier\":" + number(c.multiplier) +
         ",\"offset\":" + number(c.offset) + "}";
  }
  s += "],\"loops\":" + cli::loops_json(m) + ",\"warnings\":[";
  for (size_t k = 0; k < m.warnings.size(); ++k) s += (k ? "," : "") + quoted(m.warnings[k]);
  return s + "]}";
}

Eigen::Map<const Eigen::VectorXd> vec(const double* p, int n) { return {p, n}; }

}  // namespace
}  // namespace achd::wasm

using achd::wasm::Robot;

// Returns the robot, or null with the reason in achd_last_error(). root, tip: link names,
// empty = the URDF's root link / the whole tree (achd::load_urdf_string). mimic: an
// achd::MimicJoints value (0 error, 1 independent); side_branches an achd::SideBranches
// value (0 merge, 1 ignore); locked: the joints to lock (UrdfOptions::locked), their
// names one per line in locked_names and their values in locked_values; floating != 0: a
// free joint above the root link (UrdfOptions::floating); inertia an achd::InertiaPolicy
// value (0 accept, 1 strict, 2 repair); loops: "" or the JSON text of options.loops
// (tools/loops_json.hpp).
ACHD_EXPORT Robot* achd_robot_load(const char* xml, const char* root, const char* tip, int mimic,
                                   int side_branches, const char* locked_names, const double* locked_values,
                                   int floating, int inertia, const char* loops) {
  Robot* robot = nullptr;
  achd::wasm::guarded([&] {
    achd::UrdfOptions options;
    options.floating = floating != 0;
    options.inertia = static_cast<achd::InertiaPolicy>(inertia);
    options.mimic = static_cast<achd::MimicJoints>(mimic);
    options.side_branches = static_cast<achd::SideBranches>(side_branches);
    if (*loops) options.loops = achd::cli::loop_specs(achd::wasm::json_from_bridge(loops), "options.loops");
    std::string name;
    for (const char* p = locked_names; *p; ++p) {
      if (*p != '\n') {
        name += *p;
        continue;
      }
      options.locked[name] = *locked_values++;
      name.clear();
    }
    auto model = std::make_shared<const achd::Model>(achd::load_urdf_string(xml, root, tip, options));
    robot = new Robot{model, achd::wasm::describe(*model, xml), nullptr, {}};
  });
  return robot;
}

ACHD_EXPORT void achd_robot_delete(Robot* r) { delete r; }
ACHD_EXPORT const char* achd_robot_info(const Robot* r) { return r->info.c_str(); }

// q: num_positions() values. out: per link after the root, position (3) then rotation (9,
// row-major), in the base (the world, with a floating base).
ACHD_EXPORT int achd_robot_forward_kinematics(const Robot* r, const double* q, double* out) {
  return achd::wasm::guarded([&] {
    const std::vector<achd::Transform> poses =
        achd::forward_kinematics(*r->model, achd::wasm::vec(q, r->model->num_positions()));
    for (const achd::Transform& X : poses) {
      for (int k = 0; k < 3; ++k) *out++ = X.p[k];
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) *out++ = X.R(i, k);
    }
  });
}

// out: the 6 x nj tip Jacobian, row-major, linear rows first (a tree is an error: no tip).
ACHD_EXPORT int achd_robot_tip_jacobian(const Robot* r, const double* q, double* out) {
  return achd::wasm::guarded([&] {
    const Eigen::MatrixXd J = achd::tip_jacobian(*r->model, achd::wasm::vec(q, r->model->num_positions()));
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(out, J.rows(), J.cols()) = J;
  });
}

// out: M(q), nj x nj row-major, with the rotor inertia on the diagonal if rotor != 0.
ACHD_EXPORT int achd_robot_mass_matrix(const Robot* r, const double* q, int rotor, double* out) {
  return achd::wasm::guarded([&] {
    const int n = r->model->num_rates();
    const achd::Options o = achd::with_effects(rotor != 0 ? achd::kDefaultEffects : achd::kDefaultEffects & ~achd::kRotorInertia);
    const Eigen::MatrixXd M = achd::crba(*r->model, achd::wasm::vec(q, r->model->num_positions()), o);
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(out, n, n) = M;
  });
}

// out = RNEA(q, qd, qdd; gravity, f_ext) for the effects bits; f_ext null = none, else
// 6 per link after the root.
ACHD_EXPORT int achd_robot_rnea(const Robot* r, const double* q, const double* qd, const double* qdd,
                                const double* gravity, const double* f_ext, unsigned effects,
                                double friction_velocity, double* out) {
  return achd::wasm::guarded([&] {
    const achd::Model& m = *r->model;
    const int n = m.num_rates();
    std::vector<achd::Vector6> wrenches;
    if (f_ext)
      for (int l = 0; l < m.num_links(); ++l) wrenches.emplace_back(f_ext + 6 * l);
    achd::Options o = achd::with_effects(effects);
    o.friction_velocity = friction_velocity;
    const Eigen::VectorXd tau = achd::rnea(m, achd::wasm::vec(q, m.num_positions()), achd::wasm::vec(qd, n),
                                           achd::wasm::vec(qdd, n), achd::Vector3(gravity), wrenches, o);
    Eigen::Map<Eigen::VectorXd>(out, n) = tau;
  });
}

// The named poses of an SRDF text for this robot (achd::read_srdf_poses, srdf_pose_q) and
// its default pose, as JSON {"default": [q], "poses": [{"name", "group", "q": [q]}]}
// (q in model order, num_positions() numbers); null with the reason in achd_last_error().
// Valid until the next call.
ACHD_EXPORT const char* achd_robot_poses(const Robot* r, const char* srdf) {
  static std::string json;
  const char* out = nullptr;
  achd::wasm::guarded([&] {
    auto q_json = [](const Eigen::VectorXd& q) {
      std::string s = "[";
      for (Eigen::Index k = 0; k < q.size(); ++k) s += (k ? "," : "") + achd::wasm::number(q[k]);
      return s + "]";
    };
    const achd::Model& m = *r->model;
    json = "{\"default\":" + q_json(achd::default_pose(m)) + ",\"poses\":[";
    const std::vector<achd::SrdfPose> poses = achd::read_srdf_poses(srdf, "SRDF");
    for (size_t k = 0; k < poses.size(); ++k)
      json += std::string(k ? "," : "") + "{\"name\":" + achd::wasm::quoted(poses[k].name) +
              ",\"group\":" + achd::wasm::quoted(poses[k].group) + ",\"q\":" + q_json(achd::srdf_pose_q(m, poses[k])) + "}";
    json += "]}";
    out = json.c_str();
  });
  return out;
}
