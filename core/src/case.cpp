#include "achd/case.hpp"

#include <cmath>
#include <string>

#include "achd/error.hpp"
#include "achd/options.hpp"

namespace achd {

Case Case::zeros(const Model& model) {
  Case c;
  c.q = Eigen::VectorXd::Zero(model.num_joints());
  return c;
}

namespace {

void check_vector(const Eigen::VectorXd& v, int n, const char* field, bool optional) {
  if (optional && v.size() == 0) return;
  if (v.size() != n)
    throw Error(std::string(field) + ": expected " + std::to_string(n) + " values, got " +
                std::to_string(v.size()));
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i]))
      throw Error(std::string(field) + "[" + std::to_string(i) + "] is not finite");
}

}  // namespace

void validate(const Model& model, const Case& c) {
  const int nj = model.num_joints();
  check_vector(c.q, nj, "q", false);
  check_vector(c.qd, nj, "qd", true);
  check_vector(c.ff_torques, nj, "ff_torques", true);
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(c.gravity[k]))
      throw Error("gravity[" + std::to_string(k) + "] is not finite");
  const int nc = c.num_constraints();
  if (nc > kMaxConstraints)
    throw Error("alpha: at most " + std::to_string(kMaxConstraints) + " constraints, got " +
                std::to_string(nc));
  if (c.beta.size() != nc)
    throw Error("beta: expected " + std::to_string(nc) + " values (one per alpha column), got " +
                std::to_string(c.beta.size()));
  for (int j = 0; j < nc; ++j) {
    for (int r = 0; r < 6; ++r)
      if (!std::isfinite(c.alpha(r, j)))
        throw Error("alpha[" + std::to_string(j) + "][" + std::to_string(r) + "] is not finite");
    if (!std::isfinite(c.beta[j])) throw Error("beta[" + std::to_string(j) + "] is not finite");
  }
  if (!c.f_ext.empty()) {
    if (static_cast<int>(c.f_ext.size()) != model.num_links())
      throw Error("f_ext: expected " + std::to_string(model.num_links()) +
                  " wrenches (one per link after the root), got " + std::to_string(c.f_ext.size()));
    for (int i = 0; i < model.num_links(); ++i)
      for (int r = 0; r < 6; ++r)
        if (!std::isfinite(c.f_ext[i][r]))
          throw Error("f_ext[" + std::to_string(i) + "][" + std::to_string(r) + "] is not finite");
  }
}

void validate(const Options& o) {
  if (!std::isfinite(o.tolerance) || o.tolerance < 0)
    throw Error("options: tolerance must be finite and >= 0, got " + std::to_string(o.tolerance));
  // damping 0 would divide 0 by 0 for a zero singular value: plain truncation is the
  // Truncate policy with tolerance 0.
  if (!std::isfinite(o.damping) || o.damping <= 0)
    throw Error("options: damping must be finite and > 0, got " + std::to_string(o.damping));
  if (!std::isfinite(o.friction_velocity) || o.friction_velocity <= 0)
    throw Error("options: friction_velocity must be finite and > 0, got " +
                std::to_string(o.friction_velocity));
}

}  // namespace achd
