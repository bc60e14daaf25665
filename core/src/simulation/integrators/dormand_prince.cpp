// Integrator::DormandPrince: the explicit Runge-Kutta pair of Dormand and Prince (1980),
// order 5 with an embedded order-4 error estimate, "first same as last" (FSAL), under the
// standard step-size control (Hairer, Norsett, Wanner, Solving ODEs I, II.4).
//
// x = (q, qd, held angles), x' = f(x) (Simulator::evaluate). A substep of h:
//   k_s = f(x + h sum_{j<s} a_sj k_j),  s = 1..7 (k_1 = f(x), reused from the last k_7);
//   x' = x + h sum_j b_j k_j (5th order; b = a_7j, so k_7 = f(x') is the next k_1);
//   err = h sum_j e_j k_j, e = b - b* (b*: the 4th-order weights).
// Accepted when ||err|| <= 1, ||.|| the RMS over the components of
// err_i / (atol + rtol max(|x_i|, |x'_i|)); the next h is h min(5, max(0.2, 0.9 ||err||^-1/5)),
// not grown right after a rejection. step(dt) takes substeps until exactly dt is covered
// (the last one shortened to end on t + dt) and carries the proposed h to the next call.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "achd/simulator.hpp"
#include "held_directions.hpp"

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
// the smallest).
double growth(double err) {
  if (!(err < INFINITY)) return kMinGrowth;
  if (err == 0) return kMaxGrowth;
  return std::min(kMaxGrowth, std::max(kMinGrowth, kSafety * std::pow(err, -0.2)));
}

// A number for messages: 4 significant digits.
std::string text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

}  // namespace

void Simulator::step_dormand_prince(double dt, double w_n, Data& first) {
  const int n = model_.num_joints();
  const double rtol = options_.rtol, atol = options_.atol;
  const Eigen::Index na = held_angle_count();  // the held angles in use
  stage_ = 0;
  evaluate(q, qd, angles_, t, w_n, first, k_angle_[0]);
  // No substep size helps when the acceleration at the start is not finite.
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(first.qdd[i]))
      throw Error("the acceleration of joint '" + model_.bodies[i].joint_name + "' is not finite (qdd = " +
                  text(first.qdd[i]) + ")");
  configuration_rate(model_, q, qd, k_q_[0]);
  k_qd_[0] = first.qdd;

  double h = substep_ > 0 ? substep_ : dt;  // the proposal carried over from the last call
  double done = 0;                          // of dt, covered by accepted substeps
  int rejections = 0;
  std::int64_t accepted = 0;  // substeps accepted in this call
  for (;;) {
    const double remaining = dt - done;
    // The last substep ends on dt exactly; one within 1% of the rest takes all of it.
    const bool last = done + 1.01 * h >= dt;
    const double hs = last ? remaining : h;
    substep_ = hs;
    if (hs < kMinSubstepFraction * dt) {
      stage_ = -1;
      throw Error("the adaptive substep fell to " + text(hs) + " s, below its floor of " +
                  text(kMinSubstepFraction) + " dt (rtol " + text(rtol) + ", atol " + text(atol) +
                  "): the motion is too fast or too stiff here for these tolerances");
    }
    // Stages 2..7; stage 7 is the 5th-order solution x'.
    bool finite = true;
    for (int s = 1; s < 7 && finite; ++s) {
      stage_ = s;
      Eigen::VectorXd& qs = s == 6 ? q_next_ : q_stage_;
      Eigen::VectorXd& qds = s == 6 ? qd_next_ : qd_stage_;
      HeldAngles& as = s == 6 ? angle_next_ : angle_stage_;
      qs = q;
      qds = qd;
      as.head(na) = angles_.head(na);
      for (int j = 0; j < s; ++j) {
        if (kA[s][j] == 0) continue;
        const double c = hs * kA[s][j];
        qs += c * k_q_[j];
        qds += c * k_qd_[j];
        as.head(na) += c * k_angle_[j].head(na);
      }
      finite = qs.allFinite() && qds.allFinite() && as.head(na).allFinite();
      if (!finite) break;  // rejected below: a smaller substep
      evaluate(qs, qds, as, t + done + kC[s] * hs, w_n, stage_data_, k_angle_[s]);
      configuration_rate(model_, qs, qds, k_q_[s]);
      k_qd_[s] = stage_data_.qdd;
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
      const int nq = static_cast<int>(q.size());
      for (int i = 0; i < std::max(n, nq); ++i) {
        if (i < nq) {
          double eq = 0;
          for (int j = 0; j < 7; ++j) eq += kE[j] * k_q_[j][i];
          add(q[i], q_next_[i], hs * eq);
        }
        if (i < n) {
          double eqd = 0;
          for (int j = 0; j < 7; ++j) eqd += kE[j] * k_qd_[j][i];
          add(qd[i], qd_next_[i], hs * eqd);
        }
      }
      for (size_t set = 0; set < sets_.size(); ++set)
        for (int k = 0; k < kNumDirections; ++k) {
          if (sets_[set].held.mode[k] != DirectionMode::Hold || is_linear_direction(k)) continue;
          const size_t a = set * kNumDirections + k;
          double e = 0;
          for (int j = 0; j < 7; ++j) e += kE[j] * k_angle_[j][a];
          add(angles_[a], angle_next_[a], hs * e);
        }
    }
    const double err = finite ? (count ? std::sqrt(sum / count) : 0) : INFINITY;
    if (err <= 1) {
      q = q_next_;  // copies: q and qd keep their buffers (the JS API views them)
      normalise_configuration(model_, q);
      qd = qd_next_;
      angles_.head(na) = angle_next_.head(na);
      // FSAL: k_7 at x' is k_1 of the next substep.
      k_q_[0].swap(k_q_[6]);
      k_qd_[0].swap(k_qd_[6]);
      k_angle_[0].swap(k_angle_[6]);
      ++substeps_;
      double next = hs * (rejections ? std::min(1.0, growth(err)) : growth(err));
      // A last substep cut short to end on dt does not shrink the proposal.
      if (last && hs < h) next = std::max(next, h);
      substep_ = h = next;
      rejections = 0;
      if (last) return;
      done += hs;
      if (++accepted >= kMaxSubstepsPerStep) {
        stage_ = -1;
        throw Error(std::to_string(kMaxSubstepsPerStep) + " adaptive substeps (the last of " + text(hs) +
                    " s) covered only " + text(done) + " s of this step's " + text(dt) + " s (rtol " + text(rtol) +
                    ", atol " + text(atol) + "): the motion is too fast or too stiff here for these tolerances");
      }
    } else {
      ++rejected_substeps_;
      if (++rejections > kMaxRejections) {
        stage_ = -1;
        throw Error(std::to_string(kMaxRejections) + " adaptive substeps in a row were rejected (the last of " +
                    text(hs) + " s, its error " + text(err) + " times the tolerance)");
      }
      substep_ = h = hs * growth(err);
    }
  }
}

}  // namespace achd
