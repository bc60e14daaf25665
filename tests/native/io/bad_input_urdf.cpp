// Bad URDFs through the C++ API: load_urdf_string and load_urdf_file throw achd::Error
// naming the source, the link or joint and the problem; massless links, long chains,
// axes of any length and (on request) mimic joints are valid.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <random>

#include "achd/achd.hpp"
#include "bad_input_urdfs.hpp"
#include "hard_chain_urdf.hpp"

namespace achd::test {
namespace {

std::string error_of(const std::string& xml, const std::string& root, const std::string& tip,
                     const UrdfOptions& options = {}) {
  try {
    load_urdf_string(xml, root, tip, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BadInputUrdf, EveryKindIsRefusedWithAMessageNamingIt) {
  for (const BadUrdf& b : bad_urdfs()) {
    const std::string msg = error_of(b.xml, b.root, b.tip);
    EXPECT_EQ(msg.rfind("URDF: ", 0), 0u) << b.what << ": " << msg;
    for (const std::string& part : b.message)
      EXPECT_NE(msg.find(part), std::string::npos) << b.what << ": '" << msg << "' lacks '" << part << "'";
  }
}

TEST(BadInputUrdf, MissingFileNamesThePath) {
  try {
    load_urdf_file("/nonexistent/robot.urdf", "a", "b");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/robot.urdf: cannot open file");
  }
}

TEST(BadInputUrdf, FileErrorsStartWithThePath) {
  const std::string path = testing::TempDir() + "bad_input_negative_mass.urdf";
  std::ofstream(path) << robot(link("a") + link("b", unit_inertial("-1")) +
                               joint("j", "revolute", "a", "b"));
  try {
    load_urdf_file(path, "a", "b");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": link 'b': negative mass", 0), 0u) << e.what();
  }
}

// The inertia policies on a link whose principal moments are 1, 1, 2 + 1e-8 (the triangle
// inequality violated beyond its 1e-9 relative tolerance): accept loads it as written with
// a warning naming the link; strict refuses it; repair raises the two smaller moments by
// half the deficit each and says so.
TEST(BadInputUrdf, InertiaPoliciesOnATriangleViolation) {
  const std::string urdf =
      robot(link("a") + link("b", unit_inertial("1", "1", "0", "2.00000001")) + joint("j", "revolute", "a", "b"));
  const Model accepted = load_urdf_string(urdf, "a", "b");
  ASSERT_EQ(accepted.warnings.size(), 1u);
  EXPECT_EQ(accepted.warnings[0],
            "link 'b': inertia violates the triangle inequality (principal moments 1, 1, 2), loaded as written");
  UrdfOptions strict, repair;
  strict.inertia = InertiaPolicy::Strict;
  repair.inertia = InertiaPolicy::Repair;
  EXPECT_EQ(error_of(urdf, "a", "b", strict),
            "URDF: link 'b': inertia violates the triangle inequality (principal moments 1, 1, 2)");
  const Model repaired = load_urdf_string(urdf, "a", "b", repair);
  ASSERT_EQ(repaired.warnings.size(), 1u);
  EXPECT_EQ(repaired.warnings[0].rfind("link 'b': inertia repaired: principal moments 1, 1, 2 -> 1, 1, 2", 0), 0u)
      << repaired.warnings[0];
  // The repaired inertia: its moments about the COM sum as the triangle asks.
  EXPECT_EQ(inertia_policy_from_name("repair", "inertia"), InertiaPolicy::Repair);
  EXPECT_EQ(std::string(inertia_policy_name(InertiaPolicy::Accept)), "accept");
}

// The triangle inequality is checked to 1e-9 relative: a rod (moments 1, 1, 2 within
// 1e-12) and massless links in the middle of a chain are valid.
TEST(BadInputUrdf, BoundaryCasesThatAreValid) {
  EXPECT_NO_THROW(load_urdf_string(robot(link("a") + link("b", unit_inertial("1", "1", "0", "2.000000000001")) +
                                         joint("j", "revolute", "a", "b")),
                                   "a", "b"));
  EXPECT_NO_THROW(load_urdf_string(robot(link("a") + link("b", "") + link("c") +
                                         joint("j1", "revolute", "a", "b") +
                                         "<joint name=\"j2\" type=\"continuous\"><parent link=\"b\"/>"
                                         "<child link=\"c\"/><origin xyz=\"0.2 0 0\"/><axis xyz=\"0 1 0\"/></joint>"),
                                   "a", "c"));
}

const std::string kOneJoint = link("a") + link("b") + joint("j", "revolute", "a", "b");

TEST(BadInputUrdf, NestingUpToTheLimitLoads) {
  EXPECT_NO_THROW(load_urdf_string(robot(kOneJoint + nested(kMaxUrdfNesting - 1)), "a", "b"));
  EXPECT_EQ(error_of(robot(kOneJoint + nested(kMaxUrdfNesting)), "a", "b"),
            "URDF: cannot parse URDF: elements nested more than 100 deep (line 1), which achd refuses: "
            "its XML parser recurses once per level");
}

// The depth scan reads the text as TinyXML does. Each of these nests 200 elements for
// TinyXML although a scan by XML's own rules would see one level: a quoted "/>", a
// processing instruction or "<!" node that TinyXML ends at the first '>', an end tag
// swallowed by a UTF-8 lead byte (UTF-8 once the declaration says so) or by a numeric
// entity that runs to the next ';'.
TEST(BadInputUrdf, NestingIsCountedAsTinyXmlReadsIt) {
  auto repeat = [](const std::string& s, int n) {
    std::string out;
    for (int i = 0; i < n; ++i) out += s;
    return out;
  };
  const std::string utf8 = "<?xml version=\"1.0\"?>";
  const std::vector<std::pair<std::string, std::string>> deep = {
      {"quoted />", repeat("<x a=\"/>\">", 200) + repeat("</x>", 200)},
      {"processing instruction", "<?pi >" + nested(200) + "?>"},
      {"<! node with brackets", "<!x [" + nested(200) + "]>"},
      {"UTF-8 lead byte before an end tag", repeat("<x>\xc3</x>", 200)},
      {"entity across an end tag", repeat("<x>&#x</x>x41;", 200)},
  };
  for (const auto& [what, junk] : deep) {
    const std::string xml = (what.rfind("UTF-8", 0) == 0 ? utf8 : "") + robot(kOneJoint + junk);
    EXPECT_NE(error_of(xml, "a", "b").find("nested more than 100 deep"), std::string::npos) << what;
  }
  // Without a declaration TinyXML's encoding is unknown: the lead byte is one character.
  EXPECT_NO_THROW(load_urdf_string(robot(kOneJoint + repeat("<x>\xc3</x>", 200)), "a", "b"));
  // Text TinyXML does not read as elements is not counted.
  const std::vector<std::pair<std::string, std::string>> shallow = {
      {"comment", "<!--" + nested(200) + "-->"},
      {"CDATA", "<y><![CDATA[" + nested(200) + "]]></y>"},
      {"attribute value", "<y a=\"" + nested(200) + "\"/>"},
      {"entity in an attribute value", "<y a=\"&#x" + nested(200) + "x41;\"/>"},
  };
  for (const auto& [what, junk] : shallow)
    EXPECT_NO_THROW(load_urdf_string(robot(kOneJoint + junk), "a", "b")) << what;
}

Model one_joint_with_axis(const std::string& axis) {
  return load_urdf_string(robot(link("a") + link("b", unit_inertial("2", "0.8", "0.1", "0.6")) +
                                joint("j", "continuous", "a", "b", "<axis xyz=\"" + axis + "\"/>")),
                          "a", "b");
}

// An axis whose |a|^2 overflows became the z axis; it is the same axis as a unit one,
// bit for bit when it has one component, and axes shorter than 1e-12 are still zero.
TEST(BadInputUrdf, AxisLengthDoesNotMatter) {
  for (const auto& [huge, unit] : std::vector<std::pair<std::string, std::string>>{
           {"1e200 0 0", "1 0 0"}, {"0 -1e300 0", "0 -1 0"}, {"0 0 1.7e308", "0 0 1"}, {"1e-11 0 0", "1 0 0"}}) {
    const Model a = one_joint_with_axis(huge), b = one_joint_with_axis(unit);
    EXPECT_EQ(a.bodies[0].X_tree.R, b.bodies[0].X_tree.R) << huge;
    EXPECT_EQ(a.bodies[0].inertia, b.bodies[0].inertia) << huge;
    EXPECT_EQ(a.links[0].offset.R, b.links[0].offset.R) << huge;
  }
  const Model a = one_joint_with_axis("3e200 4e200 0"), b = one_joint_with_axis("3 4 0");
  EXPECT_TRUE(a.bodies[0].X_tree.R.isApprox(b.bodies[0].X_tree.R, 1e-15));
  EXPECT_NE(error_of(robot(link("a") + link("b") + joint("j", "continuous", "a", "b", "<axis xyz=\"1e-13 0 0\"/>")),
                     "a", "b").find("joint 'j': axis is zero"), std::string::npos);
}

// 10000 links of 1 kg, 5 cm apart, axes x, y, z in turn: the bound n eps M_ii on D's
// round-off refused it (joint 'j1756' moves nothing); every joint moves something.
TEST(BadInputUrdf, LongChainLoadsAndSolvesFinitely) {
  std::vector<LinkSpec> links(10000);
  for (size_t i = 0; i < links.size(); ++i) {
    links[i].joint_xyz = Eigen::Vector3d(0, 0, 0.05);
    links[i].axis = Eigen::Vector3d::Unit(static_cast<int>((i + 1) % 3));
  }
  const auto start = std::chrono::steady_clock::now();
  const Model m = load_urdf_string(chain_urdf(links), "link0", "link10000");
  // ~0.7 s in Release, ~6 s under ASan: linear; a quadratic check would take minutes.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30);
  ASSERT_EQ(m.num_rates(), 10000);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Case c = Case::zeros(m);
  for (int i = 0; i < m.num_rates(); ++i) c.q[i] = u(rng);
  c.gravity = Vector3(0, 0, -9.81);
  Data d(m);
  hybrid_dynamics(m, d, c);
  EXPECT_TRUE(d.qdd.allFinite());
}

// A <mimic> joint on the chain is coupled to its leader by default, refused with the mimic
// option 'error', a joint of its own with 'independent'; one off the chain does not matter.
TEST(BadInputUrdf, MimicJointsAreCoupledByDefault) {
  const std::string limit = "<axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>";
  const std::string body = link("a") + link("b") + link("c") + link("d") + joint("j1", "revolute", "a", "b") +
                           joint("j3", "revolute", "a", "d", limit + "<mimic joint=\"j1\"/>");
  const std::string with = robot(body + joint("j2", "revolute", "b", "c", limit + "<mimic joint=\"j1\" multiplier=\"2\"/>"));
  const std::string without = robot(body + joint("j2", "revolute", "b", "c", limit));
  const Model coupled = load_urdf_string(with, "a", "c");
  ASSERT_EQ(coupled.couplings.size(), 1u);
  EXPECT_EQ(coupled.couplings[0].follower, 1);
  EXPECT_EQ(coupled.couplings[0].leader, 0);
  EXPECT_EQ(coupled.couplings[0].multiplier, 2.0);
  UrdfOptions refuse;
  refuse.mimic = MimicJoints::Error;
  try {
    load_urdf_string(with, "a", "c", refuse);
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "URDF: joint 'j2': <mimic> of joint 'j1': refused (the mimic option 'error'); the default 'couple' "
              "holds it to its leader, 'independent' (CLI --mimic independent) makes it a joint of its own, as KDL "
              "does");
  }
  UrdfOptions independent;
  independent.mimic = MimicJoints::Independent;
  const Model m = load_urdf_string(with, "a", "c", independent), plain = load_urdf_string(without, "a", "c");
  ASSERT_EQ(m.num_rates(), 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(m.bodies[i].X_tree.R, plain.bodies[i].X_tree.R);
    EXPECT_EQ(m.bodies[i].X_tree.p, plain.bodies[i].X_tree.p);
    EXPECT_EQ(m.bodies[i].inertia, plain.bodies[i].inertia);
  }
  EXPECT_NO_THROW(load_urdf_string(with, "a", "b"));  // j3 and j2 are off the chain a -> b
  EXPECT_EQ(mimic_joints_from_name("independent", "mimic"), MimicJoints::Independent);
  EXPECT_EQ(mimic_joints_from_name("couple", "mimic"), MimicJoints::Couple);
  try {
    mimic_joints_from_name("fold", "mimic");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "mimic: expected 'couple', 'independent' or 'error', got 'fold'");
  }
}

}  // namespace
}  // namespace achd::test
