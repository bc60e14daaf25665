// The Delta parallel robot (robots/delta.urdf, a spanning tree, closed by the five
// spherical loop joints of robots/delta.loops.json) against an independent closed-form
// geometry written here from the robot's published dimensions (no achd kinematics in
// it): closed poses close every loop, the platform stays parallel to the base while a
// joint PD moves the arms under gravity (robots/scenes/delta_pd.json) and settles where
// its torques are the static torques by virtual work, and the torques the solver gives
// the prescribed shoulders at rest are those static torques: the bodies' gravity work
// under the mechanism's exact velocity map (complex-step derivatives of the closed form).
#include <gtest/gtest.h>

#include <array>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "achd/achd.hpp"
#include "json_file.hpp"
#include "loops_json.hpp"
#include "scene_json.hpp"

namespace {

// The URDF's numbers (robots/delta.urdf, robots/README.md): Williams' ABB IRB 360-1/1600
// example, s_B = 0.567 m, s_P = 0.076 m, L = 0.524 m, l = 1.244 m, h = 0.131 m, with the
// shoulder axes R_B = s_B / (2 sqrt 3) and the rod pairs' centres r_P = s_P / (2 sqrt 3)
// from the centres (5 digits), and the masses of the URDF.
constexpr double kRB = 0.16368, kL = 0.524, kl = 1.244, kh = 0.131, krP = 0.02194;
constexpr double kArmMass = 1.0, kRodMass = 0.15, kPlatformMass = 0.6;
const Eigen::Vector3d kGravity(0, 0, -9.81);

std::string source(const std::string& path) { return std::string(ACHD_SOURCE_DIR) + "/" + path; }

achd::Model delta(bool with_loops = true) {
  achd::UrdfOptions o;
  const std::string loops = source("robots/delta.loops.json");
  if (with_loops) o.loops = achd::cli::parse_loops(achd::cli::read_json_file(loops, "a loops file"), loops);
  return achd::load_urdf_file(source("robots/delta.urdf"), "", "", o);
}

// The closed form. Arm i (0, 1, 2) at phi_i = 2 pi i / 3: e radial, t tangential, z up.
// For the platform centre P (the platform parallel to the base), arm i's shoulder angle
// theta solves |P + r_P e - R_B e - L (cos theta e - sin theta z)| = l: with D = P + (r_P
// - R_B) e and (dx, dz) = (D.e, D.z), dx cos theta - dz sin theta = K = (|D|^2 + L^2 -
// l^2) / (2 L), whose elbow-out root is
//   (cos theta, sin theta) = (K (dx, -dz) - sqrt(rho^2 - K^2) (dz, dx)) / rho^2.
// Only + - * / and sqrt: it runs on complex numbers for complex-step derivatives.
template <class T>
struct ArmState {
  T c, s;                                // cos and sin of the shoulder angle
  Eigen::Matrix<T, 3, 1> elbow, rod;     // the elbow's centre, the rods' unit direction
  Eigen::Matrix<T, 3, 1> arm_com, rod_com[2];  // rod_com[0]: rod a (+h/2 along t), [1]: b
};

Eigen::Vector3d radial(int i) {
  const double phi = 2 * M_PI * i / 3;
  return {std::cos(phi), std::sin(phi), 0};
}
Eigen::Vector3d tangential(int i) {
  const double phi = 2 * M_PI * i / 3;
  return {-std::sin(phi), std::cos(phi), 0};
}

// (Eigen's dot() conjugates its first factor on complex numbers: the closed form needs
// the plain sum of products.)
template <class T>
T dot(const Eigen::Matrix<T, 3, 1>& a, const Eigen::Matrix<T, 3, 1>& b) {
  return a.cwiseProduct(b).sum();
}

template <class T>
ArmState<T> arm_state(const Eigen::Matrix<T, 3, 1>& P, int i) {
  using V = Eigen::Matrix<T, 3, 1>;
  const V e = radial(i).cast<T>(), t = tangential(i).cast<T>(), z = Eigen::Vector3d::UnitZ().cast<T>();
  const V D = P + T(krP - kRB) * e;
  const T dx = dot(D, e), dz = dot(D, z);
  const T K = (dot(D, D) + T(kL * kL - kl * kl)) / T(2 * kL);
  const T rho2 = dx * dx + dz * dz, root = sqrt(rho2 - K * K);
  ArmState<T> a;
  a.c = (K * dx - root * dz) / rho2;
  a.s = (-K * dz - root * dx) / rho2;
  const V arm = a.c * e - a.s * z;  // the upper arm's direction
  a.elbow = T(kRB) * e + T(kL) * arm;
  a.rod = (P + T(krP) * e - a.elbow) / T(kl);
  a.arm_com = T(kRB) * e + T(kL / 2) * arm;
  for (int j = 0; j < 2; ++j) a.rod_com[j] = a.elbow + T(j == 0 ? kh / 2 : -kh / 2) * t + T(kl / 2) * a.rod;
  return a;
}

// q in the model's order at the platform centre P, from the closed form: the shoulder
// angle theta = atan2(s, c); the rods' universal joints from the rod's direction in the
// arm's frame, u = (cos(theta + a) cos b, sin b, -sin(theta + a) cos b); the platform's
// three joints (z, x, y below rod 1a) undo rod 1a's turn Ry(theta + a) Rz(b): -b, 0,
// -(theta + a).
Eigen::VectorXd closed_q(const achd::Model& m, const Eigen::Vector3d& P) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.num_positions());
  const auto set = [&](const std::string& name, double value) {
    const int j = m.joint_index(name);
    ASSERT_GE(j, 0) << name;
    q[j] = value;
  };
  for (int i = 0; i < 3; ++i) {
    const ArmState<double> a = arm_state<double>(P, i);
    const double theta = std::atan2(a.s, a.c);
    const double b = std::asin(a.rod.dot(tangential(i)));
    const double pitch = std::atan2(-a.rod.z(), a.rod.dot(radial(i)));  // theta + a
    const std::string n = std::to_string(i + 1);
    set("arm_" + n + "_joint", theta);
    for (const char* side : {"a", "b"}) {
      set("rod_" + n + side + "_u1", pitch - theta);
      set("rod_" + n + side + "_u2", b);
    }
    if (i == 0) {
      set("platform_rz", -b);
      set("platform_rx", 0);
      set("platform_ry", -pitch);
    }
  }
  return q;
}

// The shoulders' static torques at the platform centre P by virtual work:
//   tau . dtheta + sum_bodies m_k g . dc_k = 0  for every motion of the mechanism.
// The mechanism's motions are the platform's translations dP; the closed form gives every
// centre of mass c_k(P) and theta(P), differentiated by complex steps (exact to
// round-off), so tau = -(dtheta/dP)^-T sum_k (dc_k/dP)^T m_k g. No achd in it.
Eigen::Vector3d virtual_work_torques(const Eigen::Vector3d& P) {
  using C = std::complex<double>;
  const double step = 1e-30;
  Eigen::Matrix3d dtheta_dP;                    // row i: arm i
  Eigen::Vector3d F = Eigen::Vector3d::Zero();  // the generalised gravity force in P
  for (int k = 0; k < 3; ++k) {
    Eigen::Matrix<C, 3, 1> Pc = P.cast<C>();
    Pc[k] += C(0, step);
    double work = kPlatformMass * kGravity[k];  // the platform's centre is P
    for (int i = 0; i < 3; ++i) {
      const ArmState<C> a = arm_state<C>(Pc, i);
      // d theta = cos theta d(sin theta) - sin theta d(cos theta)
      dtheta_dP(i, k) = (a.c.real() * a.s.imag() - a.s.real() * a.c.imag()) / step;
      const auto slope = [&](const Eigen::Matrix<C, 3, 1>& c) { return Eigen::Vector3d(c.imag() / step); };
      work += kArmMass * kGravity.dot(slope(a.arm_com));
      for (int j = 0; j < 2; ++j) work += kRodMass * kGravity.dot(slope(a.rod_com[j]));
    }
    F[k] = work;
  }
  return -dtheta_dP.transpose().fullPivLu().solve(F);
}

// Closed poses: the scene's (the platform centred 1.2 m below the base plane) and three
// off-centre ones across the workspace.
const Eigen::Vector3d kHome(0, 0, -1.2);
const std::vector<Eigen::Vector3d> kPoses = {kHome, {0.15, -0.1, -1.0}, {-0.2, 0.05, -1.35}, {0.05, 0.25, -1.1}};

int link(const achd::Model& m, const std::string& name) {
  const int l = m.link_index(name);
  EXPECT_GE(l, 0) << name;
  return l;
}

std::string rod_name(int i, int side) { return "rod_" + std::to_string(i + 1) + (side == 0 ? "a" : "b"); }

// Rod (i, side)'s lower end, and the platform point it is fixed to, from
// forward_kinematics (the platform's point from the closed form's layout, in its frame).
Eigen::Vector3d rod_end(const achd::Model& m, const std::vector<achd::Transform>& X, int i, int side) {
  const achd::Transform& r = X[link(m, rod_name(i, side))];
  return r.p + r.R * Eigen::Vector3d(kl, 0, 0);
}
Eigen::Vector3d platform_point(const achd::Model& m, const std::vector<achd::Transform>& X, int i, int side) {
  const achd::Transform& p = X[link(m, "platform")];
  return p.p + p.R * (krP * radial(i) + (side == 0 ? kh / 2 : -kh / 2) * tangential(i));
}

double turn_angle(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle(); }

// The joints of the three shoulders.
std::array<int, 3> shoulders(const achd::Model& m) {
  return {m.joint_index("arm_1_joint"), m.joint_index("arm_2_joint"), m.joint_index("arm_3_joint")};
}

// The 15 x 18 Jacobian of the loops' x y z at q: rod end minus platform point, each row
// the difference of the two links' point Jacobians (linear rows).
Eigen::MatrixXd loop_jacobian(const achd::Model& m, const Eigen::VectorXd& q) {
  const std::vector<achd::Transform> X = achd::forward_kinematics(m, q);
  Eigen::MatrixXd G(15, m.num_rates());
  int row = 0;
  const int platform = link(m, "platform");
  for (int i = 0; i < 3; ++i)
    for (int side = 0; side < 2; ++side) {
      if (i == 0 && side == 0) continue;
      const int rod = link(m, rod_name(i, side));
      const Eigen::Vector3d at_platform = krP * radial(i) + (side == 0 ? kh / 2 : -kh / 2) * tangential(i);
      G.middleRows<3>(row) = achd::link_jacobian(m, q, rod, Eigen::Vector3d(kl, 0, 0)).topRows<3>() -
                             achd::link_jacobian(m, q, platform, at_platform).topRows<3>();
      row += 3;
    }
  return G;
}

}  // namespace

// The loader keeps every direction of the five spherical loops: 15 columns on the tree's
// 18 joints, independent at the sampled (open) configurations and, by the SVD here, at
// the closed poses too (rank 15, a 3-dimensional null space: the 3 DoF).
TEST(DeltaRobot, FiveSphericalLoopsKeepTheirDirections) {
  const achd::Model m = delta();
  EXPECT_EQ(m.num_rates(), 18);
  ASSERT_EQ(m.loops.size(), 5u);
  for (const achd::LoopJoint& l : m.loops) {
    EXPECT_EQ(achd::loop_direction_names(l.directions), (std::vector<std::string>{"x", "y", "z"})) << l.name;
    EXPECT_EQ(l.dropped, 0u) << l.name;
  }
  EXPECT_EQ(m.num_loop_columns(), 15);
  for (const Eigen::Vector3d& P : kPoses) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(loop_jacobian(m, closed_q(m, P)));
    const Eigen::VectorXd sv = svd.singularValues();
    EXPECT_GT(sv[14], 1e-3 * sv[0]) << "P " << P.transpose();
    // platform_rx never turns on the closed poses (the platform stays parallel): every
    // motion of the mechanism leaves it at rest, so without its column (the platform hung
    // by a universal joint) the same 15 rows would keep rank 14 only, one of them
    // redundant on the closed poses alone.
    const Eigen::MatrixXd G = loop_jacobian(m, closed_q(m, P));
    Eigen::MatrixXd without_rx(15, 17);
    const int rx = m.joint_index("platform_rx");
    without_rx << G.leftCols(rx), G.rightCols(17 - rx);
    const Eigen::VectorXd sv_u = Eigen::JacobiSVD<Eigen::MatrixXd>(without_rx).singularValues();
    EXPECT_GT(sv_u[13], 1e-3 * sv_u[0]) << "P " << P.transpose();
    EXPECT_LT(sv_u[14], 1e-12 * sv_u[0]) << "P " << P.transpose();
    std::printf("P (%g, %g, %g): loop Jacobian singular values %.3g ... %.3g (15 of 15); without platform_rx the "
                "15th is %.2g\n", P.x(), P.y(), P.z(), sv[0], sv[14], sv_u[14]);
  }
  // At open (unclosed) configurations, such as the loader samples, those 15 rows are
  // independent: sampling there cannot see that redundancy.
  std::srand(7);
  const int rx = m.joint_index("platform_rx");
  for (int sample = 0; sample < 4; ++sample) {
    Eigen::VectorXd q = M_PI * Eigen::VectorXd::Random(m.num_positions());
    q[rx] = 0;
    const Eigen::MatrixXd G = loop_jacobian(m, q);
    Eigen::MatrixXd without_rx(15, 17);
    without_rx << G.leftCols(rx), G.rightCols(17 - rx);
    const Eigen::VectorXd sv_u = Eigen::JacobiSVD<Eigen::MatrixXd>(without_rx).singularValues();
    EXPECT_GT(sv_u[14], 1e-6 * sv_u[0]) << "sample " << sample;
  }
}

// Each closed pose closes every loop: the simulator's loop_error after a reset there, and,
// independently, each rod's lower end on its platform point by forward_kinematics; the
// platform's frame is the closed form's (centre P, parallel to the base) and so are the
// elbows. The scene's q0 is the home pose.
TEST(DeltaRobot, ClosedPosesCloseEveryLoop) {
  const achd::Model m = delta();
  achd::Simulator sim(m);
  for (const Eigen::Vector3d& P : kPoses) {
    const Eigen::VectorXd q = closed_q(m, P);
    sim.reset(q, Eigen::VectorXd::Zero(m.num_rates()));
    for (int k = 0; k < 5; ++k) EXPECT_LT(sim.loop_error(k), 1e-12) << m.loops[k].name << ", P " << P.transpose();
    const std::vector<achd::Transform> X = achd::forward_kinematics(m, q);
    double worst_gap = 0;
    for (int i = 0; i < 3; ++i) {
      const ArmState<double> a = arm_state<double>(P, i);
      const achd::Transform& arm = X[link(m, "upper_arm_" + std::to_string(i + 1))];
      EXPECT_LT((arm.p + arm.R * Eigen::Vector3d(kL, 0, 0) - a.elbow).norm(), 1e-12);
      for (int side = 0; side < 2; ++side)
        worst_gap = std::max(worst_gap, (rod_end(m, X, i, side) - platform_point(m, X, i, side)).norm());
    }
    EXPECT_LT(worst_gap, 1e-12) << "P " << P.transpose();
    const achd::Transform& platform = X[link(m, "platform")];
    EXPECT_LT((platform.p - P).norm(), 1e-12);
    EXPECT_LT(turn_angle(platform.R), 1e-12);
    // The rods are l long (the closed form's own check).
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(arm_state<double>(P, i).rod.norm(), 1.0, 1e-14);
  }
  const Eigen::VectorXd home = closed_q(m, kHome);
  std::printf("home pose q (model order):");
  for (int j = 0; j < home.size(); ++j) std::printf("%s %.17g", j ? "," : "", home[j] + 0.0);  // (+ 0.0: no -0)
  std::printf("\njoints:");
  for (int j = 0; j < m.num_rates(); ++j) std::printf(" %s", m.bodies[j].joint_name.c_str());
  std::printf("\n");
  const achd::cli::Scene scene = achd::cli::load_scene(source("robots/scenes/delta_pd.json"));
  ASSERT_EQ(scene.q0.size(), home.size());
  EXPECT_LT((scene.q0 - home).cwiseAbs().maxCoeff(), 1e-15);
  sim.reset(scene.q0, Eigen::VectorXd::Zero(m.num_rates()));
  for (int k = 0; k < 5; ++k) EXPECT_LT(sim.loop_error(k), 1e-12) << m.loops[k].name;
}

// The scene: from rest at the home pose, a joint PD on the three shoulders (the passive
// joints' gains 0) toward other angles, under gravity, 10 s with the simulator's defaults
// (Dormand-Prince): the platform moves but does not turn (1e-9 rad from its start
// orientation, from forward_kinematics at every output step), the loops stay closed
// (drift 1e-9 m), and the robot settles in static equilibrium.
TEST(DeltaRobot, PlatformStaysParallelUnderJointControl) {
  const achd::cli::Scene scene = achd::cli::load_scene(source("robots/scenes/delta_pd.json"));
  const achd::Model& m = scene.model;
  ASSERT_EQ(m.loops.size(), 5u);
  ASSERT_TRUE(scene.joint_control);
  EXPECT_EQ(scene.options.integrator, achd::Integrator::DormandPrince);
  const std::array<int, 3> act = shoulders(m);
  for (int j = 0; j < m.num_rates(); ++j) {
    const bool actuated = j == act[0] || j == act[1] || j == act[2];
    EXPECT_EQ(scene.control.kp[j] > 0, actuated) << m.bodies[j].joint_name;
    EXPECT_EQ(scene.control.kd[j] > 0, actuated) << m.bodies[j].joint_name;
    if (actuated) EXPECT_GT(std::abs(scene.control.target[j] - scene.q0[j]), 0.05) << m.bodies[j].joint_name;
  }
  achd::Simulator sim(m, scene.options);
  achd::cli::start_scene(scene, sim);
  const int platform = link(m, "platform");
  const achd::Transform start = achd::forward_kinematics(m, sim.q)[platform];
  double worst_turn = 0, farthest = 0;
  const std::int64_t steps = scene.steps();
  EXPECT_NEAR(steps * scene.dt, 10.0, 1e-12);
  for (std::int64_t s = 0; s < steps; ++s) {
    sim.step(scene.dt);
    const achd::Transform X = achd::forward_kinematics(m, sim.q)[platform];
    worst_turn = std::max(worst_turn, turn_angle(start.R.transpose() * X.R));
    farthest = std::max(farthest, (X.p - start.p).norm());
  }
  double drift = 0;
  for (int k = 0; k < 5; ++k) {
    EXPECT_LE(sim.loop_drift(k), 1e-9) << m.loops[k].name;
    drift = std::max(drift, sim.loop_drift(k));
  }
  EXPECT_LE(worst_turn, 1e-9);
  EXPECT_GT(farthest, 0.05);  // the platform did move
  const achd::Transform end = achd::forward_kinematics(m, sim.q)[platform];
  std::printf("delta PD, %g s: platform moved up to %.4f m (ends %.4f m away), turned at most %.3g rad; loop drift "
              "%.3g m; substeps %lld (rejected %lld)\n",
              sim.t, farthest, (end.p - start.p).norm(), worst_turn, drift, static_cast<long long>(sim.substeps()),
              static_cast<long long>(sim.rejected_substeps()));
  std::printf("shoulders at the end:");
  for (int j : act) std::printf(" %.6f (target %.6f)", sim.q[j], scene.control.target[j]);
  std::printf("\n");
  // By 10 s the robot has settled (the PD rings at about 5 Hz, damped about critically)
  // where the PD's torques are the static torques of virtual work at the platform's
  // place, and its shoulders where the closed form puts them for that place.
  EXPECT_LT(sim.qd.cwiseAbs().maxCoeff(), 1e-8);
  const Eigen::Vector3d tau_vw = virtual_work_torques(end.p);
  double worst_torque = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = act[i];
    const double tau_pd = scene.control.kp[j] * (scene.control.target[j] - sim.q[j]) - scene.control.kd[j] * sim.qd[j];
    worst_torque = std::max(worst_torque, std::abs(tau_pd - tau_vw[i]));
    const ArmState<double> a = arm_state<double>(end.p, i);
    EXPECT_NEAR(sim.q[j], std::atan2(a.s, a.c), 1e-10) << m.bodies[j].joint_name;
  }
  EXPECT_LT(worst_torque, 1e-6 * tau_vw.norm());
  std::printf("settled: PD torques within %.3g N m of the static torques by virtual work (%.6f %.6f %.6f N m)\n",
              worst_torque, tau_vw[0], tau_vw[1], tau_vw[2]);
}

// Statics by virtual work. At rest at a closed pose with the shoulders prescribed (qdd 0)
// under gravity, the solver's prescribed_torques are the static torques of virtual work
// (virtual_work_torques: the closed form's exact velocity map, no achd in it), and the
// locked mechanism does not move.
TEST(DeltaRobot, PrescribedShouldersHoldTheStaticTorquesOfVirtualWork) {
  const achd::Model m = delta();
  achd::Data d(m);
  const std::array<int, 3> act = shoulders(m);
  for (const Eigen::Vector3d& P : kPoses) {
    const Eigen::Vector3d tau_vw = virtual_work_torques(P);
    achd::Case c = achd::Case::zeros(m);
    c.q = closed_q(m, P);
    c.prescribed.assign(m.num_rates(), false);
    c.qdd_given = Eigen::VectorXd::Zero(m.num_rates());
    for (int j : act) c.prescribed[j] = true;
    achd::hybrid_dynamics(m, d, c);
    const Eigen::Vector3d tau(d.prescribed_torques[act[0]], d.prescribed_torques[act[1]],
                              d.prescribed_torques[act[2]]);
    EXPECT_LT((tau - tau_vw).norm(), 1e-9 * tau_vw.norm()) << "P " << P.transpose() << "\n achd " << tau.transpose()
                                                           << "\n virtual work " << tau_vw.transpose();
    EXPECT_LT(d.qdd.cwiseAbs().maxCoeff(), 1e-9) << "P " << P.transpose();  // the locked mechanism stays
    std::printf("P (%g, %g, %g): shoulder torques %.12f %.12f %.12f N m, virtual work differs by %.3g (relative)\n",
                P.x(), P.y(), P.z(), tau[0], tau[1], tau[2], (tau - tau_vw).norm() / tau_vw.norm());
  }
}

// The five loops all end on the platform, so the sweep rolls six unit wrenches up the
// platform's path once and takes each loop's second leg from them
// (shared_second_body.hpp): at closed poses, moving, with torques and wrenches on the
// links, the solve gives the textbook reference's qdd, nu and joint torques
// with the loops as relative Case::constraints blocks on the open tree.
TEST(DeltaRobot, LoopsThroughTheSharedPlatformGiveTheReferenceSolve) {
  const achd::Model closed = delta(), open = delta(false);
  achd::Data d(closed);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (const Eigen::Vector3d& P : kPoses) {
    achd::Case c = achd::Case::zeros(closed);
    c.q = closed_q(closed, P);
    c.qd = Eigen::VectorXd::NullaryExpr(closed.num_rates(), [&] { return U(rng); });
    c.ff_torques = Eigen::VectorXd::NullaryExpr(closed.num_rates(), [&] { return U(rng); });
    c.gravity = kGravity;
    c.f_ext.assign(closed.num_links(), achd::Vector6::Zero());
    for (auto& w : c.f_ext) w = achd::Vector6::NullaryExpr([&] { return U(rng); });
    achd::Options o;
    o.effects = achd::kAllEffects;
    achd::hybrid_dynamics(closed, d, c, o);
    ASSERT_EQ(d.workspace.shared_body, closed.links[link(closed, "platform")].body);
    achd::Case r = c;  // the loops as relative blocks of the open tree
    r.constraints = d.workspace.loop_blocks;
    const achd::ReferenceSolution ref = achd::pv_reference(open, r, o);
    const double scale = 1 + ref.nu.cwiseAbs().maxCoeff();
    EXPECT_LT((d.qdd - ref.qdd).cwiseAbs().maxCoeff(), 1e-9 * (1 + ref.qdd.cwiseAbs().maxCoeff())) << "P " << P.transpose();
    EXPECT_LT((d.nu - ref.nu).cwiseAbs().maxCoeff(), 1e-9 * scale) << "P " << P.transpose();
    EXPECT_LT((d.joint_torques - ref.joint_torques).cwiseAbs().maxCoeff(), 1e-9 * scale) << "P " << P.transpose();
  }
}
