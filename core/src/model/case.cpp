#include "achd/case.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "achd/error.hpp"
#include "achd/options.hpp"
#include "finite_probe.hpp"

namespace achd {

Case Case::zeros(const Model& model) {
  Case c;
  c.q = Eigen::VectorXd::Zero(model.num_positions());
  if (model.floating) c.q[6] = 1;  // the identity orientation, qw = 1
  return c;
}

int Case::num_constraints() const {
  int n = static_cast<int>(alpha.cols());
  for (const ConstraintBlock& b : constraints) n += static_cast<int>(b.alpha.cols());
  return n;
}

bool Case::any_prescribed() const {
#ifdef _LIBCPP_VERSION
  // libc++'s (the wasm build's) std::find on a vector<bool> tests a word at a time: 89 of
  // V8's instructions on 7 joints where the loop below costs 190
  return std::find(prescribed.begin(), prescribed.end(), true) != prescribed.end();
#else
  // libstdc++'s std::find goes bit by bit, slower than this loop
  for (bool p : prescribed)
    if (p) return true;
  return false;
#endif
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

namespace {

static_assert(sizeof(Vector6) == 6 * sizeof(double), "f_ext is checked as one array");

// Driver weights: none, or one per column, each in [0, 1] (NaN fails the test).
bool weights_valid(const ConstraintVector& w, Eigen::Index nc) {
  if (w.size() == 0) return true;
  if (w.size() != nc) return false;
  for (Eigen::Index j = 0; j < nc; ++j)
    if (!(w[j] >= 0 && w[j] <= 1)) return false;
  return true;
}

// A floating base: its quaternion nonzero (q is finite), its six entries prescribed
// all or none (the rotation mixes them: free_joint.hpp).
bool free_joint_valid(const Case& c) {
  if (!(c.q.segment<4>(3).lpNorm<Eigen::Infinity>() > 0)) return false;
  for (int k = 1; k < 6 && !c.prescribed.empty(); ++k)
    if (c.prescribed[k] != c.prescribed[0]) return false;
  return true;
}

// Extra inertia: one per joint, each finite and >= 0 (NaN fails the test).
bool extra_inertia_valid(const Model& model, const Eigen::VectorXd& x) {
  if (x.size() != model.num_rates()) return false;
  for (int i = 0; i < x.size(); ++i)
    if (!(x[i] >= 0 && std::isfinite(x[i]))) return false;
  return true;
}

// The common case, in one pass: right sizes and every number finite.
bool plainly_valid(const Model& model, const Case& c, int capacity) {
  const Eigen::Index nj = model.num_rates();
  const int nc = static_cast<int>(c.alpha.cols());
  if (nc && !model.has_tip()) return false;
  if (c.q.size() != model.num_positions() || (c.qd.size() && c.qd.size() != nj) ||
      (c.ff_torques.size() && c.ff_torques.size() != nj) || nc > kMaxConstraints ||
      c.beta.size() != nc || (!c.f_ext.empty() && static_cast<int>(c.f_ext.size()) != model.num_links()) ||
      (c.qdd_given.size() && c.qdd_given.size() != nj) ||
      c.prescribed.size() != static_cast<size_t>(c.qdd_given.size()))
    return false;
  if (model.floating && !free_joint_valid(c)) return false;
  double s = finite_probe(c.q.data(), c.q.size()) + finite_probe(c.qd.data(), c.qd.size()) +
             finite_probe(c.ff_torques.data(), c.ff_torques.size()) +
             finite_probe(c.gravity.data(), 3) + finite_probe(c.alpha.data(), 6 * nc) +
             finite_probe(c.beta.data(), nc) + finite_probe(c.qdd_given.data(), c.qdd_given.size());
  if (!c.f_ext.empty()) s += finite_probe(c.f_ext[0].data(), 6 * Eigen::Index(c.f_ext.size()));
  if (!c.f_virtual.empty()) {
    if (static_cast<int>(c.f_virtual.size()) != model.num_links()) return false;
    s += finite_probe(c.f_virtual[0].data(), 6 * Eigen::Index(c.f_virtual.size()));
  }
  if (!weights_valid(c.w_fext, nc) || !weights_valid(c.w_ff, nc)) return false;
  for (const ConstraintBlock& b : c.constraints) {
    const Eigen::Index k = b.alpha.cols();
    if (b.link < 0 || b.link >= model.num_links() || k > kMaxConstraints || b.beta.size() != k) return false;
    if (b.link_b < -1 || b.link_b >= model.num_links() || b.link_b == b.link || (b.yields >> k)) return false;
    if (!weights_valid(b.w_fext, k) || !weights_valid(b.w_ff, k)) return false;
    s += finite_probe(b.point.data(), 3) + finite_probe(b.alpha.data(), 6 * k) + finite_probe(b.beta.data(), k) +
         (b.link_b >= 0 ? finite_probe(b.point_b.data(), 3) : 0.0);
  }
  int loops = 0;  // (a model without loop joints pays nothing for them)
  if (!model.loops.empty() || c.loop_beta.size()) {
    loops = model.num_loop_columns();
    if (c.loop_beta.size() && c.loop_beta.size() != loops) return false;
    s += finite_probe(c.loop_beta.data(), c.loop_beta.size());
  }
  return s == 0 && c.num_constraints() + loops <= capacity &&
         c.constraints.size() + model.loops.size() <= static_cast<size_t>(capacity);
}

// Driver weights of nc columns: empty, or nc numbers in [0, 1].
void check_weights(const ConstraintVector& w, int nc, const std::string& field) {
  if (w.size() == 0) return;
  if (w.size() != nc)
    throw Error(field + ": expected " + std::to_string(nc) + " values (one per alpha column) or none, got " +
                std::to_string(w.size()));
  for (int j = 0; j < nc; ++j)
    if (!(w[j] >= 0 && w[j] <= 1))
      throw Error(field + "[" + std::to_string(j) + "] must be in [0, 1], got " + std::to_string(w[j]));
}

// Columns alpha (6 x nc) and beta of the tip (field "") or of block b ("constraints[b].").
void check_columns(const ConstraintMatrix& alpha, const ConstraintVector& beta, const std::string& field) {
  const int nc = static_cast<int>(alpha.cols());
  if (nc > kMaxConstraints)
    throw Error(field + "alpha: at most " + std::to_string(kMaxConstraints) + " constraints, got " +
                std::to_string(nc));
  if (beta.size() != nc)
    throw Error(field + "beta: expected " + std::to_string(nc) + " values (one per alpha column), got " +
                std::to_string(beta.size()));
  for (int j = 0; j < nc; ++j) {
    for (int r = 0; r < 6; ++r)
      if (!std::isfinite(alpha(r, j)))
        throw Error(field + "alpha[" + std::to_string(j) + "][" + std::to_string(r) + "] is not finite");
    if (!std::isfinite(beta[j])) throw Error(field + "beta[" + std::to_string(j) + "] is not finite");
  }
}

// The blocks of Case::constraints: on a link of the model, at a finite point.
void check_blocks(const Model& model, const Case& c) {
  for (size_t b = 0; b < c.constraints.size(); ++b) {
    const ConstraintBlock& block = c.constraints[b];
    const std::string field = "constraints[" + std::to_string(b) + "].";
    if (block.link < 0 || block.link >= model.num_links())
      throw Error(field + "link: " + std::to_string(block.link) + " is not a link index of the model (0 to " +
                  std::to_string(model.num_links() - 1) + ")");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(block.point[k]))
        throw Error(field + "point[" + std::to_string(k) + "] (link '" + model.links[block.link].name +
                    "') is not finite");
    if (block.link_b < -1 || block.link_b >= model.num_links())
      throw Error(field + "link_b: " + std::to_string(block.link_b) +
                  " is not a link index of the model (0 to " + std::to_string(model.num_links() - 1) +
                  ") nor -1 (none)");
    if (block.link_b == block.link)
      throw Error(field + "link_b: the block would hold link '" + model.links[block.link].name +
                  "' relative to itself; name another link or none");
    for (int k = 0; block.link_b >= 0 && k < 3; ++k)
      if (!std::isfinite(block.point_b[k]))
        throw Error(field + "point_b[" + std::to_string(k) + "] (link '" + model.links[block.link_b].name +
                    "') is not finite");
    check_columns(block.alpha, block.beta, field);
    check_weights(block.w_fext, static_cast<int>(block.alpha.cols()), field + "w_fext");
    check_weights(block.w_ff, static_cast<int>(block.alpha.cols()), field + "w_ff");
    for (int k = static_cast<int>(block.alpha.cols()); k < 8; ++k)
      if (block.yields >> k & 1u)
        throw Error(field + "yields: bit " + std::to_string(k) + " names a column the block does not have (it has " +
                    std::to_string(block.alpha.cols()) + ")");
  }
}

}  // namespace

void validate(const Model& model, const Case& c, int capacity) {
  if (plainly_valid(model, c, capacity) && (!c.extra_inertia.size() || extra_inertia_valid(model, c.extra_inertia)))
    return;
  const int nj = model.num_rates();
  check_vector(c.q, model.num_positions(), "q", false);
  if (model.floating && !(c.q.segment<4>(3).lpNorm<Eigen::Infinity>() > 0))
    throw Error("q[3..6]: the floating base's orientation quaternion (qx, qy, qz, qw) is zero");
  check_vector(c.qd, nj, "qd", true);
  check_vector(c.ff_torques, nj, "ff_torques", true);
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(c.gravity[k]))
      throw Error("gravity[" + std::to_string(k) + "] is not finite");
  check_columns(c.alpha, c.beta, "");
  check_weights(c.w_fext, static_cast<int>(c.alpha.cols()), "w_fext");
  check_weights(c.w_ff, static_cast<int>(c.alpha.cols()), "w_ff");
  if (c.alpha.cols() && !model.has_tip())
    throw Error("alpha: the model is a tree with no tip; constrain its links with constraint blocks");
  check_blocks(model, c);
  if (c.constraints.size() > static_cast<size_t>(capacity))
    throw Error("constraints: " + std::to_string(c.constraints.size()) + " blocks, more than the workspace's capacity of " +
                std::to_string(capacity) + " (Data's constraint_capacity)");
  const int nc = c.num_constraints(), loops = model.num_loop_columns();
  if (nc > capacity)
    throw Error("constraints: " + std::to_string(nc) + " columns in all, more than the workspace's capacity of " +
                std::to_string(capacity) + " (Data's constraint_capacity)");
  if (nc + loops > capacity || c.constraints.size() + model.loops.size() > static_cast<size_t>(capacity))
    throw Error("constraints: " + std::to_string(nc) + " columns and the loop joints' " + std::to_string(loops) +
                " are more than the workspace's capacity of " + std::to_string(capacity) +
                " (Data's constraint_capacity)");
  if (c.loop_beta.size() && c.loop_beta.size() != loops)
    throw Error("loop_beta: expected " + std::to_string(loops) + " values (one per loop column) or none, got " +
                std::to_string(c.loop_beta.size()));
  for (int k = 0; k < c.loop_beta.size(); ++k)
    if (!std::isfinite(c.loop_beta[k])) throw Error("loop_beta[" + std::to_string(k) + "] is not finite");
  if (!c.f_ext.empty()) {
    if (static_cast<int>(c.f_ext.size()) != model.num_links())
      throw Error("f_ext: expected " + std::to_string(model.num_links()) +
                  " wrenches (one per link after the root), got " + std::to_string(c.f_ext.size()));
    for (int i = 0; i < model.num_links(); ++i)
      for (int r = 0; r < 6; ++r)
        if (!std::isfinite(c.f_ext[i][r]))
          throw Error("f_ext[" + std::to_string(i) + "][" + std::to_string(r) + "] is not finite");
  }
  if (!c.f_virtual.empty()) {
    if (static_cast<int>(c.f_virtual.size()) != model.num_links())
      throw Error("f_virtual: expected " + std::to_string(model.num_links()) +
                  " wrenches (one per link after the root), got " + std::to_string(c.f_virtual.size()));
    for (int i = 0; i < model.num_links(); ++i)
      for (int r = 0; r < 6; ++r)
        if (!std::isfinite(c.f_virtual[i][r]))
          throw Error("f_virtual[" + std::to_string(i) + "][" + std::to_string(r) + "] (link '" +
                      model.links[i].name + "') is not finite");
  }
  // Prescribed joints: qdd_given and its mask come together, one per joint.
  const size_t n = static_cast<size_t>(nj);
  if (c.qdd_given.size() && static_cast<size_t>(c.qdd_given.size()) != n)
    throw Error("qdd_given: expected " + std::to_string(nj) + " values (one per joint), got " +
                std::to_string(c.qdd_given.size()));
  if (!c.prescribed.empty() && c.prescribed.size() != n)
    throw Error("prescribed: expected " + std::to_string(nj) + " flags (one per joint), got " +
                std::to_string(c.prescribed.size()));
  if (c.prescribed.empty() != (c.qdd_given.size() == 0))
    throw Error(c.prescribed.empty() ? "qdd_given is set but prescribed (which joints it prescribes) is empty"
                                     : "prescribed is set but qdd_given (their accelerations) is empty");
  if (model.floating && !free_joint_valid(c))
    throw Error("prescribed: the floating base's six entries (joint '" + model.root_name +
                "') must be prescribed together or not at all");
  for (int i = 0; i < c.qdd_given.size(); ++i)
    if (!std::isfinite(c.qdd_given[i]))
      throw Error("qdd_given[" + std::to_string(i) + "] (joint '" + model.bodies[i].joint_name +
                  "') is not finite");
  if (c.extra_inertia.size() && !extra_inertia_valid(model, c.extra_inertia)) {
    if (c.extra_inertia.size() != nj)
      throw Error("extra_inertia: expected " + std::to_string(nj) + " values (one per joint) or none, got " +
                  std::to_string(c.extra_inertia.size()));
    for (int i = 0; i < nj; ++i)
      if (!(c.extra_inertia[i] >= 0) || !std::isfinite(c.extra_inertia[i]))
        throw Error("extra_inertia[" + std::to_string(i) + "] (joint '" + model.bodies[i].joint_name +
                    "') must be finite and >= 0, got " + std::to_string(c.extra_inertia[i]));
  }
}

void validate(const Options& o) {
  if (!std::isfinite(o.tolerance) || o.tolerance < 0)
    throw Error("options: tolerance must be finite and >= 0, got " + std::to_string(o.tolerance));
  // damping 0 would divide 0 by 0 for a zero singular value: plain truncation is the
  // Truncate policy with tolerance 0.
  if (!std::isfinite(o.damping) || o.damping <= 0)
    throw Error("options: damping must be finite and > 0, got " + std::to_string(o.damping));
  if (!std::isfinite(o.singular_region) || o.singular_region <= 0)
    throw Error("options: singular_region must be finite and > 0, got " + std::to_string(o.singular_region));
  // max_damping 0 would divide 0 by 0 for a zero singular value, as damping above.
  if (!std::isfinite(o.max_damping) || o.max_damping <= 0)
    throw Error("options: max_damping must be finite and > 0, got " + std::to_string(o.max_damping));
  if (!std::isfinite(o.friction_velocity) || o.friction_velocity <= 0)
    throw Error("options: friction_velocity must be finite and > 0, got " +
                std::to_string(o.friction_velocity));
}

}  // namespace achd
