// The Simulator's directions: per link, a held set (held_directions.hpp) at a point of the
// link, turned into one constraint block of the simulator's case per link with active
// directions. Sets are created on first use and kept (in the order of nu) until the
// simulator goes; reset() frees their directions and keeps their weights and points.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "achd/error.hpp"
#include "achd/simulator.hpp"
#include "message_number.hpp"
#include "held_directions.hpp"
#include "direction_events.hpp"
#include "tip_kinematics.hpp"

namespace achd {
int Simulator::tip_link(const std::string& what) const {
  if (!model_.has_tip())
    throw Error(what + ": the model is a tree (loaded without a tip); name the link whose directions these are");
  return model_.num_links() - 1;
}

const LinkDirections* Simulator::find_set(int link) const {
  if (link < 0 || link >= model_.num_links())
    throw Error("direction link index " + std::to_string(link) + " is not in 0.." +
                std::to_string(model_.num_links() - 1) + " (Model::links)");
  for (const LinkDirections& s : sets_)
    if (s.link == link) return &s;
  return nullptr;
}

LinkDirections* Simulator::find_set(int link, bool create) {
  if (const LinkDirections* found = std::as_const(*this).find_set(link))
    return &sets_[static_cast<size_t>(found - sets_.data())];
  if (!create) return nullptr;
  LinkDirections set;  // sets_ holds a capacity of every link: no reallocation
  set.link = link;
  sets_.push_back(set);
  return &sets_.back();
}

void Simulator::update_blocks() {
  case_.constraints.clear();
  block_set_.clear();
  for (int s = 0; s < static_cast<int>(sets_.size()); ++s) {
    const LinkDirections& set = sets_[s];
    if (!set.held.count()) continue;
    ConstraintBlock& b = case_.constraints.emplace_back();
    b.link = set.link;
    b.point = set.point;
    direction_columns(set.held, b.alpha);
    direction_weights(set.held, b.w_fext, b.w_ff);
    block_set_.push_back(s);
  }
  update_control_terms();  // the frequency gains and hold feed-forward follow the held set
}

void Simulator::set_direction(int link, int index, DirectionMode mode, double setpoint) {
  direction_name(index);  // an achd::Error on an index outside 0..5
  LinkDirections* set = find_set(link, true);
  const std::string what = direction_label(model_, link, index);
  if (!std::isfinite(setpoint)) throw Error(what + ": setpoint is not finite");
  if (mode != DirectionMode::Free && !set->held.active(index)) {
    int columns = 0;
    for (const LinkDirections& s : sets_) columns += s.held.count();
    if (columns >= kMaxConstraintColumns)
      throw Error(what + ": " + std::to_string(kMaxConstraintColumns) +
                  " directions are already active on all links together, the most a solve takes");
  }
  const int s = static_cast<int>(set - sets_.data());
  HeldDirections& held = set->held;
  held.mode[index] = mode;
  held.setpoint[index] = mode == DirectionMode::Accelerate ? setpoint : 0;
  held.target[index] = 0;
  angles_[s * kNumDirections + index] = 0;
  if (mode == DirectionMode::Hold && is_linear_direction(index))
    held.target[index] = direction_axis(index).dot(link_pose(link).p);
  set->max_residual[index] = 0;
  events_->forget(s, index);
  update_blocks();
}

void Simulator::set_direction_point(int link, const Vector3& point) {
  LinkDirections* set = find_set(link, true);
  if (!point.allFinite())
    throw Error("the direction point of link '" + model_.links[link].name + "' is not finite");
  set->point = point;
  std::fill(anchored_.begin(), anchored_.end(), 0u);
  anchored_[static_cast<size_t>(set - sets_.data())] = (1u << kNumDirections) - 1;  // every direction
  anchor_directions(anchored_);
  set->max_residual.fill(0);
  update_blocks();
}

DirectionMode Simulator::direction_mode(int link, int index) const {
  direction_name(index);  // an achd::Error on an index outside 0..5
  const LinkDirections* set = find_set(link);
  return set ? set->held.mode[index] : DirectionMode::Free;
}

double Simulator::setpoint(int link, int index) const {
  direction_name(index);  // an achd::Error on an index outside 0..5
  const LinkDirections* set = find_set(link);
  return set ? set->held.setpoint[index] : 0.0;
}

void Simulator::set_direction_weights(int link, int index, double w_fext, double w_ff) {
  direction_name(index);  // an achd::Error on an index outside 0..5
  LinkDirections* set = find_set(link, true);
  for (const auto& [name, w] : {std::pair<const char*, double>{"w_fext", w_fext}, {"w_ff", w_ff}})
    if (!(w >= 0 && w <= 1))
      throw Error(direction_label(model_, link, index) + ": " + name + " must be in [0, 1], got " + message_number(w));
  set->held.w_fext[index] = w_fext;
  set->held.w_ff[index] = w_ff;
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
  const LinkDirections* set = find_set(link);
  if (!set) return r;
  const ChainMotion& m = thread_chain_motion(model_, q, qd);
  const TipState at = link_state(model_, m.X0, m.v, link, set->point);
  const double* angles = angles_.data() + (set - sets_.data()) * kNumDirections;
  for (int k = 0; k < kNumDirections; ++k) r[k] = direction_error(set->held, k, at, angles);
  return r;
}

std::array<double, kNumDirections> Simulator::max_residuals(int link) const {
  std::array<double, kNumDirections> r = residuals(link);
  const LinkDirections* set = find_set(link);
  if (set)
    for (int k = 0; k < kNumDirections; ++k) r[k] = std::max(std::abs(r[k]), set->max_residual[k]);
  return r;
}

Transform Simulator::link_pose(int link) const {
  const LinkDirections* set = find_set(link);
  const ChainMotion& m = thread_chain_motion(model_, q, qd);
  return link_state(model_, m.X0, m.v, link, set ? set->point : Vector3::Zero()).pose;
}

Vector6 Simulator::link_velocity(int link) const {
  const LinkDirections* set = find_set(link);
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
  for (int s = 0; s < static_cast<int>(sets_.size()); ++s) {
    if (!bits[s]) continue;
    LinkDirections& set = sets_[s];
    const Vector3 p = link_state(model_, X0_, v_, set.link, set.point).pose.p;
    for (int k = 0; k < kNumDirections; ++k) {
      if (!(bits[s] >> k & 1u) || set.held.mode[k] != DirectionMode::Hold) continue;
      if (is_linear_direction(k)) set.held.target[k] = direction_axis(k).dot(p);
      else angles_[s * kNumDirections + k] = 0;
    }
  }
}

}  // namespace achd
