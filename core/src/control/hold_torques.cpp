#include "hold_torques.hpp"

#include "achd/data.hpp"
#include "achd/hybrid_dynamics.hpp"

namespace achd {

Eigen::VectorXd hold_torques(const Model& model, const Eigen::VectorXd& pose, const Vector3& gravity,
                             const std::vector<Vector6>& f_ext, const std::vector<ConstraintBlock>& held,
                             const Options& options) {
  const int n = model.num_rates(), free = model.free_joint_rates();
  Case c = Case::zeros(model);
  c.q = pose;
  c.gravity = gravity;
  c.f_ext = f_ext;
  c.constraints = held;
  for (ConstraintBlock& b : c.constraints) b.beta.setZero(b.alpha.cols());  // at rest: no acceleration
  c.qdd_given = Eigen::VectorXd::Zero(n);
  c.prescribed.assign(n, true);
  for (int i = 0; i < free; ++i) c.prescribed[i] = false;
  Options o = options;
  o.policy = SingularityPolicy::Truncate;  // the least-norm forces of an over-determined hold
  Data data(model);
  hybrid_dynamics(model, data, c, o);
  Eigen::VectorXd tau = data.prescribed_torques;
  tau.head(free).setZero();
  return tau;
}

}  // namespace achd
