#include "held_directions.hpp"

#include "achd/error.hpp"

namespace achd {

std::string direction_label(const Model& model, int link, int index) {
  std::string label = std::string("direction ") + direction_name(index);
  if (model.has_tip() && link == model.num_links() - 1) return label;
  return label + " of link '" + model.links[link].name + "'";
}

int HeldDirections::count() const {
  int n = 0;
  for (int k = 0; k < kNumDirections; ++k) n += active(k);
  return n;
}

void direction_columns(const HeldDirections& h, ConstraintMatrix& alpha) {
  alpha.setZero(6, h.count());
  int col = 0;
  for (int k = 0; k < kNumDirections; ++k) {
    if (!h.active(k)) continue;
    if (is_linear_direction(k)) alpha.col(col).head<3>() = direction_axis(k);
    else alpha.col(col).tail<3>() = direction_axis(k);
    ++col;
  }
}

void direction_weights(const HeldDirections& h, ConstraintVector& w_fext, ConstraintVector& w_ff) {
  w_fext.resize(0);
  w_ff.resize(0);
  if (!yielding_directions(h)) return;
  w_fext.resize(h.count());
  w_ff.resize(h.count());
  int col = 0;
  for (int k = 0; k < kNumDirections; ++k) {
    if (!h.active(k)) continue;
    w_fext[col] = h.w_fext[k];
    w_ff[col++] = h.w_ff[k];
  }
}

unsigned yielding_directions(const HeldDirections& h) {
  unsigned bits = 0;
  for (int k = 0; k < kNumDirections; ++k)
    if (h.active(k) && (h.w_fext[k] < 1 || h.w_ff[k] < 1)) bits |= 1u << k;
  return bits;
}

double direction_error(const HeldDirections& h, int k, const TipState& point, const double* angles) {
  if (h.mode[k] != DirectionMode::Hold) return 0;
  if (is_linear_direction(k)) return direction_axis(k).dot(point.pose.p) - h.target[k];
  return angles[k];
}

void direction_targets(const HeldDirections& h, const TipState& point, const double* angles, double w_n,
                       double zeta, bool velocity_products, ConstraintVector& beta) {
  beta.resize(h.count());
  const Vector3 w_cross_v = point.w.cross(point.v);
  int row = 0;
  for (int k = 0; k < kNumDirections; ++k) {
    if (!h.active(k)) continue;
    const Vector3 e = direction_axis(k);
    const bool linear = is_linear_direction(k);
    double desired = h.setpoint[k];
    if (h.mode[k] == DirectionMode::Hold) {
      const double rate = e.dot(linear ? point.v : point.w);
      desired = -2 * zeta * w_n * rate - w_n * w_n * direction_error(h, k, point, angles);
    }
    beta[row++] = linear && velocity_products ? desired - e.dot(w_cross_v) : desired;
  }
}

}  // namespace achd
