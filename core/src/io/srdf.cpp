#include "achd/srdf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <tinyxml.h>

#include "achd/error.hpp"
#include "achd/urdf.hpp"
#include "xml_depth.hpp"

namespace achd {
namespace {

// "0. 0. 0.528 0 0 0 1" -> numbers; an achd::Error naming `where` on anything else.
std::vector<double> numbers(const char* text, const std::string& where) {
  std::vector<double> out;
  if (!text) throw Error(where + ": no value");
  const char* p = text;
  for (;;) {
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
    if (!*p) break;
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    if (end == p || !std::isfinite(x)) throw Error(where + ": value '" + text + "' is not a list of finite numbers");
    out.push_back(x);
    p = end;
  }
  if (out.empty()) throw Error(where + ": empty value");
  return out;
}

}  // namespace

std::vector<SrdfPose> read_srdf_poses(const std::string& xml, const std::string& source) {
  // (TinyXML recurses once per level: the URDF loader's depth limit applies here too)
  if (xml_too_deep_at(xml, kMaxUrdfNesting) != std::string::npos)
    throw Error(source + ": cannot parse SRDF: elements nested more than " + std::to_string(kMaxUrdfNesting) + " deep");
  // (three more NULs: TinyXML steps over a UTF-8 lead byte's length without looking for
  // the end of the text, as the URDF loader notes)
  const std::string padded = xml + std::string(3, '\0');
  TiXmlDocument doc;
  doc.Parse(padded.c_str());
  if (doc.Error()) throw Error(source + ": cannot parse SRDF: " + doc.ErrorDesc());
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (!robot) throw Error(source + ": cannot parse SRDF: no <robot> element");
  std::vector<SrdfPose> poses;
  for (auto* s = robot->FirstChildElement("group_state"); s; s = s->NextSiblingElement("group_state")) {
    SrdfPose pose;
    if (!s->Attribute("name")) throw Error(source + ": a <group_state> has no name");
    pose.name = s->Attribute("name");
    if (s->Attribute("group")) pose.group = s->Attribute("group");
    for (const SrdfPose& other : poses)
      if (other.name == pose.name) throw Error(source + ": group_state '" + pose.name + "' is defined twice");
    for (auto* j = s->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
      const std::string where = source + ": group_state '" + pose.name + "'";
      if (!j->Attribute("name")) throw Error(where + ": a <joint> has no name");
      const std::string name = j->Attribute("name");
      pose.joints.emplace_back(name, numbers(j->Attribute("value"), where + ", joint '" + name + "'"));
    }
    poses.push_back(std::move(pose));
  }
  return poses;
}

double default_joint_value(double lower, double upper) {
  return 0 < lower || 0 > upper ? 0.5 * (lower + upper) : 0.0;
}

Eigen::VectorXd default_pose(const Model& model) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.num_positions());
  if (model.floating) q[6] = 1;  // qw: the identity orientation
  for (int i = model.free_joint_rates(); i < model.num_rates(); ++i) {
    const JointLimits& l = model.bodies[i].limits;
    q[model.position_index(i)] = default_joint_value(l.lower, l.upper);
  }
  return q;
}

Eigen::VectorXd srdf_pose_q(const Model& model, const SrdfPose& pose) {
  Eigen::VectorXd q = default_pose(model);
  for (const auto& [name, values] : pose.joints) {
    const std::string where = "group_state '" + pose.name + "', joint '" + name + "'";
    if (model.floating && (name == "root_joint" || name == model.root_name)) {
      if (values.size() != 7)
        throw Error(where + ": a floating base takes 7 numbers (x y z qx qy qz qw), got " +
                    std::to_string(values.size()));
      // normalised after dividing by its largest component, so that neither 1e-200 nor
      // 1e200 under- or overflows
      double largest = 0;
      for (int k = 3; k < 7; ++k) largest = std::max(largest, std::abs(values[k]));
      if (!(largest > 0)) throw Error(where + ": the quaternion (qx qy qz qw) is zero");
      Eigen::Vector4d quaternion(values[3] / largest, values[4] / largest, values[5] / largest, values[6] / largest);
      quaternion.normalize();
      for (int k = 0; k < 3; ++k) q[k] = values[k];
      for (int k = 0; k < 4; ++k) q[3 + k] = quaternion[k];
      continue;
    }
    const int i = model.joint_index(name);
    if (i < model.free_joint_rates()) continue;  // not a movable joint of this model
    if (values.size() != 1)
      throw Error(where + ": expected one number, got " + std::to_string(values.size()));
    q[model.position_index(i)] = values[0];
  }
  return q;
}

const SrdfPose& find_srdf_pose(const std::vector<SrdfPose>& poses, const std::string& name,
                               const std::string& source) {
  std::string names;
  for (const SrdfPose& p : poses) {
    if (p.name == name) return p;
    names += (names.empty() ? "'" : ", '") + p.name + "'";
  }
  throw Error(source + ": no group_state '" + name + "' (" + (names.empty() ? "it has none" : "it has " + names) + ")");
}

}  // namespace achd
