// Link outputs (Data::set_link_outputs): a solve asked for some links' accelerations gives
// those bit for bit as the solve of every link does, with every other result bit for bit
// the same, and does not write the links it was not asked for. On every robot of
// robots/index.json (the trees also floating), with constraints, wrenches, couplings and loops;
// on the quadruped with 60 massless frames added; and the simulator, which asks for the
// links with directions alone.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "achd/achd.hpp"
#include "robot_index.hpp"

namespace achd::test {
namespace {

const std::string kRepo = ACHD_SOURCE_DIR;

// A value no solve writes: a link keeping it was left alone.
const Vector6 kUntouched = Vector6::Constant(-12345.678);

// q0 (after an upright floating base at the origin), random qd, ff torques and wrenches;
// the default held links (a chain: its tip) held in 3D.
Case inputs(std::mt19937& rng, const Model& m, const IndexedRobot& r) {
  std::uniform_real_distribution<double> U(-1, 1);
  Case c = Case::zeros(m);
  for (int i = 0; i < r.q0.size(); ++i) c.q[m.free_joint_positions() + i] = r.q0[i];
  c.qd = Eigen::VectorXd::NullaryExpr(m.num_rates(), [&] { return U(rng); });
  c.ff_torques = Eigen::VectorXd::NullaryExpr(m.num_rates(), [&] { return U(rng); });
  c.f_ext.assign(m.num_links(), Vector6::Zero());
  for (Vector6& w : c.f_ext) w = Vector6::NullaryExpr([&] { return U(rng); });
  if (m.has_tip()) {
    c.alpha = ConstraintMatrix::Identity(6, 3);
    c.beta = ConstraintVector::NullaryExpr(3, [&] { return U(rng); });
  }
  for (const std::string& name : r.constraints) {
    ConstraintBlock b;
    b.link = m.link_index(name);
    b.alpha = ConstraintMatrix::Identity(6, 3);
    b.beta = ConstraintVector::Zero(3);
    c.constraints.push_back(b);
  }
  return c;
}

// Every result but the link accelerations is bit for bit the same.
void expect_same_results(const Data& a, const Data& b, const std::string& what) {
  EXPECT_EQ(a.qdd, b.qdd) << what;
  EXPECT_EQ(a.nu, b.nu) << what;
  EXPECT_EQ(a.joint_torques, b.joint_torques) << what;
  EXPECT_EQ(a.constraint_torques, b.constraint_torques) << what;
  EXPECT_EQ(a.total_torques, b.total_torques) << what;
  EXPECT_EQ(a.prescribed_torques, b.prescribed_torques) << what;
  EXPECT_EQ(a.virtual_torques, b.virtual_torques) << what;
  EXPECT_EQ(a.coupling_forces, b.coupling_forces) << what;
  EXPECT_EQ(a.constraint_wrench, b.constraint_wrench) << what;
  EXPECT_EQ(a.constraint_wrenches, b.constraint_wrenches) << what;
  EXPECT_EQ(a.rank, b.rank) << what;
}

// Solves c with every link's outputs and with those of `wanted` (Model::links indices, -1
// the root link), the others' entries set to kUntouched before: the wanted equal, the
// others untouched, every other result equal.
void expect_wanted_links_alone(const Model& m, const Case& c, const std::vector<int>& wanted,
                               const std::string& what) {
  Options o;
  o.effects = kAllEffects;
  Data all(m), some(m);
  EXPECT_TRUE(all.all_link_outputs());  // a new Data: every link
  hybrid_dynamics(m, all, c, o);
  some.set_link_outputs(wanted);
  EXPECT_FALSE(some.all_link_outputs());
  for (Vector6& a : some.link_accelerations) a = kUntouched;
  hybrid_dynamics(m, some, c, o);
  expect_same_results(all, some, what);
  std::vector<bool> asked(m.num_links() + 1, false);
  for (int l : wanted) asked[l + 1] = true;
  for (int l = -1; l < m.num_links(); ++l) {
    const std::string link = what + ", link " + (l < 0 ? m.root_name : m.links[l].name);
    if (asked[l + 1]) EXPECT_EQ(some.link_accelerations[l + 1], all.link_accelerations[l + 1]) << link;
    else EXPECT_EQ(some.link_accelerations[l + 1], kUntouched) << link;
  }
}

TEST(LinkOutputs, WantedLinksEqualTheFullSolveAndTheOthersAreNotWritten) {
  std::mt19937 rng(31);
  std::vector<IndexedRobot> robots = load_robot_index(kRepo);
  for (IndexedRobot& r : load_tree_index(kRepo)) robots.push_back(std::move(r));
  int solves = 0;
  for (const IndexedRobot& r : robots)
    for (bool floating : {false, true}) {
      if (floating && !r.tip.empty()) continue;  // the chains' roots are massless bases
      UrdfOptions options = r.options;
      options.floating = floating;
      const Model m = load_urdf_string(r.urdf, r.root, r.tip, options);
      const Case c = inputs(rng, m, r);
      const std::string what = r.name + (floating ? ", floating" : "");
      // the root link, every third link and the last; then none; then every link named
      std::vector<int> some = {-1};
      for (int l = 1; l < m.num_links(); l += 3) some.push_back(l);
      some.push_back(m.num_links() - 1);
      std::vector<int> every;
      for (int l = -1; l < m.num_links(); ++l) every.push_back(l);
      expect_wanted_links_alone(m, c, some, what + ", some links");
      expect_wanted_links_alone(m, c, {}, what + ", no link");
      expect_wanted_links_alone(m, c, every, what + ", every link named");
      solves += 3;
    }
  EXPECT_GT(solves, 30);
}

TEST(LinkOutputs, SetLinkOutputsZeroesTheOthersAndSetAllRestoresEveryLink) {
  const std::vector<IndexedRobot> robots = load_robot_index(kRepo);
  const IndexedRobot& r = robots.front();
  const Model& m = r.model;
  std::mt19937 rng(32);
  const Case c = inputs(rng, m, r);
  Data full(m), d(m);
  hybrid_dynamics(m, full, c);
  hybrid_dynamics(m, d, c);
  d.set_link_outputs({m.num_links() - 1, m.num_links() - 1, 0});  // repeated, unsorted
  EXPECT_EQ(d.link_outputs(), (std::vector<int>{0, m.num_links() - 1}));
  for (int l = 0; l <= m.num_links(); ++l)
    if (l != 1 && l != m.num_links()) EXPECT_EQ(d.link_accelerations[l], Vector6::Zero()) << l;
  EXPECT_EQ(d.link_accelerations[1], full.link_accelerations[1]);  // kept from the last solve
  d.set_all_link_outputs();
  EXPECT_TRUE(d.all_link_outputs());
  hybrid_dynamics(m, d, c);
  EXPECT_EQ(d.link_accelerations, full.link_accelerations);
}

TEST(LinkOutputs, LinksOutOfRangeAreRefusedByName) {
  const std::vector<IndexedRobot> robots = load_robot_index(kRepo);
  const Model& m = robots.front().model;
  Data d(m);
  for (int l : {-2, m.num_links()}) {
    try {
      d.set_link_outputs({0, l});
      FAIL() << l;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("link_outputs[1]: " + std::to_string(l)), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(d.all_link_outputs());  // a refused list changes nothing
}

// The quadruped with 60 massless frames on fixed joints: the same joint accelerations and
// forces as the quadruped, and the frames' accelerations, when asked, those of the solve
// of every link.
TEST(LinkOutputs, MasslessFramesChangeNothingAndGiveTheirAccelerationsWhenAsked) {
  const std::string urdf = read_text(kRepo + "/robots/quadruped.urdf");
  const Model plain = load_urdf_string(urdf, "trunk", "");
  std::string frames;
  for (int k = 0; k < 60; ++k) {
    const int parent = k % (plain.num_links() + 1);
    const std::string name = "frame_" + std::to_string(k);
    frames += "<joint name=\"" + name + "_joint\" type=\"fixed\"><parent link=\"" +
              (parent ? plain.links[parent - 1].name : plain.root_name) + "\"/><child link=\"" + name +
              "\"/><origin xyz=\"0.01 0.02 -0.03\" rpy=\"0.1 0.2 " + std::to_string(0.1 * k) + "\"/></joint><link name=\"" +
              name + "\"/>";
  }
  const std::size_t end = urdf.rfind("</robot>");
  const Model framed = load_urdf_string(urdf.substr(0, end) + frames + urdf.substr(end), "trunk", "");
  ASSERT_EQ(framed.num_links(), plain.num_links() + 60);
  ASSERT_EQ(framed.num_rates(), plain.num_rates());
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> U(-1, 1);
  Case c = Case::zeros(plain);
  c.q = Eigen::VectorXd::NullaryExpr(plain.num_rates(), [&] { return U(rng); });
  c.qd = Eigen::VectorXd::NullaryExpr(plain.num_rates(), [&] { return U(rng); });
  Case held = c;
  for (const char* foot : {"lf_foot", "rh_foot"}) {
    ConstraintBlock b;
    b.alpha = ConstraintMatrix::Identity(6, 3);
    b.beta = ConstraintVector::Zero(3);
    b.link = plain.link_index(foot);
    c.constraints.push_back(b);
    b.link = framed.link_index(foot);
    held.constraints.push_back(b);
  }
  Data d_plain(plain), d_framed(framed);
  d_plain.set_link_outputs({});
  d_framed.set_link_outputs({});
  hybrid_dynamics(plain, d_plain, c);
  hybrid_dynamics(framed, d_framed, held);
  expect_same_results(d_plain, d_framed, "60 frames");
  std::vector<int> frame_links;
  for (int k = 0; k < 60; k += 7) frame_links.push_back(framed.link_index("frame_" + std::to_string(k)));
  expect_wanted_links_alone(framed, held, frame_links, "60 frames, some frames asked");
}

// The simulator asks for the accelerations of the links with directions alone (it reads
// the links' motion from the kinematics): while it holds a foot, data() holds the foot's
// (its z acceleration 0 where it is held: physical convention) and no other link's.
TEST(LinkOutputs, TheSimulatorComputesTheLinksWithDirectionsAlone) {
  const std::vector<IndexedRobot> trees = load_tree_index(kRepo);
  const IndexedRobot& r = trees.front();
  Simulator sim(r.model);
  sim.q.tail(r.q0.size()) = r.q0;
  const int foot = r.model.link_index(r.constraints.front());
  for (int k = 0; k < 3; ++k) sim.set_direction(foot, k, DirectionMode::Hold);
  sim.run(10, 1e-3);
  EXPECT_EQ(sim.data().nu.size(), 3);
  for (int l = -1; l < r.model.num_links(); ++l) {
    const Vector6& a = sim.data().link_accelerations[l + 1];
    if (l == foot) EXPECT_NEAR(a[2], 0, 1e-6) << a.transpose();
    else EXPECT_EQ(a, Vector6::Zero()) << l;
  }
  EXPECT_NE(sim.data().link_accelerations[foot + 1], Vector6::Zero());
}

}  // namespace
}  // namespace achd::test
