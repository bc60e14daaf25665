// Relative blocks that all end on one second body b (shared_second_body.hpp). Each block
// s has two legs (constraint_sweep.cpp): E_s at its first body a_s, and at b its opposite
// moved to b's origin, the 6 x n_s forces C_s. Eq. (c) is linear in E, so the two legs may
// roll to the base apart and add up there, and the second leg is C_s applied to what six
// unit wrenches at b become: rolling I_6 from b to the base gives at each body i on b's
// path P_b the six unit EZ, Z_i (6 x 1 per column: Z_i = Phi_i^T S_i), and at the base
// Phi_0. Then, with A_s,i the first leg's EZ (over P_a, a_s and its ancestors),
//   EZ_s,i = A_s,i + C_s^T Z_i,      E_s,0 = E_s,a rolled + Phi_0 C_s,
// and eqs. (d), (e) and the constraint torques split the same way:
//   K_st = sum_{P_a_s ∩ P_a_t} A_s,i A_t,i^T / D_i + C_s^T Lambda C_t + Y_s C_t + C_s^T Y_t^T
//   Lambda = sum_{P_b} Z_i Z_i^T / D_i (6 x 6),  Y_s = sum_{P_a_s ∩ P_b} A_s,i Z_i^T / D_i
//   G_s = sum_{P_a_s} A_s,i known_i + C_s^T g,  g = sum_{P_b} Z_i known_i
//   torque_i -= sum_s A_s,i^T nu_s (i on P_a_s) + Z_i^T w (i on P_b),  w = sum_s C_s nu_s.
// b's path is rolled once for six columns instead of once per block, and the k^2 blocks'
// shares of K over it are C^T (Lambda C + Y^T) + Y C, 6 terms an entry. The Delta robot's
// five loops (m = 15, all on the platform's six bodies): 58.1k -> 55.6k instructions a solve.
#include "shared_second_body.hpp"

#include "constraint_count.hpp"
#include "constraint_pairs.hpp"
#include "joint_subspace.hpp"
#include "spatial_pairs.hpp"

namespace achd {
namespace {

// The lowest common ancestor of bodies a and b (-1: the base); a parent's index is below
// its children's.
int common_ancestor(const Model& model, int a, int b) {
  while (a != b) {
    if (a > b) a = model.bodies[a].parent;
    else b = model.bodies[b].parent;
  }
  return a;
}

// The body below the base that body i hangs from (-1: the base): two bodies with different
// ones have no common ancestor.
int branch_of(const Model& model, int i) {
  if (i < 0) return -1;
  while (model.bodies[i].parent >= 0) i = model.bodies[i].parent;
  return i;
}

// The first leg of source s alone, a block on its first body: rolled to the base (its
// A_s,i into the source's EZ, E_s,a at the base into col), then its share of K_ss and
// G_s, summed from the base outward. C (6 x NC, column-major) gets the second leg's
// forces at b, taken before the roll. Returns the finite probe of K_ss.
template <int NC, bool P>
double first_leg(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given,
                 const ConstraintSource& s, double* C) {
  Data::Workspace& w = d.workspace;
  double* column = d.E.col(s.column).data();
  UnitConstraintForces<NC> E(column);
  E.opposite_moved(s.arm_b - s.arm).store(C);
  double* ez = w.ez.data() + s.ez;
  int depth = 0;
  for (int i = s.body; i >= 0; i = model.bodies[i].parent) {
    E.pass_to_parent(body_subspace(model, d, i), w.U[i], w.Dinv[i], d.r[i], ez + i * ez_stride<NC>());
    w.path[depth++] = i;
  }
  E.store(column);
  CouplingSums<NC> sums;
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

// K_st over the first legs' common path (from a_s and a_t's lowest common ancestor); K_st
// untouched (0) when they have none (the arms of a parallel robot).
template <int NS, int NT>
void first_legs_coupling(const Model& model, Data& d, const ConstraintSource& s, const ConstraintSource& t) {
  const Data::Workspace& w = d.workspace;
  const int a = common_ancestor(model, s.body, t.body);
  if (a < 0) return;
  double K[NS][NT] = {};
  for (int i = a; i >= 0; i = model.bodies[i].parent) {
    const double* es = w.ez.data() + s.ez + i * ez_stride<NS>();
    const double* et = w.ez.data() + t.ez + i * ez_stride<NT>();
    for (int k = 0; k < NS; ++k) {
      const double x = es[k] * w.Dinv[i];
      for (int l = 0; l < NT; ++l) K[k][l] += x * et[l];
    }
  }
  for (int k = 0; k < NS; ++k)
    for (int l = 0; l < NT; ++l) d.K(s.column + k, t.column + l) = d.K(t.column + l, s.column + k) = K[k][l];
}

// Y_s (NC x 6, row k at Y + 6 k) over the common path of a_s and b; false (Y untouched)
// when they have none.
template <int NC>
bool first_leg_and_unit_coupling(const Model& model, const Data& d, const ConstraintSource& s, double* Y) {
  const Data::Workspace& w = d.workspace;
  const int a = s.meet;  // b = s.body_b: where the two legs meet (add_source)
  if (a < 0) return false;
  double y[NC][6] = {};
  for (int i = a; i >= 0; i = model.bodies[i].parent) {
    const double* es = w.ez.data() + s.ez + i * ez_stride<NC>();
    const double* z = w.shared_ez.data() + 6 * i;
    for (int k = 0; k < NC; ++k) {
      const double x = es[k] * w.Dinv[i];
      for (int r = 0; r < 6; ++r) y[k][r] += x * z[r];
    }
  }
  for (int k = 0; k < NC; ++k)
    for (int r = 0; r < 6; ++r) Y[6 * k + r] = y[k][r];
  return true;
}

// The six unit wrenches at b rolled to the base: Z_i into shared_ez, Phi_0 (6 x 6,
// column-major) into Phi, Lambda (6 x 6, both triangles) and g. Returns Lambda's
// finite probe.
template <bool P>
double unit_wrenches(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given, int b,
                     double* Phi, double* Lambda, double (&g)[6]) {
  Data::Workspace& w = d.workspace;
  double identity[36] = {};
  for (int r = 0; r < 6; ++r) identity[7 * r] = 1;
  UnitConstraintForces<6> E(identity);
  int depth = 0;
  for (int i = b; i >= 0; i = model.bodies[i].parent) {
    E.pass_to_parent(body_subspace(model, d, i), w.U[i], w.Dinv[i], d.r[i], w.shared_ez.data() + 6 * i);
    w.path[depth++] = i;
  }
  E.store(Phi);
  CouplingSums<6> sums;
  while (depth > 0) {
    const int i = w.path[--depth];
    double known = w.u[i] * w.Dinv[i];
    if constexpr (P) {
      if (c.prescribed[i]) known = qdd_given[i];
    }
    sums.add(w.shared_ez.data() + 6 * i, w.Dinv[i], known);
  }
  double probe = 0;
  for (int k = 0; k < 6; ++k) {
    g[k] = sums.G[k / 2][k % 2];
    for (int l = k; l < 6; ++l) Lambda[6 * k + l] = Lambda[6 * l + k] = sums.K[k][l / 2][l % 2];
  }
  for (int k = 0; k < 6; ++k)
    for (int l = 0; l < 6; ++l) probe += Lambda[6 * k + l] * 0.0;
  return probe;
}

inline double dot6(const double* x, const double* y) {
  const Pair s = (load_pair(x) * load_pair(y) + load_pair(x + 2) * load_pair(y + 2)) + load_pair(x + 4) * load_pair(y + 4);
  return s[0] + s[1];
}

}  // namespace

int shared_second_body(const Data& d, int last) {
  const std::vector<ConstraintSource>& sources = d.workspace.sources;
  if (sources.size() < 2 || last != 0) return -1;
  const int b = sources[0].body_b;
  int m = 0;
  for (const ConstraintSource& s : sources) {
    if (!s.relative || s.body_b != b) return -1;
    m += s.columns;
  }
  return b >= 0 && m > 6 ? b : -1;
}

double shared_second_body_sweep(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given,
                                bool prescribed, int b) {
  Data::Workspace& w = d.workspace;
  const int m = static_cast<int>(d.E.cols());
  double* C = w.shared_C.data();  // column k's force at b: C + 6 k
  double probe = 0;
  d.K.setZero();  // (the first legs that meet nowhere leave their K_st at 0)
  for (const ConstraintSource& s : w.sources)
    probe += with_constraint_count(s.columns, [&](auto n) {
      constexpr int NC = decltype(n)::value;
      double* Cs = C + 6 * s.column;
      return prescribed ? first_leg<NC, true>(model, d, c, qdd_given, s, Cs)
                        : first_leg<NC, false>(model, d, c, qdd_given, s, Cs);
    });
  int branch[kMaxConstraintColumns];
  for (size_t s = 0; s < w.sources.size(); ++s) branch[s] = branch_of(model, w.sources[s].body);
  for (size_t s = 0; s < w.sources.size(); ++s)
    for (size_t t = s + 1; t < w.sources.size(); ++t)
      if (branch[s] >= 0 && branch[s] == branch[t])
      with_constraint_count(w.sources[s].columns, [&](auto ns) {
        with_constraint_count(w.sources[t].columns, [&](auto nt) {
          first_legs_coupling<decltype(ns)::value, decltype(nt)::value>(model, d, w.sources[s], w.sources[t]);
        });
      });
  double Phi[36], Lambda[36], g[6];
  probe += prescribed ? unit_wrenches<true>(model, d, c, qdd_given, b, Phi, Lambda, g)
                      : unit_wrenches<false>(model, d, c, qdd_given, b, Phi, Lambda, g);
  // Y (row k at Y + 6 k), 0 for the blocks whose first leg does not meet b's path
  double Y[6 * kMaxConstraintColumns];
  bool has_Y[kMaxConstraintColumns];
  for (const ConstraintSource& s : w.sources) {
    const bool met = with_constraint_count(s.columns, [&](auto n) {
      return first_leg_and_unit_coupling<decltype(n)::value>(model, d, s, Y + 6 * s.column);
    });
    for (int k = 0; k < s.columns; ++k) has_Y[s.column + k] = met;
  }
  // M_k = Lambda C_k + Y_k^T; E_0 += Phi_0 C_k; G_k += C_k^T g
  double M[6 * (kMaxConstraintColumns + 1)];
  for (int k = 0; k < m; ++k) {
    const double* ck = C + 6 * k;
    double* mk = M + 6 * k;
    for (int r = 0; r < 6; ++r) mk[r] = 0;
    store_pairs(mk, add_columns_times(load_pairs(mk), Lambda, ck, 6));
    if (has_Y[k])
      for (int r = 0; r < 6; ++r) mk[r] += Y[6 * k + r];
    double* e = d.E.col(k).data();
    store_pairs(e, add_columns_times(load_pairs(e), Phi, ck, 6));
    d.G0[k] += dot6(ck, g);
  }
  // K_kl += C_k^T M_l (+ Y_k C_l), l <= k, mirrored. Row k against two columns l, l + 1 at
  // a time: M interleaved by pairs of columns (pair j's row r at Mp + 12 j + 2 r, a zero
  // column past m), C_k's entries splatted, each lane summing the six products in dot6's
  // order, so that every entry is dot6's to the bit; K is symmetric here, and K(l..l+1, k)
  // is a pair of column k.
  for (int r = 0; r < 6; ++r) M[6 * m + r] = 0;
  double Mp[6 * (kMaxConstraintColumns + 1)];
  for (int j = 0; 2 * j < m; ++j)
    for (int r = 0; r < 6; r += 2) {
      const Pair a = load_pair(M + 12 * j + r), b = load_pair(M + 12 * j + 6 + r);
      store_pair(Mp + 12 * j + 2 * r, low_lanes(a, b));
      store_pair(Mp + 12 * j + 2 * r + 2, high_lanes(a, b));
    }
  Pair probes = splat(0);
  for (int k = 0; k < m; ++k) {
    const double* ck = C + 6 * k;
    const Pair c0 = splat(ck[0]), c1 = splat(ck[1]), c2 = splat(ck[2]), c3 = splat(ck[3]), c4 = splat(ck[4]),
               c5 = splat(ck[5]);
    double* Kk = &d.K(0, k);
    for (int l = 0; l <= k; l += 2) {
      const double* mp = Mp + 6 * l;
      const Pair even = (c0 * load_pair(mp) + c2 * load_pair(mp + 4)) + c4 * load_pair(mp + 8);
      const Pair odd = (c1 * load_pair(mp + 2) + c3 * load_pair(mp + 6)) + c5 * load_pair(mp + 10);
      Pair x = even + odd;
      const bool two = l < k;  // else l = k: the diagonal alone
      if (has_Y[k]) x = Pair{x[0] + dot6(Y + 6 * k, C + 6 * l), two ? x[1] + dot6(Y + 6 * k, C + 6 * l + 6) : 0.0};
      if (two) {
        const Pair v = load_pair(Kk + l) + x;
        store_pair(Kk + l, v);
        d.K(k, l) = v[0];
        d.K(k, l + 1) = v[1];
        probes += v * splat(0);
      } else {
        const double v = Kk[l] + x[0];
        Kk[l] = v;
        probe += v * 0.0;
      }
    }
  }
  probe += probes[0] + probes[1];
  return probe;
}

void shared_constraint_torques(const Model& model, Data& d) {
  const Data::Workspace& w = d.workspace;
  const int m = static_cast<int>(d.nu.size());
  double force[6] = {};  // w = sum_k C_k nu_k
  for (int k = 0; k < m; ++k)
    for (int r = 0; r < 6; ++r) force[r] += w.shared_C[6 * k + r] * d.nu[k];
  for (const ConstraintSource& s : w.sources)
    with_constraint_count(s.columns, [&](auto n) {
      constexpr int NC = decltype(n)::value;
      const ConstraintMagnitudes<NC> nu(d.nu.data() + s.column);
      const double* ez = w.ez.data() + s.ez;
      for (int i = s.body; i >= 0; i = model.bodies[i].parent)
        d.constraint_torques[i] -= nu.dot(ez + i * ez_stride<NC>());
    });
  for (int i = w.shared_body; i >= 0; i = model.bodies[i].parent)
    d.constraint_torques[i] -= dot6(w.shared_ez.data() + 6 * i, force);
}

}  // namespace achd
