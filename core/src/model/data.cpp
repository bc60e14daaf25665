#include "achd/data.hpp"

#include <algorithm>
#include <string>

#include "achd/error.hpp"

namespace achd {

Data::Data(const Model& model, int constraint_capacity) : capacity_(constraint_capacity) {
  if (constraint_capacity < 0 || constraint_capacity > kMaxConstraintColumns)
    throw Error("constraint capacity must be in [0, " + std::to_string(kMaxConstraintColumns) + "], got " +
                std::to_string(constraint_capacity));
  const int n = model.num_rates();
  qdd = constraint_torques = total_torques = joint_torques = prescribed_torques = virtual_torques =
      Eigen::VectorXd::Zero(n);
  nu.resize(0);
  constraint_wrench.setZero();
  constraint_wrenches.reserve(constraint_capacity);  // a block has at least one column
  link_accelerations.assign(model.num_links() + 1, Vector6::Zero());
  dropped.resize(0, 0);
  damped.resize(0, 0);
  damped_sigma.resize(0);
  damped_lambda.resize(0);
  X0.resize(n);
  r.assign(n, Vector3::Zero());
  v.assign(n, Vector6::Zero());
  kappa.assign(n, Vector6::Zero());
  a.assign(n, Vector6::Zero());
  IA.assign(n, Matrix6::Zero());
  pA.assign(n, Vector6::Zero());
  E.resize(6, 0);
  Workspace& w = workspace;
  w.tau = Eigen::VectorXd::Zero(n);
  w.U.assign(n, Vector6::Zero());
  w.W.assign(n, Vector6::Zero());
  w.D.assign(n, 0.0);
  w.Dinv.assign(n, 0.0);
  w.u.assign(n, 0.0);
  w.sources.reserve(constraint_capacity + 1);  // the tip's and one per block with columns
  // A block of k columns keeps k rounded up to even per body, at most 2 k.
  w.path.assign(n, 0);
  w.walked.assign(n, 0);
  w.driver_bias.assign(n, Eigen::Matrix<double, 12, 1>::Zero());
  w.driver_qdd.assign(2 * n, 0.0);
  w.virtual_force.assign(n, Vector6::Zero());
  w.ez.assign(static_cast<size_t>(n) * 2 * constraint_capacity, 0.0);
  w.shared_ez.assign(static_cast<size_t>(n) * 6, 0.0);
  coupling_forces = Eigen::VectorXd::Zero(model.couplings.size());
  if (!model.couplings.empty()) {
    // (copies of the case go here: room for every input, so that copying allocates nothing)
    Case& h = w.coupling_case;
    h.q = Eigen::VectorXd::Zero(model.num_positions());
    h.qd = h.ff_torques = h.qdd_given = Eigen::VectorXd::Zero(n);
    h.prescribed.assign(n, false);
    h.constraints.reserve(constraint_capacity);
    h.f_ext.reserve(model.num_links());
    h.f_virtual.reserve(model.num_links());
    h.loop_beta = Eigen::VectorXd::Zero(model.num_loop_columns());
    w.coupling_response = Eigen::MatrixXd::Zero(n, model.couplings.size());
  }
  w.loop_blocks.resize(model.loops.size());
  w.loop_placements.resize(model.loops.size());
  for (size_t l = 0; l < model.loops.size(); ++l) {
    const int columns = model.loops[l].num_columns();
    w.loop_blocks[l].alpha = ConstraintMatrix::Zero(6, columns);
    w.loop_blocks[l].beta = ConstraintVector::Zero(columns);
  }
  if (model.floating) w.free_qd = w.free_ff_torques = w.free_qdd_given = Eigen::VectorXd::Zero(n);
}

void Data::set_link_outputs(const std::vector<int>& links) {
  const int n = static_cast<int>(link_accelerations.size()) - 1;  // the links after the root
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i] < -1 || links[i] >= n)
      throw Error("link_outputs[" + std::to_string(i) + "]: " + std::to_string(links[i]) +
                  " is not a link index of the model (-1 for the root link, 0 to " + std::to_string(n - 1) +
                  " for Model::links)");
  link_outputs_ = links;
  std::sort(link_outputs_.begin(), link_outputs_.end());
  link_outputs_.erase(std::unique(link_outputs_.begin(), link_outputs_.end()), link_outputs_.end());
  all_link_outputs_ = false;
  // Every other link's entry 0, which no solve writes again.
  std::vector<bool> wanted(n + 1, false);
  for (const int l : link_outputs_) wanted[l + 1] = true;
  for (int l = 0; l <= n; ++l)
    if (!wanted[l]) link_accelerations[l].setZero();
}

void Data::set_all_link_outputs() {
  all_link_outputs_ = true;
  link_outputs_.clear();
}

}  // namespace achd
