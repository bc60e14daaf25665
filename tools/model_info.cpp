#include "model_info.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>
#include <urdf_parser/urdf_parser.h>

#include "achd/error.hpp"
#include "achd/srdf.hpp"
#include "console_capture.hpp"
#include "loops_json.hpp"

namespace achd::cli {
namespace {

using nlohmann::ordered_json;

// A joint limit, null when unbounded (the model's +-1e300 of continuous joints).
ordered_json bound(double x) { return std::abs(x) >= 1e300 ? ordered_json(nullptr) : ordered_json(x); }

ordered_json body_name(const Model& model, int body) {
  return body < 0 ? ordered_json(nullptr) : ordered_json(model.bodies[body].joint_name);
}

}  // namespace

// q by joint name (a floating base's free joint: its seven numbers under the root's name).
ordered_json pose_by_name(const Model& model, const Eigen::VectorXd& q) {
  ordered_json out = ordered_json::object();
  if (model.floating) out[model.root_name] = std::vector<double>(q.data(), q.data() + model.free_joint_positions());
  for (int i = model.free_joint_rates(); i < model.num_rates(); ++i)
    out[model.bodies[i].joint_name] = q[model.position_index(i)];
  return out;
}

std::string model_info_json(const Model& model, const std::string& urdf_text, const std::vector<SrdfPose>& poses) {
  urdf::ModelInterfaceSharedPtr urdf;
  {
    // The loader has parsed this text already; urdfdom's log stays off stderr.
    const ConsoleCapture console;
    urdf = urdf::parseURDF(urdf_text);
  }
  if (!urdf) throw Error("URDF: cannot read the link masses");
  const auto mass = [&](const std::string& link) {
    const urdf::LinkConstSharedPtr l = urdf->getLink(link);
    return l && l->inertial ? l->inertial->mass : 0.0;
  };

  ordered_json info;
  info["root"] = model.root_name;
  info["tip"] = model.has_tip() ? ordered_json(model.tip_name) : ordered_json(nullptr);
  info["floating"] = model.floating;
  info["joints"] = ordered_json::array();
  // A floating base's free joint: one joint of 7 positions and 6 rates (bodies 0 to 5).
  if (model.floating)
    info["joints"].push_back({{"name", model.root_name}, {"type", "floating"}, {"parent", nullptr},
                              {"link", model.root_name}, {"limits", nullptr}});
  for (int i = model.free_joint_rates(); i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    info["joints"].push_back({{"name", b.joint_name},
                              {"type", joint_type_name(b.type)},
                              {"parent", body_name(model, b.parent)},
                              {"link", b.link_name},
                              {"limits", {{"lower", bound(b.limits.lower)},
                                          {"upper", bound(b.limits.upper)},
                                          {"velocity", b.limits.velocity},
                                          {"effort", b.limits.effort}}}});
  }
  info["links"] = ordered_json::array();
  info["links"].push_back({{"name", model.root_name},
                           {"body", model.floating ? ordered_json(model.root_name) : ordered_json(nullptr)},
                           {"mass", mass(model.root_name)}});
  for (const Link& l : model.links)
    info["links"].push_back({{"name", l.name}, {"body", body_name(model, l.body)}, {"mass", mass(l.name)}});
  info["locked_joints"] = ordered_json::array();
  for (const LockedJoint& j : model.locked_joints) info["locked_joints"].push_back({{"name", j.name}, {"value", j.value}});
  info["warnings"] = model.warnings;
  if (!model.loops.empty()) info["loops"] = ordered_json::parse(loops_json(model));
  info["default_q"] = pose_by_name(model, default_pose(model));
  if (!poses.empty()) {
    info["poses"] = ordered_json::array();
    for (const SrdfPose& p : poses)
      info["poses"].push_back({{"name", p.name}, {"group", p.group}, {"q", pose_by_name(model, srdf_pose_q(model, p))}});
  }
  return info.dump(2) + "\n";
}

}  // namespace achd::cli
