// A loop joint is held as the relative block its spec describes: the solve of the robot
// closed by its loops equals the textbook reference's solve of the open tree holding
// blocks built here from the specs and the tree's own forward kinematics (not from what
// the solve computed): on the dual-arm torso, a fixed loop between the two hands (links on
// fixed joints whose origins turn them) with turned loop frames at both ends, and a
// revolute loop from the root link (the world of a fixed base) to the left forearm about
// an oblique axis, at random poses, rates and torques with gravity.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "achd/achd.hpp"

namespace achd {
namespace {

Transform pose(const Vector3& xyz, const Vector3& rpy) {
  const Matrix3 R = (Eigen::AngleAxisd(rpy[2], Vector3::UnitZ()) * Eigen::AngleAxisd(rpy[1], Vector3::UnitY()) *
                     Eigen::AngleAxisd(rpy[0], Vector3::UnitX()))
                        .toRotationMatrix();
  return Transform{R, xyz};
}

// The loop frame in its link's frame: the spec's origin turned so that z runs along the
// axis (loops.hpp), the origin itself for fixed and spherical loops.
Transform loop_frame(const LoopJointSpec& spec, const Transform& origin) {
  Matrix3 turn = Matrix3::Identity();
  if (spec.type == LoopType::Revolute || spec.type == LoopType::Prismatic)
    turn = Eigen::Quaterniond::FromTwoVectors(Vector3::UnitZ(), spec.axis.normalized()).toRotationMatrix();
  return origin * Transform{turn, Vector3::Zero()};
}

// The block the loop stands for at q: e_k^T (a_A(Q) - a_B(Q)) = beta_k for each held
// direction k (`directions`, bits x..rz) of the loop frame at link a, Q frame b's origin;
// from the root (link a = -1) the block on link b alone with -e_k.
ConstraintBlock block_of(const Model& open, const std::vector<Transform>& X, const LoopJointSpec& spec,
                         unsigned directions) {
  const int a = spec.link_a == open.root_name ? -1 : open.link_index(spec.link_a);
  const int b = open.link_index(spec.link_b);
  const Transform Xa = a < 0 ? Transform{} : X[a], Xb = X[b];
  const Transform A = Xa * loop_frame(spec, spec.origin_a), B = Xb * loop_frame(spec, spec.origin_b);
  ConstraintBlock block;
  block.alpha = ConstraintMatrix::Zero(6, __builtin_popcount(directions));
  for (int k = 0, j = 0; k < 6; ++k)
    if ((directions >> k) & 1u) block.alpha.col(j++).segment<3>(k < 3 ? 0 : 3) = A.R.col(k % 3);
  block.beta = ConstraintVector::Zero(block.alpha.cols());
  if (a < 0) {
    block.link = b;
    block.point = spec.origin_b.p;
    block.alpha = -block.alpha;
  } else {
    block.link = a;
    block.point = Xa.R.transpose() * (B.p - Xa.p);
    block.link_b = b;
    block.point_b = spec.origin_b.p;
  }
  return block;
}

TEST(LoopJointBlocks, ALoopIsTheRelativeBlockItsSpecDescribes) {
  LoopJointSpec hands;
  hands.name = "hands";
  hands.type = LoopType::Fixed;
  hands.link_a = "left_hand";
  hands.origin_a = pose(Vector3(0.05, -0.02, 0.1), Vector3(0.3, -0.2, 0.5));
  hands.link_b = "right_hand";
  hands.origin_b = pose(Vector3(-0.03, 0.04, 0.08), Vector3(-0.4, 0.1, 0.2));
  LoopJointSpec hinge;
  hinge.name = "hinge";
  hinge.type = LoopType::Revolute;
  hinge.axis = Vector3(1, 1, 0.5);
  hinge.link_a = "base_link";
  hinge.origin_a = pose(Vector3(0.4, 0.3, 0.9), Vector3(0.2, 0.1, -0.3));
  hinge.link_b = "left_forearm";
  hinge.origin_b = pose(Vector3(0.02, 0.01, 0.15), Vector3(0, 0.5, 0));
  const std::string urdf = std::string(ACHD_SOURCE_DIR) + "/robots/dual_arm_torso.urdf";
  const Model open = load_urdf_file(urdf, "", "");
  UrdfOptions with_loops;
  with_loops.loops = {hands, hinge};
  const Model closed = load_urdf_file(urdf, "", "", with_loops);
  ASSERT_EQ(closed.loops.size(), 2u);
  Data d(closed);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1);
  Options o;
  o.effects = kAllEffects;
  for (int trial = 0; trial < 5; ++trial) {
    Case c = Case::zeros(closed);
    c.q = Eigen::VectorXd::NullaryExpr(closed.num_positions(), [&] { return U(rng); });
    c.qd = Eigen::VectorXd::NullaryExpr(closed.num_rates(), [&] { return U(rng); });
    c.ff_torques = Eigen::VectorXd::NullaryExpr(closed.num_rates(), [&] { return U(rng); });
    c.gravity = Vector3(0, 0, -9.81);
    hybrid_dynamics(closed, d, c, o);
    Case r = c;
    const std::vector<Transform> X = forward_kinematics(open, c.q);
    r.constraints = {block_of(open, X, hands, closed.loops[0].directions),
                     block_of(open, X, hinge, closed.loops[1].directions)};
    const ReferenceSolution ref = pv_reference(open, r, o);
    ASSERT_EQ(d.nu.size(), ref.nu.size());
    const double scale = 1 + ref.nu.cwiseAbs().maxCoeff();
    EXPECT_LT((d.qdd - ref.qdd).cwiseAbs().maxCoeff(), 1e-9 * (1 + ref.qdd.cwiseAbs().maxCoeff())) << trial;
    EXPECT_LT((d.nu - ref.nu).cwiseAbs().maxCoeff(), 1e-9 * scale) << trial;
    EXPECT_LT((d.joint_torques - ref.joint_torques).cwiseAbs().maxCoeff(), 1e-9 * scale) << trial;
  }
}

}  // namespace
}  // namespace achd
