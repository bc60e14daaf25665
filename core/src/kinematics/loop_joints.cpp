// Loop joints resolved on a model (loops.hpp): names to links, the loop frame turned onto
// the axis, and the directions the tree cannot violate found on the relative Jacobian.
#include "achd/loops.hpp"

#include <cmath>
#include <cstdint>
#include <set>

#include <Eigen/Geometry>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"

namespace achd {

const char* loop_type_name(LoopType type) {
  switch (type) {
    case LoopType::Revolute: return "revolute";
    case LoopType::Prismatic: return "prismatic";
    case LoopType::Spherical: return "spherical";
    case LoopType::Fixed: return "fixed";
  }
  return "unknown";
}

LoopType loop_type_from_name(const std::string& name, const std::string& field) {
  for (LoopType t : {LoopType::Revolute, LoopType::Prismatic, LoopType::Spherical, LoopType::Fixed})
    if (name == loop_type_name(t)) return t;
  throw Error(field + ": unknown loop joint type '" + name + "' (revolute, prismatic, spherical or fixed)");
}

unsigned loop_type_directions(LoopType type) {
  switch (type) {
    case LoopType::Revolute: return 0b011111;   // x y z rx ry
    case LoopType::Prismatic: return 0b111011;  // x y rx ry rz
    case LoopType::Spherical: return 0b000111;  // x y z
    case LoopType::Fixed: return 0b111111;
  }
  return 0;
}

std::vector<std::string> loop_direction_names(unsigned directions) {
  std::vector<std::string> names;
  for (int k = 0; k < kNumDirections; ++k)
    if ((directions >> k) & 1u) names.push_back(direction_name(k));
  return names;
}

namespace {

// Configurations the directions are sampled at: each joint uniform in its limits (cut to
// [-pi, pi]) from a fixed seed, a floating base at the origin; the same on every load.
std::vector<Eigen::VectorXd> sample_configurations(const Model& model, int count) {
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  auto uniform = [&state] {  // xorshift64*, in [0, 1)
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return static_cast<double>((state * 2685821657736338717ull) >> 11) * 0x1.0p-53;
  };
  std::vector<Eigen::VectorXd> out;
  for (int s = 0; s < count; ++s) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(model.num_positions());
    if (model.floating) q[6] = 1;
    for (int j = model.free_joint_rates(); j < model.num_rates(); ++j) {
      const JointLimits& l = model.bodies[j].limits;
      const double lo = std::max(l.lower, -M_PI), hi = std::min(l.upper, M_PI);
      q[model.position_index(j)] = lo + (hi - lo) * uniform();
    }
    out.push_back(q);
  }
  return out;
}

// Row k of the loop's relative Jacobian at q: c_k^T (J_A(Q) - J_B(Q)), c_k the loop
// frame's direction k in base axes (on the linear rows for x y z, the angular for rx ry
// rz), Q frame b's origin, so that the row times qd is c_k^T (V_A(Q) - V_B(Q)).
Eigen::RowVectorXd relative_row(const Model& model, const Eigen::VectorXd& q, const std::vector<Transform>& poses,
                                const LoopJoint& loop, int k) {
  const auto pose = [&](int link) { return link < 0 ? Transform{} : poses[link]; };
  const Transform A = pose(loop.link_a) * loop.frame_a, B = pose(loop.link_b) * loop.frame_b;
  const Vector3 c = A.R.col(k % 3);
  const int row = k < 3 ? 0 : 3;
  Eigen::RowVectorXd out = Eigen::RowVectorXd::Zero(model.num_rates());
  if (loop.link_a >= 0) {
    const Transform& la = poses[loop.link_a];
    const Vector3 q_in_a = la.R.transpose() * (B.p - la.p);
    out += c.transpose() * link_jacobian(model, q, loop.link_a, q_in_a).middleRows<3>(row);
  }
  if (loop.link_b >= 0) out -= c.transpose() * link_jacobian(model, q, loop.link_b, loop.frame_b.p).middleRows<3>(row);
  return out;
}

// Drops each of the loop's directions whose row is, at every sample, within round-off of
// the span of the rows kept so far (`kept`: per sample an orthonormal basis, extended by
// every direction kept); `given`: the user's directions, all kept.
void find_directions(const Model& model, const std::vector<Eigen::VectorXd>& samples,
                     std::vector<std::vector<Eigen::VectorXd>>& kept, LoopJoint& loop, bool given) {
  std::vector<std::vector<Transform>> poses;
  for (const Eigen::VectorXd& q : samples) poses.push_back(forward_kinematics(model, q));
  const unsigned candidates = loop.directions;
  loop.directions = 0;
  for (int k = 0; k < kNumDirections; ++k) {
    if (!((candidates >> k) & 1u)) continue;
    std::vector<Eigen::VectorXd> residual(samples.size());
    bool independent = false;
    for (size_t s = 0; s < samples.size(); ++s) {
      Eigen::VectorXd r = relative_row(model, samples[s], poses[s], loop, k).transpose();
      const double size = r.norm();
      if (!std::isfinite(size))
        throw Error("loop '" + loop.name + "': its origins are too far from the links (its direction " +
                    direction_name(k) + " moves by more than a double holds)");
      for (int pass = 0; pass < 2; ++pass)  // Gram-Schmidt, twice for round-off
        for (const Eigen::VectorXd& e : kept[s]) r -= e.dot(r) * e;
      // A row is a length (linear rows: m per rad) or a number: 1e-9 of it, or of 1, is
      // round-off of the rows it depends on.
      if (r.norm() > 1e-9 * std::max(1.0, size)) independent = true;
      residual[s] = r;
    }
    if (!independent && !given) continue;
    loop.directions |= 1u << k;
    for (size_t s = 0; s < samples.size(); ++s)
      if (residual[s].norm() > 0) kept[s].push_back(residual[s].normalized());
  }
  loop.dropped = given ? 0 : candidates & ~loop.directions;
}

bool finite(const Transform& X) { return X.R.allFinite() && X.p.allFinite(); }

}  // namespace

void add_loops(Model& model, const std::vector<LoopJointSpec>& loops) {
  std::set<std::string> names;
  for (const LoopJoint& l : model.loops) names.insert(l.name);
  const std::vector<Eigen::VectorXd> samples = sample_configurations(model, 4);
  std::vector<std::vector<Eigen::VectorXd>> kept(samples.size());
  const auto link_of = [&](const std::string& name, const std::string& field) {
    if (name == model.root_name) {
      if (model.floating)
        throw Error(field + ": '" + name + "' is the root of a floating base; name a link fixed to it instead");
      return -1;
    }
    const int l = model.link_index(name);
    if (l < 0) throw Error(field + ": no link '" + name + "' in the model");
    return l;
  };
  for (const LoopJointSpec& spec : loops) {
    const std::string where = "loop '" + spec.name + "'";
    if (spec.name.empty()) throw Error("loop " + std::to_string(model.loops.size()) + ": name is empty");
    if (!names.insert(spec.name).second) throw Error(where + ": the name is used by another loop");
    LoopJoint loop;
    loop.name = spec.name;
    loop.type = spec.type;
    loop.link_a = link_of(spec.link_a, where + ": link_a");
    loop.link_b = link_of(spec.link_b, where + ": link_b");
    if (loop.link_a == loop.link_b)
      throw Error(where + ": link_a and link_b are the same link '" + spec.link_a + "'");
    if (!finite(spec.origin_a)) throw Error(where + ": origin_a is not finite");
    if (!finite(spec.origin_b)) throw Error(where + ": origin_b is not finite");
    Matrix3 turn = Matrix3::Identity();
    if (spec.type == LoopType::Revolute || spec.type == LoopType::Prismatic) {
      // (divided by its largest component first: 1e300 or 1e-300 neither over- nor underflows)
      const double largest = spec.axis.lpNorm<Eigen::Infinity>();
      if (!std::isfinite(largest) || !(largest > 0)) throw Error(where + ": axis must be finite and not zero");
      const Vector3 axis = (spec.axis / largest).normalized();
      turn = Eigen::Quaterniond::FromTwoVectors(Vector3::UnitZ(), axis).toRotationMatrix();
    }
    loop.frame_a = spec.origin_a * Transform{turn, Vector3::Zero()};
    loop.frame_b = spec.origin_b * Transform{turn, Vector3::Zero()};
    const auto in_body = [&](int link, const Transform& frame, int& body, Transform& body_frame) {
      body = link < 0 ? -1 : model.links[link].body;
      body_frame = link < 0 ? frame : model.links[link].offset * frame;
    };
    in_body(loop.link_a, loop.frame_a, loop.body_a, loop.body_frame_a);
    in_body(loop.link_b, loop.frame_b, loop.body_b, loop.body_frame_b);
    const unsigned allowed = loop_type_directions(spec.type);
    loop.directions = spec.directions.empty() ? allowed : 0;
    for (const std::string& d : spec.directions) {
      const int k = index_of_direction(d);
      if (k < 0 || !((allowed >> k) & 1u)) {
        std::string held;  // "x y z"
        for (const std::string& name : loop_direction_names(allowed)) held += (held.empty() ? "" : " ") + name;
        throw Error(where + ": directions: '" + d + "' is not a direction a " + loop_type_name(spec.type) +
                    " loop holds (" + held + ")");
      }
      loop.directions |= 1u << k;
    }
    find_directions(model, samples, kept, loop, !spec.directions.empty());
    if (!loop.directions)
      throw Error(where + ": the tree already holds every direction of the loop (nothing left to hold)");
    model.loops.push_back(loop);
  }
}

}  // namespace achd
