// Case::extra_inertia: added to each joint's D where the rotor inertia is, so a solve with
// extra inertia e is, to the bit, the solve on a model whose rotor inertias are r + e
// (rotor inertia on); the textbook reference solves it too; bad entries are named.
#include <gtest/gtest.h>

#include <limits>

#include "achd/achd.hpp"
#include "random_chain.hpp"

namespace achd::test {
namespace {

// Joint i prescribed with probability 1/3, with a random qdd.
void prescribe_some(std::mt19937& rng, const Model& m, Case& c) {
  const int n = m.num_rates();
  c.qdd_given = Eigen::VectorXd::Zero(n);
  c.prescribed.assign(n, false);
  for (int i = 0; i < n; ++i) {
    c.prescribed[i] = rng() % 3 == 0;
    c.qdd_given[i] = uniform(rng, -3, 3);
  }
}

TEST(ExtraInertia, IsTheRotorInertiaOfAModelCopy) {
  std::mt19937 rng(2401);
  int cases = 0;
  for_random_cases(2402, 20, true, [&](const RandomChain& ch, Case c) {
    const Model& m = ch.model;
    if (rng() % 2) prescribe_some(rng, m, c);
    Model heavier = m;
    c.extra_inertia = Eigen::VectorXd::Zero(m.num_rates());
    for (int i = 0; i < m.num_rates(); ++i) {
      c.extra_inertia[i] = uniform(rng, 0, 0.5);
      heavier.bodies[i].rotor_inertia = m.bodies[i].rotor_inertia + c.extra_inertia[i];
    }
    Options o;
    o.effects = kAllEffects;
    Data d(m), expected(m);
    hybrid_dynamics(m, d, c, o);
    Case plain = c;
    plain.extra_inertia.resize(0);
    hybrid_dynamics(heavier, expected, plain, o);
    EXPECT_EQ(d.qdd, expected.qdd) << ch.urdf;
    EXPECT_EQ(d.nu, expected.nu) << ch.urdf;
    EXPECT_EQ(d.joint_torques, expected.joint_torques) << ch.urdf;
    EXPECT_EQ(d.prescribed_torques, expected.prescribed_torques) << ch.urdf;
    // without rotor inertia, the extra inertia alone
    o.effects = kAllEffects & ~kRotorInertia;
    for (Body& b : heavier.bodies) b.rotor_inertia = 0;
    for (int i = 0; i < m.num_rates(); ++i) heavier.bodies[i].rotor_inertia = c.extra_inertia[i];
    hybrid_dynamics(m, d, c, o);
    o.effects |= kRotorInertia;
    hybrid_dynamics(heavier, expected, plain, o);
    EXPECT_EQ(d.qdd, expected.qdd) << ch.urdf;
    ++cases;
  });
  EXPECT_GE(cases, 50);
}

TEST(ExtraInertia, TheReferenceSolvesIt) {
  std::mt19937 rng(2403);
  double worst = 0;
  for_random_cases(2404, 20, true, [&](const RandomChain& ch, Case c) {
    const Model& m = ch.model;
    if (rng() % 2) prescribe_some(rng, m, c);
    c.extra_inertia = Eigen::VectorXd::Zero(m.num_rates());
    for (int i = 0; i < m.num_rates(); ++i) c.extra_inertia[i] = uniform(rng, 0, 0.5);
    Options o;
    o.effects = kAllEffects;
    Data d(m);
    hybrid_dynamics(m, d, c, o);
    const ReferenceSolution r = pv_reference(m, c, o);
    const double e = std::max(rel_error(d.qdd, r.qdd), rel_error(d.prescribed_torques, r.prescribed_torques));
    EXPECT_LE(e, 1e-8) << ch.urdf;
    worst = std::max(worst, e);
  });
  std::printf("  hybrid_dynamics vs pv_reference with extra inertia: %.3g\n", worst);
}

std::string error_of(const Model& m, const Case& c) {
  try {
    validate(m, c);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ExtraInertia, BadEntriesAreNamed) {
  const Model m = load_urdf_file(ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  Case c = Case::zeros(m);
  c.extra_inertia = Eigen::VectorXd::Constant(7, 0.1);
  EXPECT_EQ(error_of(m, c), "(no error)");
  Case bad = c;
  bad.extra_inertia = Eigen::VectorXd::Zero(6);
  EXPECT_EQ(error_of(m, bad), "extra_inertia: expected 7 values (one per joint) or none, got 6");
  bad = c;
  bad.extra_inertia[3] = -1;
  EXPECT_EQ(error_of(m, bad), "extra_inertia[3] (joint 'lwr_joint_4') must be finite and >= 0, got -1.000000");
  bad.extra_inertia[3] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_of(m, bad), "extra_inertia[3] (joint 'lwr_joint_4') must be finite and >= 0, got inf");
}

}  // namespace
}  // namespace achd::test
