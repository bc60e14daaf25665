// Integrator::DormandPrince: the explicit Runge-Kutta pair of Dormand and Prince (1980),
// order 5 with an embedded order-4 error estimate, "first same as last" (FSAL), under the
// standard step-size control (Hairer, Norsett, Wanner, Solving ODEs I, II.4).
//
// x = (q, qd, held angles), x' = f(x) (the evaluate callable). A substep of h:
//   k_s = f(x + h sum_{j<s} a_sj k_j),  s = 1..7 (k_1 = f(x), reused from the last k_7);
//   x' = x + h sum_j b_j k_j (5th order; b = a_7j, so k_7 = f(x') is the next k_1);
//   err = h sum_j e_j k_j, e = b - b* (b*: the 4th-order weights).
// Accepted when ||err|| <= 1, ||.|| the RMS over the components of
// err_i / (atol + rtol max(|x_i|, |x'_i|)); the next h is h min(5, max(0.2, 0.9 ||err||^-1/5)),
// not grown right after a rejection. step(dt) takes substeps until exactly dt is covered
// (the last one shortened to end on t + dt) and carries the proposed h to the next call.
//
// Stiffness detection (Hairer, Wanner, Solving ODEs II, IV.2, "Stiffness detection", as in
// their DOPRI5): stages 6 and 7 are at the same time t + h, so that
//   h lambda ~ h ||k_7 - k_6|| / ||x_7 - x_6||   (Euclidean norms over q and qd)
// estimates h times the Jacobian's dominant eigenvalue along the error. An explicit method's
// substeps on a stiff problem sit at the edge of its stability region, where h lambda is
// about 3.3 for this pair. After every accepted substep: h lambda > 3.25 counts a stiff
// substep (and clears the run of substeps below it); 6 substeps in a row below clear the
// count; at 15 the problem is stiff and the substeps that follow are the extrapolated
// linearly implicit Euler method's (extrapolated_implicit_euler.cpp: implicit in the PD
// controller and the joints' damping and friction; rows of the extrapolation tableau added
// until the same error norm is <= 1, order = rows <= kMaxImplicitRows; the next h is
// h min(5, max(0.2, 0.9 ||err||^-1/rows))), with lambda the last estimate. They give way
// to Dormand-Prince again when h lambda at the h they propose is <= 3.25: where
// Dormand-Prince would be stable at the stiff method's substep, it is the cheaper. A run
// whose estimate never reaches the count takes exactly the substeps it took without the
// detection.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "integrators.hpp"

namespace achd {

namespace {

// The Butcher tableau: c (stage times), a (lower triangle, row s = stage s), e = b - b*.
constexpr double kA[7][6] = {
    {},
    {1.0 / 5},
    {3.0 / 40, 9.0 / 40},
    {44.0 / 45, -56.0 / 15, 32.0 / 9},
    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84},  // = b
};
// c_s = sum_j a_sj: the stage times within a substep.
constexpr double kC[7] = {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1};
constexpr double kE[7] = {71.0 / 57600,      0,           -71.0 / 16695, 71.0 / 1920,
                          -17253.0 / 339200, 22.0 / 525, -1.0 / 40};

constexpr double kSafety = 0.9, kMinGrowth = 0.2, kMaxGrowth = 5;

// The factor a substep's size is multiplied by after an error norm of `err` (inf or NaN:
// the smallest): err^-1/5 for Dormand-Prince (its estimate is O(h^5)), err^-1/2 for the
// extrapolated implicit Euler (O(h^2)).
double growth(double err, int order = 5) {
  if (!(err < INFINITY)) return kMinGrowth;
  if (err == 0) return kMaxGrowth;
  return std::min(kMaxGrowth, std::max(kMinGrowth, kSafety * std::pow(err, order == 5 ? -0.2 : -1.0 / order)));
}

// The stiffness detection's bound on h lambda and its counts (see the top).
constexpr double kStiffHLambda = 3.25;
constexpr int kStiffSubsteps = 15, kNonstiffSubsteps = 6;

// After an accepted Dormand-Prince substep of hs (stage 6's state in ws.stage_state, stage
// 7's, x', in ws.next_state): h lambda counted; true when the problem turns stiff.
bool detect_stiffness(IntegratorWorkspace& ws, double hs) {
  const SimulationState &x6 = ws.stage_state, &x7 = ws.next_state;
  const double num = (ws.k_q[6] - ws.k_q[5]).squaredNorm() + (ws.k_qd[6] - ws.k_qd[5]).squaredNorm();
  const double den = (x7.q - x6.q).squaredNorm() + (x7.qd - x6.qd).squaredNorm();
  if (!(den > 0)) return false;
  const double h_lambda = hs * std::sqrt(num / den);
  if (!(h_lambda > kStiffHLambda)) {
    if (++ws.nonstiff_count >= kNonstiffSubsteps) ws.stiff_count = 0;
    return false;
  }
  ws.nonstiff_count = 0;
  if (++ws.stiff_count < kStiffSubsteps) return false;
  ws.stiff_count = 0;
  ws.stiff_lambda = h_lambda / hs;
  return true;
}

// A number for messages: 4 significant digits.
std::string text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

// One Dormand-Prince substep of hs from x (at x.t + done): stages 2..7 (k_1 given), x'
// into ws.next_state, and its error norm (inf when a stage is not finite).
double dormand_prince_substep(const Model& model, IntegratorWorkspace& ws, const SimulationState& x, double done,
                              double hs, double rtol, double atol, const std::vector<char>& integrated_angles,
                              Evaluate evaluate) {
  const int n = model.num_rates();
  const Eigen::Index na = x.held_angles.size();
  SimulationState& next = ws.next_state;
  // Stages 2..7; stage 7 is the 5th-order solution x'.
  bool finite = true;
  for (int s = 1; s < 7 && finite; ++s) {
    ws.stage = s;
    SimulationState& xs = s == 6 ? next : ws.stage_state;
    xs.q = x.q;
    xs.qd = x.qd;
    xs.held_angles.head(na) = x.held_angles;
    for (int j = 0; j < s; ++j) {
      if (kA[s][j] == 0) continue;
      const double c = hs * kA[s][j];
      xs.q += c * ws.k_q[j];
      xs.qd += c * ws.k_qd[j];
      xs.held_angles.head(na) += c * ws.k_angle[j].head(na);
    }
    finite = xs.q.allFinite() && xs.qd.allFinite() && xs.held_angles.head(na).allFinite();
    if (!finite) break;  // rejected below: a smaller substep
    xs.t = x.t + done + kC[s] * hs;
    evaluate(xs, ws.stage_data, ws.k_angle[s]);
    configuration_rate(model, xs.q, xs.qd, ws.k_q[s]);
    ws.k_qd[s] = ws.stage_data.qdd;
  }
  // ||err||: RMS of err_i / (atol + rtol max(|x_i|, |x'_i|)) over q, qd, held angles.
  double sum = 0;
  int count = 0;
  if (finite) {
    const auto add = [&](double x0, double x1, double e) {
      const double scale = atol + rtol * std::max(std::abs(x0), std::abs(x1));
      sum += (e / scale) * (e / scale);
      ++count;
    };
    // q has num_positions() numbers (one more than qd with a floating base's quaternion)
    const int nq = static_cast<int>(x.q.size());
    for (int i = 0; i < std::max(n, nq); ++i) {
      if (i < nq) {
        double eq = 0;
        for (int j = 0; j < 7; ++j) eq += kE[j] * ws.k_q[j][i];
        add(x.q[i], next.q[i], hs * eq);
      }
      if (i < n) {
        double eqd = 0;
        for (int j = 0; j < 7; ++j) eqd += kE[j] * ws.k_qd[j][i];
        add(x.qd[i], next.qd[i], hs * eqd);
      }
    }
    for (Eigen::Index a = 0; a < na; ++a) {
      if (!integrated_angles[a]) continue;
      double e = 0;
      for (int j = 0; j < 7; ++j) e += kE[j] * ws.k_angle[j][a];
      add(x.held_angles[a], next.held_angles[a], hs * e);
    }
  }
  return finite ? (count ? std::sqrt(sum / count) : 0) : INFINITY;
}

}  // namespace

void dormand_prince(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt, double rtol,
                    double atol, const std::vector<char>& integrated_angles, Evaluate evaluate,
                    ImplicitEvaluate implicit_evaluate, Data& first) {
  const int n = model.num_rates();
  const Eigen::Index na = x.held_angles.size();
  ws.stage = 0;
  evaluate(x, first, ws.k_angle[0]);
  // No substep size helps when the acceleration at the start is not finite.
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(first.qdd[i]))
      throw Error("the acceleration of joint '" + model.bodies[i].joint_name + "' is not finite (qdd = " +
                  text(first.qdd[i]) + ")");
  configuration_rate(model, x.q, x.qd, ws.k_q[0]);
  ws.k_qd[0] = first.qdd;

  double h = ws.substep > 0 ? ws.substep : dt;  // the proposal carried over from the last call
  double done = 0;                              // of dt, covered by accepted substeps
  int rejections = 0;
  std::int64_t accepted = 0;  // substeps accepted in this call
  SimulationState& next = ws.next_state;
  for (;;) {
    const double remaining = dt - done;
    // The last substep ends on dt exactly; one within 1% of the rest takes all of it.
    const bool last = done + 1.01 * h >= dt;
    const double hs = last ? remaining : h;
    ws.substep = hs;
    if (hs < kMinSubstepFraction * dt) {
      ws.stage = -1;
      throw Error("the adaptive substep fell to " + text(hs) + " s, below its floor of " +
                  text(kMinSubstepFraction) + " dt (rtol " + text(rtol) + ", atol " + text(atol) +
                  "): the motion is too fast or too stiff here for these tolerances");
    }
    const bool stiff = ws.stiff;
    double err;
    int order = 5;
    if (stiff) {
      ws.stage = -1;
      const ImplicitSubstep sub = extrapolated_implicit_euler(model, ws, x, x.t + done, hs, rtol, atol,
                                                              integrated_angles, implicit_evaluate);
      err = sub.err;
      order = sub.rows;
    } else {
      err = dormand_prince_substep(model, ws, x, done, hs, rtol, atol, integrated_angles, evaluate);
    }
    if (err <= 1) {
      const bool turns_stiff = !stiff && detect_stiffness(ws, hs);  // (reads the stages: before the swap)
      x.q = next.q;  // copies: q and qd keep their buffers (the JS API views them)
      normalise_configuration(model, x.q);
      x.qd = next.qd;
      x.held_angles = next.held_angles.head(na);
      // FSAL: k_7 at x' is k_1 of the next substep.
      if (!stiff) {
        ws.k_q[0].swap(ws.k_q[6]);
        ws.k_qd[0].swap(ws.k_qd[6]);
        ws.k_angle[0].swap(ws.k_angle[6]);
      }
      ++ws.substeps;
      if (stiff) ++ws.stiff_substeps;
      double next_h = hs * (rejections ? std::min(1.0, growth(err, order)) : growth(err, order));
      // A last substep cut short to end on dt does not shrink the proposal.
      if (last && hs < h) next_h = std::max(next_h, h);
      ws.substep = h = next_h;
      rejections = 0;
      if (turns_stiff) ws.stiff = true;
      if (stiff && h * ws.stiff_lambda <= kStiffHLambda) {
        // Dormand-Prince again, from k_1 = f(x') (next step's first solve when this was the last)
        ws.stiff = false;
        if (!last) {
          SimulationState& at = ws.stage_state;
          at.q = x.q;
          at.qd = x.qd;
          at.held_angles.head(na) = x.held_angles;
          at.t = x.t + done + hs;
          evaluate(at, ws.stage_data, ws.k_angle[0]);
          configuration_rate(model, x.q, x.qd, ws.k_q[0]);
          ws.k_qd[0] = ws.stage_data.qdd;
        }
      }
      if (last) return;
      done += hs;
      if (++accepted >= kMaxSubstepsPerStep) {
        ws.stage = -1;
        throw Error(std::to_string(kMaxSubstepsPerStep) + " adaptive substeps (the last of " + text(hs) +
                    " s) covered only " + text(done) + " s of this step's " + text(dt) + " s (rtol " + text(rtol) +
                    ", atol " + text(atol) + "): the motion is too fast or too stiff here for these tolerances");
      }
    } else {
      ++ws.rejected;
      if (++rejections > kMaxRejections) {
        ws.stage = -1;
        throw Error(std::to_string(kMaxRejections) + " adaptive substeps in a row were rejected (the last of " +
                    text(hs) + " s, its error " + text(err) + " times the tolerance)");
      }
      ws.substep = h = hs * growth(err, order);
    }
  }
}

}  // namespace achd
