#include "random_tree.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "random_chain.hpp"
#include "reference_dynamics.hpp"
#include "reference_kinematics.hpp"

namespace achd::test {
namespace {

int uniform_int(std::mt19937& rng, int lo, int hi) {
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}

// A random link: origin within 0.4 of its parent's, any orientation; mass in [0.2, 4] (one
// link in ten massless unless `massive`), COM within 0.3; damping and friction on one
// joint in three.
TreeLink random_link(std::mt19937& rng, int k, int parent, const std::string& type, bool massive) {
  TreeLink l;
  l.name = "l" + std::to_string(k);
  l.joint = "j" + std::to_string(k);
  l.parent = parent;
  l.type = type;
  l.origin.R = random_rotation(rng);
  l.origin.p = uniform3(rng, -0.4, 0.4);
  l.axis = uniform3(rng, -1, 1).normalized();
  if (massive || uniform(rng, 0, 1) > 0.1) {
    l.mass = uniform(rng, 0.2, 4);
    l.com = uniform3(rng, -0.3, 0.3);
    l.inertia = random_inertia(rng, l.mass);
  }
  if (type != "fixed" && uniform(rng, 0, 1) < 1.0 / 3) {
    l.damping = uniform(rng, 0, 2);
    l.friction = uniform(rng, 0, 1);
  }
  return l;
}

// The body frame of a movable link: the link frame turned so that its z is the joint
// axis (link coordinates), origin on the joint.
Transform joint_frame_in_link(const Vector3& axis) {
  Transform X;
  X.R = Eigen::Quaterniond::FromTwoVectors(Vector3::UnitZ(), axis).toRotationMatrix();
  return X;
}

Transform inverse(const Transform& X) { return {X.R.transpose(), -(X.R.transpose() * X.p)}; }

// Rotation as URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
Vector3 rpy_of(const Matrix3& R) {
  const Vector3 ypr = R.eulerAngles(2, 1, 0);
  return Vector3(ypr[2], ypr[1], ypr[0]);
}

}  // namespace

Model tree_model(const std::vector<TreeLink>& links, const std::string& tip) {
  Model m;
  m.root_name = "l0";
  m.tip_name = tip;
  // For each URDF link: the body it rides on (-1 = the root) and its frame in that body's.
  std::vector<int> body(links.size() + 1, -1);
  std::vector<Transform> in_body(links.size() + 1);
  for (std::size_t k = 1; k <= links.size(); ++k) {
    const TreeLink& l = links[k - 1];
    // parent link frame in its body's frame, then this link's frame in it
    const Transform link_in_parent_body = in_body[l.parent] * l.origin;
    Link link;
    link.name = l.name;
    if (l.type == "fixed") {
      body[k] = body[l.parent];
      in_body[k] = link_in_parent_body;
    } else {
      Body b;
      b.joint_name = l.joint;
      b.link_name = l.name;
      b.parent = body[l.parent];
      b.type = l.type == "prismatic" ? JointType::Prismatic
               : l.type == "continuous" ? JointType::Continuous
                                        : JointType::Revolute;
      const Transform joint = joint_frame_in_link(l.axis);
      b.X_tree = link_in_parent_body * joint;
      if (l.type != "continuous") b.limits = {-4, 4, 10, 100};
      b.damping = l.damping;
      b.friction = l.friction;
      m.bodies.push_back(b);
      body[k] = m.num_rates() - 1;
      in_body[k] = inverse(joint);
    }
    link.body = body[k];
    link.offset = in_body[k];
    m.links.push_back(link);
    // The link's inertia, about its origin in its frame, merged into its body's.
    if (l.mass > 0 && body[k] >= 0)
      add_inertia_to_parent(in_body[k], spatial_inertia(l.mass, l.com, l.inertia),
                            m.bodies[body[k]].inertia);
  }
  validate(m);
  return m;
}

RandomTree random_tree(std::mt19937& rng, int num_bodies, bool chain) {
  static const char* kMovable[] = {"revolute", "continuous", "prismatic"};
  RandomTree t;
  int bodies = 0;
  for (int k = 1; bodies < num_bodies; ++k) {
    // Branch at random, leaning toward the last link so that trees also grow deep.
    const int parent = chain || uniform(rng, 0, 1) < 0.4 ? k - 1 : uniform_int(rng, 0, k - 1);
    std::string type = kMovable[uniform_int(rng, 0, 2)];
    const bool last = bodies + 1 == num_bodies;
    if (uniform(rng, 0, 1) < 0.25 && !(chain && last)) type = "fixed";
    // A chain's tip, and a movable link with no massive link after it, must move mass:
    // every movable link has mass (the massless ones are fixed).
    t.links.push_back(random_link(rng, k, parent, type, type != "fixed"));
    bodies += type != "fixed";
  }
  t.model = tree_model(t.links, chain ? t.links.back().name : "");
  return t;
}

std::vector<TreeLink> join_on_root(const std::vector<TreeLink>& a, const std::vector<TreeLink>& b) {
  std::vector<TreeLink> out = a;
  const int shift = static_cast<int>(a.size());
  for (TreeLink l : b) {
    const int k = std::stoi(l.name.substr(1)) + shift;
    l.name = "l" + std::to_string(k);
    l.joint = "j" + std::to_string(k);
    if (l.parent > 0) l.parent += shift;
    out.push_back(l);
  }
  return out;
}

RandomTree random_star(std::mt19937& rng, int arms, int min_bodies, int max_bodies,
                       std::vector<int>& arm_tips) {
  RandomTree t;
  arm_tips.clear();
  for (int k = 0; k < arms; ++k) {
    const RandomTree arm = random_tree(rng, uniform_int(rng, min_bodies, max_bodies), true);
    t.links = join_on_root(t.links, arm.links);
    arm_tips.push_back(static_cast<int>(t.links.size()) - 1);
  }
  t.model = tree_model(t.links);
  return t;
}

std::string tree_urdf(const std::vector<TreeLink>& links) {
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\"?>\n<robot name=\"random_tree\">\n  <link name=\"l0\"/>\n";
  for (const TreeLink& l : links) {
    const std::string parent = l.parent == 0 ? "l0" : links[l.parent - 1].name;
    x << "  <joint name=\"" << l.joint << "\" type=\"" << l.type << "\">\n"
      << "    <parent link=\"" << parent << "\"/><child link=\"" << l.name << "\"/>\n"
      << "    <origin xyz=\"" << l.origin.p.transpose() << "\" rpy=\""
      << rpy_of(l.origin.R).transpose() << "\"/>\n";
    if (l.type != "fixed") x << "    <axis xyz=\"" << l.axis.transpose() << "\"/>\n";
    if (l.type == "revolute" || l.type == "prismatic")
      x << "    <limit lower=\"-4\" upper=\"4\" effort=\"100\" velocity=\"10\"/>\n";
    if (l.damping != 0 || l.friction != 0)
      x << "    <dynamics damping=\"" << l.damping << "\" friction=\"" << l.friction << "\"/>\n";
    x << "  </joint>\n  <link name=\"" << l.name << "\">\n";
    if (l.mass > 0) {
      const Matrix3& I = l.inertia;
      x << "    <inertial>\n      <origin xyz=\"" << l.com.transpose() << "\" rpy=\"0 0 0\"/>\n"
        << "      <mass value=\"" << l.mass << "\"/>\n"
        << "      <inertia ixx=\"" << I(0, 0) << "\" ixy=\"" << I(0, 1) << "\" ixz=\"" << I(0, 2)
        << "\" iyy=\"" << I(1, 1) << "\" iyz=\"" << I(1, 2) << "\" izz=\"" << I(2, 2)
        << "\"/>\n    </inertial>\n";
    }
    x << "  </link>\n";
  }
  x << "</robot>\n";
  return x.str();
}

Case random_tree_inputs(std::mt19937& rng, const Model& model) {
  const int n = model.num_rates();
  Case c;
  c.q = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(rng, -M_PI, M_PI); });
  c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(rng, -2, 2); });
  c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(rng, -5, 5); });
  c.gravity = uniform3(rng, -1, 1).normalized() * uniform(rng, 5, 15);
  c.f_ext.resize(model.num_links());
  for (Vector6& w : c.f_ext) w = Vector6::NullaryExpr([&] { return uniform(rng, -3, 3); });
  return c;
}

Eigen::MatrixXd stacked_constraint_jacobian(const Model& model, const Case& c) {
  const int n = model.num_rates();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const std::vector<FrameMotion> frames = reference_motion(model, c.q, zero, zero);
  Eigen::MatrixXd A(c.num_constraints(), n);
  int row = 0;
  // J at a point P of link l: v_P = v_l + w x r = v_l - [r]x w, r = R_l P.
  auto jacobian = [&](int link, const Vector3& point) {
    Eigen::MatrixXd J = reference_link_jacobian(model, c.q, link);
    const Vector3 r = frames[link].R * point;
    J.topRows<3>() -= skew(r) * J.bottomRows<3>();
    return J;
  };
  // alpha^T J_P, or alpha^T (J_P - J_Q) for a relative block
  auto add = [&](int link, const Vector3& point, const ConstraintMatrix& alpha, int link_b, const Vector3& point_b) {
    Eigen::MatrixXd J = jacobian(link, point);
    if (link_b >= 0) J -= jacobian(link_b, point_b);
    A.middleRows(row, alpha.cols()) = alpha.transpose() * J;
    row += static_cast<int>(alpha.cols());
  };
  if (c.alpha.cols()) add(model.num_links() - 1, Vector3::Zero(), c.alpha, -1, Vector3::Zero());
  for (const ConstraintBlock& b : c.constraints) add(b.link, b.point, b.alpha, b.link_b, b.point_b);
  return A;
}

double tree_coupling_condition(const Model& model, const Case& c) {
  const int nc = c.num_constraints();
  if (nc == 0) return 1;
  const int n = model.num_rates();
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (!c.any_prescribed() || !c.prescribed[i]) free.push_back(i);
  const Eigen::MatrixXd M = reference_crba(model, c.q), A = stacked_constraint_jacobian(model, c);
  Eigen::MatrixXd Mff(free.size(), free.size()), Af(nc, free.size());
  for (std::size_t i = 0; i < free.size(); ++i) {
    Af.col(i) = A.col(free[i]);
    for (std::size_t j = 0; j < free.size(); ++j) Mff(i, j) = M(free[i], free[j]);
  }
  if (free.empty()) return INFINITY;
  const Eigen::MatrixXd K = Af * Mff.ldlt().solve(Af.transpose());
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(K).singularValues();
  const double smin = s[s.size() - 1];
  return smin > 0 ? s[0] / smin : INFINITY;
}

std::optional<Case> with_random_blocks(std::mt19937& rng, const Model& model, Case c,
                                       int max_blocks, int max_columns, double max_condition) {
  // Links that move (not fixed to the root), and how many joints each one's path has.
  std::vector<int> movable, depth(model.num_links(), 0);
  for (int l = 0; l < model.num_links(); ++l) {
    for (int b = model.links[l].body; b >= 0; b = model.bodies[b].parent) ++depth[l];
    if (depth[l]) movable.push_back(l);
  }
  max_blocks = std::min<int>(max_blocks, static_cast<int>(movable.size()));
  for (int attempt = 0; attempt < 200; ++attempt) {
    c.constraints.clear();
    std::shuffle(movable.begin(), movable.end(), rng);
    const int blocks = uniform_int(rng, 0, max_blocks);
    int columns = 0;
    for (int k = 0; k < blocks; ++k) {
      const int link = movable[k];
      const int most = std::min({kMaxConstraints, depth[link], max_columns - columns,
                                 model.num_rates() - columns});
      if (most < 1) break;
      ConstraintBlock b;
      b.link = link;
      b.point = uniform3(rng, -0.3, 0.3);
      const int nc = uniform_int(rng, 1, most);
      b.alpha.resize(6, nc);
      for (int j = 0; j < nc; ++j)
        b.alpha.col(j) = Vector6::NullaryExpr([&] { return uniform(rng, -1, 1); }).normalized();
      b.beta = ConstraintVector::NullaryExpr(nc, [&] { return uniform(rng, -2, 2); });
      columns += nc;
      c.constraints.push_back(b);
    }
    if (tree_coupling_condition(model, c) < max_condition) return c;
  }
  return std::nullopt;
}

std::optional<Case> with_blocks_on(std::mt19937& rng, const Model& model, Case c,
                                   const std::vector<int>& links, int columns, double max_condition) {
  for (int attempt = 0; attempt < 200; ++attempt) {
    c.constraints.clear();
    for (const int link : links) {
      ConstraintBlock b;
      b.link = link;
      b.point = uniform3(rng, -0.3, 0.3);
      b.alpha.resize(6, columns);
      for (int j = 0; j < columns; ++j)
        b.alpha.col(j) = Vector6::NullaryExpr([&] { return uniform(rng, -1, 1); }).normalized();
      b.beta = ConstraintVector::NullaryExpr(columns, [&] { return uniform(rng, -2, 2); });
      c.constraints.push_back(b);
    }
    if (tree_coupling_condition(model, c) < max_condition) return c;
  }
  return std::nullopt;
}

std::optional<Case> random_tree_case(std::mt19937& rng, const Model& model, int max_blocks) {
  return with_random_blocks(rng, model, random_tree_inputs(rng, model), max_blocks);
}

void prescribe_random_joints(std::mt19937& rng, const Model& model, Case& c, double share) {
  const int n = model.num_rates();
  c.prescribed.assign(n, false);
  c.qdd_given = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(rng, -3, 3); });
  int free = n;
  for (int i = 0; i < n; ++i)
    if (free > 1 && uniform(rng, 0, 1) < share) {
      c.prescribed[i] = true;
      --free;
    }
}

}  // namespace achd::test
