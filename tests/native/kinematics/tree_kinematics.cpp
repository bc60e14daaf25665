// achd's kinematics and dynamics on random kinematic trees (random_tree.hpp) against the
// test references, which walk parent[i] with their own formulas (reference_kinematics.hpp,
// reference_dynamics.hpp): forward_kinematics, link_velocities, link_jacobian at a point,
// rnea and crba; and tree_urdf's text loads as the same tree. Relative errors as docs/design.md section 4.6.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "random_chain.hpp"
#include "random_tree.hpp"
#include "reference_dynamics.hpp"
#include "reference_kinematics.hpp"

namespace achd::test {
namespace {

constexpr int kTrees = 40;

double matrix_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

TEST(TreeKinematics, PosesVelocitiesAndLinkJacobiansMatchTheReference) {
  double worst_pose = 0, worst_vel = 0, worst_jac = 0;
  int links = 0;
  for_random_trees(1501, kTrees, [&](const RandomTree& t, std::mt19937& rng) {
    const Model& m = t.model;
    const Case c = random_tree_inputs(rng, m);
    const std::vector<FrameMotion> ref = reference_motion(m, c.q, c.qd, Eigen::VectorXd::Zero(m.num_rates()));
    const std::vector<Transform> poses = forward_kinematics(m, c.q);
    const std::vector<Vector6> velocities = link_velocities(m, c.q, c.qd);
    ChainWorkspace ws(m);
    Eigen::MatrixXd J;
    for (int l = 0; l < m.num_links(); ++l) {
      const double e_pose = std::max((poses[l].R - ref[l].R).cwiseAbs().maxCoeff(),
                                     (poses[l].p - ref[l].p).cwiseAbs().maxCoeff());
      const Vector6 v_ref = (Vector6() << ref[l].v, ref[l].w).finished();
      const double e_vel = rel_error(velocities[l], v_ref);
      // At a point P of the link: v_P = v_l - [r]x w, r = R_l P; J qd is the point's velocity.
      const Vector3 point = uniform3(rng, -0.5, 0.5);
      Eigen::MatrixXd J_ref = reference_link_jacobian(m, c.q, l);
      J_ref.topRows<3>() -= skew(ref[l].R * point) * J_ref.bottomRows<3>();
      link_jacobian(m, c.q, l, point, ws, J);
      const double e_jac = std::max(matrix_error(J, J_ref), matrix_error(link_jacobian(m, c.q, l, point), J_ref));
      EXPECT_LE(e_pose, 1e-12) << "link " << m.links[l].name << "\n" << tree_urdf(t.links);
      EXPECT_LE(e_vel, 1e-12) << "link " << m.links[l].name;
      EXPECT_LE(e_jac, 1e-12) << "link " << m.links[l].name;
      // Joints off the link's path have zero columns.
      std::vector<bool> on_path(m.num_rates(), false);
      for (int b = m.links[l].body; b >= 0; b = m.bodies[b].parent) on_path[b] = true;
      for (int j = 0; j < m.num_rates(); ++j)
        if (!on_path[j]) EXPECT_TRUE(J.col(j).isZero(0)) << "link " << l << " joint " << j;
      worst_pose = std::max(worst_pose, e_pose);
      worst_vel = std::max(worst_vel, e_vel);
      worst_jac = std::max(worst_jac, e_jac);
      ++links;
    }
  });
  std::printf("  %d links: max error poses %.3g, velocities %.3g, link_jacobian %.3g\n", links,
              worst_pose, worst_vel, worst_jac);
}

// rnea and crba with every effect on (random rotor inertias; the trees' damping and
// friction), a random qdd.
TEST(TreeKinematics, RneaAndCrbaMatchTheReference) {
  double worst_tau = 0, worst_M = 0;
  for_random_trees(1502, kTrees, [&](const RandomTree& t, std::mt19937& rng) {
    Model m = t.model;
    for (int i = 0; i < m.num_rates(); ++i) m.set_rotor_inertia(i, uniform(rng, 0, 0.1));
    const Case c = random_tree_inputs(rng, m);
    const Eigen::VectorXd qdd = Eigen::VectorXd::NullaryExpr(m.num_rates(), [&] { return uniform(rng, -3, 3); });
    const double e_tau = rel_error(rnea(m, c.q, c.qd, qdd, c.gravity, c.f_ext, with_effects(kAllEffects)),
                                   reference_rnea(m, c.q, c.qd, qdd, c.gravity, c.f_ext, kAllEffects, 0.05));
    const double e_M = matrix_error(crba(m, c.q), reference_crba(m, c.q));
    EXPECT_LE(e_tau, 1e-12) << tree_urdf(t.links);
    EXPECT_LE(e_M, 1e-12) << tree_urdf(t.links);
    worst_tau = std::max(worst_tau, e_tau);
    worst_M = std::max(worst_M, e_M);
  });
  std::printf("  max rel error rnea %.3g, crba %.3g\n", worst_tau, worst_M);
}

// tree_urdf writes the tree the Model was built from: the URDF loader gives the same mass
// matrix, RNEA torques (every effect) and link poses, joints and links matched by name
// (the loader orders a tree's bodies depth-first). Returns the largest relative error.
double loaded_model_error(const RandomTree& t, const Model& loaded, std::mt19937& rng) {
  const Model& m = t.model;
  EXPECT_EQ(loaded.num_rates(), m.num_rates());
  EXPECT_EQ(loaded.num_links(), m.num_links());
  if (loaded.num_rates() != m.num_rates() || loaded.num_links() != m.num_links()) return INFINITY;
  const int n = m.num_rates();
  std::vector<int> joint(n), link(m.num_links());
  for (int i = 0; i < n; ++i)
    if ((joint[i] = loaded.joint_index(m.bodies[i].joint_name)) < 0) return INFINITY;
  for (int l = 0; l < m.num_links(); ++l)
    if ((link[l] = loaded.link_index(m.links[l].name)) < 0) return INFINITY;
  const Case c = random_tree_inputs(rng, m);
  const Eigen::VectorXd& qdd = c.ff_torques;  // any numbers
  Eigen::VectorXd q(n), qd(n), qdd_loaded(n);
  for (int i = 0; i < n; ++i) q[joint[i]] = c.q[i], qd[joint[i]] = c.qd[i], qdd_loaded[joint[i]] = qdd[i];
  std::vector<Vector6> f_ext(m.num_links());
  for (int l = 0; l < m.num_links(); ++l) f_ext[link[l]] = c.f_ext[l];
  const Eigen::MatrixXd M = crba(m, c.q), M_loaded = crba(loaded, q);
  const Eigen::VectorXd tau = rnea(m, c.q, c.qd, qdd, c.gravity, c.f_ext, with_effects(kAllEffects));
  const Eigen::VectorXd tau_loaded = rnea(loaded, q, qd, qdd_loaded, c.gravity, f_ext, with_effects(kAllEffects));
  const std::vector<Transform> poses = forward_kinematics(m, c.q), poses_loaded = forward_kinematics(loaded, q);
  double e = 0;
  for (int i = 0; i < n; ++i) {
    e = std::max(e, std::abs(tau[i] - tau_loaded[joint[i]]) / std::max(1.0, tau.cwiseAbs().maxCoeff()));
    for (int j = 0; j < n; ++j)
      e = std::max(e, std::abs(M(i, j) - M_loaded(joint[i], joint[j])) / std::max(1.0, M.cwiseAbs().maxCoeff()));
  }
  for (int l = 0; l < m.num_links(); ++l)
    e = std::max({e, (poses[l].R - poses_loaded[link[l]].R).cwiseAbs().maxCoeff(),
                  (poses[l].p - poses_loaded[link[l]].p).cwiseAbs().maxCoeff()});
  return e;
}

TEST(TreeUrdf, ChainLoadsAsTheSameChain) {
  std::mt19937 rng(1504);
  double worst = 0;
  for (int k = 0; k < 20; ++k) {
    const RandomTree t = random_tree(rng, k == 0 ? 1 : std::uniform_int_distribution<int>(1, 60)(rng), true);
    const std::string urdf = tree_urdf(t.links);
    SCOPED_TRACE(urdf);
    const double e = loaded_model_error(t, load_urdf_string(urdf, "l0", t.model.tip_name), rng);
    EXPECT_LE(e, 1e-12);
    worst = std::max(worst, e);
  }
  std::printf("  max rel error of the loaded chains' M, RNEA and link poses %.3g\n", worst);
}

// Needs the loader of whole trees (an empty tip).
TEST(TreeUrdf, WholeTreeLoadsAsTheSameTree) {
  double worst = 0;
  for_random_trees(1505, 20, [&](const RandomTree& t, std::mt19937& rng) {
    const std::string urdf = tree_urdf(t.links);
    SCOPED_TRACE(urdf);
    const double e = loaded_model_error(t, load_urdf_string(urdf, "l0", ""), rng);
    EXPECT_LE(e, 1e-12);
    worst = std::max(worst, e);
  });
  std::printf("  max rel error of the loaded trees' M, RNEA and link poses %.3g\n", worst);
}

TEST(TreeKinematics, LinkJacobianNamesALinkOutOfRange) {
  std::mt19937 rng(1503);
  const RandomTree t = random_tree(rng, 3);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(t.model.num_rates());
  for (const int link : {-1, t.model.num_links()}) {
    try {
      link_jacobian(t.model, q, link);
      ADD_FAILURE() << "no error for link " << link;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("link index " + std::to_string(link)), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace achd::test
