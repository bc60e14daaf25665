// The zero-copy solver: a Case and a Data owned here, whose Eigen buffers the JS views
// point into. solve() runs hybrid_dynamics on them in place: no allocation, no copy.
#include <cstddef>
#include <limits>

#include <nlohmann/json.hpp>

#include "achd/achd.hpp"
#include "boundary.hpp"
#include "c_api.hpp"
#include "case_json.hpp"

namespace achd::wasm {

static_assert(sizeof(Vector6) == 6 * sizeof(double), "Vector6 arrays must be dense for the views");

struct Solver {
  explicit Solver(std::shared_ptr<const Model> m, int max_constraints)
      : model(std::move(m)), c(Case::zeros(*model)), data(*model), max_constraints(max_constraints) {
    const int n = model->num_rates();
    c.qd.setZero(n);
    c.ff_torques.setZero(n);
    // alpha and beta live in fixed inline storage: resizing the column count keeps the
    // values, so the views cover all max_constraints columns.
    c.alpha.setZero(6, kMaxConstraints);
    c.beta.setZero(kMaxConstraints);
    c.alpha.resize(6, 0);
    c.beta.resize(0);
    // Driver weights of the tip's columns, kept as long as alpha (fixed storage too): 1 =
    // KDL's priorities, which the solve treats as no weights at all.
    c.w_fext.setOnes(kMaxConstraints);
    c.w_ff.setOnes(kMaxConstraints);
    c.w_fext.resize(0);
    c.w_ff.resize(0);
    // Prescribed joints: a mask of all false (no joint prescribed) until set_prescribed.
    c.qdd_given.setZero(n);
    c.prescribed.assign(n, false);
    // Blocks have fixed storage each: with this reserve, setting blocks never allocates.
    c.constraints.reserve(kMaxConstraintColumns);
    parked_f_ext.assign(model->num_links(), Vector6::Zero());
    parked_f_virtual.assign(model->num_links(), Vector6::Zero());
  }
  std::shared_ptr<const Model> model;
  Case c;
  Data data;
  Options options;
  int max_constraints;
  // The f_ext buffer while external wrenches are off (c.f_ext is then empty); swapping
  // moves the buffer between the two vectors without reallocating it.
  std::vector<Vector6> parked_f_ext;
  std::vector<Vector6> parked_f_virtual;  // the same for f_virtual (c.f_virtual empty = none)
};

}  // namespace achd::wasm

using achd::wasm::Robot;
using achd::wasm::Solver;

ACHD_EXPORT Solver* achd_solver_create(const Robot* r, int max_constraints) {
  Solver* s = nullptr;
  achd::wasm::guarded([&] {
    if (max_constraints < 0 || max_constraints > achd::kMaxConstraints)
      throw achd::Error("maxConstraints must be an integer in [0, " +
                        std::to_string(achd::kMaxConstraints) + "], got " + std::to_string(max_constraints));
    s = new Solver(r->model, max_constraints);
  });
  return s;
}

ACHD_EXPORT void achd_solver_delete(Solver* s) { delete s; }

// The buffers behind the JS views, by achd::wasm::SolverBuffer index (wasm/js reads their
// names, kSolverBufferNames, from achd_constants()).
ACHD_EXPORT double* achd_solver_buffer(Solver* s, int which) {
  achd::Case& c = s->c;
  achd::Data& d = s->data;
  std::vector<achd::Vector6>& f_ext = c.f_ext.empty() ? s->parked_f_ext : c.f_ext;
  std::vector<achd::Vector6>& f_virtual = c.f_virtual.empty() ? s->parked_f_virtual : c.f_virtual;
  switch (which) {
    case achd::wasm::kSolverQ: return c.q.data();
    case achd::wasm::kSolverQd: return c.qd.data();
    case achd::wasm::kSolverFfTorques: return c.ff_torques.data();
    case achd::wasm::kSolverGravity: return c.gravity.data();
    case achd::wasm::kSolverAlpha: return c.alpha.data();
    case achd::wasm::kSolverBeta: return c.beta.data();
    case achd::wasm::kSolverFExt: return f_ext.front().data();
    case achd::wasm::kSolverQdd: return d.qdd.data();
    case achd::wasm::kSolverNu: return d.nu.data();
    case achd::wasm::kSolverJointTorques: return d.joint_torques.data();
    case achd::wasm::kSolverConstraintTorques: return d.constraint_torques.data();
    case achd::wasm::kSolverTotalTorques: return d.total_torques.data();
    case achd::wasm::kSolverLinkAccelerations: return d.link_accelerations.front().data();
    case achd::wasm::kSolverConstraintWrench: return d.constraint_wrench.data();
    case achd::wasm::kSolverDropped: return d.dropped.data();
    // Reserved for the Data's capacity when it was made: the address never changes.
    case achd::wasm::kSolverConstraintWrenches: return reinterpret_cast<double*>(d.constraint_wrenches.data());
    case achd::wasm::kSolverQddGiven: return c.qdd_given.data();
    case achd::wasm::kSolverWFext: return c.w_fext.data();
    case achd::wasm::kSolverWFf: return c.w_ff.data();
    case achd::wasm::kSolverFVirtual: return f_virtual.front().data();
    case achd::wasm::kSolverPrescribedTorques: return d.prescribed_torques.data();
    case achd::wasm::kSolverVirtualTorques: return d.virtual_torques.data();
    case achd::wasm::kSolverCouplingForces: return d.coupling_forces.data();
    default: return nullptr;
  }
}

ACHD_EXPORT int achd_solver_set_num_constraints(Solver* s, int nc) {
  return achd::wasm::guarded([&] {
    if (nc < 0 || nc > s->max_constraints)
      throw achd::Error("numConstraints must be an integer in [0, " + std::to_string(s->max_constraints) +
                        "] (maxConstraints), got " + std::to_string(nc));
    s->c.alpha.resize(6, nc);
    s->c.beta.resize(nc);
    s->c.w_fext.resize(nc);
    s->c.w_ff.resize(nc);
  });
}

// The constraint blocks of the solves that follow (Case::constraints): a case's
// "constraints" as the bridge's JSON text (wasm/js/json_text.mjs), parsed by the case
// parser (achd::cli::constraint_blocks) and copied into the solver's reserved blocks, so
// that a solve never allocates.
ACHD_EXPORT int achd_solver_set_constraints(Solver* s, const char* text) {
  return achd::wasm::guarded([&] {
    achd::Case parsed;
    achd::cli::constraint_blocks(achd::wasm::json_from_bridge(text), *s->model, parsed);
    const std::vector<achd::ConstraintBlock>& given = parsed.constraints;
    if (given.size() > static_cast<size_t>(achd::kMaxConstraintColumns))
      throw achd::Error("constraints: at most " + std::to_string(achd::kMaxConstraintColumns) + " blocks, got " +
                        std::to_string(given.size()));
    std::vector<achd::ConstraintBlock>& blocks = s->c.constraints;
    blocks.resize(given.size());
    for (size_t b = 0; b < given.size(); ++b) blocks[b] = given[b];
  });
}

// The constraint columns of the blocks (their entries in nu, after the tip's).
ACHD_EXPORT int achd_solver_block_columns(const Solver* s) {
  int columns = 0;
  for (const achd::ConstraintBlock& b : s->c.constraints) columns += static_cast<int>(b.alpha.cols());
  return columns;
}

ACHD_EXPORT int achd_solver_num_blocks(const Solver* s) { return static_cast<int>(s->c.constraints.size()); }

ACHD_EXPORT void achd_solver_use_external_wrenches(Solver* s, int on) {
  if ((on != 0) == !s->c.f_ext.empty()) return;
  s->c.f_ext.swap(s->parked_f_ext);
}

ACHD_EXPORT void achd_solver_use_virtual_wrenches(Solver* s, int on) {
  if ((on != 0) == !s->c.f_virtual.empty()) return;
  s->c.f_virtual.swap(s->parked_f_virtual);
}

// The prescribed joints of the solves that follow (Case::prescribed): mask[i] != 0 for
// joint i, whose acceleration is then the qdd_given view's entry i. All zero: none.
ACHD_EXPORT void achd_solver_set_prescribed(Solver* s, const double* mask) {
  for (size_t i = 0; i < s->c.prescribed.size(); ++i) s->c.prescribed[i] = mask[i] != 0;
}

// convention, policy: enum values (indices into kConventionNames, kSingularityPolicyNames);
// effects: achd::Effect bits.
ACHD_EXPORT void achd_solver_set_options(Solver* s, int convention, int policy, double tolerance,
                                         int absolute_tolerance, double damping, unsigned effects,
                                         double friction_velocity) {
  achd::Options& o = s->options;
  o.convention = static_cast<achd::Convention>(convention);
  o.policy = static_cast<achd::SingularityPolicy>(policy);
  o.tolerance = tolerance;
  o.absolute_tolerance = absolute_tolerance != 0;
  o.damping = damping;
  o.effects = effects;
  o.friction_velocity = friction_velocity;
}

ACHD_EXPORT int achd_solver_solve(Solver* s) {
  return achd::wasm::guarded([&] { achd::hybrid_dynamics(*s->model, s->data, s->c, s->options); });
}

ACHD_EXPORT int achd_solver_rank(const Solver* s) { return s->data.rank; }
// Blocks' yielding columns (ConstraintBlock::yields): Data::effort_ratio and Data::yielded.
ACHD_EXPORT double achd_solver_effort_ratio(const Solver* s) { return s->data.effort_ratio; }
ACHD_EXPORT double achd_solver_yielded(const Solver* s) { return s->data.yielded; }
// sigma_min, or NaN with the message in last_error() (K beyond the range of a double).
ACHD_EXPORT double achd_solver_sigma_min(const Solver* s) {
  double out = std::numeric_limits<double>::quiet_NaN();
  achd::wasm::guarded([&] { out = achd::sigma_min(s->data); });
  return out;
}

// solver.result(): the outputs of the last solve as the CLI writes them
// (achd::cli::result_json); valid until the next call, or null with the reason in
// achd_last_error() (sigma_min beyond the range of a double, blocks set after the solve).
ACHD_EXPORT const char* achd_solver_result(const Solver* s) {
  static std::string json;
  const char* out = nullptr;
  achd::wasm::guarded([&] {
    if (s->data.constraint_wrenches.size() != s->c.constraints.size() + s->model->loops.size())
      throw achd::Error("result(): the constraint blocks changed after the last solve (call solve() first)");
    json = achd::cli::result_json(*s->model, s->data, s->c, achd::cli::Digits::Shortest);
    out = json.c_str();
  });
  return out;
}

// Why `name` is not a movable joint of the solver's model, as the case parser says it
// (achd::cli::no_joint). Valid until the next call.
ACHD_EXPORT const char* achd_solver_no_joint(const Solver* s, const char* name) {
  static std::string message;
  message = achd::cli::no_joint(*s->model, name);
  return message.c_str();
}

// The options the solver holds, as achd::wasm::describe writes them (for the tests that
// compare the wrapper's choices with the C++ defaults); valid until the next call.
ACHD_EXPORT const char* achd_solver_options(const Solver* s) {
  static std::string json;
  json = achd::wasm::describe(s->options);
  return json.c_str();
}
