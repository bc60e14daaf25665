// Bad cases through the C++ API (hybrid_dynamics validates its Case) and through the
// JSON parser shared by the CLI (parse_case): NaN/Inf in every input, wrong lengths,
// unknown fields, seven constraints. Each error names the field and the index.
#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "achd/achd.hpp"
#include "case_json.hpp"

namespace achd::test {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

Model robot() {
  return load_urdf_file(ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
}

Case good(const Model& m) {
  Case c = Case::zeros(m);
  c.qd = Eigen::VectorXd::Zero(7);
  c.ff_torques = Eigen::VectorXd::Zero(7);
  c.alpha.setZero(6, 2);
  c.alpha(0, 0) = c.alpha(4, 1) = 1;
  c.beta.setZero(2);
  c.f_ext.assign(m.num_links(), Vector6::Zero());
  return c;
}

std::string error_of(const Model& m, const Case& c) {
  Data d(m);
  try {
    hybrid_dynamics(m, d, c);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BadInputCase, NonFiniteNumbersInEveryFieldNameFieldAndIndex) {
  const Model m = robot();
  ASSERT_EQ(error_of(m, good(m)), "(no error)");
  const std::vector<std::pair<std::function<void(Case&, double)>, std::string>> fields = {
      {[](Case& c, double x) { c.q[3] = x; }, "q[3] is not finite"},
      {[](Case& c, double x) { c.qd[6] = x; }, "qd[6] is not finite"},
      {[](Case& c, double x) { c.ff_torques[0] = x; }, "ff_torques[0] is not finite"},
      {[](Case& c, double x) { c.gravity[2] = x; }, "gravity[2] is not finite"},
      {[](Case& c, double x) { c.alpha(5, 1) = x; }, "alpha[1][5] is not finite"},
      {[](Case& c, double x) { c.beta[1] = x; }, "beta[1] is not finite"},
      {[](Case& c, double x) { c.f_ext[2][4] = x; }, "f_ext[2][4] is not finite"},
  };
  for (const auto& [set, message] : fields)
    for (double x : {kNaN, kInf, -kInf}) {
      Case c = good(m);
      set(c, x);
      EXPECT_EQ(error_of(m, c), message) << x;
    }
}

TEST(BadInputCase, WrongLengthsNameTheFieldAndBothCounts) {
  const Model m = robot();
  Case c = good(m);
  c.q.setZero(6);
  EXPECT_EQ(error_of(m, c), "q: expected 7 values, got 6");
  c = good(m);
  c.qd.setZero(8);
  EXPECT_EQ(error_of(m, c), "qd: expected 7 values, got 8");
  c = good(m);
  c.ff_torques.setZero(1);
  EXPECT_EQ(error_of(m, c), "ff_torques: expected 7 values, got 1");
  c = good(m);
  c.beta.setZero(1);
  EXPECT_EQ(error_of(m, c), "beta: expected 2 values (one per alpha column), got 1");
  c = good(m);
  c.f_ext.pop_back();
  EXPECT_EQ(error_of(m, c), "f_ext: expected 7 wrenches (one per link after the root), got 6");
}

std::string json_error_of(const Model& m, const std::string& text) {
  try {
    cli::parse_case(text, m, "case.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BadInputCase, JsonErrorsNameTheSourceFieldAndIndex) {
  const Model m = robot();
  const std::string q = "\"q\": [0, 0, 0, 0, 0, 0, 0], \"gravity\": [0, 0, -9.81]";
  ASSERT_EQ(json_error_of(m, "{" + q + "}"), "(no error)");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{" + q + ", \"qdd\": [1]}", "case.json: unknown field 'qdd'"},
      {"{\"gravity\": [0, 0, -9.81]}", "case.json: missing required field 'q'"},
      {"{\"q\": [0, 0, 0, 0, 0, 0, 0]}", "case.json: missing required field 'gravity'"},
      {"{\"q\": [0, 0, 0, 0, 0, 0], \"gravity\": [0, 0, -9.81]}", "case.json: q: expected 7 values, got 6"},
      {"{\"q\": [0, 0, 0, \"x\", 0, 0, 0], \"gravity\": [0, 0, -9.81]}", "case.json: q[3] must be a number"},
      {"{" + q + ", \"ff_torques\": [0, 0]}", "case.json: ff_torques: expected 7 values, got 2"},
      {"{" + q + ", \"alpha\": [[1, 0, 0, 0, 0]], \"beta\": [0]}", "case.json: alpha[0]: expected 6 values, got 5"},
      {"{" + q + ", \"alpha\": [[1, 0, 0, 0, 0, 0]], \"beta\": [0, 1]}",
       "case.json: beta: expected 1 values (one per alpha column), got 2"},
      {"{" + q + ", \"f_ext\": [[0, 0, 0, 0, 0, 0]]}",
       "case.json: f_ext: expected 7 wrenches (one per link after the root), got 1"},
      {"[1, 2]", "case.json: the case must be a JSON object"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(json_error_of(m, text), message) << text;
  EXPECT_EQ(json_error_of(m, "").rfind("case.json: invalid JSON", 0), 0u);
}

// JSON has no NaN or Inf: a NaN literal is a syntax error and 1e999 overflows; both are
// refused as invalid JSON naming the source and the token, in every field.
TEST(BadInputCase, JsonNaNAndInfAreInvalidJsonNamingTheToken) {
  const Model m = robot();
  const std::string q = "\"q\": [0, 0, 0, 0, 0, 0, 0], \"gravity\": [0, 0, -9.81]";
  for (const std::string bad : {"NaN", "Infinity", "1e999", "-1e999"}) {
    for (const std::string& text :
         {"{\"q\": [0, 0, 0, " + bad + ", 0, 0, 0], \"gravity\": [0, 0, -9.81]}",
          "{\"q\": [0, 0, 0, 0, 0, 0, 0], \"gravity\": [0, " + bad + ", 0]}",
          "{" + q + ", \"qd\": [0, 0, 0, 0, 0, 0, " + bad + "]}",
          "{" + q + ", \"ff_torques\": [0, 0, 0, 0, 0, 0, " + bad + "]}",
          "{" + q + ", \"alpha\": [[1, 0, 0, 0, 0, " + bad + "]], \"beta\": [0]}",
          "{" + q + ", \"alpha\": [[1, 0, 0, 0, 0, 0]], \"beta\": [" + bad + "]}",
          "{" + q + ", \"f_ext\": [[0, 0, 0, 0, 0, " + bad + "]]}"}) {
      const std::string msg = json_error_of(m, text);
      EXPECT_EQ(msg.rfind("case.json: invalid JSON", 0), 0u) << text << " -> " << msg;
      if (bad[0] != 'N' && bad[0] != 'I')  // overflow names the number
        EXPECT_NE(msg.find(bad), std::string::npos) << msg;
    }
  }
}

TEST(BadInputCase, SevenOrMoreConstraintsAreRefusedNamingAlphaAndTheCount) {
  const Model m = robot();
  for (int nc : {7, 12}) {
    std::string alpha = "[", beta = "[";
    for (int k = 0; k < nc; ++k) {
      alpha += std::string(k ? ", " : "") + "[1, 0, 0, 0, 0, 0]";
      beta += std::string(k ? ", " : "") + "0";
    }
    const std::string text = "{\"q\": [0, 0, 0, 0, 0, 0, 0], \"gravity\": [0, 0, -9.81], \"alpha\": " +
                             alpha + "], \"beta\": " + beta + "]}";
    EXPECT_EQ(json_error_of(m, text),
              "case.json: alpha: at most 6 constraints, got " + std::to_string(nc));
  }
}

// Options are input too: a non-finite or negative tolerance or damping is refused.
TEST(BadInputCase, NonFiniteOrNegativeSolverOptionsAreRefused) {
  const Model m = robot();
  for (double x : {kNaN, kInf, -1.0}) {
    Options o;
    o.tolerance = x;
    Data d(m);
    EXPECT_THROW(hybrid_dynamics(m, d, good(m), o), Error) << "tolerance " << x;
    o = Options();
    o.policy = SingularityPolicy::Damped;
    o.damping = x;
    EXPECT_THROW(hybrid_dynamics(m, d, good(m), o), Error) << "damping " << x;
  }
}

}  // namespace
}  // namespace achd::test
