// hybrid_dynamics() never allocates: malloc/calloc/realloc and operator new are counted
// while it runs, for every robot of robots/index.json, every constraint count 0..6, with
// qd, f_ext and ff torques nonzero, in both conventions and both singularity policies,
// without and with prescribed joints; nor with some or no link outputs asked for
// (Data::set_link_outputs).
// Nor do the workspace forms of rnea, crba, forward_kinematics, link_velocities,
// tip_jacobian and link_jacobian, once their outputs have their sizes.
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <new>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "achd/achd.hpp"
#include "robot_index.hpp"

extern "C" void* __libc_malloc(std::size_t);
extern "C" void* __libc_calloc(std::size_t, std::size_t);
extern "C" void* __libc_realloc(void*, std::size_t);
extern "C" void __libc_free(void*);

namespace {
bool g_counting = false;
long g_allocations = 0;
void count() {
  if (g_counting) ++g_allocations;
}
}  // namespace

extern "C" void* malloc(std::size_t n) {
  count();
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t n, std::size_t s) {
  count();
  return __libc_calloc(n, s);
}
extern "C" void* realloc(void* p, std::size_t n) {
  count();
  return __libc_realloc(p, n);
}
void* operator new(std::size_t n) {
  count();
  if (void* p = __libc_malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t) noexcept { __libc_free(p); }

namespace {

const std::string kRepo = ACHD_SOURCE_DIR;

// Allocations made by one hybrid_dynamics() call.
long allocations_of_solve(const achd::Model& m, achd::Data& d, const achd::Case& c,
                          const achd::Options& o) {
  g_allocations = 0;
  g_counting = true;
  achd::hybrid_dynamics(m, d, c, o);
  g_counting = false;
  return g_allocations;
}

TEST(NoAllocation, CountingAllocatorSeesEveryKindOfAllocation) {
  g_allocations = 0;
  g_counting = true;
  std::vector<double>* v = new std::vector<double>(100);  // operator new, twice
  Eigen::VectorXd x = Eigen::VectorXd::Zero(100);         // Eigen's malloc
  g_counting = false;
  delete v;
  EXPECT_EQ(g_allocations, 3);
  EXPECT_EQ(x.size(), 100);
}

TEST(NoAllocation, HybridDynamicsOnEveryRobotAndConstraintCount) {
  std::ifstream in(kRepo + "/robots/index.json");
  ASSERT_TRUE(in) << kRepo;
  const nlohmann::json index = nlohmann::json::parse(in);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> U(-1, 1);
  int solves = 0;
  for (const auto& r : index["robots"]) {
    if (!r.contains("tip")) continue;  // the trees: tests/native/dynamics/tree_identities.cpp
    const achd::Model m = achd::load_urdf_file(kRepo + "/" + r["urdf"].get<std::string>(),
                                               r["root"].get<std::string>(), r["tip"].get<std::string>());
    achd::Data d(m);
    const int n = m.num_rates();
    achd::Case c = achd::Case::zeros(m);
    for (int i = 0; i < n; ++i) c.q[i] = r["q0"][i].get<double>();
    c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    c.f_ext.assign(m.num_links(), achd::Vector6::Zero());
    for (auto& w : c.f_ext) w = achd::Vector6::NullaryExpr([&] { return U(rng); });
    for (int nc = 0; nc <= achd::kMaxConstraints; ++nc) {
      c.alpha = achd::ConstraintMatrix::NullaryExpr(6, nc, [&] { return U(rng); });
      c.beta = achd::ConstraintVector::NullaryExpr(nc, [&] { return U(rng); });
      for (auto conv : {achd::Convention::Physical, achd::Convention::Kdl})
        for (auto policy : {achd::SingularityPolicy::Truncate, achd::SingularityPolicy::Damped,
                            achd::SingularityPolicy::VariableDamping}) {
          achd::Options o;
          o.convention = conv;
          o.policy = policy;
          o.effects = achd::kAllEffects;
          EXPECT_EQ(allocations_of_solve(m, d, c, o), 0)
              << r["name"] << " nc=" << nc << " kdl=" << (conv == achd::Convention::Kdl)
              << " policy=" << static_cast<int>(policy);
          ASSERT_TRUE(d.qdd.allFinite());
          ++solves;
          // The same solve with every other joint's acceleration prescribed.
          achd::Case p = c;
          p.qdd_given = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
          p.prescribed.assign(n, false);
          for (int i = 0; i < n; i += 2) p.prescribed[i] = true;
          EXPECT_EQ(allocations_of_solve(m, d, p, o), 0) << r["name"] << " nc=" << nc << " prescribed";
          ASSERT_TRUE(d.prescribed_torques.allFinite());
        }
    }
  }
  const auto chains = std::count_if(index["robots"].begin(), index["robots"].end(),
                                    [](const nlohmann::json& r) { return r.contains("tip"); });
  EXPECT_EQ(solves, static_cast<int>(chains) * 7 * 6);
}

// variable_damping in its singular region, each way the joints' efforts decide: the LWR
// at rest holding its tip in 6D beside its stretched pose keeps the exact solve (URDF
// efforts), lies between the exact and the damped solve (efforts at 4/3 of what the exact
// solve needs) and keeps the damped solve (no effort limits).
TEST(NoAllocation, VariableDampingWhereTheJointEffortsDecide) {
  const achd::Model lwr = achd::load_urdf_file(kRepo + "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  achd::Case c = achd::Case::zeros(lwr);
  c.q << 0.3, 0.15, -0.2, -0.15, 0.4, 0.1, 0.1;
  c.alpha = achd::ConstraintMatrix::Identity(6, 6);
  c.beta = achd::ConstraintVector::Zero(6);
  achd::Options o;
  o.policy = achd::SingularityPolicy::VariableDamping;
  achd::Data exact(lwr);
  achd::Options truncate;
  truncate.policy = achd::SingularityPolicy::Truncate;
  achd::hybrid_dynamics(lwr, exact, c, truncate);
  for (double effort : {-1.0, exact.joint_torques.cwiseAbs().maxCoeff() / 0.75, 0.0}) {
    achd::Model m = lwr;
    if (effort >= 0)
      for (achd::Body& b : m.bodies) b.limits.effort = effort;
    achd::Data d(m);
    EXPECT_EQ(allocations_of_solve(m, d, c, o), 0) << "effort " << effort;
    EXPECT_EQ(d.damped.cols() == 0, effort < 0) << "effort " << effort;
  }
}

// Columns that give way to the joints' efforts (ConstraintBlock::yields): the UR5 near its
// stretched elbow holding rx with z pushed, each way the efforts decide (followed, partly
// given up, wholly given up), with and without variable_damping's exact solve.
TEST(NoAllocation, PushedColumnsGivingWayToTheJointEfforts) {
  const achd::Model m = achd::load_urdf_file(kRepo + "/robots/ur5.urdf", "base_link", "wrist_3_link");
  achd::Case c = achd::Case::zeros(m);
  c.q << 0.2, -1.0, 0.05, -1.5, -1.4, 0.3;
  achd::ConstraintBlock& b = c.constraints.emplace_back();
  b.link = m.link_index("wrist_3_link");
  b.alpha = achd::ConstraintMatrix::Zero(6, 2);
  b.alpha(2, 0) = b.alpha(3, 1) = 1;
  b.beta = achd::ConstraintVector::Zero(2);
  b.yields = 1;
  int seen[3] = {0, 0, 0};
  for (bool exact : {false, true})
    for (double beta_z = 0.1; beta_z < 1e5; beta_z *= 3) {
      b.beta[0] = beta_z;
      achd::Options o;
      o.policy = achd::SingularityPolicy::VariableDamping;
      o.exact_within_efforts = exact;
      achd::Data d(m);
      EXPECT_EQ(allocations_of_solve(m, d, c, o), 0) << "beta_z " << beta_z;
      ++seen[d.yielded == 0 ? 0 : d.yielded < 1 ? 1 : 2];
    }
  for (int regime : seen) EXPECT_GT(regime, 0);
}

// Constraint blocks on any links: 1 to 6 blocks on random links of every chain robot, up
// to 36 columns in all (the largest capacity), so that the several-block sweep and the
// coupling solve of more than 6 columns run, under every policy, with driver weights.
TEST(NoAllocation, HybridDynamicsWithConstraintBlocksUpToTheCapacity) {
  std::ifstream in(kRepo + "/robots/index.json");
  ASSERT_TRUE(in) << kRepo;
  const nlohmann::json index = nlohmann::json::parse(in);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(-1, 1);
  int solves = 0;
  for (const auto& r : index["robots"]) {
    if (!r.contains("tip")) continue;  // the trees: tests/native/dynamics/tree_identities.cpp
    const achd::Model m = achd::load_urdf_file(kRepo + "/" + r["urdf"].get<std::string>(),
                                               r["root"].get<std::string>(), r["tip"].get<std::string>());
    achd::Data d(m);
    const int n = m.num_rates();
    achd::Case c = achd::Case::zeros(m);
    for (int i = 0; i < n; ++i) c.q[i] = r["q0"][i].get<double>();
    c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    c.f_ext.assign(m.num_links(), achd::Vector6::Zero());
    for (auto& w : c.f_ext) w = achd::Vector6::NullaryExpr([&] { return U(rng); });
    for (int blocks = 1; blocks <= 6; ++blocks) {
      const int columns = blocks == 6 ? 6 : 1 + static_cast<int>(rng() % 6);
      c.constraints.assign(blocks, {});
      for (achd::ConstraintBlock& b : c.constraints) {
        b.link = static_cast<int>(rng() % m.num_links());
        b.point = achd::Vector3::NullaryExpr([&] { return U(rng); });
        // every other block relative to a second link (two legs rolled and met)
        if ((&b - c.constraints.data()) % 2 && m.num_links() > 1) {
          b.link_b = (b.link + 1 + static_cast<int>(rng() % (m.num_links() - 1))) % m.num_links();
          b.point_b = achd::Vector3::NullaryExpr([&] { return U(rng); });
        }
        b.alpha = achd::ConstraintMatrix::NullaryExpr(6, columns, [&] { return U(rng); });
        b.beta = achd::ConstraintVector::NullaryExpr(columns, [&] { return U(rng); });
        // driver priorities on every other block (driver_priorities.cpp runs)
        if (blocks % 2) {
          b.w_fext = achd::ConstraintVector::NullaryExpr(columns, [&] { return (U(rng) + 1) / 2; });
          b.w_ff = achd::ConstraintVector::NullaryExpr(columns, [&] { return (U(rng) + 1) / 2; });
        }
      }
      for (auto policy : {achd::SingularityPolicy::Truncate, achd::SingularityPolicy::Damped,
                          achd::SingularityPolicy::VariableDamping}) {
        achd::Options o;
        o.policy = policy;
        o.effects = achd::kAllEffects;
        EXPECT_EQ(allocations_of_solve(m, d, c, o), 0)
            << r["name"] << " blocks=" << blocks << " columns=" << c.num_constraints()
            << " policy=" << static_cast<int>(policy);
        ASSERT_TRUE(d.qdd.allFinite() && d.nu.allFinite());
        ASSERT_EQ(d.nu.size(), c.num_constraints());
        ++solves;
      }
    }
  }
  EXPECT_GT(solves, 0);
}

// The tree robots of robots/index.json (no tip) with their default held links held in 6D
// and in 3D (the four-bar: its loop joint alone, which every solve holds), every policy,
// with driver weights and virtual wrenches, on a fixed and on a floating base.
TEST(NoAllocation, HybridDynamicsOnTheTreeRobotsHoldingTheirDefaultLinks) {
  std::ifstream in(kRepo + "/robots/index.json");
  ASSERT_TRUE(in) << kRepo;
  const nlohmann::json index = nlohmann::json::parse(in);
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> U(-1, 1);
  int solves = 0;
  for (const auto& r : index["robots"])
  for (bool floating : {false, true}) {
    if (r.contains("tip")) continue;
    achd::UrdfOptions options;
    if (r.contains("mimic")) options.mimic = achd::mimic_joints_from_name(r["mimic"], "mimic");
    options.floating = floating;
    if (r.contains("loops")) options.loops = achd::test::read_loops_file(kRepo + "/" + r["loops"].get<std::string>());
    const achd::Model m =
        achd::load_urdf_file(kRepo + "/" + r["urdf"].get<std::string>(), r["root"].get<std::string>(), "", options);
    achd::Data d(m);
    const int n = m.num_rates();
    achd::Case c = achd::Case::zeros(m);  // a floating base: at the origin, upright
    const int first = floating ? 7 : 0;   // where the joints' positions start in q
    for (int i = first; i < c.q.size(); ++i) c.q[i] = r["q0"][i - first].get<double>();
    c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    c.f_ext.assign(m.num_links(), achd::Vector6::Zero());
    for (auto& w : c.f_ext) w = achd::Vector6::NullaryExpr([&] { return U(rng); });
    c.f_virtual = c.f_ext;
    for (int columns : {3, 6}) {
      c.constraints.clear();
      for (const auto& link : r.value("constraints", nlohmann::json::array())) {
        achd::ConstraintBlock b;
        b.link = m.link_index(link.get<std::string>());
        b.alpha = achd::ConstraintMatrix::Identity(6, columns);
        b.beta = achd::ConstraintVector::Zero(columns);
        b.w_fext = achd::ConstraintVector::Constant(columns, 0.5);
        c.constraints.push_back(b);
      }
      for (auto policy : {achd::SingularityPolicy::Truncate, achd::SingularityPolicy::Damped,
                          achd::SingularityPolicy::VariableDamping}) {
        achd::Options o;
        o.policy = policy;
        o.effects = achd::kAllEffects;
        EXPECT_EQ(allocations_of_solve(m, d, c, o), 0) << r["name"] << " columns=" << columns;
        ASSERT_TRUE(d.qdd.allFinite() && d.nu.allFinite());
        ++solves;
      }
    }
  }
  // quadruped, dual-arm torso, Panda with fingers, humanoid, four-bar; fixed and floating
  EXPECT_EQ(solves, 5 * 2 * 2 * 3);
}

// Solves asked for some links' accelerations or for none (Data::set_link_outputs, the
// path `achd bench` and the simulator take): every robot of robots/index.json (the trees
// also on a floating base), its default held links (a chain: its tip) held in 3D, with and without
// wrenches on the links.
TEST(NoAllocation, HybridDynamicsWithSomeOrNoLinkOutputs) {
  std::ifstream in(kRepo + "/robots/index.json");
  ASSERT_TRUE(in) << kRepo;
  const nlohmann::json index = nlohmann::json::parse(in);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  int solves = 0;
  for (const auto& r : index["robots"])
    for (bool floating : {false, true}) {
      if (floating && r.contains("tip")) continue;  // the chains' roots are massless bases
      achd::UrdfOptions options;
      if (r.contains("mimic")) options.mimic = achd::mimic_joints_from_name(r["mimic"], "mimic");
      if (r.contains("loops")) options.loops = achd::test::read_loops_file(kRepo + "/" + r["loops"].get<std::string>());
      options.floating = floating;
      const achd::Model m = achd::load_urdf_file(kRepo + "/" + r["urdf"].get<std::string>(),
                                                 r["root"].get<std::string>(), r.value("tip", ""), options);
      const int n = m.num_rates();
      achd::Case c = achd::Case::zeros(m);
      for (int i = m.free_joint_positions(); i < c.q.size(); ++i)
        c.q[i] = r["q0"][i - m.free_joint_positions()].get<double>();
      c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
      c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
      if (m.has_tip()) {
        c.alpha = achd::ConstraintMatrix::Identity(6, 3);
        c.beta = achd::ConstraintVector::Zero(3);
      }
      for (const auto& link : r.value("constraints", nlohmann::json::array())) {
        achd::ConstraintBlock b;
        b.link = m.link_index(link.get<std::string>());
        b.alpha = achd::ConstraintMatrix::Identity(6, 3);
        b.beta = achd::ConstraintVector::Zero(3);
        c.constraints.push_back(b);
      }
      for (const std::vector<int>& wanted : {std::vector<int>{}, std::vector<int>{-1, m.num_links() - 1}}) {
        achd::Data d(m);
        d.set_link_outputs(wanted);
        for (bool wrenches : {false, true}) {
          c.f_ext.clear();
          if (wrenches)
            for (int l = 0; l < m.num_links(); ++l) c.f_ext.push_back(achd::Vector6::NullaryExpr([&] { return U(rng); }));
          achd::Options o;
          o.effects = achd::kAllEffects;
          achd::hybrid_dynamics(m, d, c, o);  // the first solve of a case sizes the loop case's copies
          EXPECT_EQ(allocations_of_solve(m, d, c, o), 0)
              << r["name"] << (floating ? " floating" : "") << " links asked " << wanted.size();
          ASSERT_TRUE(d.qdd.allFinite());
          ++solves;
        }
      }
    }
  const auto chains = std::count_if(index["robots"].begin(), index["robots"].end(),
                                    [](const nlohmann::json& r) { return r.contains("tip"); });
  const auto trees = static_cast<long>(index["robots"].size()) - chains;
  EXPECT_EQ(solves, static_cast<int>((chains + 2 * trees) * 2 * 2));
}

TEST(NoAllocation, WorkspaceFormsOfKinematicsAndDynamicsOnEveryRobot) {
  std::ifstream in(kRepo + "/robots/index.json");
  ASSERT_TRUE(in) << kRepo;
  const nlohmann::json index = nlohmann::json::parse(in);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(-1, 1);
  for (const auto& r : index["robots"]) {
    if (!r.contains("tip")) continue;  // the trees: tests/native/dynamics/tree_identities.cpp
    const achd::Model m = achd::load_urdf_file(kRepo + "/" + r["urdf"].get<std::string>(),
                                               r["root"].get<std::string>(), r["tip"].get<std::string>());
    const int n = m.num_rates();
    const Eigen::VectorXd q = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    const Eigen::VectorXd qd = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    const Eigen::VectorXd qdd = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    std::vector<achd::Vector6> f_ext(m.num_links());
    for (auto& w : f_ext) w = achd::Vector6::NullaryExpr([&] { return U(rng); });
    achd::ChainWorkspace ws(m);
    Eigen::VectorXd tau(n);
    Eigen::MatrixXd M(n, n), J(6, n);
    std::vector<achd::Transform> poses(m.num_links());
    std::vector<achd::Vector6> velocities(m.num_links());
    g_allocations = 0;
    g_counting = true;
    for (int k = 0; k < 2; ++k) {
      achd::rnea(m, ws, q, qd, qdd, achd::Vector3(0, 0, -9.81), f_ext, achd::with_effects(achd::kAllEffects), tau);
      achd::crba(m, ws, q, {}, M);
      achd::forward_kinematics(m, q, ws, poses);
      achd::link_velocities(m, q, qd, ws, velocities);
      achd::tip_jacobian(m, q, ws, J);
      achd::link_jacobian(m, q, m.num_links() - 1, achd::Vector3(0.1, 0.2, 0.3), ws, J);
    }
    g_counting = false;
    EXPECT_EQ(g_allocations, 0) << r["name"];
    // They computed something: the value forms give the same.
    EXPECT_EQ(tau, achd::rnea(m, q, qd, qdd, achd::Vector3(0, 0, -9.81), f_ext, achd::with_effects(achd::kAllEffects)));
    EXPECT_EQ(M, achd::crba(m, q));
  }
}

}  // namespace

// Loop joints: every solve sets the loops' blocks at the case's q in the Data's storage
// (the case is not copied). The four-bar's revolute loop on a fixed base, and the
// floating quadruped with its front feet closed by a spherical loop and its hind feet by a
// fixed one, beside a block on one link, with every input nonzero.
TEST(NoAllocation, HybridDynamicsWithLoopJoints) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> U(-1, 1);
  achd::LoopJointSpec pin;
  pin.name = "coupler_rocker";
  pin.type = achd::LoopType::Revolute;
  pin.axis = achd::Vector3(0, 1, 0);
  pin.link_a = "coupler", pin.link_b = "rocker";
  pin.origin_a.p = achd::Vector3(0.12, 0, 0), pin.origin_b.p = achd::Vector3(0.08, 0, 0);
  achd::LoopJointSpec front{"front_feet", "lf_foot", "rf_foot"}, hind{"hind_feet", "lh_foot", "rh_foot"};
  front.type = achd::LoopType::Spherical;
  hind.type = achd::LoopType::Fixed;
  achd::UrdfOptions four_bar, quadruped;
  four_bar.loops = {pin};
  quadruped.loops = {front, hind};
  quadruped.floating = true;
  const achd::Model models[] = {achd::load_urdf_file(kRepo + "/robots/four_bar.urdf", "", "", four_bar),
                                achd::load_urdf_file(kRepo + "/robots/quadruped.urdf", "", "", quadruped)};
  for (const achd::Model& m : models) {
    ASSERT_GT(m.num_loop_columns(), 0);
    achd::Data d(m);
    const int n = m.num_rates();
    achd::Case c = achd::Case::zeros(m);
    for (int i = m.free_joint_positions(); i < c.q.size(); ++i) c.q[i] = U(rng);
    c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
    c.f_ext.assign(m.num_links(), achd::Vector6::Zero());
    for (auto& w : c.f_ext) w = achd::Vector6::NullaryExpr([&] { return U(rng); });
    c.loop_beta = Eigen::VectorXd::NullaryExpr(m.num_loop_columns(), [&] { return U(rng); });
    achd::ConstraintBlock b;
    b.link = m.num_links() - 1;
    b.alpha = achd::ConstraintMatrix::Identity(6, 3);
    b.beta = achd::ConstraintVector::Zero(3);
    c.constraints.push_back(b);
    for (auto policy : {achd::SingularityPolicy::Truncate, achd::SingularityPolicy::VariableDamping}) {
      achd::Options o;
      o.policy = policy;
      o.effects = achd::kAllEffects;
      achd::hybrid_dynamics(m, d, c, o);  // the first solve of a case sizes the free joint's copies
      EXPECT_EQ(allocations_of_solve(m, d, c, o), 0) << m.root_name;
      ASSERT_TRUE(d.qdd.allFinite() && d.nu.allFinite());
      EXPECT_EQ(d.nu.size(), 3 + m.num_loop_columns());
    }
  }
}

// The Delta robot's five loops, every one ending on the platform: the sweep that rolls the
// platform's path once for all of them (shared_second_body.hpp), every policy.
TEST(NoAllocation, HybridDynamicsWithLoopsSharingTheirSecondBody) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> U(-1, 1);
  achd::UrdfOptions options;
  options.loops = achd::test::read_loops_file(kRepo + "/robots/delta.loops.json");
  const achd::Model m = achd::load_urdf_file(kRepo + "/robots/delta.urdf", "", "", options);
  achd::Data d(m);
  const int n = m.num_rates();
  achd::Case c = achd::Case::zeros(m);
  for (int i = 0; i < c.q.size(); ++i) c.q[i] = U(rng);
  c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
  c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return U(rng); });
  c.f_ext.assign(m.num_links(), achd::Vector6::Zero());
  for (auto& w : c.f_ext) w = achd::Vector6::NullaryExpr([&] { return U(rng); });
  c.loop_beta = Eigen::VectorXd::NullaryExpr(m.num_loop_columns(), [&] { return U(rng); });
  for (auto policy : {achd::SingularityPolicy::Truncate, achd::SingularityPolicy::Damped,
                      achd::SingularityPolicy::VariableDamping}) {
    achd::Options o;
    o.policy = policy;
    o.effects = achd::kAllEffects;
    EXPECT_EQ(allocations_of_solve(m, d, c, o), 0);
    EXPECT_GE(d.workspace.shared_body, 0);
    ASSERT_TRUE(d.qdd.allFinite() && d.nu.allFinite());
  }
}
