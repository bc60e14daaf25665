#pragma once
// One case posed to KDL's ChainHdSolver_Vereshchagin (the speed and parity reference),
// built once so that solve() times only the solver. Compiled only when KDL is found.
#include <memory>
#include <string>

#include "achd/achd.hpp"

namespace achd::cli {

class KdlProblem {
 public:
  // The chain root -> tip of the URDF (file path, or XML text when `is_xml`), and the
  // case in achd's conventions: root_acc = -gravity, alpha as a KDL::Jacobian (linear
  // rows first), beta_kdl = beta - alpha_lin^T g, f_ext as base-oriented KDL::Wrenches.
  KdlProblem(const std::string& urdf, bool is_xml, const std::string& root, const std::string& tip,
             const Case& c);
  ~KdlProblem();
  KdlProblem(const KdlProblem&) = delete;
  KdlProblem& operator=(const KdlProblem&) = delete;

  void solve();                   // one CartToJnt; throws achd::Error if KDL fails
  Eigen::VectorXd qdd() const;    // of the last solve

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace achd::cli
