// Vereshchagin's constraint sweep (1989, eqs. c-f; KDL's E, M, G) on a tree, for blocks of
// columns on any links. Each block s (the tip's columns, one Case::constraints block or a
// loop joint's)
// acts at a point of one link, riding on body b_s. Its unit constraint forces E_s start at
// b_s, moved from the point (arm a_s) to the body's origin, and roll inward along the
// path P_s = {b_s and its ancestors} to the base, as on a chain:
//   EZ_s,i = E_s^T S_i;   E_s <- X_i^T (E_s - U_i EZ_s,i^T / D_i)        (eq. c)
// A body off P_s is not on the way: E_s has no share in its articulated body. The
// coupling of two blocks therefore sums only over the bodies both pass, from the lowest
// common ancestor of b_s and b_t to the base:
//   K_st = -M_0,st = sum_{i in P_s ∩ P_t} EZ_s,i EZ_t,i^T / D_i           (eq. d)
//   G_s  = sum_{i in P_s} EZ_s,i known_i                                   (eq. e)
// (known_i = u_i / D_i, or a prescribed joint's qdd_given, which adds nothing to K), and
// the constraint torque of joint i is -S_i^T E nu = -sum_{s: i in P_s} EZ_s,i^T nu_s.
// With one block on a chain's tip this is KDL's sweep. Cost: O(m d) for the columns and
// the torques, O(m^2 d) for K, d the depth of the tree.
//
// A relative block (alpha^T (a_P - a_Q) = beta, P on body b_s, Q on body b'_s) has two
// legs: E_s at b_s as above, and its opposite -E_s, moved to Q, at b'_s. Each rolls by
// eq. (c) to the bodies' lowest common ancestor c_s (the base, if none), where the two
// forces stand at one origin and add up; the sum rolls on from c_s as one column. Its
// path P_s is the union of the two legs and the trunk from c_s: the ancestors of b_s and
// b'_s. Eqs. (d) and (e) and the constraint torques hold over that path unchanged; P_s ∩
// P_t is found by marking P_s and walking P_t (O(|P_t|), no search for common ancestors:
// the Delta robot's five loops all pass the platform's six bodies).
#include "constraint_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "constraint_count.hpp"
#include "constraint_pairs.hpp"
#include "driver_priorities.hpp"
#include "finite_probe.hpp"
#include "free_joint.hpp"
#include "free_joint_constraints.hpp"
#include "joint_subspace.hpp"
#include "loop_blocks.hpp"
#include "shared_second_body.hpp"
#include "solve_blocks.hpp"
#include "wrench_torques.hpp"

namespace achd {
namespace {

// floor(log2 x) for a finite x > 0, from its exponent bits (subnormals count as -1023).
inline int exponent_of(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return static_cast<int>(bits >> 52) - 1023;  // x > 0: no sign bit
}

// 2^k for k in [-1022, 1023], from its exponent bits.
inline double power_of_two(int k) {
  const std::uint64_t bits = static_cast<std::uint64_t>(k + 1023) << 52;
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

// The power of two s_k = 2^-e, e = round(log2 |alpha_k|), that brings alpha column k to a
// length in [2^-1/2, 2^1/2). The sweeps solve for the columns alpha_k s_k with beta_k s_k,
// whose force is nu_k / s_k: multiplying by a power of two is exact, so the solve does not
// depend on a column's scale (a column and its beta scaled by 2^j give the same qdd and
// rank to the bit, nu_k scaled by 2^-j), a column of 1e-200 neither underflows K nor drops
// out, and a unit column (s_k = 1) is untouched. With y = alpha_k 2^-m, 2^m <= max |entry|
// (so that the squares neither overflow nor underflow): |alpha_k|^2 = |y|^2 4^m, and
// round(log2 |alpha_k|) = ceil(floor(log2 |alpha_k|^2) / 2) = m + (floor(log2 |y|^2) + 1) / 2
// (|y|^2 in [1, 24), so the last term is 0, 1 or 2, an integer shift).
double column_scale(const double* column) {
  // Every unit column, at the cost of |alpha_k|^2 by pairs: |alpha_k|^2 in [1/2, 2) is e = 0.
  const double length2 = squared_norm(load_pairs(column));
  if (length2 >= 0.5 && length2 < 2) return 1;
  double largest = 0;
  for (int r = 0; r < 6; ++r) largest = std::max(largest, std::abs(column[r]));
  if (largest == 0) return 1;
  const int m = std::min(std::max(exponent_of(largest), -1022), 1022);
  const double down = power_of_two(-m);
  double y2 = 0;
  for (int r = 0; r < 6; ++r) y2 += (column[r] * down) * (column[r] * down);
  const int e = m + ((exponent_of(y2) + 1) >> 1);
  return power_of_two(-std::min(std::max(e, -1022), 1022));
}

// The columns of source s as the case gives them (the tip's or its block's, a loop's
// block as set_loop_blocks made it).
const ConstraintMatrix& alpha_of(const Case& c, const Data& d, const ConstraintSource& s) {
  return s.block < 0 ? c.alpha : solve_block(c, d, s.block).alpha;
}
const ConstraintVector& beta_of(const Case& c, const Data& d, const ConstraintSource& s) {
  return s.block < 0 ? c.beta : solve_block(c, d, s.block).beta;
}

// The lowest common ancestor of bodies a and b (-1: the base). Parents come before their
// children, so the larger index is never an ancestor of the smaller.
int common_ancestor(const Model& model, int a, int b) {
  while (a != b) {
    if (a > b) a = model.bodies[a].parent;
    else b = model.bodies[b].parent;
  }
  return a;
}

// The arm from the origin of the body link `link` rides on (the root's, for a link fixed
// to it) to `point` of the link (its frame), in base axes.
__attribute__((always_inline)) inline Vector3 arm_of(const Model& model, const Data& d, int link, const Vector3& point) {
  const Link& l = model.links[link];
  const Vector3 in_body = point.isZero(0) ? l.offset.p : Vector3(l.offset.p + l.offset.R * point);
  return l.body < 0 ? in_body : Vector3(d.X0[l.body].R * in_body);
}

// Where a block of the case acts: on link `link` at `point` (its frame), relative to link
// `link_b` at `point_b` when link_b >= 0 (ConstraintSource's body, arm, relative, body_b,
// arm_b).
ConstraintSource placed(const Model& model, const Data& d, int link, const Vector3& point, int link_b,
                        const Vector3& point_b) {
  ConstraintSource s;
  s.body = model.links[link].body;
  s.arm = arm_of(model, d, link, point);
  if (link_b >= 0) {
    s.relative = true;
    s.body_b = model.links[link_b].body;
    s.arm_b = arm_of(model, d, link_b, point_b);
  }
  return s;
}

// Appends the source of alpha's columns acting where `s` is placed (placed, or a loop's
// placement).
void add_source(const Model& model, Data& d, const ConstraintMatrix& alpha, ConstraintSource s, int block, int& m,
                int& ez) {
  Data::Workspace& w = d.workspace;
  s.column = m;
  s.columns = static_cast<int>(alpha.cols());
  s.block = block;
  s.ez = ez;
  if (s.relative) s.meet = common_ancestor(model, s.body, s.body_b);
  else s.body_b = s.meet = s.body;
  // E = alpha s moved from the point to the body's origin: [f; n + arm x f]
  for (int k = 0; k < s.columns; ++k) {
    const double scale = column_scale(alpha.col(k).data());
    const Vector3 f = alpha.col(k).head<3>() * scale;
    w.alpha_scale[m + k] = scale;
    w.has_force[m + k] = alpha.col(k).head<3>().squaredNorm() != 0;
    d.E.col(m + k).head<3>() = f;
    d.E.col(m + k).tail<3>() = alpha.col(k).tail<3>() * scale + s.arm.cross(f);
  }
  w.sources.push_back(s);
  m += s.columns;
  ez += model.num_rates() * (s.columns + (s.columns & 1));
}

// The last body a block's columns pass one axis at a time: the base's child, or with the
// free-joint step the root's children (free_joint_constraints.cpp takes the free joint).
inline int last_body(const Data& d) { return d.workspace.free_joint_step ? kFreeJointBodies : 0; }

// A relative block's two legs, E from P's body and its opposite from Q's, each rolled to
// where they meet, then added into E. (Kept out of roll_to_base, so that a block on one
// link rolls through the one loop it always had.)
template <int NC>
__attribute__((noinline)) void roll_legs(const Model& model, Data& d, const ConstraintSource& s,
                                         UnitConstraintForces<NC>& E) {
  Data::Workspace& w = d.workspace;
  double* ez = w.ez.data() + s.ez;
  const int last = last_body(d);
  UnitConstraintForces<NC> B = E.opposite_moved(s.arm_b - s.arm);
  for (int i = s.body; i > s.meet && i >= last; i = model.bodies[i].parent)
    E.pass_to_parent(body_subspace(model, d, i), w.U[i], w.Dinv[i], d.r[i], ez + i * ez_stride<NC>());
  for (int i = s.body_b; i > s.meet && i >= last; i = model.bodies[i].parent)
    B.pass_to_parent(body_subspace(model, d, i), w.U[i], w.Dinv[i], d.r[i], ez + i * ez_stride<NC>());
  E.add(B);
}

template <int NC>
void roll_to_base(const Model& model, Data& d, const ConstraintSource& s) {
  Data::Workspace& w = d.workspace;
  double* column = d.E.col(s.column).data();
  UnitConstraintForces<NC> E(column);
  if (s.relative) roll_legs<NC>(model, d, s, E);  // the two legs to where they meet, then as one
  double* ez = w.ez.data() + s.ez;
  const int last = last_body(d);
  for (int i = s.meet; i >= last; i = model.bodies[i].parent)
    E.pass_to_parent(body_subspace(model, d, i), w.U[i], w.Dinv[i], d.r[i], ez + i * ez_stride<NC>());
  E.store(column);
}

// The diagonal block K_ss and G_s of source s, summed from the base outward (so that a
// chain's K is summed in body order). Returns its finite probe.
template <int NC, bool P>
double own_coupling(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given,
                    const ConstraintSource& s) {
  Data::Workspace& w = d.workspace;
  CouplingSums<NC> sums;
  const double* ez = w.ez.data() + s.ez;
  int depth = 0;
  for_each_on_path(model, s, last_body(d), [&](int i) { w.path[depth++] = i; });
  while (depth > 0) {
    const int i = w.path[--depth];
    double known = w.u[i] * w.Dinv[i];
    if constexpr (P) {
      if (c.prescribed[i]) known = qdd_given[i];
    }
    sums.add(ez + i * ez_stride<NC>(), w.Dinv[i], known);
  }
  return sums.store(d.K, d.G0, s.column);
}

// The off-diagonal block K_st (and K_ts) of two sources of NS and NT columns: over the
// common part of their paths, each entry summed in a register in the order of the walk.
// When either is relative, the bodies of P_s are marked in d.workspace.walked (by
// mutual_couplings_marked) and P_s ∩ P_t is the bodies of t's path found marked. Returns its
// finite probe.
template <int NS, int NT>
double mutual_coupling(const Model& model, Data& d, const ConstraintSource& s, const ConstraintSource& t,
                       int ancestor) {
  const Data::Workspace& w = d.workspace;
  double K[NS][NT] = {};
  const int last = last_body(d);
  auto add = [&](int i) {
    const double* es = w.ez.data() + s.ez + i * ez_stride<NS>();
    const double* et = w.ez.data() + t.ez + i * ez_stride<NT>();
    for (int k = 0; k < NS; ++k) {
      const double a = es[k] * w.Dinv[i];
      for (int l = 0; l < NT; ++l) K[k][l] += a * et[l];
    }
  };
  if (!s.relative && !t.relative) {
    for (int i = ancestor; i >= last; i = model.bodies[i].parent) add(i);
  } else {
    const unsigned char* on_s = w.walked.data();
    for_each_on_path(model, t, last, [&](int i) {
      if (on_s[i]) add(i);
    });
  }
  double probe = 0;
  for (int k = 0; k < NS; ++k)
    for (int l = 0; l < NT; ++l) {
      d.K(s.column + k, t.column + l) = d.K(t.column + l, s.column + k) = K[k][l];
      probe += K[k][l] * 0.0;
    }
  return probe;
}

// mutual_coupling of sources a and b, dispatched on their column counts (ancestor: the
// lowest common ancestor of two blocks on one link each, unused otherwise).
inline double pair_coupling(const Model& model, Data& d, const ConstraintSource& a, const ConstraintSource& b,
                            int ancestor) {
  return with_constraint_count(a.columns, [&](auto ns) {
    return with_constraint_count(b.columns, [&](auto nt) {
      return mutual_coupling<decltype(ns)::value, decltype(nt)::value>(model, d, a, b, ancestor);
    });
  });
}

// K's off-diagonal blocks when some source is relative: each source's path is marked in
// walked while it pairs with the later ones (walked is 0 everywhere before and after).
// Returns their finite probe. (Out of line: blocks on one link never come here.)
__attribute__((noinline)) double mutual_couplings_marked(const Model& model, Data& d) {
  const Data::Workspace& w = d.workspace;
  unsigned char* walked = d.workspace.walked.data();
  double probe = 0;
  for (size_t s = 0; s + 1 < w.sources.size(); ++s) {  // (the last pairs with none after it)
    const ConstraintSource& a = w.sources[s];
    for_each_on_path(model, a, last_body(d), [&](int i) { walked[i] = 1; });
    for (size_t t = s + 1; t < w.sources.size(); ++t) probe += pair_coupling(model, d, a, w.sources[t], -1);
    for_each_on_path(model, a, last_body(d), [&](int i) { walked[i] = 0; });
  }
  return probe;
}

template <int NC>
void add_constraint_torques(const Model& model, Data& d, const ConstraintSource& s) {
  const Data::Workspace& w = d.workspace;
  const ConstraintMagnitudes<NC> nu(d.nu.data() + s.column);
  const double* ez = w.ez.data() + s.ez;
  for_each_on_path(model, s, last_body(d),
                   [&](int i) { d.constraint_torques[i] -= nu.dot(ez + i * ez_stride<NC>()); });
}

// kappa -= kappa at a relative block's second point Q. (Out of line: the blocks on one
// link never come here.)
__attribute__((noinline)) void subtract_kappa_b(const Data& d, const ConstraintSource& s, Vector6& kappa) {
  if (s.body_b >= 0) kappa -= motion_shift(d.kappa[s.body_b], s.arm_b);
}

}  // namespace

int constraint_sources(const Model& model, Data& d, const Case& c) {
  Data::Workspace& w = d.workspace;
  w.sources.clear();
  set_loop_betas(c, d);
  const int m = num_solve_columns(c, d);
  d.E.resize(6, m);
  w.alpha_scale.resize(m);
  int column = 0, ez = 0;
  if (c.alpha.cols())
    add_source(model, d, c.alpha, placed(model, d, model.num_links() - 1, Vector3::Zero(), -1, Vector3::Zero()), -1,
               column, ez);
  const int own = static_cast<int>(c.constraints.size());
  for (int b = 0; b < own; ++b) {
    const ConstraintBlock& block = c.constraints[b];
    if (block.alpha.cols())
      add_source(model, d, block.alpha, placed(model, d, block.link, block.point, block.link_b, block.point_b), b,
                 column, ez);
  }
  for (size_t l = 0; l < w.loop_blocks.size(); ++l)
    add_source(model, d, w.loop_blocks[l].alpha, w.loop_placements[l], own + static_cast<int>(l), column, ez);
  return m;
}

double constraint_sweep(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given,
                        bool prescribed) {
  use_free_joint_step(model, d, c, prescribed);
  Data::Workspace& w = d.workspace;
  const int m = static_cast<int>(d.E.cols());
  d.K.resize(m, m);
  d.G0.resize(m);
  // (a driver weight reads every block's EZ_i along its whole path: the legs then roll apart)
  w.shared_body = shared_second_body(d, last_body(d));
  if (w.shared_body >= 0 && has_driver_weights(c)) w.shared_body = -1;
  if (w.shared_body >= 0) return shared_second_body_sweep(model, d, c, qdd_given, prescribed, w.shared_body);
  // (the blocks of two sources whose paths share no body passed one at a time stay 0: a
  // floating base's legs, which meet in the free joint its 6-DoF step couples)
  if (w.sources.size() > 1) d.K.setZero();
  double probe = 0;
  bool relative = false;
  for (const ConstraintSource& s : w.sources) {
    relative = relative || s.relative;
    probe += with_constraint_count(s.columns, [&](auto n) {
      constexpr int NC = decltype(n)::value;
      roll_to_base<NC>(model, d, s);
      return prescribed ? own_coupling<NC, true>(model, d, c, qdd_given, s)
                        : own_coupling<NC, false>(model, d, c, qdd_given, s);
    });
  }
  if (relative) {
    probe += mutual_couplings_marked(model, d);
  } else {
    for (size_t s = 0; s < w.sources.size(); ++s)
      for (size_t t = s + 1; t < w.sources.size(); ++t) {
        const ConstraintSource &a = w.sources[s], &b = w.sources[t];
        const int ancestor = common_ancestor(model, a.body, b.body);
        if (ancestor >= last_body(d)) probe += pair_coupling(model, d, a, b, ancestor);
      }
  }
  if (w.free_joint_step) probe += free_joint_coupling(d);
  return probe;
}

void constraint_rhs(Data& d, const Case& c, const Options& o, bool moving) {
  Data::Workspace& w = d.workspace;
  const bool gravity = o.effects & kGravity, physical = o.convention == Convention::Physical;
  w.rhs.resize(d.E.cols());
  for (const ConstraintSource& s : w.sources) {
    // kappa at the point: what its acceleration would be with qdd = 0 and no gravity (a
    // relative block: at P less at Q)
    Vector6 kappa = Vector6::Zero();
    if (moving && s.body >= 0) kappa = motion_shift(d.kappa[s.body], s.arm);
    if (moving && s.relative) subtract_kappa_b(d, s, kappa);
    const ConstraintMatrix& alpha = alpha_of(c, d, s);
    const ConstraintVector& beta = beta_of(c, d, s);
    // alpha_lin^T g: a relative block sees g at both of its points, where it cancels
    const bool gravity_at_point = physical && !s.relative;
    for (int k = 0; k < s.columns; ++k) {
      const int col = s.column + k;
      const double scale = w.alpha_scale[col];
      double r = d.G0[col] - beta[k] * scale;
      if (moving) r += (alpha.col(k) * scale).dot(kappa);
      if (gravity) {
        if (!w.free_joint_step) r -= d.E.col(col).head<3>().dot(c.gravity);  // else E_0 = 0
        if (gravity_at_point) r += (alpha.col(k).head<3>() * scale).dot(c.gravity);
      }
      w.rhs[col] = r;
    }
  }
}

void constraint_torques(const Model& model, Data& d) {
  // (the inward sweep has set them to 0)
  if (d.workspace.shared_body >= 0) return shared_constraint_torques(model, d);
  for (const ConstraintSource& s : d.workspace.sources)
    with_constraint_count(s.columns, [&](auto n) { add_constraint_torques<decltype(n)::value>(model, d, s); });
  if (d.workspace.free_joint_step) free_joint_constraint_torques(model, d);
}

void unscale_constraint_forces(Data& d) {
  const Data::Workspace& w = d.workspace;
  const int m = static_cast<int>(d.nu.size());
  for (int k = 0; k < m; ++k) d.nu[k] *= w.alpha_scale[k];
  for (Eigen::Index j = 0; j < d.dropped.cols(); ++j) {
    for (int k = 0; k < m; ++k) d.dropped(k, j) *= w.alpha_scale[k];
    d.dropped.col(j).normalize();
  }
  for (Eigen::Index j = 0; j < d.damped.cols(); ++j) {
    for (int k = 0; k < m; ++k) d.damped(k, j) *= w.alpha_scale[k];
    d.damped.col(j).normalize();
  }
}

double constraint_wrenches_and_joint_torques(const Model& model, Data& d, const Case& c,
                                             const Eigen::VectorXd& ff_torques, bool prescribed) {
  if (ff_torques.size()) d.joint_torques = ff_torques;
  else d.joint_torques.setZero();
  if (!c.f_virtual.empty()) d.joint_torques += d.virtual_torques;
  if (prescribed)
    for (int i = 0; i < model.num_rates(); ++i)
      if (c.prescribed[i]) d.joint_torques[i] = d.prescribed_torques[i];
  d.constraint_wrench.setZero();
  // (resized within the capacity the Data reserved, then zeroed: a block without columns
  // has no source below and keeps 0)
  d.constraint_wrenches.resize(num_solve_blocks(c, d));
  for (Vector6& w : d.constraint_wrenches) w.setZero();
  double probe = 0;
  // A shared second body b (shared_second_body.hpp): the sum of what each block's wrench
  // at P is at Q, [f; n + (q - p_b) x f], taken about b's origin
  const int shared_body = d.workspace.shared_body, last = last_body(d);
  Vector3 shared_f = Vector3::Zero(), shared_n = Vector3::Zero();
  RootWrench root;
  for (const ConstraintSource& s : d.workspace.sources) {
    // the wrench w = [f; n] = alpha nu at the point p; tau_i -= z_i . (n + (p - p_i) x f)
    // (revolute) or z_i . f (prismatic), for each body on the path
    const ConstraintMatrix& alpha = alpha_of(c, d, s);
    SpatialVector wrench{};
    for (int k = 0; k < s.columns; ++k) wrench = wrench + load_pairs(alpha.col(k).data()) * d.nu[s.column + k];
    Vector6& out = s.block < 0 ? d.constraint_wrench : d.constraint_wrenches[s.block];
    store_pairs(out, wrench);
    probe += finite_probe(wrench);
    const Vector3 f = out.head<3>(), n = out.tail<3>();
    probe += subtract_wrench_torques(model, d, s, f, n, last, root);
    if (shared_body < 0) {
      if (s.relative) probe += add_opposite_wrench(model, d, s, f, n, last, root);
    } else {  // [f; n] at Q, moved to b's origin
      shared_f += f;
      shared_n += n + s.arm_b.cross(f);
    }
  }
  // the blocks' opposite wrenches summed at their shared second body: one walk along its path
  if (shared_body >= 0) probe += add_shared_opposite_wrench(model, d, shared_body, shared_f, shared_n, last, root);
  if (last > 0) probe += free_joint_wrench_torques(model, d, root);
  return probe;
}

void constraint_force_torques(const Model& model, Data& d, const Case& c, const ConstraintVector& nu) {
  d.joint_torques.setZero();
  const int last = last_body(d);
  RootWrench root;
  for (const ConstraintSource& s : d.workspace.sources) {
    const ConstraintMatrix& alpha = alpha_of(c, d, s);
    Vector6 wrench = Vector6::Zero();
    for (int k = 0; k < s.columns; ++k)
      wrench += alpha.col(k) * (nu[s.column + k] * d.workspace.alpha_scale[s.column + k]);
    const Vector3 f = wrench.head<3>(), n = wrench.tail<3>();
    subtract_wrench_torques(model, d, s, f, n, last, root);
    if (s.relative) add_opposite_wrench(model, d, s, f, n, last, root);
  }
  if (last > 0) free_joint_wrench_torques(model, d, root);
}

}  // namespace achd
