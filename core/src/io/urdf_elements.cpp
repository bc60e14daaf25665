#include "urdf_elements.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <tinyxml.h>

#include "achd/error.hpp"
#include "link_inertia.hpp"
#include "sin_cos.hpp"

namespace achd {
namespace {

bool finite3(double x, double y, double z) {
  return std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
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

}  // namespace

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
    if (j->Attribute("name")) angles.joint_position.emplace(j->Attribute("name"), static_cast<int>(angles.joint_position.size()));
    if (j->Attribute("name") && rpy_of(j->FirstChildElement("origin"), rpy)) angles.joint[j->Attribute("name")] = rpy;
  }
  for (auto* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
    const TiXmlElement* inertial = l->FirstChildElement("inertial");
    urdf::Vector3 rpy;
    if (l->Attribute("name") && inertial && rpy_of(inertial->FirstChildElement("origin"), rpy))
      angles.inertial[l->Attribute("name")] = rpy;
    const TiXmlElement* moments = inertial ? inertial->FirstChildElement("inertia") : nullptr;
    if (l->Attribute("name") && moments) {
      std::array<double, 6>& r = angles.inertia_roundoff[l->Attribute("name")];
      const char* names[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
      for (int k = 0; k < 6; ++k) r[k] = written_roundoff(moments->Attribute(names[k]));
    }
  }
  return angles;
}

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

Matrix6 link_inertia(const urdf::Link& link, const urdf::Vector3* rpy, const double* roundoff,
                     InertiaPolicy policy, std::vector<std::string>& warnings) {
  if (!link.inertial) return Matrix6::Zero();  // massless link: valid
  const urdf::Inertial& in = *link.inertial;
  WrittenInertia written;
  written.mass = in.mass;
  const double v[6] = {in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz};
  for (int k = 0; k < 6; ++k) {
    written.moments[k] = v[k];
    written.roundoff[k] = roundoff ? roundoff[k] : 0;
  }
  const Matrix3 Ic = checked_rotational_inertia(link.name, written, policy, warnings);
  const std::string where = "link '" + link.name + "'";
  const Transform com = to_transform(in.origin, rpy, where + " <inertial>");
  const Matrix6 I = spatial_inertia(in.mass, com.p, com.R * Ic * com.R.transpose());
  if (!I.allFinite())
    throw Error(where + ": <inertial> overflows: its inertia about the link frame is not finite");
  return I;
}

Body make_body(const urdf::Joint& j, const Transform& X_tree, int parent, Matrix3& R_axis) {
  const std::string where = "joint '" + j.name + "'";
  Body b;
  b.joint_name = j.name;
  b.link_name = j.child_link_name;
  b.parent = parent;
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

}  // namespace achd
