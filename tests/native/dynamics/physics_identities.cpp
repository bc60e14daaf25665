// Physics identities of the hybrid solver on random chains (random_chain.hpp), with the
// relative error of docs/design.md section 4.6: the solver agrees with the reference RNEA
// (reference_dynamics.hpp, which shares no kernel with it), its constraint outputs
// satisfy the constraints, and its accelerations agree with a separate point-velocity
// kinematics sweep (reference_kinematics.hpp). achd's own rnea, crba, link_velocities,
// tip_jacobian and forward_kinematics, in both their forms, agree with the references.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include <Eigen/Geometry>

#include "random_chain.hpp"
#include "reference_dynamics.hpp"
#include "reference_kinematics.hpp"

namespace achd::test {
namespace {

constexpr int kChains = 40;

Eigen::VectorXd stack(const std::vector<Vector6>& v) {
  Eigen::VectorXd r(6 * v.size());
  for (size_t i = 0; i < v.size(); ++i) r.segment<6>(6 * i) = v[i];
  return r;
}

void report(const char* what, double max_error, int cases) {
  std::printf("  max rel error %-46s %.3g over %d cases\n", what, max_error, cases);
}

// With no constraints, the reference RNEA(q, qd, qdd; g, f_ext) returns the applied torques; and f_ext
// acts exactly like the joint torques sum_l J_l^T f_l (J_l from the reference sweep).
TEST(Unconstrained, RneaReproducesAppliedTorquesAndWrenches) {
  double worst_rnea = 0, worst_wrench = 0;
  int cases = 0;
  for_random_cases(101, kChains, true, [&](const RandomChain& ch, const Case& c) {
    if (c.num_constraints()) return;
    const Model& m = ch.model;
    Data d(m);
    hybrid_dynamics(m, d, c);
    const Eigen::VectorXd qdd = d.qdd;
    const double e1 = rel_error(reference_rnea(m, c.q, c.qd, qdd, c.gravity, c.f_ext), c.ff_torques);
    Case no_wrench = c;
    no_wrench.f_ext.clear();
    for (int l = 0; l < m.num_links(); ++l)
      no_wrench.ff_torques += reference_link_jacobian(m, c.q, l).transpose() * c.f_ext[l];
    hybrid_dynamics(m, d, no_wrench);
    const double e2 = rel_error(d.qdd, qdd);
    EXPECT_LE(e1, 1e-10) << ch.urdf;
    EXPECT_LE(e2, 1e-10) << ch.urdf;
    worst_rnea = std::max(worst_rnea, e1);
    worst_wrench = std::max(worst_wrench, e2);
    ++cases;
  });
  report("reference RNEA(qdd) vs ff", worst_rnea, cases);
  report("qdd(f_ext) vs qdd(ff + J^T f_ext)", worst_wrench, cases);
}

// alpha^T a_tip == beta: physical (real acceleration), and kdl with
// beta_kdl = beta - alpha_lin^T g against KDL's accelerations a - [g; 0].
TEST(Constrained, TipAccelerationMeetsBetaInBothConventions) {
  double worst_phys = 0, worst_kdl = 0;
  int cases = 0;
  for_random_cases(202, kChains, true, [&](const RandomChain& ch, const Case& c) {
    const int nc = c.num_constraints();
    if (!nc) return;
    const Model& m = ch.model;
    Data d(m);
    hybrid_dynamics(m, d, c);
    const double e1 = rel_error(c.alpha.transpose() * d.link_accelerations.back(), c.beta);
    Case kdl = c;
    kdl.beta = c.beta - c.alpha.topRows<3>().transpose() * c.gravity;
    Options o;
    o.convention = Convention::Kdl;
    hybrid_dynamics(m, d, kdl, o);
    const double e2 = rel_error(c.alpha.transpose() * d.link_accelerations.back(), kdl.beta);
    EXPECT_LE(e1, 1e-10) << "nc " << nc << "\n" << ch.urdf;
    EXPECT_LE(e2, 1e-10) << "nc " << nc << "\n" << ch.urdf;
    worst_phys = std::max(worst_phys, e1);
    worst_kdl = std::max(worst_kdl, e2);
    ++cases;
  });
  report("alpha^T a_tip vs beta (physical)", worst_phys, cases);
  report("alpha^T a_tip vs beta_kdl (kdl)", worst_kdl, cases);
}

// joint_torques == reference RNEA(q, qd, qdd; g, f_ext) == ff - J^T alpha nu; the free robot driven
// by joint_torques moves with the same qdd; constraint_wrench == alpha nu.
TEST(Constrained, JointTorquesAreTheTorquesThatProduceTheMotion) {
  double worst_rnea = 0, worst_jt = 0, worst_free = 0, worst_wrench = 0;
  int cases = 0;
  for_random_cases(303, kChains, true, [&](const RandomChain& ch, const Case& c) {
    const Model& m = ch.model;
    Data d(m);
    hybrid_dynamics(m, d, c);
    const Eigen::VectorXd qdd = d.qdd, tau = d.joint_torques;
    const Eigen::VectorXd nu = d.nu;
    const Eigen::MatrixXd J = tip_jacobian(m, c.q);
    const double e1 = rel_error(tau, reference_rnea(m, c.q, c.qd, qdd, c.gravity, c.f_ext));
    const double e2 = rel_error(tau, c.ff_torques - J.transpose() * (c.alpha * nu));
    const double e4 = rel_error(d.constraint_wrench, c.alpha * nu);
    Case free = c;
    free.alpha.resize(6, 0);
    free.beta.resize(0);
    free.ff_torques = tau;
    hybrid_dynamics(m, d, free);
    const double e3 = rel_error(d.qdd, qdd);
    EXPECT_LE(e1, 1e-10) << ch.urdf;
    EXPECT_LE(e2, 1e-10) << ch.urdf;
    EXPECT_LE(e3, 1e-10) << ch.urdf;
    EXPECT_LE(e4, 1e-12);
    worst_rnea = std::max(worst_rnea, e1);
    worst_jt = std::max(worst_jt, e2);
    worst_free = std::max(worst_free, e3);
    worst_wrench = std::max(worst_wrench, e4);
    ++cases;
  });
  report("joint_torques vs reference RNEA(qdd)", worst_rnea, cases);
  report("joint_torques vs ff - J^T alpha nu", worst_jt, cases);
  report("qdd(free, joint_torques) vs qdd", worst_free, cases);
  report("constraint_wrench vs alpha nu", worst_wrench, cases);
}

// Every link's spatial acceleration equals [vdot - w x v; wdot] of the reference sweep
// driven by the solver's qdd (plus [g; 0] below it in the kdl convention); the tip
// Jacobian, link poses and link velocities agree with the reference kinematics.
TEST(Kinematics, LinkAccelerationsPosesAndJacobianMatchReferenceSweep) {
  double worst_acc = 0, worst_kdl = 0, worst_jac = 0, worst_pose = 0, worst_vel = 0;
  int cases = 0;
  for_random_cases(404, kChains, true, [&](const RandomChain& ch, const Case& c) {
    const Model& m = ch.model;
    Data d(m);
    hybrid_dynamics(m, d, c);
    const std::vector<FrameMotion> ref = reference_motion(m, c.q, c.qd, d.qdd);
    std::vector<Vector6> expected(1, Vector6::Zero()), expected_kdl;
    for (const FrameMotion& f : ref) expected.push_back(f.spatial_acceleration());
    Vector6 g_shift;
    g_shift << c.gravity, Vector3::Zero();
    for (const Vector6& a : expected) expected_kdl.push_back(a - g_shift);
    const double e1 = rel_error(stack(d.link_accelerations), stack(expected));
    Options o;
    o.convention = Convention::Kdl;
    Case kdl = c;
    kdl.beta = c.beta - c.alpha.topRows<3>().transpose() * c.gravity;
    hybrid_dynamics(m, d, kdl, o);
    const double e2 = rel_error(stack(d.link_accelerations), stack(expected_kdl));
    const Eigen::MatrixXd J = tip_jacobian(m, c.q);
    const Eigen::MatrixXd Jref = reference_link_jacobian(m, c.q, m.num_links() - 1);
    const double e3 = (J - Jref).cwiseAbs().maxCoeff() / std::max(1.0, Jref.cwiseAbs().maxCoeff());
    const std::vector<Transform> poses = forward_kinematics(m, c.q);
    double e4 = 0;
    for (int l = 0; l < m.num_links(); ++l)
      e4 = std::max({e4, (poses[l].R - ref[l].R).cwiseAbs().maxCoeff(),
                     (poses[l].p - ref[l].p).cwiseAbs().maxCoeff()});
    const std::vector<Vector6> velocities = link_velocities(m, c.q, c.qd);
    std::vector<Vector6> expected_velocities;
    for (const FrameMotion& f : ref) expected_velocities.push_back((Vector6() << f.v, f.w).finished());
    const double e5 = rel_error(stack(velocities), stack(expected_velocities));
    EXPECT_LE(e1, 1e-10) << ch.urdf;
    EXPECT_LE(e2, 1e-10) << ch.urdf;
    EXPECT_LE(e3, 1e-12) << ch.urdf;
    EXPECT_LE(e4, 1e-12) << ch.urdf;
    EXPECT_LE(e5, 1e-12) << ch.urdf;
    worst_vel = std::max(worst_vel, e5);
    worst_acc = std::max(worst_acc, e1);
    worst_kdl = std::max(worst_kdl, e2);
    worst_jac = std::max(worst_jac, e3);
    worst_pose = std::max(worst_pose, e4);
    ++cases;
  });
  report("link accelerations vs reference sweep", worst_acc, cases);
  report("link accelerations (kdl) vs reference - [g;0]", worst_kdl, cases);
  report("tip_jacobian vs reference Jacobian", worst_jac, cases);
  report("forward_kinematics vs reference poses", worst_pose, cases);
  report("link_velocities vs reference velocities", worst_vel, cases);
}

// achd::rnea and achd::crba against the reference RNEA and CRBA, every effect on (rotor
// inertias, damping and friction random), a random qdd; their workspace forms give the
// same bits as the value forms, with one workspace reused across calls.
TEST(ReferenceDynamics, RneaAndCrbaEqualTheReference) {
  double worst_rnea = 0, worst_crba = 0;
  int cases = 0;
  std::mt19937 rng(505);
  std::uniform_real_distribution<double> U(-1, 1);
  for_random_cases(505, kChains, true, [&](const RandomChain& ch, const Case& c) {
    Model m = ch.model;
    for (Body& b : m.bodies) {
      b.rotor_inertia = 0.1 * (1 + U(rng));
      b.damping = 0.5 * (1 + U(rng));
      b.friction = 0.5 * (1 + U(rng));
    }
    const int n = m.num_rates();
    const Eigen::VectorXd qdd = Eigen::VectorXd::NullaryExpr(n, [&] { return 3 * U(rng); });
    const Eigen::VectorXd tau = rnea(m, c.q, c.qd, qdd, c.gravity, c.f_ext, with_effects(kAllEffects));
    const double e1 =
        rel_error(tau, reference_rnea(m, c.q, c.qd, qdd, c.gravity, c.f_ext, kAllEffects, 0.05));
    const Eigen::MatrixXd M = crba(m, c.q), Mref = reference_crba(m, c.q, true);
    const double e2 = (M - Mref).cwiseAbs().maxCoeff() / std::max(1.0, Mref.cwiseAbs().maxCoeff());
    EXPECT_LE(e1, 1e-12) << ch.urdf;
    EXPECT_LE(e2, 1e-12) << ch.urdf;
    // Workspace forms, the workspace used twice: the same bits.
    ChainWorkspace ws(m);
    Eigen::VectorXd tau_ws;
    Eigen::MatrixXd M_ws, J_ws;
    std::vector<Transform> poses;
    std::vector<Vector6> velocities;
    for (int k = 0; k < 2; ++k) {
      rnea(m, ws, c.q, c.qd, qdd, c.gravity, c.f_ext, with_effects(kAllEffects), tau_ws);
      crba(m, ws, c.q, {}, M_ws);
      tip_jacobian(m, c.q, ws, J_ws);
      forward_kinematics(m, c.q, ws, poses);
      link_velocities(m, c.q, c.qd, ws, velocities);
      EXPECT_EQ(tau_ws, tau);
      EXPECT_EQ(M_ws, M);
      EXPECT_EQ(J_ws, tip_jacobian(m, c.q));
      const std::vector<Transform> fk = forward_kinematics(m, c.q);
      const std::vector<Vector6> lv = link_velocities(m, c.q, c.qd);
      ASSERT_EQ(poses.size(), fk.size());
      ASSERT_EQ(velocities, lv);
      for (size_t l = 0; l < fk.size(); ++l) EXPECT_TRUE(poses[l].R == fk[l].R && poses[l].p == fk[l].p);
    }
    worst_rnea = std::max(worst_rnea, e1);
    worst_crba = std::max(worst_crba, e2);
    ++cases;
  });
  report("rnea vs reference RNEA (every effect)", worst_rnea, cases);
  report("crba vs reference CRBA", worst_crba, cases);
}

// A workspace made for another model, or a q of the wrong size, is an achd::Error that
// names the function.
TEST(ReferenceDynamics, WorkspaceFormsCheckTheirArguments) {
  std::mt19937 rng(606);
  const RandomChain a = random_chain(rng, 3, false), b = random_chain(rng, 5, false);
  ChainWorkspace ws(a.model);
  const Eigen::VectorXd qa = Eigen::VectorXd::Zero(a.model.num_rates());
  const Eigen::VectorXd qb = Eigen::VectorXd::Zero(b.model.num_rates());
  Eigen::MatrixXd M;
  Eigen::VectorXd tau;
  const auto message = [](const auto& call) -> std::string {
    try {
      call();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message([&] { crba(b.model, ws, qb, {}, M); }),
            "crba: the workspace was made for a model with 3 joints, this one has 5");
  EXPECT_EQ(message([&] { crba(a.model, ws, qb, {}, M); }), "crba: q must have 3 values, got 5");
  EXPECT_EQ(message([&] { rnea(a.model, ws, qa, qb, qa, Vector3::Zero(), {}, with_effects(kAllEffects), tau); }),
            "rnea: q, qd and qdd must have 3 values");
  EXPECT_EQ(message([&] { tip_jacobian(b.model, qb, ws, M); }),
            "tip_jacobian: the workspace was made for a model with 3 joints, this one has 5");
  EXPECT_EQ(message([&] { crba(a.model, ws, qa, {}, M); }), "");
  // Finite inputs whose torques overflow are named, not handed on as Inf or NaN.
  EXPECT_EQ(message([&] { rnea(a.model, ws, qa, qa, qa, Vector3(1e308, 1e308, 1e308), {}, {}, tau); }),
            "rnea: the torques are not finite (the inputs overflow)");
  EXPECT_EQ(message([&] { rnea(a.model, ws, qa, qa, qa, Vector3(5e-324, 0, 0), {}, {}, tau); }), "");
}

// Transform's two maps are each other's duals: moving a motion m and a force f from a
// child frame C to its parent P keeps their power, (X^-1 m) . (X^T f) = m . f, and the
// angular part of a motion is only rotated. (free_motions.cpp uses motion_to_parent.)
TEST(Spatial, MotionToParentKeepsThePowerOfForceToParent) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int k = 0; k < 100; ++k) {
    Transform X;
    X.R = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    X.p = Vector3(u(rng), u(rng), u(rng));
    Vector6 m, f;
    for (int r = 0; r < 6; ++r) m[r] = u(rng), f[r] = u(rng);
    const Vector6 mp = X.motion_to_parent(m), fp = X.force_to_parent(f);
    EXPECT_NEAR(mp.dot(fp), m.dot(f), 1e-13 * (1 + std::abs(m.dot(f))));
    EXPECT_LE((mp.tail<3>() - X.R * m.tail<3>()).norm(), 1e-15 * 8);
    // The velocity of C's origin seen from P: a point fixed in C at p_C moves with
    // R v + w_P x (R p_C) in P at that point; taken at P's origin it is v_P + w_P x p_P.
    const Vector3 at_c_origin = mp.head<3>() + mp.tail<3>().cross(X.p);
    EXPECT_LE((at_c_origin - X.R * m.head<3>()).norm(), 1e-13);
  }
}

}  // namespace
}  // namespace achd::test
