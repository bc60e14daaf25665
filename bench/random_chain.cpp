#include "random_chain.hpp"

#include <random>
#include <sstream>

namespace achd::bench {

std::string robots_dir() { return ACHD_ROBOTS_DIR; }

std::string random_chain_urdf(int links, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), pos(0.5, 1.5);
  std::ostringstream x;
  x.precision(17);
  // Principal moments a, b, c > 0 with a + b >= c etc.: draw two, bound the third.
  auto inertial = [&] {
    const double m = pos(rng) * 2, a = 0.01 * pos(rng), b = 0.01 * pos(rng);
    const double c = std::abs(a - b) + (a + b - std::abs(a - b)) * (0.5 + 0.4 * u(rng));
    x << "<inertial><origin xyz=\"" << 0.1 * u(rng) << " " << 0.1 * u(rng) << " " << 0.1 * u(rng)
      << "\" rpy=\"" << u(rng) << " " << u(rng) << " " << u(rng) << "\"/><mass value=\"" << m
      << "\"/><inertia ixx=\"" << a << "\" iyy=\"" << b << "\" izz=\"" << c
      << "\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>";
  };
  // The root link is the fixed base: no inertia (KDL warns about one and ignores it).
  x << "<robot name=\"chain" << links << "\"><link name=\"link0\"/>";
  for (int i = 1; i <= links; ++i) {
    Vector3 axis(u(rng), u(rng), u(rng));
    axis /= axis.norm();
    x << "<link name=\"link" << i << "\">";
    inertial();
    x << "</link><joint name=\"j" << i << "\" type=\"continuous\"><parent link=\"link" << i - 1
      << "\"/><child link=\"link" << i << "\"/><origin xyz=\"" << 0.2 * u(rng) << " "
      << 0.2 * u(rng) << " " << 0.1 + 0.2 * pos(rng) << "\" rpy=\"" << u(rng) << " " << u(rng)
      << " " << u(rng) << "\"/><axis xyz=\"" << axis.x() << " " << axis.y() << " " << axis.z()
      << "\"/></joint>";
  }
  x << "</robot>";
  return x.str();
}

Case random_case(const Model& model, int nc, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = model.num_rates();
  Case c = Case::zeros(model);
  c.q = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
  c.qd = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
  c.ff_torques = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
  c.f_ext.assign(model.num_links(), Vector6::Zero());
  for (Vector6& w : c.f_ext) w = Vector6::NullaryExpr([&] { return u(rng); });
  c.alpha = ConstraintMatrix::NullaryExpr(6, nc, [&] { return u(rng); });
  c.beta = ConstraintVector::NullaryExpr(nc, [&] { return u(rng); });
  return c;
}

}  // namespace achd::bench
