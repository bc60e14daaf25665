// URDF -> Model through urdfdom: walk from the tip up to the root, then build the
// chain root -> tip, merging links behind fixed joints into the body before them.
#include "achd/urdf.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "achd/error.hpp"
#include "console_capture.hpp"
#include "sin_cos.hpp"
#include "xml_depth.hpp"

namespace achd {
namespace {

urdf::ModelInterfaceSharedPtr parse(const std::string& xml, std::string& why) {
  static std::mutex mutex;  // console_bridge's handler is process-global
  std::lock_guard<std::mutex> lock(mutex);
  urdf::ModelInterfaceSharedPtr model;
  ConsoleCapture console;
  try {
    model = urdf::parseURDF(xml);
    why = console.first_error();
  } catch (const std::exception& e) {
    why = e.what();
    model.reset();
  }
  return model;
}

bool finite3(double x, double y, double z) {
  return std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
}

// The rpy attributes of the joints' origins and of the links' inertial origins, read as
// urdfdom reads them. urdfdom turns rpy into a quaternion with the C library's sin and
// cos, whose last bits differ between glibc (native) and musl (wasm): the two builds would
// load a URDF into models an ulp apart, which a long chain amplifies past 1e-12. With the
// angles themselves, the loader builds every rotation with achd's sin_cos instead.
struct OriginAngles {
  std::map<std::string, urdf::Vector3> joint, inertial;  // by joint / link name
};

OriginAngles read_origin_angles(const std::string& xml) {
  OriginAngles angles;
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (!robot) return angles;  // urdfdom has accepted the text: it had one
  auto rpy_of = [](const TiXmlElement* origin, urdf::Vector3& out) {
    const char* rpy = origin ? origin->Attribute("rpy") : nullptr;
    if (rpy) out.init(rpy);
    return rpy != nullptr;
  };
  for (auto* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    urdf::Vector3 rpy;
    if (j->Attribute("name") && rpy_of(j->FirstChildElement("origin"), rpy)) angles.joint[j->Attribute("name")] = rpy;
  }
  for (auto* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
    const TiXmlElement* inertial = l->FirstChildElement("inertial");
    urdf::Vector3 rpy;
    if (l->Attribute("name") && inertial && rpy_of(inertial->FirstChildElement("origin"), rpy))
      angles.inertial[l->Attribute("name")] = rpy;
  }
  return angles;
}

// R = Rz(yaw) Ry(pitch) Rx(roll): URDF's fixed-axis roll, pitch, yaw.
Matrix3 rotation_from_rpy(const urdf::Vector3& rpy) {
  double sr, cr, sp, cp, sy, cy;
  sin_cos(rpy.x, sr, cr);
  sin_cos(rpy.y, sp, cp);
  sin_cos(rpy.z, sy, cy);
  Matrix3 R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,   //
      -sp, cp * sr, cp * cr;
  return R;
}

// The pose of an origin; `rpy`, when the element had one, gives its rotation.
Transform to_transform(const urdf::Pose& pose, const urdf::Vector3* rpy, const std::string& where) {
  const urdf::Vector3& p = pose.position;
  const urdf::Rotation& r = pose.rotation;
  if (!finite3(p.x, p.y, p.z) || !finite3(r.x, r.y, r.z) || !std::isfinite(r.w) ||
      (rpy && !finite3(rpy->x, rpy->y, rpy->z)))
    throw Error(where + ": origin is not finite");
  Transform t;
  t.R = rpy ? rotation_from_rpy(*rpy)
            : Matrix3(Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix());
  t.p = Vector3(p.x, p.y, p.z);
  return t;
}

template <class Map>
const urdf::Vector3* find_angles(const Map& map, const std::string& name) {
  const auto it = map.find(name);
  return it == map.end() ? nullptr : &it->second;
}

// Spatial inertia of a URDF link about the link frame origin. Checks mass >= 0, the
// rotational inertia at the COM positive semi-definite and the triangle inequality
// (each principal moment <= the sum of the other two) to 1e-9 relative.
Matrix6 link_inertia(const urdf::Link& link, const urdf::Vector3* rpy) {
  if (!link.inertial) return Matrix6::Zero();  // massless link: valid
  const urdf::Inertial& in = *link.inertial;
  const std::string where = "link '" + link.name + "'";
  // The messages name the field and its value as urdfdom's own do (urdfdom refuses
  // "nan" and "inf" itself, natively and in wasm, see wasm/urdfdom_shim; these checks
  // keep non-finite numbers out whatever its parser lets through).
  if (!std::isfinite(in.mass))
    throw Error(where + ": mass [" + std::to_string(in.mass) + "] is not finite");
  if (in.mass < 0) throw Error(where + ": negative mass " + std::to_string(in.mass));
  const double v[6] = {in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz};
  const char* names[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  for (int k = 0; k < 6; ++k)
    if (!std::isfinite(v[k]))
      throw Error(where + ": inertia " + names[k] + " [" + std::to_string(v[k]) + "] is not finite");
  Matrix3 Ic;
  Ic << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  const Eigen::SelfAdjointEigenSolver<Matrix3> eig(Ic, Eigen::EigenvaluesOnly);
  const Vector3 m = eig.eigenvalues();
  const double tol = 1e-9 * std::max(m.cwiseAbs().maxCoeff(), 1e-300);
  if (m.minCoeff() < -tol) throw Error(where + ": inertia is not positive semi-definite");
  if (m[0] + m[1] < m[2] - tol)
    throw Error(where + ": inertia violates the triangle inequality (principal moments " +
                std::to_string(m[0]) + ", " + std::to_string(m[1]) + ", " + std::to_string(m[2]) +
                ")");
  const Transform com = to_transform(in.origin, rpy, where + " <inertial>");
  const Matrix6 I = spatial_inertia(in.mass, com.p, com.R * Ic * com.R.transpose());
  if (!I.allFinite())
    throw Error(where + ": <inertial> overflows: its inertia about the link frame is not finite");
  return I;
}

// A rotation whose z column is the unit vector a: the smallest turn taking e_z to a,
//   R = 1 + [v]x + [v]x^2 / (1 + c),  v = e_z x a,  c = e_z . a   (Rodrigues),
// used for a_z >= 0; for a_z < 0, the turn to -a after a half turn about x, which keeps
// 1 + c away from 0. Axes along +-x, +-y, +-z give exact 0/1 entries.
Matrix3 frame_with_z_along(const Vector3& a) {
  const Vector3 b = a.z() >= 0 ? a : Vector3(-a);
  const Vector3 v(-b.y(), b.x(), 0);
  const Matrix3 vx = skew(v);
  Matrix3 R = Matrix3::Identity() + vx + vx * vx / (1 + b.z());
  if (a.z() < 0) R.rightCols<2>() = -R.rightCols<2>();  // R diag(1, -1, -1)
  return R;
}

// The unit vector along a joint axis. The axis is first scaled by the power of two that
// brings its largest component into [1, 2): exact, so the result is bit for bit
// a / |a| wherever |a|^2 neither overflows nor underflows, and an axis of 1e200 is the
// same axis as one of 1 (|a|^2 = inf made it 0, and the frame then fell back to z).
// Axes shorter than 1e-12 are refused as zero.
Vector3 unit_axis(const Vector3& a, const std::string& where) {
  const double largest = a.cwiseAbs().maxCoeff();
  if (largest == 0) throw Error(where + ": axis is zero");
  const int e = std::ilogb(largest);
  const Vector3 scaled(std::ldexp(a.x(), -e), std::ldexp(a.y(), -e), std::ldexp(a.z(), -e));
  if (std::ldexp(scaled.norm(), e) < 1e-12) throw Error(where + ": axis is zero");
  return scaled.normalized();
}

// The body of movable joint j, its frame the joint frame with z along the axis: X_tree
// is the URDF joint origin (from the previous body's frame) turned by R_axis =
// frame_with_z_along(axis), which is returned as well.
Body make_body(const urdf::Joint& j, const Transform& X_tree, int index, Matrix3& R_axis) {
  const std::string where = "joint '" + j.name + "'";
  Body b;
  b.joint_name = j.name;
  b.link_name = j.child_link_name;
  b.parent = index - 1;
  b.X_tree = X_tree;
  switch (j.type) {
    case urdf::Joint::REVOLUTE: b.type = JointType::Revolute; break;
    case urdf::Joint::CONTINUOUS: b.type = JointType::Continuous; break;
    case urdf::Joint::PRISMATIC: b.type = JointType::Prismatic; break;
    default:
      throw Error(where + ": unsupported joint type '" +
                  (j.type == urdf::Joint::FLOATING ? "floating"
                   : j.type == urdf::Joint::PLANAR ? "planar"
                                                    : "unknown") +
                  "' (achd supports revolute, continuous, prismatic and fixed)");
  }
  const urdf::Vector3& a = j.axis;
  if (!finite3(a.x, a.y, a.z)) throw Error(where + ": axis is not finite");
  R_axis = frame_with_z_along(unit_axis(Vector3(a.x, a.y, a.z), where));
  b.X_tree.R = X_tree.R * R_axis;
  if (j.limits && b.type != JointType::Continuous) {
    const urdf::JointLimits& l = *j.limits;
    if (!std::isfinite(l.lower) || !std::isfinite(l.upper) || !std::isfinite(l.velocity) ||
        !std::isfinite(l.effort))
      throw Error(where + ": <limit> is not finite");
    if (l.lower > l.upper) throw Error(where + ": <limit> lower > upper");
    b.limits = {l.lower, l.upper, l.velocity, l.effort};
  } else if (j.limits) {
    b.limits.velocity = j.limits->velocity;
    b.limits.effort = j.limits->effort;
  }
  if (j.dynamics) {
    b.damping = j.dynamics->damping;
    b.friction = j.dynamics->friction;
    if (!std::isfinite(b.damping) || b.damping < 0)
      throw Error(where + ": <dynamics damping> must be finite and >= 0");
    if (!std::isfinite(b.friction) || b.friction < 0)
      throw Error(where + ": <dynamics friction> must be finite and >= 0");
  }
  return b;
}

Model build(const urdf::ModelInterface& urdf_model, const OriginAngles& angles,
            const std::string& root, const std::string& tip, const UrdfOptions& options,
            const std::string& source) {
  const auto root_link = urdf_model.getLink(root);
  if (!root_link) throw Error(source + ": unknown root link '" + root + "'");
  const auto tip_link = urdf_model.getLink(tip);
  if (!tip_link) throw Error(source + ": unknown tip link '" + tip + "'");
  if (root == tip) throw Error(source + ": root and tip are the same link '" + root + "'");

  // Joints from the tip up to the root.
  std::vector<urdf::JointConstSharedPtr> joints;
  std::set<std::string> seen = {tip};
  for (auto link = tip_link; link->name != root;) {
    if (!link->parent_joint)
      throw Error(source + ": tip link '" + tip + "' is not below root link '" + root + "'");
    joints.push_back(link->parent_joint);
    link = urdf_model.getLink(link->parent_joint->parent_link_name);
    if (!link)
      throw Error(source + ": tip link '" + tip + "' is not below root link '" + root + "'");
    if (!seen.insert(link->name).second)
      throw Error(source + ": the links form a cycle through link '" + link->name + "'");
  }

  Model model;
  model.root_name = root;
  model.tip_name = tip;
  Transform offset;  // current link's frame relative to the current body (or the root)
  int body = -1;
  for (auto it = joints.rbegin(); it != joints.rend(); ++it) {
    const urdf::Joint& j = **it;
    const std::string where = "joint '" + j.name + "'";
    if (j.mimic && j.type != urdf::Joint::FIXED && options.mimic == MimicJoints::Error)
      throw Error(where + ": <mimic> of joint '" + j.mimic->joint_name +
                  "': achd has no coupled joints; load with the mimic option 'independent' "
                  "(CLI --mimic independent) to make it a joint of its own, as KDL does");
    const Transform X = offset * to_transform(j.parent_to_joint_origin_transform,
                                              find_angles(angles.joint, j.name), where);
    // Behind fixed joints, origins add up: their sum can overflow although each is finite.
    if (!X.p.allFinite())
      throw Error(where + ": origin overflows: its position from " +
                  (body >= 0 ? "joint '" + model.bodies[body].joint_name + "'" : "the root link '" + root + "'") +
                  " is not finite");
    const auto child = urdf_model.getLink(j.child_link_name);
    const Matrix6 inertia = link_inertia(*child, find_angles(angles.inertial, child->name));
    if (j.type == urdf::Joint::FIXED) {
      offset = X;  // the child rides on the current body
      if (body >= 0 && !inertia.isZero(0)) {  // a massless link adds nothing, wherever it is
        model.bodies[body].inertia += inertia_to_parent(offset, inertia);
        if (!model.bodies[body].inertia.allFinite())
          throw Error(where + ": origin overflows: link '" + child->name + "' moved by it to joint '" +
                      model.bodies[body].joint_name + "' has an inertia that is not finite");
      }
    } else {
      Matrix3 R_axis;
      model.bodies.push_back(make_body(j, X, static_cast<int>(model.bodies.size()), R_axis));
      body = model.num_joints() - 1;
      // The child link's frame in the body (joint) frame is R_axis^T, constant as the
      // joint turns about or slides along z.
      offset = Transform{R_axis.transpose(), Vector3::Zero()};
      model.bodies[body].inertia = inertia_to_parent(offset, inertia);
    }
    model.links.push_back({child->name, body, offset});
  }
  validate(model);
  return model;
}

// Every message starts with the source (file path or "URDF").
Model load(const std::string& text, const std::string& root, const std::string& tip,
           const UrdfOptions& options, const std::string& source) {
  const std::size_t too_deep = xml_too_deep_at(text, kMaxUrdfNesting);
  if (too_deep != std::string::npos)
    throw Error(source + ": cannot parse URDF: elements nested more than " + std::to_string(kMaxUrdfNesting) +
                " deep (line " + std::to_string(1 + std::count(text.begin(), text.begin() + too_deep, '\n')) +
                "), which achd refuses: its XML parser recurses once per level");
  // TinyXML steps over a UTF-8 sequence's length from its lead byte without looking for
  // the end of the text: three more NULs keep a lead byte at the end from reading past it.
  const std::string xml = text + std::string(3, '\0');
  std::string why;
  const auto parsed = parse(xml, why);
  // urdfdom links point to their children and parent joints by shared_ptr: a cycle in
  // the URDF (which it accepts when another link is the root, or when a joint is its
  // child's parent) would never be freed.
  struct BreakCycles {
    const urdf::ModelInterfaceSharedPtr& model;
    ~BreakCycles() {
      if (!model) return;
      for (auto& entry : model->links_) {
        entry.second->child_links.clear();
        entry.second->child_joints.clear();
        entry.second->parent_joint.reset();
      }
    }
  } break_cycles{parsed};
  // urdfdom logs some errors and still returns a model (a mass "inf" becomes an
  // inertial of mass 0): every logged error is fatal.
  if (!parsed || !why.empty())
    throw Error(source + ": cannot parse URDF" + (why.empty() ? std::string() : ": " + why));
  try {
    return build(*parsed, read_origin_angles(xml), root, tip, options, source);
  } catch (const Error& e) {
    const std::string msg = e.what();
    throw Error(msg.rfind(source + ":", 0) == 0 ? msg : source + ": " + msg);
  }
}

}  // namespace

const char* mimic_joints_name(MimicJoints mimic) {
  return mimic == MimicJoints::Independent ? "independent" : "error";
}

MimicJoints mimic_joints_from_name(const std::string& name, const std::string& field) {
  for (MimicJoints m : {MimicJoints::Error, MimicJoints::Independent})
    if (name == mimic_joints_name(m)) return m;
  throw Error(field + ": expected 'error' or 'independent', got '" + name + "'");
}

Model load_urdf_string(const std::string& xml, const std::string& root, const std::string& tip,
                       const UrdfOptions& options) {
  return load(xml, root, tip, options, "URDF");
}

Model load_urdf_file(const std::string& path, const std::string& root, const std::string& tip,
                     const UrdfOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return load(text.str(), root, tip, options, path);
}

}  // namespace achd
