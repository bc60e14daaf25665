// Finite results or a named error. A solve of finite inputs can still overflow: velocities
// near 1e155 square to infinity in the velocity products, torques near 1e308 overflow
// their sums, a nearly singular constraint can ask for an infinite force. The solve probes
// what it returns as it writes it (hybrid_dynamics.cpp); only when that fails does this
// walk the intermediate quantities in the order the sweeps computed them and name the
// first that is not finite, so the message points at the cause, not at a symptom.
#include "overflow_error.hpp"

#include <cmath>
#include <string>

#include "achd/error.hpp"
#include "finite_probe.hpp"

namespace achd {
namespace {

bool finite(const double* x, Eigen::Index n) { return finite_probe(x, n) == 0; }
template <class V>
bool finite(const V& v) {
  return finite(v.data(), v.size());
}

std::string joint(const Model& model, int i) { return "joint '" + model.bodies[i].joint_name + "'"; }

[[noreturn]] void overflow(const std::string& what) { throw Error("the solve overflows: " + what); }

// Block b of the solve in the user's terms: constraints[b] and its link, or the loop joint.
std::string block_name(const Model& model, const Case& c, int b) {
  const int own = static_cast<int>(c.constraints.size());
  if (b >= own) return "loop '" + model.loops[b - own].name + "'";
  return "constraints[" + std::to_string(b) + "] (link '" + model.links[c.constraints[b].link].name + "')";
}

// The loop frame's direction (x ... rz) that column j of a loop holds: its j-th held one.
const char* loop_direction(const LoopJoint& loop, int j) {
  for (int k = 0; k < kNumDirections; ++k)
    if (((loop.directions >> k) & 1u) && j-- == 0) return direction_name(k);
  return "?";  // unreachable: a loop has one column per held direction
}

}  // namespace

void name_the_first_overflow(const Model& model, const Data& d, const Case& c, int nc) {
  const int n = model.num_rates();
  // Step 1, outward: velocities, velocity-product accelerations, joint torques.
  for (int i = 0; i < n; ++i) {
    if (!finite(d.v[i]))
      overflow(joint(model, i) + ": the body velocity is not finite (qd too large)");
    if (!finite(d.kappa[i]))
      overflow(joint(model, i) + ": the velocity products (Coriolis, centrifugal) are not finite "
                                 "(qd too large for this robot)");
    if (!std::isfinite(d.workspace.tau[i]))
      overflow(joint(model, i) + ": the applied joint torque (ff_torques and the torques of f_virtual, "
                                 "less damping and friction) is not finite");
  }
  // Step 2, inward from the tip: articulated inertias and bias forces.
  for (int i = n - 1; i >= 0; --i) {
    if (!finite(d.IA[i]))
      overflow(joint(model, i) + ": the articulated inertia is not finite (link masses, inertias "
                                 "or distances too large)");
    if (!finite(d.pA[i]) || !std::isfinite(d.workspace.u[i]))
      overflow(joint(model, i) + ": the articulated bias force is not finite (ff_torques, qdd_given, "
                                 "f_ext, gravity or velocity products too large for this robot)");
  }
  // Steps 2-3 for the constraints: the coupling K, its right-hand side, the forces nu.
  // Column k of nu: the tip's (alpha[k]), column j of a block (constraints[b].alpha[j]) or
  // of a loop joint (its direction j); beta[k] is the loop's loop_beta entry.
  const int own = static_cast<int>(c.constraints.size());
  const auto loop_of = [&](const ConstraintSource& s) { return s.block >= own ? s.block - own : -1; };
  const auto source_of = [&](int k) -> const ConstraintSource* {
    for (const ConstraintSource& s : d.workspace.sources)
      if (k < s.column + s.columns) return &s;
    return nullptr;
  };
  const auto column = [&](int k) {
    const std::string number = "constraint column " + std::to_string(k);
    const ConstraintSource* s = source_of(k);
    if (!s) return number;
    const int j = k - s->column;
    if (s->block < 0) return number + " (alpha[" + std::to_string(j) + "])";
    if (loop_of(*s) >= 0) {
      const LoopJoint& loop = model.loops[loop_of(*s)];
      return number + " (loop '" + loop.name + "', its direction " + loop_direction(loop, j) + ")";
    }
    return number + " (constraints[" + std::to_string(s->block) + "].alpha[" + std::to_string(j) + "], link '" +
           model.links[c.constraints[s->block].link].name + "')";
  };
  // Where column k's beta comes from: beta[k] (nu's numbering), or the loop's loop_beta entry.
  const auto beta_name = [&](int k) {
    const ConstraintSource* s = source_of(k);
    if (!s || loop_of(*s) < 0) return "beta[" + std::to_string(k) + "]";
    int first = 0;  // the loop's first entry in loop_beta
    for (int l = 0; l < loop_of(*s); ++l) first += model.loops[l].num_columns();
    return "loop_beta[" + std::to_string(first + k - s->column) + "]";
  };
  for (int k = 0; k < nc; ++k)
    if (!finite(d.K.col(k).data(), nc))
      overflow(column(k) + ": the coupling K = E^T D^-1 E is not finite (the robot is too light along it)");
  for (int k = 0; k < nc; ++k)
    if (!std::isfinite(d.workspace.rhs[k]))
      overflow(column(k) + ": the constraint's right-hand side is not finite (" + beta_name(k) +
               ", gravity or velocity products too large)");
  for (int k = 0; k < nc; ++k)
    if (!std::isfinite(d.nu[k]))
      overflow(column(k) + ": the constraint force nu[" + std::to_string(k) +
               "] is not finite (the constraint needs a force beyond the range of a double)");
  // Step 4, outward: accelerations, then what is derived from them.
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(d.qdd[i]) || !finite(d.a[i]))
      overflow(joint(model, i) + ": the acceleration qdd[" + std::to_string(i) + "] is not finite");
  const auto link_acceleration = [&](int l) {  // link_accelerations index, 0: the root link
    if (!finite(d.link_accelerations[l]))
      overflow("link '" + (l ? model.links[l - 1].name : model.root_name) +
               "': its acceleration (link_accelerations[" + std::to_string(l) + "]) is not finite");
  };
  if (d.all_link_outputs()) {
    for (int l = 0; l <= model.num_links(); ++l) link_acceleration(l);
  } else {
    for (const int l : d.link_outputs()) link_acceleration(l + 1);  // the links the solve wrote
  }
  if (!finite(d.constraint_wrench)) overflow("the constraint wrench alpha nu is not finite");
  for (size_t b = 0; b < d.constraint_wrenches.size(); ++b)
    if (!finite(d.constraint_wrenches[b]))
      overflow(block_name(model, c, static_cast<int>(b)) + ": the constraint wrench alpha nu is not finite");
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(d.joint_torques[i]))
      overflow(joint(model, i) + ": joint_torques[" + std::to_string(i) + "] = ff - J^T alpha nu is not finite");
    if (!std::isfinite(d.constraint_torques[i]))
      overflow(joint(model, i) + ": constraint_torques[" + std::to_string(i) + "] is not finite");
    if (!std::isfinite(d.total_torques[i]))
      overflow(joint(model, i) + ": total_torques[" + std::to_string(i) + "] = D qdd is not finite");
    if (!std::isfinite(d.prescribed_torques[i]))
      overflow(joint(model, i) + ": prescribed_torques[" + std::to_string(i) +
               "], the torque its given acceleration (qdd_given) needs, is not finite");
  }
  overflow("a result is not finite");  // unreachable: every result was checked above
}

}  // namespace achd
