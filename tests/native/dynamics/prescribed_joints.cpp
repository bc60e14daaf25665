// Prescribed joints (Case::qdd_given, Case::prescribed): the hybrid solve against dense
// references. With P the rows of the prescribed joints, the solve is the KKT system
//   [ M   A^T  -P^T ] [ qdd    ]   [ tau_0 - h          ]
//   [ A   0     0   ] [ nu     ] = [ beta - alpha^T b   ]
//   [ P   0     0   ] [ lambda ]   [ qdd_given (P rows) ]
// (M from the reference CRBA, h = the reference RNEA(q, qd, 0), A = alpha^T J, b the tip's
// acceleration at qdd = 0, tau_0 = ff with the prescribed joints' entries ignored), whose
// lambda is Data::prescribed_torques; and joint_torques = RNEA(q, qd, qdd) on every joint.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cstdio>
#include <cstring>
#include <limits>

#include "achd/achd.hpp"
#include "case_json.hpp"
#include "random_chain.hpp"
#include "reference_dynamics.hpp"
#include "reference_kinematics.hpp"

namespace achd::test {
namespace {

// Marks each joint prescribed with probability 1/2 (at least one), with a random qdd.
void prescribe_some(std::mt19937& rng, const Model& m, Case& c) {
  const int n = m.num_rates();
  std::uniform_real_distribution<double> U(-3, 3);
  c.qdd_given = Eigen::VectorXd::Zero(n);
  c.prescribed.assign(n, false);
  for (int i = 0; i < n; ++i) {
    c.prescribed[i] = rng() % 2;
    c.qdd_given[i] = U(rng);
  }
  c.prescribed[rng() % n] = true;
}

struct Dense {
  Eigen::VectorXd qdd, nu, lambda;
  double condition = 0;  // of the coupling of the free joints, A_f M_ff^-1 A_f^T
};

Dense dense_solve(const Model& m, const Case& c) {
  const int n = m.num_rates(), nc = c.num_constraints();
  std::vector<int> given;
  for (int i = 0; i < n; ++i)
    if (!c.prescribed.empty() && c.prescribed[i]) given.push_back(i);
  const int np = static_cast<int>(given.size());
  const Eigen::MatrixXd M = reference_crba(m, c.q);
  const Eigen::VectorXd h = reference_rnea(m, c.q, c.qd, Eigen::VectorXd::Zero(n), c.gravity, c.f_ext);
  const Eigen::MatrixXd A = c.alpha.transpose() * reference_link_jacobian(m, c.q, m.num_links() - 1);
  const Vector6 b = reference_motion(m, c.q, c.qd, Eigen::VectorXd::Zero(n)).back().spatial_acceleration();
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(np, n);
  Eigen::VectorXd tau0 = c.ff_torques;
  for (int k = 0; k < np; ++k) {
    P(k, given[k]) = 1;
    tau0[given[k]] = 0;
  }
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + nc + np, n + nc + np);
  kkt.topLeftCorner(n, n) = M;
  kkt.block(0, n, n, nc) = A.transpose();
  kkt.block(0, n + nc, n, np) = -P.transpose();
  kkt.block(n, 0, nc, n) = A;
  kkt.block(n + nc, 0, np, n) = P;
  Eigen::VectorXd rhs(n + nc + np);
  rhs << tau0 - h, c.beta - c.alpha.transpose() * b, P * c.qdd_given;
  const Eigen::VectorXd x = kkt.fullPivLu().solve(rhs);
  Dense out{x.head(n), x.segment(n, nc), x.tail(np)};
  // The free joints' coupling: the constraint problem the solve is left with.
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (c.prescribed.empty() || !c.prescribed[i]) free.push_back(i);
  if (nc) {
    Eigen::MatrixXd Mff(free.size(), free.size()), Af(nc, free.size());
    for (size_t r = 0; r < free.size(); ++r) {
      Af.col(r) = A.col(free[r]);
      for (size_t s = 0; s < free.size(); ++s) Mff(r, s) = M(free[r], free[s]);
    }
    const Eigen::MatrixXd K = Af * Mff.ldlt().solve(Af.transpose());
    const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(K).singularValues();
    out.condition = sv[nc - 1] > 0 ? sv[0] / sv[nc - 1] : std::numeric_limits<double>::infinity();
  } else {
    out.condition = 1;
  }
  return out;
}

Eigen::VectorXd given_torques(const Case& c, const Data& d) {
  Eigen::VectorXd t(c.prescribed.size());
  int k = 0;
  for (size_t i = 0; i < c.prescribed.size(); ++i)
    if (c.prescribed[i]) t[k++] = d.prescribed_torques[i];
  return t.head(k);
}

TEST(PrescribedJoints, RandomChainsMatchDenseKktAndRnea) {
  std::mt19937 rng(1401);
  int cases = 0;
  double worst_qdd = 0, worst_nu = 0, worst_lambda = 0, worst_rnea = 0;
  for_random_cases(1402, 40, true, [&](const RandomChain& ch, Case c) {
    SCOPED_TRACE(ch.urdf);
    const Model& m = ch.model;
    // Redraw the prescribed set until the free joints can still follow the constraints
    // (a well-conditioned coupling of the free joints; none can when too many are given).
    Dense ref;
    for (int attempt = 0; attempt < 20; ++attempt) {
      prescribe_some(rng, m, c);
      ref = dense_solve(m, c);
      if (ref.condition < 1e4) break;
    }
    if (!(ref.condition < 1e4)) return;
    Data d(m);
    hybrid_dynamics(m, d, c);
    for (int i = 0; i < m.num_rates(); ++i) {
      if (c.prescribed[i]) EXPECT_EQ(d.qdd[i], c.qdd_given[i]) << "joint " << i;
      else EXPECT_EQ(d.prescribed_torques[i], 0.0) << "joint " << i;
    }
    const Eigen::VectorXd rnea = reference_rnea(m, c.q, c.qd, d.qdd, c.gravity, c.f_ext);
    const double e_qdd = rel_error(d.qdd, ref.qdd), e_nu = rel_error(d.nu, ref.nu),
                 e_lambda = rel_error(given_torques(c, d), ref.lambda), e_rnea = rel_error(d.joint_torques, rnea);
    EXPECT_LE(e_qdd, 1e-8);
    EXPECT_LE(e_nu, 1e-8);
    EXPECT_LE(e_lambda, 1e-8);
    EXPECT_LE(e_rnea, 1e-10);
    worst_qdd = std::max(worst_qdd, e_qdd);
    worst_nu = std::max(worst_nu, e_nu);
    worst_lambda = std::max(worst_lambda, e_lambda);
    worst_rnea = std::max(worst_rnea, e_rnea);
    ++cases;
  });
  std::printf("  %d cases: qdd vs KKT %.3g, nu %.3g, prescribed_torques %.3g, joint_torques vs RNEA %.3g\n", cases,
              worst_qdd, worst_nu, worst_lambda, worst_rnea);
  EXPECT_GE(cases, 100);
}

// With damping and friction on, a prescribed joint's torque includes what they take:
// joint_torques (prescribed_torques in place of ff) is still RNEA with those terms.
TEST(PrescribedJoints, PassiveTermsAreInThePrescribedTorques) {
  std::mt19937 rng(1410);
  int cases = 0;
  double worst = 0;
  for_random_cases(1404, 20, true, [&](const RandomChain& ch, Case c) {
    const Model& m = ch.model;
    prescribe_some(rng, m, c);
    if (!(dense_solve(m, c).condition < 1e4)) return;
    Options o;
    o.effects = kAllEffects;
    Data d(m);
    hybrid_dynamics(m, d, c, o);
    const Eigen::VectorXd rnea =
        reference_rnea(m, c.q, c.qd, d.qdd, c.gravity, c.f_ext, kAllEffects, o.friction_velocity);
    const double e = rel_error(d.joint_torques, rnea);
    EXPECT_LE(e, 1e-10) << ch.urdf;
    worst = std::max(worst, e);
    ++cases;
  });
  std::printf("  %d cases: joint_torques vs RNEA with damping and friction %.3g\n", cases, worst);
  EXPECT_GE(cases, 50);
}

// A prescribed joint's torque, given back as its ff_torques with the joint free, gives the
// same solve (where the free joints alone can satisfy the constraints).
TEST(PrescribedJoints, PrescribedTorqueAsFeedForwardGivesTheSameSolve) {
  std::mt19937 rng(1403);
  int cases = 0;
  for_random_cases(1404, 20, true, [&](const RandomChain& ch, Case c) {
    const Model& m = ch.model;
    prescribe_some(rng, m, c);
    if (!(dense_solve(m, c).condition < 1e4)) return;
    Data d(m), free(m);
    hybrid_dynamics(m, d, c);
    Case f = c;
    for (int i = 0; i < m.num_rates(); ++i)
      if (c.prescribed[i]) f.ff_torques[i] = d.prescribed_torques[i];
    f.qdd_given.resize(0);
    f.prescribed.clear();
    hybrid_dynamics(m, free, f);
    EXPECT_LE(rel_error(free.qdd, d.qdd), 1e-8) << ch.urdf;
    EXPECT_LE(rel_error(free.nu, d.nu), 1e-8) << ch.urdf;
    EXPECT_LE(rel_error(free.joint_torques, d.joint_torques), 1e-8) << ch.urdf;
    ++cases;
  });
  EXPECT_GE(cases, 50);
}

// Every joint prescribed: inverse dynamics. The constraints have no joint left to act
// through (K = 0, nu = 0), and prescribed_torques = joint_torques = RNEA(q, qd, qdd_given).
TEST(PrescribedJoints, EveryJointPrescribedIsInverseDynamics) {
  std::mt19937 rng(1405);
  int cases = 0;
  double worst = 0;
  for_random_cases(1406, 40, true, [&](const RandomChain& ch, Case c) {
    const Model& m = ch.model;
    const int n = m.num_rates();
    prescribe_some(rng, m, c);
    c.prescribed.assign(n, true);
    const Eigen::VectorXd rnea = reference_rnea(m, c.q, c.qd, c.qdd_given, c.gravity, c.f_ext);
    // Under both policies (the damped one's lambda is 0 for K = 0).
    for (const SingularityPolicy policy : {SingularityPolicy::Truncate, SingularityPolicy::Damped}) {
      Options o;
      o.policy = policy;
      Data d(m);
      hybrid_dynamics(m, d, c, o);
      EXPECT_EQ(d.qdd, c.qdd_given);
      const double e = rel_error(d.prescribed_torques, rnea);
      EXPECT_LE(e, 1e-12) << ch.urdf;
      EXPECT_EQ(d.prescribed_torques, d.joint_torques);
      EXPECT_EQ(d.rank, 0);
      for (int k = 0; k < c.num_constraints(); ++k) EXPECT_EQ(d.nu[k], 0.0);
      worst = std::max(worst, e);
    }
    ++cases;
  });
  std::printf("  %d cases: prescribed_torques vs reference RNEA %.3g\n", cases, worst);
}

void expect_same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  EXPECT_EQ(std::memcmp(a.data(), b.data(), sizeof(double) * a.size()), 0) << what;
}

// No joint prescribed (an all-false mask, whatever qdd_given holds) is the solve without
// the fields, bit for bit, under both policies.
TEST(PrescribedJoints, NoJointPrescribedIsTheSolveWithoutTheFields) {
  std::mt19937 rng(1407);
  int cases = 0;
  for_random_cases(1408, 20, true, [&](const RandomChain& ch, const Case& c) {
    const Model& m = ch.model;
    for (const SingularityPolicy policy : {SingularityPolicy::Truncate, SingularityPolicy::Damped}) {
      Options o;
      o.policy = policy;
      o.effects = kAllEffects;
      Case none = c;
      prescribe_some(rng, m, none);
      none.prescribed.assign(m.num_rates(), false);
      Data a(m), b(m);
      hybrid_dynamics(m, a, c, o);
      hybrid_dynamics(m, b, none, o);
      expect_same_bits(a.qdd, b.qdd, "qdd");
      expect_same_bits(a.joint_torques, b.joint_torques, "joint_torques");
      expect_same_bits(a.constraint_torques, b.constraint_torques, "constraint_torques");
      expect_same_bits(a.total_torques, b.total_torques, "total_torques");
      ASSERT_EQ(a.nu.size(), b.nu.size());
      EXPECT_EQ(std::memcmp(a.nu.data(), b.nu.data(), sizeof(double) * a.nu.size()), 0);
      EXPECT_EQ(b.prescribed_torques, Eigen::VectorXd::Zero(m.num_rates()));
      ++cases;
    }
  });
  EXPECT_GE(cases, 100);
}

// A solve into a Data that held a prescribed solve leaves no prescribed torque behind.
TEST(PrescribedJoints, DataReusedWithoutPrescriptionHasZeroPrescribedTorques) {
  std::mt19937 rng(1409);
  const RandomChain ch = random_chain(rng, 6, false);
  Case c = random_case(rng, ch.model, 0);
  Data d(ch.model);
  prescribe_some(rng, ch.model, c);
  hybrid_dynamics(ch.model, d, c);
  EXPECT_NE(d.prescribed_torques, Eigen::VectorXd::Zero(ch.model.num_rates()));
  c.prescribed.clear();
  c.qdd_given.resize(0);
  hybrid_dynamics(ch.model, d, c);
  EXPECT_EQ(d.prescribed_torques, Eigen::VectorXd::Zero(ch.model.num_rates()));
}

Model lwr() { return load_urdf_file(ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7"); }

std::string error_of(const Model& m, const Case& c) {
  Data d(m);
  try {
    hybrid_dynamics(m, d, c);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PrescribedJoints, BadFieldsAreNamed) {
  const Model m = lwr();
  Case c = Case::zeros(m);
  c.qdd_given = Eigen::VectorXd::Zero(7);
  c.prescribed.assign(7, false);
  c.prescribed[2] = true;
  EXPECT_EQ(error_of(m, c), "(no error)");
  Case bad = c;
  bad.qdd_given[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of(m, bad), "qdd_given[4] (joint 'lwr_joint_5') is not finite");
  bad = c;
  bad.qdd_given = Eigen::VectorXd::Zero(6);
  EXPECT_EQ(error_of(m, bad), "qdd_given: expected 7 values (one per joint), got 6");
  bad = c;
  bad.prescribed.assign(8, true);
  EXPECT_EQ(error_of(m, bad), "prescribed: expected 7 flags (one per joint), got 8");
  bad = c;
  bad.prescribed.clear();
  EXPECT_EQ(error_of(m, bad), "qdd_given is set but prescribed (which joints it prescribes) is empty");
  bad = c;
  bad.qdd_given.resize(0);
  EXPECT_EQ(error_of(m, bad), "prescribed is set but qdd_given (their accelerations) is empty");
}

std::string json_error(const Model& m, const std::string& text) {
  try {
    cli::parse_case(text, m, "c.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PrescribedJoints, CaseJsonByNameOrArray) {
  const Model m = lwr();
  const std::string q = R"("q": [0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1], "gravity": [0, 0, -9.81])";
  const Case by_name = cli::parse_case("{" + q + R"(, "qdd_given": {"lwr_joint_2": 1.5, "lwr_joint_5": -0.7}})", m, "c");
  const Case by_index = cli::parse_case("{" + q + R"(, "qdd_given": [null, 1.5, null, null, -0.7, null, null]})", m, "c");
  const std::vector<bool> mask = {false, true, false, false, true, false, false};
  EXPECT_EQ(by_name.prescribed, mask);
  EXPECT_EQ(by_index.prescribed, mask);
  EXPECT_EQ(by_name.qdd_given, by_index.qdd_given);
  EXPECT_EQ(by_name.qdd_given[1], 1.5);
  EXPECT_EQ(by_name.qdd_given[4], -0.7);
  Data d(m);
  hybrid_dynamics(m, d, by_name);
  const std::string out = cli::result_json(m, d, by_name);
  EXPECT_NE(out.find("\"prescribed_torques\": [null, "), std::string::npos) << out;
  const Case plain = cli::parse_case("{" + q + "}", m, "c");
  hybrid_dynamics(m, d, plain);
  EXPECT_EQ(cli::result_json(m, d, plain).find("prescribed_torques"), std::string::npos);

  EXPECT_EQ(json_error(m, "{" + q + R"(, "qdd_given": {"elbow": 1}})"),
            "c.json: qdd_given: no movable joint 'elbow' between the root and the tip");
  EXPECT_EQ(json_error(m, "{" + q + R"(, "qdd_given": {"lwr_joint_3": "fast"}})"),
            "c.json: qdd_given['lwr_joint_3'] must be a number");
  EXPECT_EQ(json_error(m, "{" + q + R"(, "qdd_given": [null, 1]})"),
            "c.json: qdd_given: expected 7 values (one per joint, null where not prescribed), got 2");
  EXPECT_EQ(json_error(m, "{" + q + R"(, "qdd_given": [null, null, true, null, null, null, null]})"),
            "c.json: qdd_given[2] (joint 'lwr_joint_3') must be a number");
  EXPECT_EQ(json_error(m, "{" + q + R"(, "qdd_given": 3})"),
            "c.json: qdd_given must be an object {joint name: acceleration} or an array of 7 numbers or nulls "
            "(null: the joint is not prescribed)");
}

}  // namespace
}  // namespace achd::test
