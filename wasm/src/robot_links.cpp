#include "robot_links.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include <Eigen/Geometry>
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "achd/error.hpp"
#include "json_out.hpp"

namespace achd::wasm {
namespace {

// urdfdom logs through console_bridge; the loader has heard it already about this text.
class Quiet : public console_bridge::OutputHandler {
 public:
  Quiet() { console_bridge::useOutputHandler(this); }
  ~Quiet() override { console_bridge::restorePreviousOutputHandler(); }
  Quiet(const Quiet&) = delete;
  Quiet& operator=(const Quiet&) = delete;
  void log(const std::string&, console_bridge::LogLevel, const char*, int) override {}
};

std::string numbers(std::initializer_list<double> xs) {
  std::string s = "[";
  for (const double x : xs) s += (s.size() > 1 ? "," : "") + number(x);
  return s + "]";
}

Eigen::Isometry3d pose(const urdf::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return T;
}

std::string placement(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d& R = T.linear();
  const Eigen::Vector3d& p = T.translation();
  return "\"position\":" + numbers({p[0], p[1], p[2]}) + ",\"rotation\":" +
         numbers({R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)});
}

const char* joint_type(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown";
  }
}

std::string geometry(const urdf::Geometry& g) {
  switch (g.type) {
    case urdf::Geometry::BOX: {
      const auto& b = static_cast<const urdf::Box&>(g);
      return "{\"type\":\"box\",\"size\":" + numbers({b.dim.x, b.dim.y, b.dim.z}) + "}";
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      return "{\"type\":\"cylinder\",\"radius\":" + number(c.radius) + ",\"length\":" + number(c.length) + "}";
    }
    case urdf::Geometry::SPHERE:
      return "{\"type\":\"sphere\",\"radius\":" + number(static_cast<const urdf::Sphere&>(g).radius) + "}";
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(g);
      return "{\"type\":\"mesh\",\"filename\":" + quoted(m.filename) + ",\"scale\":" +
             numbers({m.scale.x, m.scale.y, m.scale.z}) + "}";
    }
    default: throw Error("a geometry urdfdom does not name");
  }
}

// The colour a visual's material gives, null without one (a material named but defined
// nowhere, or a texture alone: urdfdom then keeps its cleared colour, opaque black).
std::string color(const urdf::Visual& v) {
  const urdf::MaterialSharedPtr& m = v.material;
  if (!m) return "null";
  const urdf::Color& c = m->color;
  if (!m->texture_filename.empty() && c.r == 0 && c.g == 0 && c.b == 0 && c.a == 1) return "null";
  return numbers({c.r, c.g, c.b, c.a});
}

std::string visuals(const urdf::Link& link) {
  std::string s = "[";
  for (const urdf::VisualSharedPtr& v : link.visual_array) {
    if (!v || !v->geometry) continue;
    s += (s.size() > 1 ? ",{" : "{") + placement(pose(v->origin)) + ",\"geometry\":" + geometry(*v->geometry) +
         ",\"color\":" + color(*v) + "}";
  }
  return s + "]";
}

// The motion of joint j at `value` (rad or m) after its origin.
Eigen::Isometry3d motion(const urdf::Joint& j, double value) {
  Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  if (axis.norm() == 0 || value == 0) return M;
  axis.normalize();
  if (j.type == urdf::Joint::PRISMATIC) M.translation() = value * axis;
  else if (j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS)
    M.linear() = Eigen::AngleAxisd(value, axis).toRotationMatrix();
  return M;
}

}  // namespace

std::string describe_links(const Model& model, const std::string& urdf_text) {
  urdf::ModelInterfaceSharedPtr urdf;
  {
    const Quiet quiet;
    urdf = urdf::parseURDF(urdf_text);
  }
  if (!urdf) throw Error("URDF: cannot read the links' visuals and masses");
  // urdfdom links point to their children and parent joints by shared_ptr: break the
  // cycles so that the model is freed.
  struct Release {
    const urdf::ModelInterfaceSharedPtr& model;
    ~Release() {
      for (auto& entry : model->links_) {
        entry.second->child_links.clear();
        entry.second->child_joints.clear();
      }
    }
  } release{urdf};

  std::map<std::string, int> frame = {{model.root_name, 0}};
  for (int l = 0; l < model.num_links(); ++l) frame[model.links[l].name] = l + 1;
  std::map<std::string, double> locked;
  for (const LockedJoint& j : model.locked_joints) locked[j.name] = j.value;

  const auto body_of = [&](int index) {
    if (index == 0) return model.floating ? quoted(model.root_name) : std::string("null");
    const int body = model.links[index - 1].body;
    return body < 0 ? std::string("null") : quoted(model.bodies[body].joint_name);
  };
  // (a link that is not the root has a parent joint: the loader walked down to it)
  const auto entry = [&](const urdf::Link& link, int index, bool root, const std::string& offset) {
    const urdf::JointSharedPtr j = root ? urdf::JointSharedPtr() : link.parent_joint;
    return "{\"name\":" + quoted(link.name) + ",\"frame\":" + std::to_string(index) +
           ",\"parent\":" + (j ? quoted(j->parent_link_name) : "null") +
           ",\"joint\":" + (j ? "{\"name\":" + quoted(j->name) + ",\"type\":\"" + joint_type(j->type) + "\"}" : "null") +
           ",\"body\":" + body_of(index) +
           ",\"mass\":" + number(link.inertial ? link.inertial->mass : 0.0) + ",\"offset\":" + offset +
           ",\"visuals\":" + visuals(link) + "}";
  };

  std::string s = "[";
  const auto add = [&](const std::string& item) { s += (s.size() > 1 ? "," : "") + item; };
  std::vector<std::string> names = {model.root_name};
  for (const Link& l : model.links) names.push_back(l.name);
  for (size_t k = 0; k < names.size(); ++k) {
    const urdf::LinkConstSharedPtr link = urdf->getLink(names[k]);
    if (!link) throw Error("URDF: no link '" + names[k] + "' in the text the robot was loaded from");
    try {
      add(entry(*link, static_cast<int>(k), k == 0, "null"));
    } catch (const Error& e) {
      throw Error("URDF: link '" + link->name + "': " + e.what() + " in its visuals");
    }
  }
  // The other links, by name: those whose parents lead to a link of the model ride on it.
  for (const auto& item : urdf->links_) {
    const urdf::Link& link = *item.second;
    if (frame.count(link.name)) continue;
    Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
    std::string at = link.name;
    std::set<std::string> seen;
    while (!frame.count(at)) {
      const urdf::LinkConstSharedPtr l = urdf->getLink(at);
      if (!l || !l->parent_joint || !seen.insert(at).second) break;
      const urdf::Joint& j = *l->parent_joint;
      const auto value = locked.find(j.name);
      offset = pose(j.parent_to_joint_origin_transform) * motion(j, value == locked.end() ? 0 : value->second) * offset;
      at = j.parent_link_name;
    }
    if (!frame.count(at)) continue;  // above the root, or on a branch the robot does not carry
    try {
      add(entry(link, frame.at(at), false, "{" + placement(offset) + "}"));
    } catch (const Error& e) {
      throw Error("URDF: link '" + link.name + "': " + e.what() + " in its pose or visuals");
    }
  }
  return s + "]";
}

}  // namespace achd::wasm
