// The drivers (prescribed joints, driver weights, virtual wrenches) through `achd solve`: driver weights (w_fext, w_ff on the tip's
// columns and on a block's) and virtual wrenches (f_virtual by link name) read from the
// case file give the library's solve of the same Case, with virtual_torques in the
// result; weights outside [0, 1], of the wrong count, and wrenches on unknown links are
// named errors.
#include <gtest/gtest.h>

#include <fstream>
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
  for (const auto& [tail, needle] : cases) {
    const CliRun r = run_cli(dir, {"solve", kUrdf, "--root", "lwr_base_link", "--tip", "lwr_link_7", "--case",
                                   write(dir, head + tail)});
    EXPECT_EQ(r.exit_code, 2) << tail;
    EXPECT_NE(r.err.find(needle), std::string::npos) << needle << " not in: " << r.err;
    EXPECT_EQ(r.out, "");
  }
}

}  // namespace
}  // namespace achd::test
