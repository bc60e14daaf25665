// The Simulator's directions (direction_sets.hpp holds them): the public calls that set
// and read them, each link's block in the simulator's case, and the held directions'
// residuals, poses and re-anchoring from the state.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "achd/error.hpp"
#include "achd/simulator.hpp"
#include "direction_sets.hpp"
#include "held_directions.hpp"
#include "integrators.hpp"
#include "simulator_checks.hpp"
#include "message_number.hpp"
#include "tip_kinematics.hpp"

namespace achd {

int Simulator::tip_link(const std::string& what) const {
  if (!model_.has_tip())
    throw Error(what + ": the model is a tree (loaded without a tip); name the link whose directions these are");
  return model_.num_links() - 1;
}

const std::vector<LinkDirections>& Simulator::direction_sets() const { return directions_->sets(); }

LinkDirections& Simulator::set_of(int link) {
  const size_t sets = directions_->sets().size();
  const int s = directions_->find_or_create(link);
  if (directions_->sets().size() != sets) {
    // The solves compute the accelerations of the links with directions alone (data()
    // reports them; the steps read the links' motion from the kinematics).
    std::vector<int> links;
    for (const LinkDirections& set : directions_->sets()) links.push_back(set.link);
    for (Data* d : {&data_[0], &data_[1], &limit_data_, &integrator_->stage_data}) d->set_link_outputs(links);
  }
  // a new set's held angles, zero (the only allocation of a set: not in a step)
  const Eigen::Index before = held_angles.size(), after = (s + 1) * kNumDirections;
  if (after > before) {
    held_angles.conservativeResize(after);
    held_angles.tail(after - before).setZero();
  }
  return directions_->sets()[s];
}

void Simulator::update_blocks() {
  directions_->write_blocks(case_.constraints);
  update_control_terms();  // the frequency gains and hold feed-forward follow the held set
}

void Simulator::set_direction(int link, int index, DirectionMode mode, double setpoint) {
  direction_name(index);  // an achd::Error on an index outside 0..5
  LinkDirections& set = set_of(link);
  const std::string what = direction_label(model_, link, index);
  if (!std::isfinite(setpoint)) throw Error(what + ": setpoint is not finite");
  if (mode != DirectionMode::Free && !set.held.active(index) && directions_->active_columns() >= kMaxConstraintColumns)
    throw Error(what + ": " + std::to_string(kMaxConstraintColumns) +
                " directions are already active on all links together, the most a solve takes");
  const int s = static_cast<int>(&set - directions_->sets().data());
  const double target = mode == DirectionMode::Hold && is_linear_direction(index)
                            ? direction_axis(index).dot(link_pose(link).p) : 0.0;
  directions_->set(s, index, mode, setpoint, target);
  held_angles[s * kNumDirections + index] = 0;
  update_blocks();
}

void Simulator::set_direction_point(int link, const Vector3& point) {
  LinkDirections& set = set_of(link);
  if (!point.allFinite())
    throw Error("the direction point of link '" + model_.links[link].name + "' is not finite");
  set.point = point;
  std::vector<unsigned>& bits = directions_->anchored();
  std::fill(bits.begin(), bits.end(), 0u);
  bits[static_cast<size_t>(&set - directions_->sets().data())] = (1u << kNumDirections) - 1;  // every direction
  anchor_directions(bits);
  set.max_residual.fill(0);
  update_blocks();
}

DirectionMode Simulator::direction_mode(int link, int index) const {
  direction_name(index);  // an achd::Error on an index outside 0..5
  const LinkDirections* set = directions_->find(link);
  return set ? set->held.mode[index] : DirectionMode::Free;
}

double Simulator::setpoint(int link, int index) const {
  direction_name(index);  // an achd::Error on an index outside 0..5
  const LinkDirections* set = directions_->find(link);
  return set ? set->held.setpoint[index] : 0.0;
}

void Simulator::set_direction_weights(int link, int index, double w_fext, double w_ff) {
  direction_name(index);  // an achd::Error on an index outside 0..5
  LinkDirections& set = set_of(link);
  for (const auto& [name, w] : {std::pair<const char*, double>{"w_fext", w_fext}, {"w_ff", w_ff}})
    if (!(w >= 0 && w <= 1))
      throw Error(direction_label(model_, link, index) + ": " + name + " must be in [0, 1], got " + message_number(w));
  set.held.w_fext[index] = w_fext;
  set.held.w_ff[index] = w_ff;
  update_blocks();
}

void Simulator::set_direction(int index, DirectionMode mode, double setpoint) {
  set_direction(tip_link("set_direction"), index, mode, setpoint);
}
DirectionMode Simulator::direction_mode(int index) const { return direction_mode(tip_link("direction_mode"), index); }
double Simulator::setpoint(int index) const { return setpoint(tip_link("setpoint"), index); }
void Simulator::set_direction_weights(int index, double w_fext, double w_ff) {
  set_direction_weights(tip_link("set_direction_weights"), index, w_fext, w_ff);
}

std::array<double, kNumDirections> Simulator::residuals(int link) const {
  std::array<double, kNumDirections> r{};
  const LinkDirections* set = directions_->find(link);
  if (!set) return r;
  const ChainMotion& m = thread_chain_motion(model_, q, qd);
  const TipState at = link_state(model_, m.X0, m.v, link, set->point);
  const double* angles = held_angles.data() + (set - directions_->sets().data()) * kNumDirections;
  for (int k = 0; k < kNumDirections; ++k) r[k] = direction_error(set->held, k, at, angles);
  return r;
}

std::array<double, kNumDirections> Simulator::max_residuals(int link) const {
  std::array<double, kNumDirections> r = residuals(link);
  const LinkDirections* set = directions_->find(link);
  if (!set) return r;
  const int s = static_cast<int>(set - directions_->sets().data());
  for (int k = 0; k < kNumDirections; ++k)
    r[k] = std::max(directions_->events().released(s, k) ? 0.0 : std::abs(r[k]), set->max_residual[k]);
  return r;
}

std::array<double, kNumDirections> Simulator::released_seconds(int link) const {
  std::array<double, kNumDirections> r{};
  const LinkDirections* set = directions_->find(link);
  if (!set) return r;
  const int s = static_cast<int>(set - directions_->sets().data());
  for (int k = 0; k < kNumDirections; ++k) r[k] = directions_->events().released_seconds(s, k, t);
  return r;
}

std::array<double, kNumDirections> Simulator::loop_released_seconds(int loop) const {
  check_loop(model_, loop, "loop_released_seconds");
  std::array<double, kNumDirections> r{};
  for (int k = 0; k < kNumDirections; ++k) r[k] = directions_->events().loop_released_seconds(loop, k, t);
  return r;
}

Transform Simulator::link_pose(int link) const {
  const LinkDirections* set = directions_->find(link);
  const ChainMotion& m = thread_chain_motion(model_, q, qd);
  return link_state(model_, m.X0, m.v, link, set ? set->point : Vector3::Zero()).pose;
}

Vector6 Simulator::link_velocity(int link) const {
  const LinkDirections* set = directions_->find(link);
  const ChainMotion& m = thread_chain_motion(model_, q, qd);
  const TipState at = link_state(model_, m.X0, m.v, link, set ? set->point : Vector3::Zero());
  Vector6 out;
  out << at.v, at.w;
  return out;
}

std::array<double, kNumDirections> Simulator::residuals() const { return residuals(tip_link("residuals")); }
std::array<double, kNumDirections> Simulator::max_residuals() const { return max_residuals(tip_link("max_residuals")); }
Transform Simulator::tip_pose() const { return link_pose(tip_link("tip_pose")); }
Vector6 Simulator::tip_velocity() const { return link_velocity(tip_link("tip_velocity")); }

// A released or yielding Hold direction continues where its point is (linear: target =
// e . p_point; angular: held angle 0), so that the stabilisation does not yank it back
// to the target it lost.
void Simulator::anchor_directions(const std::vector<unsigned>& bits) {
  body_motion(model_, q, qd, X0_, r_, v_);
  std::vector<LinkDirections>& sets = directions_->sets();
  for (int s = 0; s < static_cast<int>(sets.size()); ++s) {
    if (!bits[s]) continue;
    LinkDirections& set = sets[s];
    const Vector3 p = link_state(model_, X0_, v_, set.link, set.point).pose.p;
    for (int k = 0; k < kNumDirections; ++k) {
      if (!(bits[s] >> k & 1u) || set.held.mode[k] != DirectionMode::Hold) continue;
      if (is_linear_direction(k)) set.held.target[k] = direction_axis(k).dot(p);
      else held_angles[s * kNumDirections + k] = 0;
    }
  }
}

}  // namespace achd
