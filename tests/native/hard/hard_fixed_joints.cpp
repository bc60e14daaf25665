// Fixed joints at the root, in the middle, next to each other and at the tip: the
// solver's results equal those of the same robot with the fixed bodies merged by hand
// (mass, COM and inertia combined here, independently of the loader) into their
// parents. alpha acts at the tip link's origin, so the merged robot either keeps a
// massless fixed tip frame at the same place, or has no fixed joint at all and gets
// alpha moved to the last body's origin: [f; n] at the tool = [f; n + r x f] there.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "achd/achd.hpp"
#include "hard_chain_urdf.hpp"
#include "reference_dynamics.hpp"

namespace achd::test {
namespace {

struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Pose operator*(const Pose& b) const { return {R * b.R, p + R * b.p}; }
};

// URDF rpy is R = Rz(yaw) Ry(pitch) Rx(roll).
Pose pose(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Pose t;
  t.R = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
  t.p = xyz;
  return t;
}

Eigen::Vector3d rpy_of(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d ypr = R.eulerAngles(2, 1, 0);
  return {ypr.z(), ypr.y(), ypr.x()};
}

// Mass, COM and inertia about the COM (full 3x3) in some frame.
struct Inertial {
  double m = 0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
};

Inertial inertial_of(const LinkSpec& l) {
  const Pose com = pose(l.com, l.com_rpy);
  Eigen::Matrix3d I;
  I << l.inertia_diag.x(), l.ixy, l.ixz, l.ixy, l.inertia_diag.y(), l.iyz, l.ixz, l.iyz,
      l.inertia_diag.z();
  return {l.mass, com.p, com.R * I * com.R.transpose()};
}

// a + b, b given in a frame at pose X relative to a's frame: masses add, the COM is the
// mass-weighted mean, and each inertia is rotated into a's axes and shifted to the new
// COM by the parallel-axis theorem, I + m (|d|^2 1 - d d^T).
Inertial merge(const Inertial& a, const Inertial& b, const Pose& X) {
  Inertial r;
  r.m = a.m + b.m;
  const Eigen::Vector3d cb = X.p + X.R * b.c;
  r.c = (a.m * a.c + b.m * cb) / r.m;
  const auto shift = [](double m, const Eigen::Vector3d& d) {
    return Eigen::Matrix3d(m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  r.I = a.I + shift(a.m, a.c - r.c) + X.R * b.I * X.R.transpose() + shift(b.m, cb - r.c);
  return r;
}

LinkSpec with_inertial(LinkSpec l, const Inertial& in) {
  l.mass = in.m;
  l.com = in.c;
  l.com_rpy.setZero();
  l.inertia_diag = in.I.diagonal();
  l.ixy = in.I(0, 1);
  l.ixz = in.I(0, 2);
  l.iyz = in.I(1, 2);
  return l;
}

LinkSpec link(const std::string& name, const std::string& type, Eigen::Vector3d xyz,
              Eigen::Vector3d rpy, Eigen::Vector3d axis, double mass, Eigen::Vector3d com,
              Eigen::Vector3d diag, double ixy = 0) {
  LinkSpec l;
  l.name = name;
  l.joint_type = type;
  l.joint_xyz = xyz;
  l.joint_rpy = rpy;
  l.axis = axis;
  l.mass = mass;
  l.com = com;
  l.com_rpy = {0.2, -0.1, 0.3};
  l.inertia_diag = diag;
  l.ixy = ixy;
  return l;
}

// link0 -f0-> plate -j1-> l1 -f1-> l1a -j2-> l2 -f2-> l2a -f3-> l2b -j3-> l3 -f4-> tool
std::vector<LinkSpec> with_fixed() {
  using V = Eigen::Vector3d;
  return {
      link("plate", "fixed", V(0, 0, 0.1), V(0, 0, 0.4), V(0, 0, 1), 3.0, V(0, 0, 0.02), V(0.1, 0.1, 0.2)),
      link("l1", "revolute", V(0.05, 0, 0.05), V(0.1, 0, 0), V(0, 0, 1), 2.0, V(0, 0.02, 0.1), V(0.03, 0.025, 0.01), 0.002),
      link("l1a", "fixed", V(0, 0, 0.2), V(0.3, 0.2, -0.1), V(0, 0, 1), 0.7, V(0.01, 0, 0.03), V(0.004, 0.005, 0.006)),
      link("l2", "revolute", V(0, 0.05, 0.1), V(-0.2, 0, 0.5), V(0, 1, 0), 1.5, V(0.2, 0, 0), V(0.01, 0.04, 0.04)),
      link("l2a", "fixed", V(0.4, 0, 0), V(0, 0.5, 0), V(0, 0, 1), 0.4, V(0, 0.01, 0), V(0.001, 0.002, 0.002)),
      link("l2b", "fixed", V(0.05, 0.02, 0), V(0.1, 0, -0.3), V(0, 0, 1), 0.3, V(0.02, 0, 0.01), V(0.001, 0.001, 0.001)),
      link("l3", "revolute", V(0.05, 0, 0), V(0, -0.4, 0.2), V(1, 0, 0), 0.8, V(0.1, 0, 0), V(0.002, 0.006, 0.006)),
      link("tool", "fixed", V(0.2, 0.03, -0.02), V(0.5, 0.1, 0), V(0, 0, 1), 0.25, V(0.02, 0, 0), V(0.0005, 0.0004, 0.0003)),
  };
}

// The same robot with the fixed bodies merged into their parents by hand. keep_tip: a
// massless fixed `tool` frame stays at the end (tool's mass goes into l3).
std::vector<LinkSpec> merged(bool keep_tip) {
  const std::vector<LinkSpec> a = with_fixed();
  const auto P = [&](int i) { return pose(a[i].joint_xyz, a[i].joint_rpy); };
  std::vector<LinkSpec> b;
  // j1 origin: f0 * j1 (plate's mass rides on the fixed base and is not dynamics).
  LinkSpec l1 = a[1];
  const Pose o1 = P(0) * P(1);
  l1.joint_xyz = o1.p;
  l1.joint_rpy = rpy_of(o1.R);
  b.push_back(with_inertial(l1, merge(inertial_of(a[1]), inertial_of(a[2]), P(2))));
  // j2 origin: f1 * j2
  LinkSpec l2 = a[3];
  const Pose o2 = P(2) * P(3);
  l2.joint_xyz = o2.p;
  l2.joint_rpy = rpy_of(o2.R);
  const Inertial l2_all =
      merge(merge(inertial_of(a[3]), inertial_of(a[4]), P(4)), inertial_of(a[5]), P(4) * P(5));
  b.push_back(with_inertial(l2, l2_all));
  // j3 origin: f2 * f3 * j3
  LinkSpec l3 = a[6];
  const Pose o3 = P(4) * P(5) * P(6);
  l3.joint_xyz = o3.p;
  l3.joint_rpy = rpy_of(o3.R);
  b.push_back(with_inertial(l3, merge(inertial_of(a[6]), inertial_of(a[7]), P(7))));
  if (keep_tip) {
    LinkSpec tool = a[7];
    tool.has_inertial = false;
    b.push_back(tool);
  }
  return b;
}

Case the_case(const Model& m) {
  Case c = Case::zeros(m);
  c.q << 0.4, -0.7, 1.1;
  c.qd = Eigen::Vector3d(0.5, -1.2, 2.0);
  c.ff_torques = Eigen::Vector3d(1.0, -2.0, 0.5);
  c.alpha.setZero(6, 2);
  c.alpha(0, 0) = 1;                                 // tool x
  c.alpha.col(1) << 0, 0.6, 0, 0, 0, 0.8;            // tool y and rotation about z
  c.beta.resize(2);
  c.beta << 0.3, -0.4;
  return c;
}

// Same physics through different round-off paths of a well-conditioned 3-joint arm
// (cond(M), cond(K) < 1e3): 1e-12 relative.
void expect_same(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const char* what) {
  const double scale = std::max(1.0, b.cwiseAbs().maxCoeff());
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-12 * scale) << what << "\n" << a.transpose()
                                                          << "\n" << b.transpose();
}

TEST(HardFixedJoints, MergedByHandWithAMasslessToolFrameGivesTheSameResults) {
  const Model a = load_urdf_string(chain_urdf(with_fixed()), "link0", "tool");
  const Model b = load_urdf_string(chain_urdf(merged(true)), "link0", "tool");
  ASSERT_EQ(a.num_rates(), 3);
  ASSERT_EQ(a.num_links(), 8);
  ASSERT_EQ(b.num_links(), 4);
  Data da(a), db(b);
  hybrid_dynamics(a, da, the_case(a));
  hybrid_dynamics(b, db, the_case(b));
  expect_same(da.qdd, db.qdd, "qdd");
  expect_same(da.nu, db.nu, "nu");
  expect_same(da.joint_torques, db.joint_torques, "joint_torques");
  expect_same(da.constraint_torques, db.constraint_torques, "constraint_torques");
  expect_same(da.link_accelerations.back(), db.link_accelerations.back(), "tool acceleration");
  // The constraints hold at the tool in both.
  const Case c = the_case(a);
  expect_same(c.alpha.transpose() * da.link_accelerations.back(), c.beta, "alpha^T a_tool");
}

TEST(HardFixedJoints, MergedByHandWithoutAnyFixedJointAndAlphaMovedToTheLastBody) {
  const Model a = load_urdf_string(chain_urdf(with_fixed()), "link0", "tool");
  const Model b = load_urdf_string(chain_urdf(merged(false)), "link0", "l3");
  const Case ca = the_case(a);
  Case cb = the_case(b);
  // r: from l3's origin to the tool's origin, base axes, at q.
  const Transform l3 = forward_kinematics(b, cb.q).back();
  const Vector3 r = l3.R * pose(with_fixed()[7].joint_xyz, with_fixed()[7].joint_rpy).p;
  for (int k = 0; k < cb.num_constraints(); ++k)
    cb.alpha.col(k).tail<3>() += r.cross(Vector3(cb.alpha.col(k).head<3>()));
  Data da(a), db(b);
  hybrid_dynamics(a, da, ca);
  hybrid_dynamics(b, db, cb);
  expect_same(da.qdd, db.qdd, "qdd");
  expect_same(da.nu, db.nu, "nu");
  expect_same(da.joint_torques, db.joint_torques, "joint_torques");
  expect_same(da.constraint_wrench.head<3>(), db.constraint_wrench.head<3>(), "constraint force");
}

// No constraints, gravity only: a plain forward-dynamics check of the merge, and the
// identity joint_torques = RNEA(qdd) on the robot with fixed joints.
TEST(HardFixedJoints, FreeMotionAndInverseDynamicsMatchTheMergedRobot) {
  const Model a = load_urdf_string(chain_urdf(with_fixed()), "link0", "tool");
  const Model b = load_urdf_string(chain_urdf(merged(false)), "link0", "l3");
  Case ca = the_case(a), cb = the_case(b);
  for (Case* c : {&ca, &cb}) {
    c->alpha.resize(6, 0);
    c->beta.resize(0);
  }
  Data da(a), db(b);
  hybrid_dynamics(a, da, ca);
  hybrid_dynamics(b, db, cb);
  expect_same(da.qdd, db.qdd, "qdd");
  expect_same(reference_rnea(a, ca.q, ca.qd, da.qdd, ca.gravity), ca.ff_torques, "RNEA(qdd) = ff");
  expect_same(crba(a, ca.q).diagonal(), crba(b, cb.q).diagonal(), "M diagonal");
}

}  // namespace
}  // namespace achd::test
