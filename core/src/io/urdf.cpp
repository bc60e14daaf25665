// URDF -> Model through urdfdom: the tree below the root walked depth first, or the chain
// root -> tip found from the tip up and built from the root down, then what hangs off
// it; links behind fixed (or locked) joints are merged into the body before them.
#include "achd/urdf.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <vector>

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "achd/srdf.hpp"
#include "console_capture.hpp"
#include "coupled_joints.hpp"
#include "link_inertia.hpp"
#include "massless_joints.hpp"
#include "read_text_file.hpp"
#include "urdf_elements.hpp"
#include "xml_depth.hpp"

namespace achd {
namespace {

urdf::ModelInterfaceSharedPtr parse(const std::string& xml, std::string& why) {
  static std::mutex mutex;  // console_bridge's handler is process-global
  std::lock_guard<std::mutex> lock(mutex);
  urdf::ModelInterfaceSharedPtr model;
  ConsoleCapture console;
  try {
    model = urdf::parseURDF(xml);
    why = console.first_error();
  } catch (const std::exception& e) {
    why = e.what();
    model.reset();
  }
  return model;
}

// What the walk knows of a link once it has placed it: the body it rides on (-1: the
// root) and its frame relative to that body's frame.
struct Placed {
  int body = -1;
  Transform offset;
};

// The links below the root, placed one by one from their parents (a link is placed
// after its parent): through a movable joint a link starts a body of its own; through a
// fixed joint, or a movable side joint that is locked, it rides on its parent's body,
// whose inertia takes its mass.
class Walk {
 public:
  Walk(const urdf::ModelInterface& urdf_model, const OriginAngles& angles, const UrdfOptions& options,
       Model& model)
      : urdf_(urdf_model), angles_(angles), options_(options), model_(model) {
    placed_[model.root_name] = Placed{};
  }

  // The child joints of a link in the order of the file (urdfdom orders them by name).
  std::vector<urdf::JointConstSharedPtr> children(const urdf::Link& link) const {
    std::vector<urdf::JointConstSharedPtr> out(link.child_joints.begin(), link.child_joints.end());
    auto position = [&](const urdf::JointConstSharedPtr& j) {
      const auto it = angles_.joint_position.find(j->name);
      return it == angles_.joint_position.end() ? -1 : it->second;
    };
    // (joints the file position map lacks, -1, keep urdfdom's order by name: a total order,
    // so std::sort needs no temporary buffer, which stable_sort would allocate)
    std::sort(out.begin(), out.end(), [&](const auto& a, const auto& b) {
      const int pa = position(a), pb = position(b);
      return pa != pb ? pa < pb : a->name < b->name;
    });
    return out;
  }

  // A floating base: the free joint's six bodies (free_joint.hpp) between the world and the
  // root link, which rides on the last of them with its inertia; at q = 0 (the identity pose)
  // their frames have z along the world x, y, z axes, twice.
  void add_free_joint(const urdf::Link& root) {
    Matrix3 along_x, along_y;
    along_x << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // columns e_y, e_z, e_x: z along x
    along_y << 0, 1, 0, 0, 0, 1, 1, 0, 0;  // columns e_z, e_x, e_y: z along y
    const Matrix3 steps[3] = {along_x, along_x.transpose() * along_y, along_y.transpose()};
    for (int k = 0; k < 6; ++k) {
      Body b;
      b.joint_name = b.link_name = root.name;
      b.parent = k - 1;
      b.type = k < 3 ? JointType::Prismatic : JointType::Continuous;
      b.X_tree = Transform{steps[k % 3], Vector3::Zero()};
      model_.bodies.push_back(b);
    }
    model_.bodies.back().inertia = inertia_of(root);
    placed_[root.name] = Placed{5, Transform{}};
  }

  // Places j's child link as a link of the model: a body of its own if j is movable,
  // riding on its parent's body if j is fixed or locked (options.locked); appends it to
  // Model::links.
  void add_link(const urdf::Joint& j) {
    const std::string where = "joint '" + j.name + "'";
    if (j.mimic && j.type != urdf::Joint::FIXED && options_.mimic == MimicJoints::Error)
      throw Error(where + ": <mimic> of joint '" + j.mimic->joint_name +
                  "': refused (the mimic option 'error'); the default 'couple' holds it to its leader, "
                  "'independent' (CLI --mimic independent) makes it a joint of its own, as KDL does");
    const Placed& parent = placed_.at(j.parent_link_name);
    const int body = parent.body;
    const Matrix6 inertia = child_inertia(j);
    Placed child;
    double held = 0;
    if (j.type == urdf::Joint::FIXED || locked_value(j, held)) {  // (a movable one locked)
      child = Placed{body, rigid_offset(j, parent)};  // the child rides on the parent's body
      add_inertia(j, child, inertia);
    } else {
      Matrix3 R_axis;
      model_.bodies.push_back(make_body(j, origin(j, parent), body, R_axis));
      child.body = model_.num_rates() - 1;
      // The child link's frame in the body (joint) frame is R_axis^T, constant as the
      // joint turns about or slides along z.
      child.offset = Transform{R_axis.transpose(), Vector3::Zero()};
      model_.bodies[child.body].inertia = inertia_to_parent(child.offset, inertia);
      if (j.mimic && options_.mimic == MimicJoints::Couple) mimics_.push_back(&j);
    }
    placed_[j.child_link_name] = child;
    model_.links.push_back({j.child_link_name, child.body, child.offset});
  }

  // Places j's child link rigidly on its parent's body, j (if movable) locked (rigid_offset);
  // the link is not a link of the model (a chain's links are its path's).
  void add_side_link(const urdf::Joint& j) {
    const Placed& parent = placed_.at(j.parent_link_name);
    const Matrix6 inertia = child_inertia(j);
    const Placed child{parent.body, rigid_offset(j, parent)};
    add_inertia(j, child, inertia);
    placed_[j.child_link_name] = child;
  }

  // The couplings of the movable <mimic> joints placed as bodies (MimicJoints::Couple):
  // each to its leader, which must be a movable joint of the model too. A <mimic> naming a
  // joint the file does not have at all couples to nothing: its joint moves on its own,
  // with a warning (a leader the file has but the model holds fixed is an error).
  void add_couplings() {
    for (const urdf::Joint* j : mimics_) {
      const int follower = model_.joint_index(j->name), leader = model_.joint_index(j->mimic->joint_name);
      if (!urdf_.getJoint(j->mimic->joint_name)) {
        model_.warnings.push_back("joint '" + j->name + "': <mimic> of joint '" + j->mimic->joint_name +
                                  "', which the file does not have: it moves on its own");
        continue;
      }
      if (leader < model_.free_joint_rates())
        throw Error("joint '" + j->name + "': <mimic> of joint '" + j->mimic->joint_name +
                    "', which is not a movable joint of the loaded robot (fixed, locked or not loaded); load with "
                    "the mimic option 'independent' (CLI --mimic independent) to make it a joint of its own");
      if (!std::isfinite(j->mimic->multiplier) || !std::isfinite(j->mimic->offset))
        throw Error("joint '" + j->name + "': <mimic> multiplier and offset must be finite");
      model_.couplings.push_back({follower, leader, j->mimic->multiplier, j->mimic->offset});
    }
  }

 private:
  // Whether movable joint j is held by options.locked, and where: named there, or (coupled
  // <mimic> joints) following a leader that is held, at multiplier * leader + offset, so
  // that holding a hand's leader holds its coupled fingers with it and keeps the coupling.
  // Walks up the leaders without recursing (a file may chain many <mimic>s; a cycle of
  // them, or a leader that is missing or fixed, ends the walk: not held), and remembers
  // what it found for each joint on the way.
  bool locked_value(const urdf::Joint& j, double& value) {
    if (options_.locked.empty()) return false;
    std::vector<const urdf::Joint*> followers;  // j and the leaders up to the end
    std::set<std::string> seen;
    bool held = false;
    double v = 0;
    for (const urdf::Joint* at = &j;;) {
      const auto given = options_.locked.find(at->name);
      if (given != options_.locked.end()) {
        held = true;
        v = given->second;
        break;
      }
      const auto known = held_.find(at->name);
      if (known != held_.end()) {
        held = known->second.first;
        v = known->second.second;
        break;
      }
      if (!at->mimic || options_.mimic != MimicJoints::Couple || !seen.insert(at->name).second) break;
      followers.push_back(at);
      const auto leader = urdf_.getJoint(at->mimic->joint_name);
      if (!leader || leader->type == urdf::Joint::FIXED) break;
      at = leader.get();
    }
    for (auto it = followers.rbegin(); it != followers.rend(); ++it) {
      if (held) v = (*it)->mimic->multiplier * v + (*it)->mimic->offset;
      held_[(*it)->name] = {held, held ? v : 0.0};
    }
    value = v;
    return held;
  }

  // The frame of j's child link relative to the body its parent link rides on, j fixed or
  // (if movable) locked at its options.locked value (or its held leader's, locked_value) or
  // else default_joint_value (0, or the middle of its limits), listed in Model::locked_joints.
  Transform rigid_offset(const urdf::Joint& j, const Placed& parent) {
    Transform X = origin(j, parent);
    if (j.type == urdf::Joint::FIXED) return X;
    const std::string where = "joint '" + j.name + "'";
    Matrix3 R_axis;
    const Body b = make_body(j, X, parent.body, R_axis);
    double value = 0;
    const bool given = locked_value(j, value);
    if (!given) value = default_joint_value(b.limits.lower, b.limits.upper);  // 0, or the middle of its limits
    const bool named = options_.locked.count(j.name) > 0;
    if (!std::isfinite(value))
      throw Error("locked " + where + ": value is not finite" +
                  (named || !given ? "" : " (it follows joint '" + j.mimic->joint_name + "', which is held)"));
    if (value < b.limits.lower || value > b.limits.upper)
      throw Error("locked " + where + ": value " + inertia_number(value) + " is outside its limits [" +
                  inertia_number(b.limits.lower) + ", " + inertia_number(b.limits.upper) + "]" +
                  (!given ? " (give it a value with --lock " + j.name + "=VALUE)"
                   : named ? ""
                           : " (it follows joint '" + j.mimic->joint_name + "', which is held: " +
                                 inertia_number(j.mimic->multiplier) + " times its value plus " +
                                 inertia_number(j.mimic->offset) + ")"));
    X = joint_transform(b, value) * Transform{R_axis.transpose(), Vector3::Zero()};
    if (!X.p.allFinite()) throw Error(where + ": origin overflows: its locked position is not finite");
    model_.locked_joints.push_back({j.name, value});
    return X;
  }

  // The frame of j relative to the body its parent link rides on.
  Transform origin(const urdf::Joint& j, const Placed& parent) const {
    const std::string where = "joint '" + j.name + "'";
    const Transform X = parent.offset * to_transform(j.parent_to_joint_origin_transform,
                                                     find_angles(angles_.joint, j.name), where);
    // Behind fixed joints, origins add up: their sum can overflow although each is finite.
    if (!X.p.allFinite())
      throw Error(where + ": origin overflows: its position from " +
                  (parent.body >= 0 ? "joint '" + model_.bodies[parent.body].joint_name + "'"
                                    : "the root link '" + model_.root_name + "'") +
                  " is not finite");
    return X;
  }

  Matrix6 child_inertia(const urdf::Joint& j) { return inertia_of(*urdf_.getLink(j.child_link_name)); }

  Matrix6 inertia_of(const urdf::Link& link) {
    const auto roundoff = angles_.inertia_roundoff.find(link.name);
    return link_inertia(link, find_angles(angles_.inertial, link.name),
                        roundoff == angles_.inertia_roundoff.end() ? nullptr : roundoff->second.data(),
                        options_.inertia, model_.warnings);
  }

  // Adds a rigidly riding link's inertia to its body (nothing on the root, which does
  // not move; a massless link adds nothing, wherever it is).
  void add_inertia(const urdf::Joint& j, const Placed& link, const Matrix6& inertia) {
    if (link.body < 0 || inertia.isZero(0)) return;
    Body& body = model_.bodies[link.body];
    body.inertia += inertia_to_parent(link.offset, inertia);
    if (!body.inertia.allFinite())
      throw Error("joint '" + j.name + "': origin overflows: link '" + j.child_link_name + "' moved by it to joint '" +
                  body.joint_name + "' has an inertia that is not finite");
  }

  const urdf::ModelInterface& urdf_;
  const OriginAngles& angles_;
  const UrdfOptions& options_;
  Model& model_;
  std::map<std::string, Placed> placed_;  // by link name
  std::vector<const urdf::Joint*> mimics_;  // movable <mimic> joints placed as bodies
  std::map<std::string, std::pair<bool, double>> held_;  // locked_value's findings, by joint
};

// Every link below `from` in depth-first order (a link, then each child joint's subtree in
// the order of the file) except those whose names are in `skip` (and their subtrees): their
// parent joints. Refuses a cycle, which urdfdom accepts when it does not reach its root.
std::vector<urdf::JointConstSharedPtr> subtree_joints(const urdf::ModelInterface& urdf_model, const Walk& walk,
                                                      const urdf::Link& from, const std::set<std::string>& skip) {
  std::vector<urdf::JointConstSharedPtr> out;
  std::set<std::string> seen = {from.name};
  std::vector<urdf::JointConstSharedPtr> stack;  // explicit: a long chain must not recurse
  auto push_children = [&](const urdf::Link& link) {
    const auto children = walk.children(link);
    for (auto it = children.rbegin(); it != children.rend(); ++it)
      if (!skip.count((*it)->child_link_name)) stack.push_back(*it);
  };
  push_children(from);
  while (!stack.empty()) {
    const urdf::JointConstSharedPtr j = stack.back();
    stack.pop_back();
    if (!seen.insert(j->child_link_name).second)
      throw Error("the links form a cycle through link '" + j->child_link_name + "'");
    out.push_back(j);
    const auto child = urdf_model.getLink(j->child_link_name);
    if (child) push_children(*child);
  }
  return out;
}

// A `locked` entry must name a movable joint of the loaded robot (a chain's path and side
// branches, or the tree).
void check_locked_names(const urdf::ModelInterface& urdf_model, const Model& model, const UrdfOptions& options) {
  for (const auto& entry : options.locked) {
    const std::string& name = entry.first;
    bool locked = false;
    for (const LockedJoint& l : model.locked_joints) locked = locked || l.name == name;
    if (locked) continue;
    const auto joint = urdf_model.getJoint(name);
    const std::string what =
        !joint ? "there is no joint of that name"
        : joint->type == urdf::Joint::FIXED ? "it is a fixed joint"
        : options.side_branches == SideBranches::Ignore ? "side branches are ignored (the KDL convention)"
                                                        : "it does not hang off the chain from '" + model.root_name +
                                                              "' to '" + model.tip_name + "'";
    throw Error("locked joint '" + name + "': not a movable joint of the loaded robot (" + what + ")");
  }
}

// The last checks of a loaded model: the repairs the policy allows, then validate().
void finish(Model& model, const UrdfOptions& options) {
  if (model.num_rates() == 0 && !model.has_tip())
    throw Error("the tree below '" + model.root_name + "' has no movable joint; load it with a floating base "
                "(CLI --floating, JS {floating: true}) to move it as a free body");
  if (options.inertia == InertiaPolicy::Repair) {
    repair_joints_moving_nothing(model);
    validate(model);
    add_loops(model, options.loops);
    return;
  }
  try {
    validate(model);
  } catch (const Error&) {
    check_coupled_joints_move_something(model);  // (a better message for a coupled joint)
    throw;
  }
  add_loops(model, options.loops);
}

// The model of the tree or chain as the URDF and the options give it, not yet checked
// (finish).
Model build(const urdf::ModelInterface& urdf_model, const OriginAngles& angles,
            const std::string& root_given, const std::string& tip, const UrdfOptions& options,
            const std::string& source) {
  if (root_given.empty() && !urdf_model.getRoot())
    throw Error(source + ": the URDF has no root link");
  const std::string root = root_given.empty() ? urdf_model.getRoot()->name : root_given;
  const auto root_link = urdf_model.getLink(root);
  if (!root_link) throw Error(source + ": unknown root link '" + root + "'");

  Model model;
  model.root_name = root;
  model.tip_name = tip;
  model.floating = options.floating;
  Walk walk(urdf_model, angles, options, model);
  if (options.floating) walk.add_free_joint(*root_link);
  if (tip.empty()) {
    // The whole tree below the root: every link in depth-first order, so that each body's
    // subtree is the range of bodies after it.
    for (const auto& j : subtree_joints(urdf_model, walk, *root_link, {})) walk.add_link(*j);
    walk.add_couplings();
    check_locked_names(urdf_model, model, options);
    return model;
  }

  const auto tip_link = urdf_model.getLink(tip);
  if (!tip_link) throw Error(source + ": unknown tip link '" + tip + "'");
  if (root == tip) throw Error(source + ": root and tip are the same link '" + root + "'");
  // Joints from the tip up to the root.
  std::vector<urdf::JointConstSharedPtr> joints;
  std::set<std::string> path = {tip};
  for (auto link = tip_link; link->name != root;) {
    if (!link->parent_joint)
      throw Error(source + ": tip link '" + tip + "' is not below root link '" + root + "'");
    joints.push_back(link->parent_joint);
    link = urdf_model.getLink(link->parent_joint->parent_link_name);
    if (!link)
      throw Error(source + ": tip link '" + tip + "' is not below root link '" + root + "'");
    if (!path.insert(link->name).second)
      throw Error(source + ": the links form a cycle through link '" + link->name + "'");
  }
  // The path root -> tip: its bodies and links.
  for (auto it = joints.rbegin(); it != joints.rend(); ++it) walk.add_link(**it);
  // What hangs off the path (below the root, off the path, the tip's children included),
  // path link by path link from the root: merged into the body it hangs from.
  if (options.side_branches == SideBranches::Merge) {
    std::vector<urdf::LinkConstSharedPtr> path_links = {root_link};
    for (auto it = joints.rbegin(); it != joints.rend(); ++it)
      path_links.push_back(urdf_model.getLink((*it)->child_link_name));
    for (const auto& link : path_links)
      for (const auto& side : walk.children(*link)) {
        if (path.count(side->child_link_name)) continue;
        walk.add_side_link(*side);
        const auto side_link = urdf_model.getLink(side->child_link_name);
        if (!side_link) continue;
        for (const auto& j : subtree_joints(urdf_model, walk, *side_link, {})) walk.add_side_link(*j);
      }
  }
  walk.add_couplings();
  check_locked_names(urdf_model, model, options);
  return model;
}

// The model build() walks, checked (finish): under the default inertia policy, first
// walked again with the joints that move no mass held (massless_joints.hpp), each such
// joint (or coupled group) a warning.
Model build_checked(const urdf::ModelInterface& urdf_model, const OriginAngles& angles, const std::string& root,
                    const std::string& tip, const UrdfOptions& options, const std::string& source) {
  Model model = build(urdf_model, angles, root, tip, options, source);
  if (options.inertia == InertiaPolicy::Accept) {
    const MasslessLocks locks = massless_joint_locks(model);
    if (!locks.values.empty()) {
      UrdfOptions held = options;
      held.locked.insert(locks.values.begin(), locks.values.end());
      model = build(urdf_model, angles, root, tip, held, source);
      model.warnings.insert(model.warnings.end(), locks.warnings.begin(), locks.warnings.end());
    }
  }
  finish(model, options);
  return model;
}

// Every message starts with the source (file path or "URDF").
Model load(const std::string& text, const std::string& root, const std::string& tip,
           const UrdfOptions& options, const std::string& source) {
  const std::size_t too_deep = xml_too_deep_at(text, kMaxUrdfNesting);
  if (too_deep != std::string::npos)
    throw Error(source + ": cannot parse URDF: elements nested more than " + std::to_string(kMaxUrdfNesting) +
                " deep (line " + std::to_string(1 + std::count(text.begin(), text.begin() + too_deep, '\n')) +
                "), which achd refuses: its XML parser recurses once per level");
  // TinyXML steps over a UTF-8 sequence's length from its lead byte without looking for
  // the end of the text: three more NULs keep a lead byte at the end from reading past it.
  const std::string xml = text + std::string(3, '\0');
  std::string why;
  const auto parsed = parse(xml, why);
  // urdfdom links point to their children and parent joints by shared_ptr: a cycle in
  // the URDF (which it accepts when another link is the root, or when a joint is its
  // child's parent) would never be freed.
  struct BreakCycles {
    const urdf::ModelInterfaceSharedPtr& model;
    ~BreakCycles() {
      if (!model) return;
      for (auto& entry : model->links_) {
        entry.second->child_links.clear();
        entry.second->child_joints.clear();
        entry.second->parent_joint.reset();
      }
    }
  } break_cycles{parsed};
  // urdfdom logs some errors and still returns a model (a mass "inf" becomes an
  // inertial of mass 0): every logged error is fatal.
  if (!parsed || !why.empty())
    throw Error(source + ": cannot parse URDF" + (why.empty() ? std::string() : ": " + why));
  try {
    return build_checked(*parsed, read_origin_angles(xml), root, tip, options, source);
  } catch (const Error& e) {
    const std::string msg = e.what();
    throw Error(msg.rfind(source + ":", 0) == 0 ? msg : source + ": " + msg);
  }
}

}  // namespace

const char* mimic_joints_name(MimicJoints mimic) {
  return mimic == MimicJoints::Independent ? "independent" : mimic == MimicJoints::Couple ? "couple" : "error";
}

const char* inertia_policy_name(InertiaPolicy policy) {
  return policy == InertiaPolicy::Strict ? "strict" : policy == InertiaPolicy::Repair ? "repair" : "accept";
}

InertiaPolicy inertia_policy_from_name(const std::string& name, const std::string& field) {
  for (InertiaPolicy p : {InertiaPolicy::Accept, InertiaPolicy::Strict, InertiaPolicy::Repair})
    if (name == inertia_policy_name(p)) return p;
  throw Error(field + ": expected 'accept', 'strict' or 'repair', got '" + name + "'");
}

MimicJoints mimic_joints_from_name(const std::string& name, const std::string& field) {
  for (MimicJoints m : {MimicJoints::Error, MimicJoints::Independent, MimicJoints::Couple})
    if (name == mimic_joints_name(m)) return m;
  throw Error(field + ": expected 'couple', 'independent' or 'error', got '" + name + "'");
}

Model load_urdf_string(const std::string& xml, const std::string& root, const std::string& tip,
                       const UrdfOptions& options) {
  return load(xml, root, tip, options, "URDF");
}

Model load_urdf_file(const std::string& path, const std::string& root, const std::string& tip,
                     const UrdfOptions& options) {
  // A regular file only, at most kMaxUrdfFileBytes (read_text_file.hpp).
  return load(read_text_file(path, kMaxUrdfFileBytes, "a URDF file"), root, tip, options, path);
}

}  // namespace achd
