#include "link_inertia.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <Eigen/Eigenvalues>

#include "achd/error.hpp"

namespace achd {

std::string inertia_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

double written_roundoff(const char* text) {
  if (!text) return 0;
  while (std::isspace(static_cast<unsigned char>(*text))) ++text;
  char* end = nullptr;
  if (std::strtod(text, &end) == 0) return 0;  // an exact zero, however written
  // Digits after the point (in the mantissa) and the exponent.
  const char* point = std::strchr(text, '.');
  const char* exponent = std::strpbrk(text, "eE");
  if (exponent && exponent > end) exponent = nullptr;
  if (point && point > end) point = nullptr;
  if (!point && !exponent) return 0;  // an integer: taken as exact
  int decimals = 0;
  if (point)
    for (const char* c = point + 1; c < (exponent ? exponent : end) && std::isdigit(static_cast<unsigned char>(*c)); ++c)
      ++decimals;
  // (clamped: an exponent past any double's says nothing more, and atoi would overflow)
  const long power = exponent ? std::max(-400L, std::min(400L, std::strtol(exponent + 1, nullptr, 10))) : 0;
  return 0.5 * std::pow(10.0, static_cast<double>(power - decimals));
}

namespace {

std::string moments_text(const Vector3& m) {
  return inertia_number(m[0]) + ", " + inertia_number(m[1]) + ", " + inertia_number(m[2]);
}

}  // namespace

Matrix3 checked_rotational_inertia(const std::string& link, const WrittenInertia& written, InertiaPolicy policy,
                                   std::vector<std::string>& warnings) {
  const std::string where = "link '" + link + "'";
  // The messages name the field and its value as urdfdom's own do (urdfdom refuses "nan"
  // and "inf" itself, natively and in wasm, see wasm/urdfdom_shim; these checks keep
  // non-finite numbers out whatever its parser lets through).
  if (!std::isfinite(written.mass))
    throw Error(where + ": mass [" + inertia_number(written.mass) + "] is not finite");
  if (written.mass < 0) throw Error(where + ": negative mass " + inertia_number(written.mass));
  const char* names[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  const double* v = written.moments;
  for (int k = 0; k < 6; ++k)
    if (!std::isfinite(v[k]))
      throw Error(where + ": inertia " + names[k] + " [" + inertia_number(v[k]) + "] is not finite");
  Matrix3 Ic;
  Ic << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
  const Eigen::SelfAdjointEigenSolver<Matrix3> eig(Ic);
  const Vector3 m = eig.eigenvalues();  // ascending
  // Round-off of the eigen decomposition itself, and of the numbers as the file wrote
  // them: rounding each entry by at most r_ij moves an eigenvalue by at most
  // |E|_2 <= |E|_F = sqrt(sum_ij r_ij^2) (Weyl's inequality; off-diagonals count twice).
  const double* r = written.roundoff;
  const double computed = 1e-9 * std::max(m.cwiseAbs().maxCoeff(), 1e-300);
  const double file = std::sqrt(r[0] * r[0] + r[3] * r[3] + r[5] * r[5] + 2 * (r[1] * r[1] + r[2] * r[2] + r[4] * r[4]));
  const double tol = computed + file;

  Vector3 fixed = m;
  if (m[0] < -computed) {
    const std::string moments = "principal moments " + moments_text(m);
    if (policy == InertiaPolicy::Strict)
      throw Error(where + ": inertia is not positive semi-definite (" + moments + ")");
    if (policy == InertiaPolicy::Repair) {
      for (int k = 0; k < 3; ++k) fixed[k] = std::max(fixed[k], 0.0);
    } else if (m[0] >= -tol) {
      warnings.push_back(where + ": " + moments + ": the negative ones are within the file's round-off (" +
                         inertia_number(file) + ") of zero, loaded as written");
    } else {
      // Loaded as written: the dynamics are defined as long as the body it rides on stays
      // positive semi-definite, which validate() checks (a light link on a heavy body does).
      warnings.push_back(where + ": inertia is not positive semi-definite (" + moments +
                         "), loaded as written");
    }
  }
  // The triangle inequality: each principal moment at most the sum of the other two.
  const double deficit = fixed[2] - fixed[0] - fixed[1];
  if (deficit > tol) {
    const std::string text = where + ": inertia violates the triangle inequality (principal moments " +
                             moments_text(fixed) + ")";
    if (policy == InertiaPolicy::Strict) throw Error(text);
    if (policy == InertiaPolicy::Accept) {
      warnings.push_back(text + ", loaded as written");
    } else {
      fixed[0] += deficit / 2;  // the least change (in the sum of squares) that closes it
      fixed[1] += deficit / 2;
    }
  }
  if (fixed == m) return Ic;
  if (policy == InertiaPolicy::Repair)
    warnings.push_back(where + ": inertia repaired: principal moments " + moments_text(m) + " -> " +
                       moments_text(fixed));
  const Matrix3& V = eig.eigenvectors();
  return V * fixed.asDiagonal() * V.transpose();
}

Matrix6 floor_inertia(double robot_mass) {
  const double mass = robot_mass > 0 ? 1e-3 * robot_mass : 1e-3;
  const double radius = 0.01;
  return spatial_inertia(mass, Vector3::Zero(), Matrix3::Identity() * (0.4 * mass * radius * radius));
}

}  // namespace achd
