// Parity with KDL's ChainHdSolver_Vereshchagin (Debian liborocos-kdl 1.5.1), achd in the
// kdl convention: the same URDF text through kdl_parser, root_acc = -g, alpha as a
// KDL::Jacobian (linear rows first), beta_kdl, f_ext as base-oriented KDL::Wrenches.
// Every robot of robots/index.json without fixed joints, and random chains without
// fixed joints (KDL needs one joint per segment).
#include <gtest/gtest.h>

#include <cstdio>
#include <optional>

#include <kdl/chainhdsolver_vereshchagin.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include "random_chain.hpp"
#include "robot_index.hpp"

namespace achd::test {
namespace {

struct Worst {
  double qdd = 0, ct = 0, tt = 0, nu = 0, acc = 0;
  int cases = 0;
  void print(const char* what) const {
    std::printf("  %s: %d cases, max rel error qdd %.3g, constraint_torques %.3g, "
                "total_torques %.3g, nu %.3g, link accelerations %.3g\n",
                what, cases, qdd, ct, tt, nu, acc);
  }
};

Eigen::VectorXd twists(const std::vector<KDL::Twist>& t) {
  Eigen::VectorXd r(6 * t.size());
  for (size_t i = 0; i < t.size(); ++i)
    for (int k = 0; k < 6; ++k) r[6 * i + k] = t[i](k);  // KDL: linear first
  return r;
}

Eigen::VectorXd stack(const std::vector<Vector6>& v) {
  Eigen::VectorXd r(6 * v.size());
  for (size_t i = 0; i < v.size(); ++i) r.segment<6>(6 * i) = v[i];
  return r;
}

// Solves `c` (physical beta) with KDL and with achd (convention kdl) and compares.
void compare(const std::string& urdf, const std::string& root, const std::string& tip,
             const Model& model, const Case& c, Worst& w) {
  KDL::Tree tree;
  ASSERT_TRUE(kdl_parser::treeFromString(urdf, tree));
  KDL::Chain chain;
  ASSERT_TRUE(tree.getChain(root, tip, chain));
  const int n = model.num_rates(), nc = c.num_constraints();
  ASSERT_EQ(static_cast<int>(chain.getNrOfJoints()), n);
  ASSERT_EQ(static_cast<int>(chain.getNrOfSegments()), model.num_links());

  Case kc = c;  // achd in KDL's convention: beta_kdl = beta - alpha_lin^T g
  kc.beta = c.beta - c.alpha.topRows<3>().transpose() * c.gravity;
  KDL::ChainHdSolver_Vereshchagin solver(
      chain, KDL::Twist(KDL::Vector(-c.gravity.x(), -c.gravity.y(), -c.gravity.z()),
                        KDL::Vector::Zero()),
      nc);
  KDL::JntArray q(n), qd(n), qdd(n), ff(n), ct(n), tt(n), beta(nc);
  q.data = c.q;
  qd.data = c.qd;
  ff.data = c.ff_torques;
  beta.data = kc.beta;
  KDL::Jacobian alpha(nc);
  alpha.data = c.alpha;
  KDL::Wrenches f_ext(model.num_links());
  for (int l = 0; l < model.num_links(); ++l)
    f_ext[l] = KDL::Wrench(KDL::Vector(c.f_ext[l][0], c.f_ext[l][1], c.f_ext[l][2]),
                           KDL::Vector(c.f_ext[l][3], c.f_ext[l][4], c.f_ext[l][5]));
  ASSERT_GE(solver.CartToJnt(q, qd, qdd, alpha, beta, f_ext, ff, ct), 0);
  solver.getTotalTorque(tt);
  Eigen::VectorXd nu(nc);
  solver.getContraintForceMagnitude(nu);
  std::vector<KDL::Twist> acc(model.num_links() + 1);
  solver.getTransformedLinkAcceleration(acc);

  Options o;
  o.convention = Convention::Kdl;
  Data d(model);
  hybrid_dynamics(model, d, kc, o);
  const double e[5] = {rel_error(d.qdd, qdd.data), rel_error(d.constraint_torques, ct.data),
                       rel_error(d.total_torques, tt.data), rel_error(d.nu, nu.head(nc)),
                       rel_error(stack(d.link_accelerations), twists(acc))};
  const char* names[5] = {"qdd", "constraint_torques", "total_torques", "nu",
                          "link_accelerations"};
  for (int k = 0; k < 5; ++k) EXPECT_LE(e[k], 1e-9) << names[k] << ", nc " << nc;
  w.qdd = std::max(w.qdd, e[0]);
  w.ct = std::max(w.ct, e[1]);
  w.tt = std::max(w.tt, e[2]);
  w.nu = std::max(w.nu, e[3]);
  w.acc = std::max(w.acc, e[4]);
  ++w.cases;
}

TEST(KdlParity, RobotsWithoutFixedJoints) {
  std::mt19937 rng(606);
  int robots = 0;
  for (const IndexedRobot& r : load_robot_index(ACHD_SOURCE_DIR)) {
    if (r.has_fixed_joints()) continue;
    ++robots;
    SCOPED_TRACE(r.name);
    Worst w;
    // At most as many constraints as the tip Jacobian's rank at q0 (planar2: 2).
    for (int nc = 0; nc <= tip_jacobian_rank(r.model, r.q0); ++nc) {
      for (const bool standard_gravity : {true, false}) {
        const std::optional<Case> c = case_at(rng, r.model, r.q0, nc, standard_gravity);
        if (!c) {
          std::printf("  %s: nc %d: no case with condition < 1e4 in 100 draws (hard cases)\n",
                      r.name.c_str(), nc);
          continue;
        }
        compare(r.urdf, r.root, r.tip, r.model, *c, w);
      }
    }
    w.print(r.name.c_str());
    EXPECT_GT(w.cases, 0);
  }
  EXPECT_GE(robots, 4);
}

TEST(KdlParity, RandomChainsWithoutFixedJoints) {
  Worst w;
  for_random_cases(707, 30, false, [&](const RandomChain& ch, const Case& c) {
    compare(ch.urdf, ch.root, ch.tip, ch.model, c, w);
  });
  w.print("random chains");
}

}  // namespace
}  // namespace achd::test
