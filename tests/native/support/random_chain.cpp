#include "random_chain.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>

namespace achd::test {

double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Vector3 uniform3(std::mt19937& rng, double lo, double hi) {
  return Vector3(uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi));
}

Matrix3 random_rotation(std::mt19937& rng) {
  Eigen::Quaterniond r(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1),
                       uniform(rng, -1, 1));
  return r.normalized().toRotationMatrix();
}

// Principal moments obeying the triangle inequality (each < sum of the other two),
// rotated by a random rotation: a physical, positive definite inertia about the COM.
Matrix3 random_inertia(std::mt19937& rng, double mass) {
  const double a = uniform(rng, 0.005, 0.1) * mass, b = uniform(rng, 0.005, 0.1) * mass;
  const double c = uniform(rng, std::abs(a - b) + 0.1 * std::min(a, b), 0.95 * (a + b));
  const Matrix3 R = random_rotation(rng);
  return R * Vector3(a, b, c).asDiagonal() * R.transpose();
}

RandomChain random_chain(std::mt19937& rng, int num_links, bool allow_fixed) {
  static const char* kMovable[] = {"revolute", "continuous", "prismatic"};
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\"?>\n<robot name=\"random\">\n  <link name=\"l0\"/>\n";
  bool any_movable = false;
  for (int i = 1; i <= num_links; ++i) {
    std::string type = kMovable[std::uniform_int_distribution<int>(0, 2)(rng)];
    if (allow_fixed && uniform(rng, 0, 1) < 0.25) type = "fixed";
    if (i == num_links && !any_movable) type = "revolute";
    any_movable |= type != "fixed";
    const Vector3 xyz = uniform3(rng, -0.4, 0.4), rpy = uniform3(rng, -M_PI, M_PI);
    const Vector3 axis = uniform3(rng, -1, 1).normalized();
    x << "  <joint name=\"j" << i << "\" type=\"" << type << "\">\n"
      << "    <parent link=\"l" << i - 1 << "\"/><child link=\"l" << i << "\"/>\n"
      << "    <origin xyz=\"" << xyz.transpose() << "\" rpy=\"" << rpy.transpose() << "\"/>\n";
    if (type != "fixed") x << "    <axis xyz=\"" << axis.transpose() << "\"/>\n";
    if (type == "revolute" || type == "prismatic")
      x << "    <limit lower=\"-4\" upper=\"4\" effort=\"100\" velocity=\"10\"/>\n";
    x << "  </joint>\n  <link name=\"l" << i << "\">\n";
    // Massless links in the middle of the chain are valid; the last link has mass so
    // that every joint moves something.
    if (i == num_links || uniform(rng, 0, 1) > 0.1) {
      const double mass = uniform(rng, 0.2, 4);
      const Vector3 com = uniform3(rng, -0.3, 0.3), com_rpy = uniform3(rng, -M_PI, M_PI);
      const Matrix3 I = random_inertia(rng, mass);
      x << "    <inertial>\n      <origin xyz=\"" << com.transpose() << "\" rpy=\""
        << com_rpy.transpose() << "\"/>\n      <mass value=\"" << mass << "\"/>\n"
        << "      <inertia ixx=\"" << I(0, 0) << "\" ixy=\"" << I(0, 1) << "\" ixz=\"" << I(0, 2)
        << "\" iyy=\"" << I(1, 1) << "\" iyz=\"" << I(1, 2) << "\" izz=\"" << I(2, 2)
        << "\"/>\n    </inertial>\n";
    }
    x << "  </link>\n";
  }
  x << "</robot>\n";
  RandomChain chain;
  chain.urdf = x.str();
  chain.tip = "l" + std::to_string(num_links);
  chain.model = load_urdf_string(chain.urdf, chain.root, chain.tip);
  return chain;
}

Case random_case(std::mt19937& rng, const Model& model, int num_constraints) {
  const int n = model.num_rates();
  Case c;
  c.q = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(rng, -M_PI, M_PI); });
  c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(rng, -2, 2); });
  c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(rng, -5, 5); });
  c.gravity = uniform3(rng, -1, 1).normalized() * uniform(rng, 5, 15);
  c.f_ext.resize(model.num_links());
  for (Vector6& w : c.f_ext) w = Vector6::NullaryExpr([&] { return uniform(rng, -3, 3); });
  c.alpha.resize(6, num_constraints);
  for (int k = 0; k < num_constraints; ++k)
    c.alpha.col(k) = Vector6::NullaryExpr([&] { return uniform(rng, -1, 1); }).normalized();
  c.beta = ConstraintVector::NullaryExpr(num_constraints, [&] { return uniform(rng, -2, 2); });
  return c;
}

double coupling_condition(const Model& model, const Case& c) {
  if (c.num_constraints() == 0) return 1;
  const Eigen::MatrixXd M = crba(model, c.q);
  const Eigen::MatrixXd A = c.alpha.transpose() * tip_jacobian(model, c.q);
  const Eigen::MatrixXd K = A * M.ldlt().solve(A.transpose());
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(K).singularValues();
  const double smin = s[s.size() - 1];
  return smin > 0 ? s[0] / smin : INFINITY;
}

Case well_conditioned_case(std::mt19937& rng, const Model& model, int num_constraints,
                           double max_condition) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    Case c = random_case(rng, model, num_constraints);
    if (coupling_condition(model, c) < max_condition) return c;
  }
  throw std::runtime_error("no case with coupling condition below the bound in 100 draws");
}

std::optional<Case> case_at(std::mt19937& rng, const Model& model, const Eigen::VectorXd& q,
                            int num_constraints, bool standard_gravity) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    Case c = random_case(rng, model, num_constraints);
    c.q = q;
    if (standard_gravity) c.gravity = Vector3(0, 0, -9.81);
    if (coupling_condition(model, c) < 1e4) return c;
  }
  return std::nullopt;
}

int tip_jacobian_rank(const Model& model, const Eigen::VectorXd& q) {
  Eigen::FullPivLU<Eigen::MatrixXd> lu(tip_jacobian(model, q));
  lu.setThreshold(1e-8);
  return std::min(static_cast<int>(lu.rank()), kMaxConstraints);
}

int tip_jacobian_rank(std::mt19937& rng, const Model& model) {
  return tip_jacobian_rank(model, Eigen::VectorXd::NullaryExpr(
                                      model.num_rates(), [&] { return uniform(rng, -M_PI, M_PI); }));
}

double rel_error(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return INFINITY;
  if (!a.size()) return 0;
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

}  // namespace achd::test
