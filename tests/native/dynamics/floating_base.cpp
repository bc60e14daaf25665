// A floating base (UrdfOptions::floating; free_joint.hpp): seeded random trees loaded with
// a free joint between the world and their root link, and the quadruped. Physics that a
// free-floating robot must obey, checked through the public coordinates (q: position and
// quaternion; qd, qdd: [v; w] of the root's origin, world axes):
//   - free fall: at rest with no torques, every link accelerates with g and no joint moves;
//   - without gravity, external wrenches or constraints, the spatial momentum (world axes,
//     about the world origin) is constant: sum_l (I_l a_l + v_l x* I_l v_l) = 0, whatever
//     the joint torques (they are internal);
//   - the free joint's qdd is the root link's acceleration: dv/dt = a_lin + w x v, dw/dt = a_ang;
//   - RNEA at the solved qdd reproduces joint_torques, which are ff - sum_k J_k^T alpha_k nu_k,
//     and drive the unconstrained robot to the same qdd; every block's alpha^T a_P = beta;
//   - the fast path equals pv_reference;
//   - the free joint prescribed at rest (qdd = 0, qd = 0) is the fixed base.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include <Eigen/SVD>

#include "achd/achd.hpp"
#include "random_chain.hpp"
#include "random_tree.hpp"

namespace achd::test {
namespace {

// The root link's own inertia, which the random trees (massless root: a fixed base does
// not feel it) get here: mass, COM and a diagonal inertia about the COM, link axes.
struct RootInertia {
  double mass;
  Vector3 com;
  Matrix3 inertia;
};

RootInertia random_root_inertia(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.5, 3.0);
  const double a = u(rng) * 0.05, b = u(rng) * 0.05, c = u(rng) * 0.05;
  return {u(rng), Vector3(0.02, -0.01, 0.03), Vector3(b + c, a + c, a + b).asDiagonal()};
}

std::string with_root_inertia(std::string urdf, const RootInertia& r) {
  auto num = [](double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return std::string(buf);
  };
  const std::string root = "<link name=\"l0\"><inertial><origin xyz=\"" + num(r.com[0]) + " " + num(r.com[1]) +
                           " " + num(r.com[2]) + "\"/><mass value=\"" + num(r.mass) + "\"/><inertia ixx=\"" +
                           num(r.inertia(0, 0)) + "\" iyy=\"" + num(r.inertia(1, 1)) + "\" izz=\"" +
                           num(r.inertia(2, 2)) + "\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>";
  const std::string plain = "<link name=\"l0\"/>";
  urdf.replace(urdf.find(plain), plain.size(), root);
  return urdf;
}

std::string robot_path(const std::string& file) { return std::string(ACHD_SOURCE_DIR) + "/robots/" + file; }

Model load_floating(const std::string& urdf) {
  UrdfOptions options;
  options.floating = true;
  return load_urdf_string(urdf, "", "", options);
}

// Random public inputs: position, unit quaternion, joint angles, [v; w], joint rates, ff
// (the free joint's wrench zero: nothing pushes the root), f_ext, gravity.
Case random_floating_case(std::mt19937& rng, const Model& m) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = m.num_rates();
  Case c;
  c.q.resize(m.num_positions());
  for (int k = 0; k < 3; ++k) c.q[k] = 2 * u(rng);
  Eigen::Vector4d h(u(rng), u(rng), u(rng), u(rng));
  c.q.segment<4>(3) = h.normalized();
  for (int i = 7; i < c.q.size(); ++i) c.q[i] = 2 * u(rng);
  c.qd.resize(n);
  for (int i = 0; i < n; ++i) c.qd[i] = u(rng);
  c.ff_torques.resize(n);
  for (int i = 0; i < n; ++i) c.ff_torques[i] = i < 6 ? 0.0 : 5 * u(rng);
  c.f_ext.assign(m.num_links(), Vector6::Zero());
  for (Vector6& f : c.f_ext)
    for (int k = 0; k < 6; ++k) f[k] = u(rng);
  c.gravity = Vector3(u(rng), u(rng), u(rng)).normalized() * 9.81;
  return c;
}

// Blocks of 1..6 random unit columns at random points on `count` distinct random links,
// redrawn until K = A M^-1 A^T (public crba and link_jacobian) has condition below 1e4.
bool add_random_blocks(std::mt19937& rng, const Model& m, Case& c, int count) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::MatrixXd M = crba(m, c.q);
  for (int attempt = 0; attempt < 200; ++attempt) {
    c.constraints.clear();
    std::vector<int> links(m.num_links());
    for (int l = 0; l < m.num_links(); ++l) links[l] = l;
    std::shuffle(links.begin(), links.end(), rng);
    int rows = 0;
    for (int b = 0; b < count && b < m.num_links(); ++b) {
      ConstraintBlock block;
      block.link = links[b];
      block.point = Vector3(u(rng), u(rng), u(rng)) * 0.1;
      const int k = std::uniform_int_distribution<int>(1, 6)(rng);
      block.alpha.resize(6, k);
      block.beta.resize(k);
      for (int j = 0; j < k; ++j) {
        for (int r = 0; r < 6; ++r) block.alpha(r, j) = u(rng);
        block.alpha.col(j).normalize();
        block.beta[j] = u(rng);
      }
      rows += k;
      c.constraints.push_back(block);
    }
    Eigen::MatrixXd A(rows, m.num_rates());
    int row = 0;
    for (const ConstraintBlock& b : c.constraints) {
      A.middleRows(row, b.alpha.cols()) = b.alpha.transpose() * link_jacobian(m, c.q, b.link, b.point);
      row += static_cast<int>(b.alpha.cols());
    }
    const Eigen::MatrixXd K = A * M.ldlt().solve(A.transpose());
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(K);
    const auto s = svd.singularValues();
    if (s[s.size() - 1] > 0 && s[0] / s[s.size() - 1] < 1e4) return true;
  }
  return false;
}

// Calls f(model, tree, root inertia, rng) on `count` random floating trees of 1..40 bodies.
template <class F>
void for_floating_trees(unsigned seed, int count, F f) {
  std::mt19937 rng(seed);
  for (int k = 0; k < count; ++k) {
    const int bodies = k == 0 ? 1 : std::uniform_int_distribution<int>(1, 40)(rng);
    const RandomTree t = random_tree(rng, bodies);
    const RootInertia root = random_root_inertia(rng);
    const Model m = load_floating(with_root_inertia(tree_urdf(t.links), root));
    f(m, t, root, rng);
  }
}

TEST(FloatingBase, LoaderPutsTheFreeJointFirstAndCountsTheRootMass) {
  const std::string path = robot_path("quadruped.urdf");
  const Model fixed = load_urdf_file(path, "", "");
  UrdfOptions options;
  options.floating = true;
  const Model m = load_urdf_file(path, "", "", options);
  EXPECT_TRUE(m.floating);
  EXPECT_EQ(m.num_rates(), fixed.num_rates() + 6);
  EXPECT_EQ(m.num_positions(), fixed.num_rates() + 7);
  EXPECT_EQ(m.joint_index(m.root_name), 0);
  EXPECT_GT(m.bodies[5].inertia(0, 0), 1.0);  // the trunk's mass, which the fixed base ignores
  const Case zeros = Case::zeros(m);
  EXPECT_EQ(zeros.q.size(), m.num_positions());
  EXPECT_EQ(zeros.q[6], 1.0);
  Case c = zeros;
  c.q.segment<4>(3).setZero();
  Data d(m);
  try {
    hybrid_dynamics(m, d, c);
    ADD_FAILURE() << "a zero quaternion was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("quaternion"), std::string::npos) << e.what();
  }
}

// At rest with no torques and no wrenches every link accelerates with g and no joint moves.
TEST(FloatingBase, FreeFall) {
  double worst = 0;
  auto check = [&](const Model& m, std::mt19937& rng) {
    Case c = random_floating_case(rng, m);
    c.qd.setZero();
    c.ff_torques.setZero();
    c.f_ext.clear();
    Data d(m);
    hybrid_dynamics(m, d, c);
    Vector6 g = Vector6::Zero();
    g.head<3>() = c.gravity;
    for (const Vector6& a : d.link_accelerations) worst = std::max(worst, (a - g).norm() / 9.81);
    worst = std::max(worst, (d.qdd.head<6>() - g).norm() / 9.81);
    worst = std::max(worst, d.qdd.tail(m.num_rates() - 6).norm() / 9.81);
  };
  for_floating_trees(5101, 20, [&](const Model& m, const RandomTree&, const RootInertia&, std::mt19937& rng) {
    check(m, rng);
  });
  UrdfOptions options;
  options.floating = true;
  std::mt19937 rng(7);
  check(load_urdf_file(robot_path("quadruped.urdf"), "", "", options), rng);
  check(load_urdf_file(robot_path("dual_arm_torso.urdf"), "", "", options), rng);
  std::printf("free fall: worst relative error %.2e\n", worst);
  EXPECT_LE(worst, 1e-12);
}

// Spatial momentum about the world origin, world axes, of every link (the random tree's
// URDF links, with their own inertias) and its rate: sum_l X_l^* (I_l v_l) and
// sum_l X_l^* (I_l a_l + v_l x* I_l v_l), with a_l the links' spatial accelerations.
struct Momentum {
  Vector6 rate = Vector6::Zero();
  double scale = 0;  // sum of the terms' norms
};

Matrix6 link_spatial_inertia(double mass, const Vector3& com, const Matrix3& I_com, const Matrix3& R) {
  // In world axes about the link origin: [m 1, -m [c]x; m [c]x, I_c + m [c]x [c]x^T]
  const Vector3 cw = R * com;
  const Matrix3 Iw = R * I_com * R.transpose();
  Matrix6 I = Matrix6::Zero();
  I.topLeftCorner<3, 3>() = mass * Matrix3::Identity();
  I.topRightCorner<3, 3>() = -mass * skew(cw);
  I.bottomLeftCorner<3, 3>() = mass * skew(cw);
  I.bottomRightCorner<3, 3>() = Iw + mass * skew(cw) * skew(cw).transpose();
  return I;
}

void add_link_momentum(Momentum& h, const Matrix6& I, const Vector3& p, const Vector6& v, const Vector6& a) {
  const Vector6 Iv = I * v;
  const Vector6 f = I * a + cross_force(v, Iv);
  h.rate += force_shift(f, p);
  h.scale += (I * a).norm() + cross_force(v, Iv).norm();
}

TEST(FloatingBase, MomentumIsConservedWithoutExternalForces) {
  double worst = 0;
  for_floating_trees(5203, 30, [&](const Model& m, const RandomTree& t, const RootInertia& root,
                                   std::mt19937& rng) {
    Case c = random_floating_case(rng, m);
    c.gravity.setZero();
    c.f_ext.clear();
    Options o;
    o.effects = kAllEffects & ~kRotorInertia;  // damping and friction are internal too
    Data d(m);
    hybrid_dynamics(m, d, c, o);
    const std::vector<Transform> poses = forward_kinematics(m, c.q);
    const std::vector<Vector6> v = link_velocities(m, c.q, c.qd);
    Momentum h;
    // the root link l0: its pose and velocity are the free joint's
    const Matrix3 R = Eigen::Quaterniond(c.q[6], c.q[3], c.q[4], c.q[5]).normalized().toRotationMatrix();
    add_link_momentum(h, link_spatial_inertia(root.mass, root.com, root.inertia, R), c.q.head<3>(),
                      c.qd.head<6>(), d.link_accelerations[0]);
    for (const TreeLink& link : t.links) {
      if (link.mass == 0) continue;
      const int l = m.link_index(link.name);  // the loader's order is depth-first
      const Matrix6 I = link_spatial_inertia(link.mass, link.com, link.inertia, poses[l].R);
      add_link_momentum(h, I, poses[l].p, v[l], d.link_accelerations[l + 1]);
    }
    worst = std::max(worst, h.rate.norm() / h.scale);
  });
  std::printf("momentum rate: worst relative %.2e\n", worst);
  EXPECT_LE(worst, 1e-10);
}

// The free joint's qdd is the root link's acceleration in the public form: with a the root's
// spatial acceleration (link_accelerations[0]), dv/dt = a_lin + w x v and dw/dt = a_ang.
TEST(FloatingBase, FreeJointAccelerationIsTheRootsAcceleration) {
  double worst = 0;
  for_floating_trees(5307, 20, [&](const Model& m, const RandomTree&, const RootInertia&, std::mt19937& rng) {
    const Case c = random_floating_case(rng, m);
    Data d(m);
    hybrid_dynamics(m, d, c);
    const Vector6& a = d.link_accelerations[0];
    const Vector3 v = c.qd.head<3>(), w = c.qd.segment<3>(3);
    Vector6 expected;
    expected << a.head<3>() + w.cross(v), a.tail<3>();
    worst = std::max(worst, rel_error(d.qdd.head<6>(), expected));
  });
  std::printf("free joint qdd against the root's acceleration: worst relative %.2e\n", worst);
  EXPECT_LE(worst, 1e-12);
}

// With constraint blocks on random links: RNEA(q, qd, qdd) = joint_torques =
// ff - sum_k J_k^T alpha_k nu_k, they drive the unconstrained robot to the same qdd, every
// block's alpha^T a_P = beta, M qdd + h = joint_torques with the public mass matrix, and
// the fast path equals pv_reference.
TEST(FloatingBase, ConstrainedIdentitiesAndReference) {
  double worst_rnea = 0, worst_crba = 0, worst_jt = 0, worst_free = 0, worst_beta = 0, worst_ref = 0;
  int cases = 0;
  Options o;
  o.effects = kAllEffects;
  for_floating_trees(5419, 30, [&](const Model& m, const RandomTree&, const RootInertia&, std::mt19937& rng) {
    Case c = random_floating_case(rng, m);
    const int blocks = std::uniform_int_distribution<int>(1, 4)(rng);
    if (!add_random_blocks(rng, m, c, blocks)) return;
    ++cases;
    Data d(m);
    hybrid_dynamics(m, d, c, o);
    worst_rnea = std::max(worst_rnea, rel_error(d.joint_torques, rnea(m, c.q, c.qd, d.qdd, c.gravity, c.f_ext,
                                                                        o)));
    // M qdd + h = joint_torques with the public mass matrix (crba) and h = RNEA(q, qd, 0)
    const Eigen::VectorXd h = rnea(m, c.q, c.qd, Eigen::VectorXd::Zero(m.num_rates()), c.gravity, c.f_ext,
                                   o);
    worst_crba = std::max(worst_crba, rel_error(crba(m, c.q) * d.qdd + h, d.joint_torques));
    Eigen::VectorXd expected = c.ff_torques;
    int row = 0;
    for (const ConstraintBlock& b : c.constraints) {
      const Eigen::VectorXd nu = d.nu.segment(row, b.alpha.cols());
      expected -= link_jacobian(m, c.q, b.link, b.point).transpose() * (b.alpha * nu);
      // alpha^T a_P: the link's acceleration moved to the point
      const Transform pose = forward_kinematics(m, c.q)[b.link];
      const Vector6 aP = motion_shift(d.link_accelerations[b.link + 1], pose.R * b.point);
      worst_beta = std::max(worst_beta, rel_error(b.alpha.transpose() * aP, b.beta));
      row += static_cast<int>(b.alpha.cols());
    }
    worst_jt = std::max(worst_jt, rel_error(d.joint_torques, expected));
    Case free = c;
    free.constraints.clear();
    free.ff_torques = d.joint_torques;
    Data df(m);
    hybrid_dynamics(m, df, free, o);
    worst_free = std::max(worst_free, rel_error(df.qdd, d.qdd));
    const ReferenceSolution ref = pv_reference(m, c, o);
    worst_ref = std::max({worst_ref, rel_error(ref.qdd, d.qdd), rel_error(ref.nu, Eigen::VectorXd(d.nu)),
                          rel_error(ref.joint_torques, d.joint_torques)});
    // The free joint prescribed (its columns then roll through its six bodies one axis at
    // a time, not in the 6-DoF step): still the reference.
    Case given = c;
    given.prescribed.assign(m.num_rates(), false);
    given.qdd_given = Eigen::VectorXd::Zero(m.num_rates());
    for (int k = 0; k < 6; ++k) {
      given.prescribed[k] = true;
      given.qdd_given[k] = std::uniform_real_distribution<double>(-2, 2)(rng);
    }
    if (m.num_rates() > 6 + 1) {  // something left free for the blocks to act through
      Data dg(m);
      try {
        hybrid_dynamics(m, dg, given, o);
        const ReferenceSolution rg = pv_reference(m, given, o);
        worst_ref = std::max({worst_ref, rel_error(rg.qdd, dg.qdd), rel_error(rg.prescribed_torques, dg.prescribed_torques)});
      } catch (const Error&) {
        // (blocks that only the free joint could satisfy: singular either way)
      }
    }
  });
  std::printf("%d constrained floating trees: rnea %.2e, M qdd + h %.2e, joint_torques %.2e, unconstrained %.2e, alpha^T a %.2e, "
              "pv_reference %.2e\n", cases, worst_rnea, worst_crba, worst_jt, worst_free, worst_beta, worst_ref);
  EXPECT_GE(cases, 25);
  EXPECT_LE(worst_rnea, 1e-10);
  EXPECT_LE(worst_crba, 1e-10);
  EXPECT_LE(worst_jt, 1e-10);
  EXPECT_LE(worst_free, 1e-10);
  EXPECT_LE(worst_beta, 1e-10);
  EXPECT_LE(worst_ref, 1e-12);
}

// The free joint prescribed at rest (qd = 0 on it, qdd_given = 0) holds the root still: the
// joints move as on a fixed base, whose frame is the root's (gravity turned into it).
TEST(FloatingBase, PrescribedAtRestIsTheFixedBase) {
  double worst = 0;
  std::mt19937 rng(5521);
  for (int k = 0; k < 20; ++k) {
    const RandomTree t = random_tree(rng, std::uniform_int_distribution<int>(1, 40)(rng));
    const RootInertia root = random_root_inertia(rng);
    const std::string urdf = with_root_inertia(tree_urdf(t.links), root);
    const Model floating = load_floating(urdf);
    const Model fixed = load_urdf_string(urdf, "", "");
    Case c = random_floating_case(rng, floating);
    c.qd.head<6>().setZero();
    c.f_ext.clear();
    c.prescribed.assign(floating.num_rates(), false);
    c.qdd_given = Eigen::VectorXd::Zero(floating.num_rates());
    for (int i = 0; i < 6; ++i) c.prescribed[i] = true;
    Case f;
    f.q = c.q.tail(fixed.num_rates());
    f.qd = c.qd.tail(fixed.num_rates());
    f.ff_torques = c.ff_torques.tail(fixed.num_rates());
    const Matrix3 R = Eigen::Quaterniond(c.q[6], c.q[3], c.q[4], c.q[5]).normalized().toRotationMatrix();
    f.gravity = R.transpose() * c.gravity;
    Data dc(floating), df(fixed);
    hybrid_dynamics(floating, dc, c);
    hybrid_dynamics(fixed, df, f);
    worst = std::max(worst, rel_error(dc.qdd.tail(fixed.num_rates()), df.qdd));
    EXPECT_LE(dc.qdd.head<6>().norm(), 1e-12);
  }
  std::printf("free joint held at rest against the fixed base: worst relative %.2e\n", worst);
  EXPECT_LE(worst, 1e-12);
}

// A loop joint on a floating robot is the relative block it becomes: the four-bar closed
// by its revolute loop, on a free joint, solved with loop_beta equals the same robot loaded
// without the loop and holding that block (the loop's frames and columns, beta =
// loop_beta) as a case block. (The floating solve once dropped loop_beta on its way into
// the free joint's coordinates and solved with beta = 0.)
TEST(FloatingBase, LoopJointsTakeTheirLoopBeta) {
  UrdfOptions o;
  o.floating = true;
  const Model open = load_urdf_file(robot_path("four_bar.urdf"), "", "", o);
  LoopJointSpec loop;
  loop.name = "coupler_rocker";
  loop.link_a = "coupler";
  loop.origin_a.p = Vector3(0.12, 0, 0);
  loop.link_b = "rocker";
  loop.origin_b.p = Vector3(0.08, 0, 0);
  loop.type = LoopType::Revolute;
  loop.axis = Vector3(0, 1, 0);
  o.loops = {loop};
  const Model closed = load_urdf_file(robot_path("four_bar.urdf"), "", "", o);
  ASSERT_EQ(closed.num_loop_columns(), 2);
  Case c = Case::zeros(closed);
  c.q << 0.1, -0.2, 0.3, 0.1, 0.2, -0.3, 0.9, 0.3, 2.1, -0.4;
  c.qd = Eigen::VectorXd::LinSpaced(closed.num_rates(), -1, 1.5);
  c.loop_beta = Eigen::Vector2d(0.25, -1.5);
  Data dc(closed), dz(closed), db(open);
  hybrid_dynamics(closed, dc, c);
  Case zero_beta = c;
  zero_beta.loop_beta.setZero();
  hybrid_dynamics(closed, dz, zero_beta);
  Case block = c;
  block.loop_beta.resize(0);
  block.constraints = {dc.workspace.loop_blocks[0]};
  block.constraints[0].beta = c.loop_beta;
  hybrid_dynamics(open, db, block);
  EXPECT_LE(rel_error(dc.qdd, db.qdd), 1e-12);
  EXPECT_LE(rel_error(dc.nu, db.nu), 1e-12);
  EXPECT_GT(rel_error(dc.qdd, dz.qdd), 1e-3);  // (loop_beta moves the answer)
}

}  // namespace
}  // namespace achd::test
