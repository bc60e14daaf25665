// The command line on whole robots, through the real `achd` binary: inputs by
// name (q, qd, ff_torques by joint, f_ext by link) give the results of the arrays; results
// name their joints and links; constraint blocks are read by link name, with errors naming
// the field and index; without --tip the whole tree loads; --lock and locked side joints
// are reported by `achd info` and in results; --convention kdl loads a chain as KDL does;
// `achd bench` takes every case `achd solve` takes. The small tree is
// tests/fixtures/small_tree.urdf.
#include <gtest/gtest.h>

#include <fstream>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "case_json.hpp"
#include "cli_run.hpp"

namespace achd::test {
namespace {

using nlohmann::json;

const std::string kKuka = ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf";
const std::string kTree = ACHD_SOURCE_DIR "/tests/fixtures/small_tree.urdf";
const std::vector<std::string> kKukaChain = {"--root", "lwr_base_link", "--tip", "lwr_link_7"};
const std::vector<double> kKukaQ = {0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1};
const std::vector<std::string> kKukaJoints = {"lwr_joint_1", "lwr_joint_2", "lwr_joint_3", "lwr_joint_4",
                                              "lwr_joint_5", "lwr_joint_6", "lwr_joint_7"};

class CliTrees : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = make_temp_dir("achd_cli_trees"); }

  static std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }

  // `achd command urdf args...`; must succeed with nothing on stderr.
  static std::string ok(const std::string& command, const std::string& urdf, std::vector<std::string> args) {
    args.insert(args.begin(), {command, urdf});
    const CliRun r = run_cli(dir_, args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    return r.out;
  }
  static json solve(const std::string& urdf, std::vector<std::string> args, const json& c) {
    args.insert(args.end(), {"--case", write("case.json", c.dump())});
    const std::string out = ok("solve", urdf, args);
    return out.empty() ? json() : json::parse(out);
  }
  static json info(const std::string& urdf, const std::vector<std::string>& args) {
    const std::string out = ok("info", urdf, args);
    return out.empty() ? json() : json::parse(out);
  }

  // Exit 2, nothing on stdout, one line "achd: error: ..." holding `message`.
  static void refused(std::vector<std::string> args, const std::string& message) {
    const CliRun r = run_cli(dir_, args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err.rfind("achd: error: ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << "'" << message << "' not in: " << r.err;
  }

  static inline std::string dir_;
};

json kuka_case() { return {{"q", kKukaQ}, {"gravity", {0, 0, -9.81}}}; }

// Inputs by name: the same solve as the arrays, printed to the same bits; joints and
// links not named are 0 / no wrench. (Before: "q must be an array of 7 numbers".)
TEST_F(CliTrees, InputsByNameEqualTheArrays) {
  json by_array = kuka_case(), by_name = kuka_case();
  by_array["qd"] = {0.1, -0.2, 0.3, 0, 0.5, 0, 0.7};
  by_array["ff_torques"] = {1, 0, 0, 2, 0, 0, 0};
  by_array["f_ext"] = json::array();
  for (int l = 0; l < 7; ++l)
    by_array["f_ext"].push_back(l == 6 ? json{0, 0, -5, 0.1, 0, 0} : json{0, 0, 0, 0, 0, 0});
  by_array["alpha"] = {{0, 0, 1, 0, 0, 0}};
  by_array["beta"] = {0.2};
  by_name["q"] = json::object();
  for (int i = 6; i >= 0; --i) by_name["q"][kKukaJoints[i]] = kKukaQ[i];
  by_name["qd"] = {{"lwr_joint_1", 0.1}, {"lwr_joint_2", -0.2}, {"lwr_joint_3", 0.3}, {"lwr_joint_5", 0.5},
                   {"lwr_joint_7", 0.7}};
  by_name["ff_torques"] = {{"lwr_joint_4", 2}, {"lwr_joint_1", 1}};
  by_name["f_ext"] = {{"lwr_link_7", {0, 0, -5, 0.1, 0, 0}}};
  by_name["alpha"] = by_array["alpha"];
  by_name["beta"] = by_array["beta"];
  std::vector<std::string> args = kKukaChain;
  const std::string a = write("by_array.json", by_array.dump()), n = write("by_name.json", by_name.dump());
  std::vector<std::string> with_a = args, with_n = args;
  with_a.insert(with_a.end(), {"--case", a});
  with_n.insert(with_n.end(), {"--case", n});
  const std::string out_a = ok("solve", kKuka, with_a), out_n = ok("solve", kKuka, with_n);
  EXPECT_EQ(out_n, out_a);
  EXPECT_NE(json::parse(out_a).at("qdd"), solve(kKuka, kKukaChain, kuka_case()).at("qdd"));  // inputs mattered
}

// Every result names its joints (the order of qdd) and links (of link_accelerations, the
// root link first), and has one constraint wrench per block (none here); a model with no
// locked joint has no "locked_joints".
TEST_F(CliTrees, ResultsNameJointsAndLinks) {
  const json r = solve(kKuka, kKukaChain, kuka_case());
  EXPECT_EQ(r.at("joints"), json(kKukaJoints));
  EXPECT_EQ(r.at("links"), json({"lwr_base_link", "lwr_link_1", "lwr_link_2", "lwr_link_3", "lwr_link_4",
                                 "lwr_link_5", "lwr_link_6", "lwr_link_7"}));
  EXPECT_EQ(r.at("links").size(), r.at("link_accelerations").size());
  EXPECT_EQ(r.at("constraint_wrenches"), json::array());
  EXPECT_FALSE(r.contains("locked_joints"));
}

// Constraint blocks and inputs by name that are wrong: the error names the field and the
// index, in the user's terms.
TEST_F(CliTrees, BadBlocksAndNamesAreNamed) {
  const json col = {0, 0, 1, 0, 0, 0};
  const std::vector<std::pair<json, std::string>> bad = {
      {{{"constraints", {{{"link", "lwr_link_7"}, {"alpha", {col}}}, {{"link", "x"}, {"alpha", {col}}}}}},
       "constraints[1].link: no link 'x'"},
      {{{"constraints", {{{"link", "lwr_base_link"}, {"alpha", {col}}}}}},
       "constraints[0].link: 'lwr_base_link' is the root link"},
      {{{"constraints", {{{"link", 7}, {"alpha", {col}}}}}}, "constraints[0].link must be a link name"},
      {{{"constraints", {{{"alpha", {col}}}}}}, "constraints[0]: missing required field 'link'"},
      {{{"constraints", {{{"link", "lwr_link_3"}}}}}, "constraints[0]: missing required field 'alpha'"},
      {{{"constraints", {{{"link", "lwr_link_3"}, {"alpha", {col}}, {"where", 1}}}}},
       "constraints[0]: unknown field 'where'"},
      {{{"constraints", {{{"link", "lwr_link_3"}, {"alpha", {{0, 0, 1, 0, 0}}}}}}},
       "constraints[0].alpha[0]: expected 6 values, got 5"},
      {{{"constraints", {{{"link", "lwr_link_3"}, {"alpha", {col}}, {"beta", {1, 2}}}}}},
       "constraints[0].beta: expected 1 values (one per alpha column), got 2"},
      {{{"constraints", {{{"link", "lwr_link_3"}, {"alpha", {col}}, {"point", {0, 1}}}}}},
       "constraints[0].point: expected 3 values, got 2"},
      {{{"constraints", {{{"link", "lwr_link_3"}, {"alpha", {col, col, col, col, col, col, col}}}}}},
       "constraints[0].alpha: at most 6 constraints, got 7"},
      {{{"constraints", json::array({1})}}, "constraints[0] must be an object {link, alpha, beta, point, link_b, point_b}"},
      {{{"constraints", 1}}, "constraints must be an array of blocks"},
      {{{"q", {{"lwr_joint_9", 1}}}}, "q: no movable joint 'lwr_joint_9' between the root and the tip"},
      {{{"qd", {{"lwr_joint_2", "fast"}}}}, "qd['lwr_joint_2'] must be a number"},
      {{{"ff_torques", "none"}}, "ff_torques must be an array of 7 numbers or an object {joint name: value}"},
      {{{"f_ext", {{"lwr_base_link", col}}}}, "f_ext: 'lwr_base_link' is the root link"},
      {{{"f_ext", {{"lwr_link_9", col}}}}, "f_ext: no link 'lwr_link_9'"},
      {{{"f_ext", {{"lwr_link_2", {0, 0}}}}}, "f_ext['lwr_link_2']: expected 6 values, got 2"},
  };
  for (const auto& [fields, message] : bad) {
    json c = kuka_case();
    c.update(fields);
    std::vector<std::string> args = {"solve", kKuka};
    args.insert(args.end(), kKukaChain.begin(), kKukaChain.end());
    args.insert(args.end(), {"--case", write("bad.json", c.dump())});
    SCOPED_TRACE(c.dump());
    refused(args, "bad.json: " + message);
  }
}

// The case JSON into Case::constraints: link by name -> index, columns, beta (absent:
// zeros), point (absent: the link's origin), in the order given.
TEST_F(CliTrees, BlocksAreReadIntoTheCase) {
  const Model m = load_urdf_file(kKuka, "lwr_base_link", "lwr_link_7");
  json c = kuka_case();
  c["constraints"] = {{{"link", "lwr_link_7"}, {"alpha", {{1, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 1}}}, {"beta", {0.5, -1}},
                       {"point", {0, 0, 0.1}}},
                      {{"link", "lwr_link_3"}, {"alpha", {{0, 0, 1, 0, 0, 0}}}}};
  const Case k = cli::case_from_json(c, m, "case.json");
  ASSERT_EQ(k.constraints.size(), 2u);
  EXPECT_EQ(k.constraints[0].link, m.link_index("lwr_link_7"));
  EXPECT_EQ(k.constraints[0].alpha.cols(), 2);
  EXPECT_EQ(k.constraints[0].alpha(5, 1), 1);
  EXPECT_EQ(k.constraints[0].beta[0], 0.5);
  EXPECT_EQ(k.constraints[0].beta[1], -1);
  EXPECT_EQ(k.constraints[0].point, Vector3(0, 0, 0.1));
  EXPECT_EQ(k.constraints[1].link, m.link_index("lwr_link_3"));
  EXPECT_EQ(k.constraints[1].beta.size(), 1);
  EXPECT_EQ(k.constraints[1].beta[0], 0);
  EXPECT_EQ(k.constraints[1].point, Vector3::Zero());
  EXPECT_EQ(k.num_constraints(), 3);
}

// A tree built in code (no loader): base -> j0 -> {j1, j2}, a camera riding on j0's body,
// a locked side joint. Its case reads by name, its result names joints and links and has
// one constraint wrench per block, alpha nu; the messages speak of a tree.
Model hand_built_tree() {
  Model m;
  m.root_name = "base";
  const auto body = [&](const std::string& joint, const std::string& link, int parent, const Vector3& p, double angle) {
    Body b;
    b.joint_name = joint;
    b.link_name = link;
    b.parent = parent;
    b.X_tree.p = p;
    b.X_tree.R = Eigen::AngleAxisd(angle, Vector3::UnitX()).toRotationMatrix();
    b.inertia = spatial_inertia(1.0 + parent, Vector3(0.05, 0, 0.2), 0.01 * Matrix3::Identity());
    m.bodies.push_back(b);
    Link l;
    l.name = link;
    l.body = static_cast<int>(m.bodies.size()) - 1;
    m.links.push_back(l);
  };
  body("j0", "a", -1, Vector3(0, 0, 0.1), 0);
  body("j1", "b", 0, Vector3(0.1, 0.1, 0.3), 0.7);
  body("j2", "c", 0, Vector3(0.1, -0.1, 0.3), -1.1);
  Link cam;
  cam.name = "cam";
  cam.body = 0;
  cam.offset.p = Vector3(0.05, 0, 0.1);
  m.links.push_back(cam);
  m.locked_joints.push_back({"side", 0.25});
  validate(m);
  return m;
}

TEST_F(CliTrees, HandBuiltTreeReadsAndNamesByName) {
  const Model m = hand_built_tree();
  json c = {{"q", {{"j2", 0.3}, {"j1", -0.4}}}, {"qd", {{"j0", 0.2}}}, {"gravity", {0, 0, -9.81}},
            {"f_ext", {{"cam", {0, 0, -1, 0, 0.1, 0}}}},
            {"constraints", {{{"link", "b"}, {"alpha", {{0, 0, 1, 0, 0, 0}}}, {"point", {0, 0, 0.1}}},
                             {{"link", "c"}, {"alpha", {{1, 0, 0, 0, 0, 0}, {0, 0, 1, 0, 0, 0}}}, {"beta", {0.1, 0}}}}}};
  const Case k = cli::case_from_json(c, m, "tree.json");
  EXPECT_EQ(k.q, Eigen::Vector3d(0, -0.4, 0.3));
  EXPECT_EQ(k.f_ext[3], (Vector6() << 0, 0, -1, 0, 0.1, 0).finished());
  EXPECT_EQ(k.f_ext[0], Vector6::Zero());
  Data d(m);
  hybrid_dynamics(m, d, k);
  const json r = json::parse(cli::result_json(m, d, k));
  EXPECT_EQ(r.at("joints"), json({"j0", "j1", "j2"}));
  EXPECT_EQ(r.at("links"), json({"base", "a", "b", "c", "cam"}));
  EXPECT_EQ(r.at("link_accelerations").size(), 5u);
  EXPECT_EQ(r.at("nu").size(), 3u);
  ASSERT_EQ(r.at("constraint_wrenches").size(), 2u);
  EXPECT_EQ(r.at("constraint_wrenches")[0][2].get<double>(), d.constraint_wrenches[0][2]);
  EXPECT_EQ(r.at("constraint_wrenches")[1][0].get<double>(), d.constraint_wrenches[1][0]);
  EXPECT_EQ(r.at("locked_joints"), json::parse(R"([{"name": "side", "value": 0.25}])"));
  const auto error_of = [&](const json& fields) {
    json bad = {{"q", json::object()}, {"gravity", {0, 0, -9.81}}};
    bad.update(fields);
    try {
      cli::case_from_json(bad, m, "tree.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error_of({{"q", {{"side", 1}}}}),
            "tree.json: q: joint 'side' is locked at 0.25 (a side joint of the chain; --lock sets its position)");
  EXPECT_EQ(error_of({{"qd", {{"x", 1}}}}), "tree.json: qd: no movable joint 'x' below the root link 'base'");
  EXPECT_EQ(error_of({{"constraints", {{{"link", "zz"}, {"alpha", json::array()}}}}}),
            "tree.json: constraints[0].link: no link 'zz' below the root link 'base'");
  EXPECT_EQ(error_of({{"f_ext", {{"base", {0, 0, 0, 0, 0, 0}}}}}),
            "tree.json: f_ext: 'base' is the root link, which is fixed (nothing acts on the model through it)");
  EXPECT_NE(error_of({{"alpha", {{0, 0, 1, 0, 0, 0}}}}).find("alpha: the model is a tree with no tip"), std::string::npos);
}

// A block on the tip link at its origin is the tip's alpha: the same solve (needs the
// solver of blocks); its constraint wrench is the tip's.
TEST_F(CliTrees, TipBlockSolvesAsTheTipConstraint) {
  json tip = kuka_case(), block = kuka_case();
  tip["alpha"] = {{0, 0, 1, 0, 0, 0}, {0, 0, 0, 1, 0, 0}};
  tip["beta"] = {0.3, -0.1};
  block["constraints"] = {{{"link", "lwr_link_7"}, {"alpha", tip["alpha"]}, {"beta", tip["beta"]}}};
  const json a = solve(kKuka, kKukaChain, tip), b = solve(kKuka, kKukaChain, block);
  ASSERT_TRUE(b.is_object());
  for (const char* key : {"qdd", "joint_torques", "nu"}) {
    ASSERT_EQ(a.at(key).size(), b.at(key).size()) << key;
    for (size_t i = 0; i < a.at(key).size(); ++i)
      EXPECT_NEAR(b.at(key)[i].get<double>(), a.at(key)[i].get<double>(),
                  1e-12 * std::max(1.0, std::abs(a.at(key)[i].get<double>())))
          << key << "[" << i << "]";
  }
  ASSERT_EQ(b.at("constraint_wrenches").size(), 1u);
  for (int r = 0; r < 6; ++r)
    EXPECT_NEAR(b.at("constraint_wrenches")[0][r].get<double>(), a.at("constraint_wrench")[r].get<double>(), 1e-9);
}

// achd info: the model as JSON, a chain with its tip.
TEST_F(CliTrees, InfoDescribesAChain) {
  const json i = info(ACHD_SOURCE_DIR "/robots/planar2.urdf", {"--root", "base_link", "--tip", "link2"});
  const json expected = json::parse(R"({
    "root": "base_link", "tip": "link2", "floating": false,
    "joints": [
      {"name": "joint1", "type": "revolute", "parent": null, "link": "link1",
       "limits": {"lower": -3.141592653589793, "upper": 3.141592653589793, "velocity": 10.0, "effort": 100.0}},
      {"name": "joint2", "type": "revolute", "parent": "joint1", "link": "link2",
       "limits": {"lower": -3.141592653589793, "upper": 3.141592653589793, "velocity": 10.0, "effort": 100.0}}],
    "links": [{"name": "base_link", "body": null, "mass": 0.0}, {"name": "link1", "body": "joint1", "mass": 1.0},
              {"name": "link2", "body": "joint2", "mass": 1.0}],
    "locked_joints": [], "warnings": [],
    "default_q": {"joint1": 0.0, "joint2": 0.0}})");
  EXPECT_EQ(i, expected);
  refused({"info"}, "info: expected one URDF file");
  refused({"info", kKuka, "--case", "c.json"}, "unknown option --case");
  refused({"info", kKuka, "--convention", "rbdl"}, "option --convention: expected 'physical' or 'kdl'");
}

// Without --tip (and without --root) the whole tree: every movable joint, parents before
// children (each body's subtree after it), every link with the body it rides on, the
// fixed camera on the torso's; the default pose inside the limits. (Needs the loader of
// trees; before: "unknown root link ''".)
TEST_F(CliTrees, InfoDescribesTheWholeTree) {
  const json i = info(kTree, {});
  ASSERT_TRUE(i.is_object());
  EXPECT_EQ(i.at("root"), "base");
  EXPECT_TRUE(i.at("tip").is_null());
  std::vector<std::string> joints, parents;
  for (const json& j : i.at("joints")) {
    joints.push_back(j.at("name"));
    parents.push_back(j.at("parent").is_null() ? "-" : j.at("parent").get<std::string>());
  }
  EXPECT_EQ(joints, (std::vector<std::string>{"torso_yaw", "left_hip", "left_knee", "right_hip", "right_knee"}));
  EXPECT_EQ(parents, (std::vector<std::string>{"-", "torso_yaw", "left_hip", "torso_yaw", "right_hip"}));
  EXPECT_EQ(i.at("joints")[4].at("type"), "prismatic");
  std::map<std::string, json> links;
  for (const json& l : i.at("links")) links[l.at("name")] = l;
  EXPECT_EQ(i.at("links")[0].at("name"), "base");
  EXPECT_EQ(links.size(), 9u);
  EXPECT_EQ(links["camera"].at("body"), "torso_yaw");
  EXPECT_EQ(links["left_foot"].at("body"), "left_knee");
  EXPECT_EQ(links["right_foot"].at("mass"), 0.15);
  EXPECT_EQ(i.at("locked_joints"), json::array());
  EXPECT_DOUBLE_EQ(i.at("default_q").at("left_knee"), 0.5 * (0.2 + 2.5));  // 0 is below its limits: the middle
  EXPECT_EQ(i.at("default_q").at("left_hip"), 0.0);
}

// A tree solves with inputs by name and names its outputs; a tip constraint on a tree is
// refused, blocks on its feet are taken.
TEST_F(CliTrees, WholeTreeSolves) {
  const json c = {{"q", {{"left_knee", 0.8}, {"right_hip", 0.2}}}, {"gravity", {0, 0, -9.81}}};
  const json r = solve(kTree, {}, c);
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r.at("joints"), json({"torso_yaw", "left_hip", "left_knee", "right_hip", "right_knee"}));
  EXPECT_EQ(r.at("links").size(), 9u);
  EXPECT_EQ(r.at("links")[0], "base");
  EXPECT_EQ(r.at("link_accelerations").size(), 9u);
  json tip = c;
  tip["alpha"] = {{0, 0, 1, 0, 0, 0}};
  tip["beta"] = {0};
  refused({"solve", kTree, "--case", write("tip.json", tip.dump())}, "tree");
  json feet = c;
  feet["constraints"] = {{{"link", "left_foot"}, {"alpha", {{0, 0, 1, 0, 0, 0}}}},
                         {{"link", "right_foot"}, {"alpha", {{1, 0, 0, 0, 0, 0}}}, {"point", {0, 0, -0.02}}}};
  const json held = solve(kTree, {}, feet);
  ASSERT_TRUE(held.is_object());
  EXPECT_EQ(held.at("nu").size(), 2u);
  EXPECT_EQ(held.at("constraint_wrenches").size(), 2u);
}

// --root without --tip on a robot that is a chain: the tree below it is that chain, and
// solves as the chain does (<= 1e-12). (Before: "missing option --tip".)
TEST_F(CliTrees, ChainLoadedAsATreeSolvesAsTheChain) {
  json c = kuka_case();
  c["qd"] = {0.1, -0.2, 0.3, 0, 0.5, 0, 0.7};
  c["constraints"] = {{{"link", "lwr_link_7"}, {"alpha", {{0, 0, 1, 0, 0, 0}}}}};
  const json chain = solve(kKuka, kKukaChain, c);
  const json tree = solve(kKuka, {"--root", "lwr_base_link"}, c);
  ASSERT_TRUE(tree.is_object());
  EXPECT_EQ(tree.at("joints"), chain.at("joints"));
  EXPECT_EQ(tree.at("links"), chain.at("links"));
  for (const char* key : {"qdd", "joint_torques", "nu", "link_accelerations", "constraint_wrenches"}) {
    const json a = tree.at(key).flatten(), b = chain.at(key).flatten();
    ASSERT_EQ(a.size(), b.size()) << key;
    for (auto it = b.begin(); it != b.end(); ++it)
      EXPECT_NEAR(a.at(it.key()).get<double>(), it.value().get<double>(),
                  1e-12 * std::max(1.0, std::abs(it.value().get<double>())))
          << key << it.key();
  }
}

// A chain with side branches: the right leg's movable joints are locked (at 0, or at
// --lock's value) and reported by info and in results; naming a locked joint in a case
// says so; --convention kdl ignores the side branches as KDL's chain does.
TEST_F(CliTrees, LockedSideJointsAreReported) {
  const std::vector<std::string> chain = {"--root", "base", "--tip", "left_foot", "--lock", "right_knee=0.05"};
  const json i = info(kTree, chain);
  ASSERT_TRUE(i.is_object());
  EXPECT_EQ(i.at("tip"), "left_foot");
  const json locked = json::parse(R"([{"name": "right_hip", "value": 0.0}, {"name": "right_knee", "value": 0.05}])");
  EXPECT_EQ(i.at("locked_joints"), locked);
  EXPECT_EQ(i.at("joints").size(), 3u);
  // a chain's links are its path (root link first); the side links' mass rides on the torso
  EXPECT_EQ(i.at("links").size(), 5u);
  const json c = {{"q", {{"left_knee", 0.8}}}, {"gravity", {0, 0, -9.81}}};
  const json r = solve(kTree, chain, c);
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r.at("locked_joints"), locked);
  // The locked value moves the merged mass: another value, another solve. (The hip
  // swings the leg sideways, which changes the torso's inertia about its yaw axis; the
  // prismatic knee slides the shank along that axis, which does not.)
  std::vector<std::string> other = chain;
  other.insert(other.end(), {"--lock", "right_hip=0.4"});
  EXPECT_NE(solve(kTree, other, c).at("qdd"), r.at("qdd"));
  json bad = c;
  bad["q"]["right_hip"] = 0.1;
  std::vector<std::string> args = {"solve", kTree, "--case", write("locked.json", bad.dump())};
  args.insert(args.end(), chain.begin(), chain.end());
  refused(args, "q: joint 'right_hip' is locked at 0");
  refused({"info", kTree, "--root", "base", "--tip", "left_foot", "--lock", "left_knee=3"},
          "locked joint 'left_knee': value 3 is outside its limits [0.2, 2.5]");
  refused({"info", kTree, "--lock", "right_knee"}, "option --lock: expected JOINT=VALUE, got 'right_knee'");
  refused({"info", kTree, "--lock", "right_knee=1", "--lock", "right_knee=2"}, "joint 'right_knee' is locked twice");
  const json kdl = info(kTree, {"--root", "base", "--tip", "left_foot", "--convention", "kdl"});
  ASSERT_TRUE(kdl.is_object());
  EXPECT_EQ(kdl.at("locked_joints"), json::array());
  EXPECT_EQ(kdl.at("links").size(), 5u);  // base, torso, left_thigh, left_shank, left_foot
  EXPECT_NE(solve(kTree, {"--root", "base", "--tip", "left_foot", "--convention", "kdl"}, c).at("qdd"), r.at("qdd"))
      << "ignoring the side branches drops their mass";
}

// achd bench takes every case achd solve takes (names, blocks, a tree), with or without
// --link-outputs; --against kdl needs a chain without blocks.
TEST_F(CliTrees, BenchTakesWhatSolveTakes) {
  json named = kuka_case();
  named["q"] = {{"lwr_joint_2", 0.6}, {"lwr_joint_4", -1.2}};
  const std::vector<std::string> quick = {"--iterations", "1", "--repeats", "1"};
  std::vector<std::string> args = kKukaChain;
  args.insert(args.end(), quick.begin(), quick.end());
  args.insert(args.end(), {"--case", write("named.json", named.dump())});
  EXPECT_TRUE(json::parse(ok("bench", kKuka, args)).contains("achd_ns"));
  json blocks = kuka_case();
  blocks["constraints"] = {{{"link", "lwr_link_4"}, {"alpha", {{0, 0, 1, 0, 0, 0}}}}};
  const std::string blocks_path = write("blocks.json", blocks.dump());
  args = kKukaChain;
  args.insert(args.end(), quick.begin(), quick.end());
  args.insert(args.end(), {"--case", blocks_path});
  const std::string out = ok("bench", kKuka, args);
  EXPECT_TRUE(!out.empty() && json::parse(out).contains("achd_ns"));
  const std::string tree_case = write("tree.json", json({{"q", json::object()}, {"gravity", {0, 0, -9.81}}}).dump());
  std::vector<std::string> tree_args = {"--case", tree_case};
  tree_args.insert(tree_args.end(), quick.begin(), quick.end());
  const std::string tree_out = ok("bench", kTree, tree_args);
  EXPECT_TRUE(!tree_out.empty() && json::parse(tree_out).contains("achd_ns"));
  tree_args.push_back("--link-outputs");
  const std::string outputs_out = ok("bench", kTree, tree_args);
  EXPECT_TRUE(!outputs_out.empty() && json::parse(outputs_out).contains("achd_ns"));
  refused({"bench", kKuka, "--root", "lwr_base_link", "--tip", "lwr_link_7", "--case", blocks_path, "--against", "kdl"},
          "--against kdl: KDL's solver has no constraint blocks");
  refused({"bench", kTree, "--case", tree_case, "--against", "kdl"}, "--against kdl: KDL's solver takes a chain; give --tip");
}

// --floating: the free joint first, named after the root link, 7 numbers in q and 6 in
// qd; by name it may be left out (identity pose at the origin, at rest) or given as
// arrays; `achd info` reports it as one joint of type "floating"; a free fall from rest
// accelerates the root with g; a wrong length names the floating base.
TEST_F(CliTrees, FloatingBase) {
  const std::string quadruped = ACHD_SOURCE_DIR "/robots/quadruped.urdf";
  const json model = info(quadruped, {"--floating"});
  EXPECT_EQ(model["floating"], true);
  ASSERT_EQ(model["joints"].size(), 13u);
  EXPECT_EQ(model["joints"][0]["name"], "trunk");
  EXPECT_EQ(model["joints"][0]["type"], "floating");
  EXPECT_EQ(model["default_q"]["trunk"], json({0, 0, 0, 0, 0, 0, 1}));

  json by_name = {{"q", {{"lf_kfe", -1.2}}}, {"gravity", {0, 0, -9.81}}};
  const json named = solve(quadruped, {"--floating"}, by_name);
  ASSERT_EQ(named["joints"].size(), 13u);
  EXPECT_EQ(named["joints"][0], "trunk");
  ASSERT_EQ(named["qdd"].size(), 18u);
  // at rest, no torques: the trunk falls with g, no joint moves
  for (int k = 0; k < 18; ++k) EXPECT_NEAR(named["qdd"][k].get<double>(), k == 2 ? -9.81 : 0.0, 1e-12) << k;

  json arrays = by_name;
  std::vector<double> q(19, 0.0);
  q[6] = 1;
  q[7 + 2] = -1.2;  // lf_kfe is the third leg joint
  arrays["q"] = q;
  EXPECT_EQ(solve(quadruped, {"--floating"}, arrays)["qdd"], named["qdd"]);

  json moving = by_name;
  moving["q"]["trunk"] = {0.1, 0.2, 0.3, 0, 0, 0.2588190451, 0.9659258263};
  moving["qd"] = {{"trunk", {0.1, 0, 0, 0, 0, 1}}};
  EXPECT_EQ(solve(quadruped, {"--floating"}, moving)["qdd"].size(), 18u);

  json wrong = by_name;
  wrong["q"]["trunk"] = {0, 0, 0, 1};
  refused({"solve", quadruped, "--floating", "--case", write("wrong.json", wrong.dump())},
          "q['trunk'] (the floating base): expected 7 values, got 4");
  json zero = by_name;
  zero["q"]["trunk"] = {0, 0, 0, 0, 0, 0, 0};
  refused({"solve", quadruped, "--floating", "--case", write("zero.json", zero.dump())},
          "the floating base's orientation quaternion (qx, qy, qz, qw) is zero");
  const std::string bench = ok("bench", quadruped, {"--floating", "--iterations", "10", "--repeats", "1",
                                                    "--case", write("bench.json", moving.dump())});
  EXPECT_NE(bench.find("achd_ns"), std::string::npos);
}

}  // namespace
}  // namespace achd::test
