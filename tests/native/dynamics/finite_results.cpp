// Every number a solve returns is finite, or the solve throws an achd::Error that names
// the cause. Finite inputs that overflow inside the sweeps (velocities near 1e155,
// torques near 1e308, links so light that 1 / D overflows) must fail with a message
// naming the joint; constraint columns of any scale must give the same motion (the solve
// scales each column by a power of two, exactly).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "achd/achd.hpp"
#include "hard_chain_urdf.hpp"
#include "random_chain.hpp"

namespace achd::test {
namespace {

const std::string kLwr = std::string(ACHD_SOURCE_DIR) + "/robots/kuka_lwr4.urdf";

Model lwr() { return load_urdf_file(kLwr, "lwr_base_link", "lwr_link_7"); }

Case lwr_case(const Model& model) {
  Case c = Case::zeros(model);
  c.q << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  return c;
}

bool all_finite(const Model& model, const Data& d) {
  bool ok = d.qdd.allFinite() && d.joint_torques.allFinite() && d.constraint_torques.allFinite() &&
            d.total_torques.allFinite() && d.nu.allFinite() && d.constraint_wrench.allFinite() &&
            std::isfinite(sigma_min(d));
  for (int l = 0; l <= model.num_links(); ++l) ok = ok && d.link_accelerations[l].allFinite();
  return ok;
}

// The solve either returns finite numbers everywhere or throws an achd::Error whose
// message contains `names` (a joint, a field); returns the message ("" on success).
std::string finite_or_named(const Model& model, const Case& c, const std::string& names,
                            const Options& o = {}) {
  Data d(model);
  try {
    hybrid_dynamics(model, d, c, o);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(names), std::string::npos) << e.what();
    return e.what();
  }
  EXPECT_TRUE(all_finite(model, d));
  return "";
}

TEST(FiniteResults, JointVelocitiesWhoseProductsOverflowNameTheJoint) {
  const Model model = lwr();
  // Before: qdd, torques and link accelerations NaN, exit 0 from the CLI.
  for (double qd : {1e155, 1e200, 1e300}) {
    Case c = lwr_case(model);
    c.qd = Eigen::VectorXd::Zero(7);
    c.qd[0] = c.qd[6] = qd;
    const std::string msg = finite_or_named(model, c, "joint 'lwr_joint_");
    EXPECT_NE(msg.find("overflows"), std::string::npos) << qd;
  }
  // Large but representable: finite answers.
  Case c = lwr_case(model);
  c.qd = Eigen::VectorXd::Constant(7, 1e50);
  EXPECT_EQ(finite_or_named(model, c, "joint"), "");
}

TEST(FiniteResults, TorquesNearTheLargestDoubleNameTheJoint) {
  const Model model = lwr();
  Case c = lwr_case(model);
  c.ff_torques = Eigen::VectorXd::Zero(7);
  c.ff_torques << 1e308, 1e308, 0, 0, 0, 0, -1e308;
  const std::string msg = finite_or_named(model, c, "joint 'lwr_joint_");
  EXPECT_NE(msg.find("ff_torques"), std::string::npos) << msg;
  c.ff_torques.setConstant(1e300);  // huge, the answer still fits: finite
  c.f_ext.assign(model.num_links(), Vector6::Constant(1e300));
  finite_or_named(model, c, "joint 'lwr_joint_");
}

TEST(FiniteResults, EveryHugeInputGivesFiniteNumbersOrANamedError) {
  const Model model = lwr();
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int exponent = 0; exponent <= 308; exponent += 11) {
    const double big = std::pow(10.0, exponent);
    for (int field = 0; field < 5; ++field) {
      Case c = lwr_case(model);
      c.alpha = Eigen::Matrix<double, 6, 2>::Zero();
      c.alpha(2, 0) = c.alpha(3, 1) = 1;
      c.beta = Eigen::Vector2d::Zero();
      for (int i = 0; i < 7; ++i) c.q[i] += unit(rng);
      if (field == 0) c.qd = Eigen::VectorXd::Constant(7, big * unit(rng));
      if (field == 1) c.ff_torques = Eigen::VectorXd::Constant(7, big * unit(rng));
      if (field == 2) c.f_ext.assign(model.num_links(), Vector6::Constant(big * unit(rng)));
      if (field == 3) c.gravity = Vector3::Constant(big * unit(rng));
      if (field == 4) c.beta = Eigen::Vector2d(big, -big);
      for (const SingularityPolicy policy : {SingularityPolicy::Truncate, SingularityPolicy::Damped}) {
        Options o;
        o.policy = policy;
        finite_or_named(model, c, "overflows", o);
      }
    }
  }
}

// mass 1e-300 kg with inertia 1e-310 kg m^2, or a denormal mass: D > 0, but 1 / D
// overflows (before: qdd NaN, exit 0).
TEST(FiniteResults, LinksTooLightToInvertNameTheJoint) {
  for (const auto& [mass, inertia] : {std::pair{1e-300, 1e-310}, std::pair{4e-320, 4e-320}}) {
    std::vector<LinkSpec> links(3);
    for (auto& l : links) l.joint_xyz = {0, 0, 0.3};
    links[1].axis = {0, 1, 0};
    links[2].mass = mass;
    links[2].inertia_diag = {inertia, inertia, inertia};
    links[0].mass = links[1].mass = mass;
    links[0].inertia_diag = links[1].inertia_diag = {inertia, inertia, inertia};
    Model model;
    try {
      model = load_urdf_string(chain_urdf(links), "link0", "link3");
    } catch (const Error& e) {
      // A loader that refuses the robot must name the joint too.
      EXPECT_NE(std::string(e.what()).find("joint 'j"), std::string::npos) << e.what();
      continue;
    }
    Case c = Case::zeros(model);
    c.q << 0.1, 0.2, 0.3;
    c.alpha = Eigen::Matrix<double, 6, 1>::Unit(0);
    c.beta = Eigen::VectorXd::Zero(1);
    finite_or_named(model, c, "joint 'j");
  }
}

// Scaling alpha column k and beta_k by s: same qdd and rank, nu_k scaled by 1 / s. For
// powers of two the solve is the same to the bit (the internal scaling is exact); for
// any other s it agrees to round-off. Before: a column of 1e-160 gave nu = -inf and NaN
// everywhere; 1e-200 or 1e160 dropped the constraint with rank 0.
TEST(FiniteResults, AConstraintColumnsScaleDoesNotChangeTheMotion) {
  int checked = 0;
  for_random_cases(1313, 12, true, [&](const RandomChain& chain, const Case& c) {
    const int nc = c.num_constraints();
    if (nc == 0) return;
    const Model& model = chain.model;
    Data ref(model);
    hybrid_dynamics(model, ref, c, {});
    for (const double s : {0x1p-600, 0x1p-1, 0x1p+3, 0x1p+700, 1e-160, 1e-200, 3.0, 1e160, 1e300}) {
      const int k = checked % nc;
      Case scaled = c;
      scaled.alpha.col(k) *= s;
      scaled.beta[k] *= s;
      Data d(model);
      hybrid_dynamics(model, d, scaled, {});
      ++checked;
      ASSERT_EQ(d.rank, ref.rank) << s;
      Eigen::VectorXd nu = d.nu;
      nu[k] *= s;
      if (std::exp2(std::round(std::log2(s))) == s) {
        EXPECT_EQ(d.qdd, ref.qdd) << s;  // bit for bit
        EXPECT_EQ(nu, ref.nu) << s;
        EXPECT_EQ(d.joint_torques, ref.joint_torques) << s;
      } else {
        EXPECT_LE(rel_error(d.qdd, ref.qdd), 1e-12) << s;
        EXPECT_LE(rel_error(nu, ref.nu), 1e-12) << s;
        EXPECT_LE(rel_error(d.joint_torques, ref.joint_torques), 1e-12) << s;
      }
    }
  });
  EXPECT_GE(checked, 100);
}

// sigma_min is computed on the coupling matrix of the scaled columns: finite even where
// K's entries would overflow when squared.
TEST(FiniteResults, SigmaMinIsFiniteForVeryLightRobots) {
  std::vector<LinkSpec> links(3);
  for (auto& l : links) {
    l.joint_xyz = {0, 0, 0.3};
    l.mass = 1e-250;
    l.inertia_diag = {1e-251, 1e-251, 1e-251};
  }
  links[1].axis = {0, 1, 0};
  const Model model = load_urdf_string(chain_urdf(links), "link0", "link3");
  Case c = Case::zeros(model);
  c.q << 0.1, 0.5, 0.3;
  c.alpha = Eigen::Matrix<double, 6, 3>::Zero();
  c.alpha(0, 0) = c.alpha(2, 1) = c.alpha(4, 2) = 1;
  c.beta = Eigen::Vector3d::Zero();
  Data d(model);
  hybrid_dynamics(model, d, c, {});
  const double s = sigma_min(d);
  EXPECT_TRUE(std::isfinite(s) && s > 0) << s;
  // K ~ 1 / mass: sigma_min within a modest factor of K's scale, not 0 or inf
  EXPECT_GT(s, 1e200);
}

}  // namespace
}  // namespace achd::test
