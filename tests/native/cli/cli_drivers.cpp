// The drivers (prescribed joints, driver weights, virtual wrenches) through `achd solve`: driver weights (w_fext, w_ff on the tip's
// columns and on a block's) and virtual wrenches (f_virtual by link name) read from the
// case file give the library's solve of the same Case, with virtual_torques in the
// result; weights outside [0, 1], of the wrong count, and wrenches on unknown links are
// named errors. A block's yields (its columns that give way to the joints' efforts) give
// the library's solve with ConstraintBlock::yields, with effort_ratio and yielded in the
// result; a wrong count or a non-boolean is a named error.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>
#include <nlohmann/json.hpp>

#include "achd/achd.hpp"
#include "cli_run.hpp"

namespace achd::test {
namespace {

const std::string kUrdf = std::string(ACHD_SOURCE_DIR) + "/robots/kuka_lwr4.urdf";

std::string write(const std::string& dir, const std::string& text) {
  const std::string path = dir + "/case.json";
  std::ofstream(path) << text;
  return path;
}

// `achd solve` on the LWR with each case head + tail exits 2, its message holding the
// needle, and writes nothing on stdout.
void expect_named_errors(const std::string& dir, const std::string& head,
                         const std::vector<std::pair<std::string, std::string>>& cases) {
  for (const auto& [tail, needle] : cases) {
    const CliRun r = run_cli(dir, {"solve", kUrdf, "--root", "lwr_base_link", "--tip", "lwr_link_7", "--case",
                                   write(dir, head + tail)});
    EXPECT_EQ(r.exit_code, 2) << tail;
    EXPECT_NE(r.err.find(needle), std::string::npos) << needle << " not in: " << r.err;
    EXPECT_EQ(r.out, "");
  }
}

const char* kCase = R"({
  "q": [0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1], "qd": [0.1, -0.2, 0.3, 0.1, 0, 0.2, -0.1],
  "gravity": [0, 0, -9.81], "ff_torques": [1, -2, 0.5, 1, 0, 0.3, 0.1],
  "alpha": [[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0]], "beta": [0.5, 0], "w_fext": [0, 1], "w_ff": [0.5, 1],
  "constraints": [{"link": "lwr_link_4", "alpha": [[1, 0, 0, 0, 0, 0]], "beta": [0.1], "w_fext": [0.25]}],
  "f_ext": {"lwr_link_7": [0, 0, 20, 0, 0, 0]},
  "f_virtual": {"lwr_link_5": [1, 2, 3, 0.1, 0.2, 0.3]}
})";

TEST(CliDrivers, WeightsAndVirtualWrenchesGiveTheLibrarySolve) {
  const std::string dir = make_temp_dir("achd_cli_drivers");
  const CliRun r = run_cli(dir, {"solve", kUrdf, "--root", "lwr_base_link", "--tip", "lwr_link_7", "--case",
                                 write(dir, kCase)});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json out = nlohmann::json::parse(r.out);

  const Model m = load_urdf_file(kUrdf, "lwr_base_link", "lwr_link_7");
  Case c = Case::zeros(m);
  c.q << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  c.qd = Eigen::VectorXd(7);
  c.qd << 0.1, -0.2, 0.3, 0.1, 0, 0.2, -0.1;
  c.ff_torques = Eigen::VectorXd(7);
  c.ff_torques << 1, -2, 0.5, 1, 0, 0.3, 0.1;
  c.alpha = ConstraintMatrix::Zero(6, 2);
  c.alpha(2, 0) = c.alpha(3, 1) = 1;
  c.beta = ConstraintVector(2);
  c.beta << 0.5, 0;
  c.w_fext = ConstraintVector(2);
  c.w_fext << 0, 1;
  c.w_ff = ConstraintVector(2);
  c.w_ff << 0.5, 1;
  ConstraintBlock b;
  b.link = m.link_index("lwr_link_4");
  b.alpha = ConstraintMatrix::Zero(6, 1);
  b.alpha(0, 0) = 1;
  b.beta = ConstraintVector::Constant(1, 0.1);
  b.w_fext = ConstraintVector::Constant(1, 0.25);
  c.constraints.push_back(b);
  c.f_ext.assign(m.num_links(), Vector6::Zero());
  c.f_ext[m.link_index("lwr_link_7")][2] = 20;
  c.f_virtual.assign(m.num_links(), Vector6::Zero());
  c.f_virtual[m.link_index("lwr_link_5")] << 1, 2, 3, 0.1, 0.2, 0.3;
  Data d(m);
  hybrid_dynamics(m, d, c);
  for (int i = 0; i < 7; ++i) {
    EXPECT_DOUBLE_EQ(out["qdd"][i].get<double>(), d.qdd[i]) << i;
    EXPECT_DOUBLE_EQ(out["virtual_torques"][i].get<double>(), d.virtual_torques[i]) << i;
  }
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(out["nu"][k].get<double>(), d.nu[k]) << k;
  // The weights changed the solve: without them the tip's z column would hold beta = 0.5.
  Case plain = c;
  plain.w_fext.resize(0), plain.w_ff.resize(0), plain.constraints[0].w_fext.resize(0);
  Data e(m);
  hybrid_dynamics(m, e, plain);
  EXPECT_GT((d.qdd - e.qdd).norm(), 1e-3);
}

TEST(CliDrivers, BadWeightsAndWrenchesAreNamed) {
  const std::string dir = make_temp_dir("achd_cli_drivers");
  const std::string head = R"({"q": [0, 0.5, 0, -1, 0, 0.5, 0], "gravity": [0, 0, -9.81], )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"("alpha": [[0, 0, 1, 0, 0, 0]], "w_fext": [1.5]})", "w_fext[0] must be in [0, 1]"},
      {R"("alpha": [[0, 0, 1, 0, 0, 0]], "w_ff": [1, 0]})", "w_ff: expected 1 values"},
      {R"("constraints": [{"link": "lwr_link_3", "alpha": [[1, 0, 0, 0, 0, 0]], "w_ff": [-0.1]}]})",
       "constraints[0].w_ff[0] must be in [0, 1]"},
      {R"("f_virtual": {"no_such_link": [1, 0, 0, 0, 0, 0]}})", "f_virtual: "},
      {R"("f_virtual": [[1, 0, 0, 0, 0, 0]]})", "f_virtual: expected"}};
  expect_named_errors(dir, head, cases);
}

// The UR5's last link held in x and pushed up along z at beta_z: the push followed, then
// given up, as the joints' efforts allow.
TEST(CliDrivers, YieldingColumnsGiveTheLibrarySolve) {
  const std::string dir = make_temp_dir("achd_cli_drivers");
  const std::string ur5 = std::string(ACHD_SOURCE_DIR) + "/robots/ur5.urdf";
  const Model m = load_urdf_file(ur5, "", "");
  for (double beta_z : {40.0, 200.0}) {
    const std::string text = R"({"q": [0, -1.2, 1.5, -0.3, 1.2, 0], "gravity": [0, 0, -9.81],
      "constraints": [{"link": "wrist_3_link", "alpha": [[1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]],
                       "beta": [0, )" + std::to_string(beta_z) + R"(], "yields": [false, true]}]})";
    const CliRun r = run_cli(dir, {"solve", ur5, "--policy", "variable_damping", "--case", write(dir, text)});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json out = nlohmann::json::parse(r.out);
    Case c = Case::zeros(m);
    c.q << 0, -1.2, 1.5, -0.3, 1.2, 0;
    ConstraintBlock b;
    b.link = m.link_index("wrist_3_link");
    b.alpha = ConstraintMatrix::Zero(6, 2);
    b.alpha(0, 0) = b.alpha(2, 1) = 1;
    b.beta = ConstraintVector(2);
    b.beta << 0, beta_z;
    b.yields = 0b10;
    c.constraints.push_back(b);
    Options o;
    o.policy = SingularityPolicy::VariableDamping;
    Data d(m);
    hybrid_dynamics(m, d, c, o);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(out["qdd"][i].get<double>(), d.qdd[i]) << i;
    for (int k = 0; k < 2; ++k) EXPECT_EQ(out["nu"][k].get<double>(), d.nu[k]) << k;
    EXPECT_EQ(out["effort_ratio"].get<double>(), d.effort_ratio);
    EXPECT_EQ(out["yielded"].get<double>(), d.yielded);
    if (beta_z == 40.0) {  // within the efforts: followed
      EXPECT_LT(d.effort_ratio, 1);
      EXPECT_EQ(d.yielded, 0);
      EXPECT_NE(d.nu[1], 0);
    } else {  // beyond twice the efforts: given up, x still held
      EXPECT_GT(d.effort_ratio, 2);
      EXPECT_EQ(d.yielded, 1);
      EXPECT_EQ(d.nu[1], 0);
      EXPECT_NE(d.nu[0], 0);
    }
  }
  // Without yields the result has no effort_ratio.
  const CliRun plain = run_cli(dir, {"solve", ur5, "--policy", "variable_damping", "--case",
                                     write(dir, R"({"q": [0, -1.2, 1.5, -0.3, 1.2, 0], "gravity": [0, 0, -9.81],
      "constraints": [{"link": "wrist_3_link", "alpha": [[0, 0, 1, 0, 0, 0]], "beta": [200]}]})")});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("effort_ratio"));
}

TEST(CliDrivers, BadYieldsAreNamed) {
  const std::string dir = make_temp_dir("achd_cli_drivers");
  const std::string head = R"({"q": [0, 0.5, 0, -1, 0, 0.5, 0], "gravity": [0, 0, -9.81], "constraints": [{"link": "lwr_link_3", "alpha": [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0]], )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"("yields": [true]}]})", "constraints[0].yields: expected 2 booleans (one per alpha column), got 1"},
      {R"("yields": [true, 1]}]})", "constraints[0].yields[1] must be true or false"},
      {R"("yields": true}]})", "constraints[0].yields must be an array of booleans"}};
  expect_named_errors(dir, head, cases);
}

}  // namespace
}  // namespace achd::test
