#include "direction_sets.hpp"

#include <algorithm>
#include <cmath>

#include "achd/error.hpp"
#include "held_directions.hpp"
#include "message_number.hpp"

namespace achd {

DirectionSets::DirectionSets(const Model& model) : events_(kMaxDirectionEvents, model.num_links(), static_cast<int>(model.loops.size())) {
  // room for every link, so that setting a direction never moves a set and no step allocates
  const int links = model.num_links();
  sets_.reserve(links);
  block_set_.reserve(links);
  integrated_.reserve(static_cast<size_t>(links) * kNumDirections);
  anchored_.assign(links, 0);
}

const LinkDirections* DirectionSets::find(int link) const {
  if (link < 0 || link >= static_cast<int>(anchored_.size()))
    throw Error("direction link index " + std::to_string(link) + " is not in 0.." +
                std::to_string(anchored_.size() - 1) + " (Model::links)");
  for (const LinkDirections& s : sets_)
    if (s.link == link) return &s;
  return nullptr;
}

int DirectionSets::find_or_create(int link) {
  if (const LinkDirections* found = find(link)) return static_cast<int>(found - sets_.data());
  LinkDirections set;
  set.link = link;
  sets_.push_back(set);
  integrated_.resize(sets_.size() * kNumDirections, 0);
  return static_cast<int>(sets_.size()) - 1;
}

int DirectionSets::active_columns() const {
  int columns = 0;
  for (const LinkDirections& s : sets_) columns += s.held.count();
  return columns;
}

void DirectionSets::release_all() {
  for (LinkDirections& set : sets_) {
    HeldDirections freed;
    freed.w_fext = set.held.w_fext;
    freed.w_ff = set.held.w_ff;
    set.held = freed;
    set.max_residual.fill(0);
  }
  events_.clear();
}

void DirectionSets::set(int s, int k, DirectionMode mode, double setpoint, double target) {
  LinkDirections& set = sets_[s];
  set.held.mode[k] = mode;
  set.held.setpoint[k] = mode == DirectionMode::Accelerate ? setpoint : 0;
  set.held.target[k] = mode == DirectionMode::Hold && is_linear_direction(k) ? target : 0;
  set.max_residual[k] = 0;
  events_.forget(s, k);
}

void DirectionSets::write_blocks(std::vector<ConstraintBlock>& blocks) {
  blocks.clear();
  block_set_.clear();
  for (int s = 0; s < static_cast<int>(sets_.size()); ++s) {
    const LinkDirections& set = sets_[s];
    for (int k = 0; k < kNumDirections; ++k)
      integrated_[s * kNumDirections + k] = set.held.mode[k] == DirectionMode::Hold && !is_linear_direction(k);
    if (!set.held.count()) continue;
    ConstraintBlock& b = blocks.emplace_back();
    b.link = set.link;
    b.point = set.point;
    direction_columns(set.held, b.alpha);
    direction_weights(set.held, b.w_fext, b.w_ff);
    // a pushed (accelerated) direction gives way where the joints' efforts cannot follow it
    b.yields = 0;
    for (int k = 0, column = 0; k < kNumDirections; ++k) {
      if (!set.held.active(k)) continue;
      if (set.held.mode[k] == DirectionMode::Accelerate) b.yields |= 1u << column;
      ++column;
    }
    block_set_.push_back(s);
  }
}

void DirectionSets::record_residuals(const Model& model, const std::vector<Transform>& X0,
                                     const std::vector<Vector6>& v, const HeldAngles& angles) {
  for (size_t s = 0; s < sets_.size(); ++s) {
    LinkDirections& set = sets_[s];
    if (!set.held.count()) continue;
    const TipState at = link_state(model, X0, v, set.link, set.point);
    for (int k = 0; k < kNumDirections; ++k)
      if (!events_.released(static_cast<int>(s), k))
        set.max_residual[k] = std::max(set.max_residual[k],
                                     std::abs(direction_error(set.held, k, at, angles.data() + s * kNumDirections)));
  }
}

bool DirectionSets::update_events(const Model& model, const Data& first, double t, std::int64_t step, double w) {
  events_.update(model, sets_, first, t, step, w, anchored_);
  bool anchor = false;
  for (size_t s = 0; s < sets_.size(); ++s) {
    anchored_[s] |= yielding_directions(sets_[s].held);
    anchor = anchor || anchored_[s];
  }
  return anchor;
}

// "z, rx" on a chain's tip; "x, y, z of link 'lf_foot', z of link 'rf_foot'"
std::string DirectionSets::held_text(const Model& model) const {
  std::string held;
  for (const LinkDirections& set : sets_) {
    std::string h;
    for (int k = 0; k < kNumDirections; ++k)
      if (set.held.mode[k] == DirectionMode::Hold) h += (h.empty() ? "" : ", ") + std::string(direction_name(k));
    if (h.empty()) continue;
    const std::string label = direction_label(model, set.link, 0);  // "direction x[ of link '...']"
    held += (held.empty() ? "" : ", ") + h + label.substr(11);
  }
  return held;
}

bool DirectionSets::any_accelerated() const {
  for (const LinkDirections& set : sets_)
    for (int k = 0; k < kNumDirections; ++k)
      if (set.held.mode[k] == DirectionMode::Accelerate) return true;
  return false;
}

// "z = 1 m/s^2, rx of link 'hand' = 0.5 rad/s^2"
std::string DirectionSets::accelerated_text(const Model& model) const {
  std::string accelerated;
  for (const LinkDirections& set : sets_)
    for (int k = 0; k < kNumDirections; ++k)
      if (set.held.mode[k] == DirectionMode::Accelerate)
        accelerated += (accelerated.empty() ? "" : ", ") + direction_label(model, set.link, k).substr(10) + " = " +
                       message_number(set.held.setpoint[k]) + (is_linear_direction(k) ? " m/s^2" : " rad/s^2");
  return accelerated;
}

}  // namespace achd
