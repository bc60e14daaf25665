#pragma once
// The robot model: an immutable kinematic tree of rigid bodies below a root link (a
// serial chain between a root and a tip link is the tree with one branch). Fixed joints
// are merged into their parent body, so a Body is one movable joint plus everything
// rigidly attached after it; every URDF link keeps its own frame in `links` so that
// wrenches, accelerations and constraints stay where the user named them.
#include <string>
#include <vector>

#include "achd/spatial.hpp"

namespace achd {

enum class JointType { Revolute, Continuous, Prismatic };

const char* joint_type_name(JointType type);

struct JointLimits {
  double lower = -1e300, upper = 1e300;  // rad or m; continuous joints: unbounded
  double velocity = 0, effort = 0;       // 0 = not given
};

// One movable joint and the rigid body it moves (the joint's child link merged with
// the links attached to it by fixed joints). The body frame is the joint frame: its
// origin on the joint and its z axis along the joint axis (a revolute joint turns about
// it, a prismatic joint slides along it), as in Featherstone's and Denavit-Hartenberg's
// joint frames; the URDF child link's own frame is kept in Model::links.
struct Body {
  std::string joint_name;  // the URDF joint
  std::string link_name;   // the URDF child link (its frame: Model::links)
  int parent = -1;         // body index of the parent (< this body's), -1 = the root
  JointType type = JointType::Revolute;
  Transform X_tree;                 // parent body frame -> body frame at q = 0
  Matrix6 inertia = Matrix6::Zero();  // spatial inertia about the body origin, merged
  double damping = 0;                 // N m s/rad or N s/m, from URDF <dynamics>
  double friction = 0;                // Coulomb friction torque or force, URDF <dynamics>
  double rotor_inertia = 0;           // armature, kg m^2 or kg; set from C++
  JointLimits limits;
};

// A URDF link after the root: it rides on body `body` (-1: rigidly fixed to the root)
// at the constant pose `offset` relative to that body's frame.
struct Link {
  std::string name;
  int body = -1;
  Transform offset;
};

// A joint whose motion follows another's (URDF <mimic>): q_follower = multiplier q_leader
// + offset, so qd and qdd follow with the multiplier (joint_couplings.hpp solves it).
struct JointCoupling {
  int follower = 0, leader = 0;  // body (joint rate) indices
  double multiplier = 1, offset = 0;
};

// The most couplings a model may have.
constexpr int kMaxCouplings = 32;

// The joint a loop closure stands for: which relative motions of its two frames it allows.
enum class LoopType { Revolute, Prismatic, Spherical, Fixed };

// A loop joint (loop_joints.hpp): a joint between two links of the tree that the tree
// cannot hold (URDF has no loops), closed by relative constraint columns. Its loop frame
// sits at `frame_a` on link a and at `frame_b` on link b, the two coinciding while the loop
// is closed, z along the joint's axis (revolute: the turn, prismatic: the slide). Held:
// the loop frame's directions x y z rx ry rz with bit k of `directions` set (the joint
// type's, less those found redundant at load: `dropped`), as alpha^T (a_A - a_B) = beta
// with alpha the direction in base axes, a_A link a's spatial acceleration at frame b's
// origin and a_B link b's there (loop_blocks.hpp).
struct LoopJoint {
  std::string name;
  LoopType type = LoopType::Fixed;
  int link_a = -1, link_b = -1;  // Model::links indices; -1: the root (fixed base only)
  Transform frame_a, frame_b;    // the loop frame in link a's and in link b's frame
  unsigned directions = 0;       // held directions of the loop frame, bit k = x..rz
  unsigned dropped = 0;          // the type's directions the tree cannot violate
  // Set by add_loops from the links: the bodies links a and b ride on (-1: the base) and
  // the loop frame in each body's frame (the link's offset times frame_a or frame_b).
  int body_a = -1, body_b = -1;
  Transform body_frame_a, body_frame_b;
  int num_columns() const;
};

// A movable joint of the URDF that the model holds fixed (a side branch of a chain): its
// child link rides rigidly on the body it hangs from, at the joint position `value`.
struct LockedJoint {
  std::string name;
  double value = 0;  // rad or m
};

struct Model {
  // tip_name is empty for a tree (a model loaded without a tip): then the case's tip
  // constraints (Case::alpha) do not apply, constraint blocks name their links.
  std::string root_name, tip_name;
  // A floating base: a free joint (6 DoF) between the world and the root link, which moves.
  // Its q is [x, y, z, qx, qy, qz, qw] (the root's origin in the world, its orientation as a
  // unit quaternion, scalar last), its qd [v; w] (the origin's velocity, the angular
  // velocity, world axes), its qdd their time derivative, its torques a wrench [f; n] on
  // the root about its origin, world axes. It comes first: bodies 0 to 5 stand for it (all
  // named after the root link; body 5 carries the root link's inertia and the links fixed
  // to it), so vectors indexed by joint hold 6 + n values and q holds 7 + n
  // (num_positions). The base frame is the world: gravity, alpha and every "base axes"
  // result are in world axes. (free_joint.hpp: how the six bodies work.)
  bool floating = false;
  std::vector<Body> bodies;  // movable joints, parents before children
  std::vector<Link> links;   // every link after the root, parents before children; a
                             // chain's tip last
  std::vector<LockedJoint> locked_joints;  // held fixed by the loader, reported
  // Coupled joints (URDF <mimic>, UrdfOptions::mimic Couple): every solve holds each as a
  // joint-space constraint; their forces follow the constraint columns' in nu.
  std::vector<JointCoupling> couplings;
  // Loop joints (UrdfOptions::loops, resolve_loops): every solve holds their columns after
  // the case's blocks; their forces follow those blocks' in nu.
  std::vector<LoopJoint> loops;
  // What the loader found odd in the file but loaded (or repaired), one line per finding,
  // naming the link: inertias violating the triangle inequality, moments within round-off
  // of zero, repairs (achd::InertiaPolicy).
  std::vector<std::string> warnings;

  // Joint rates (the length of qd, qdd and the joint torques; nv): one per body, so a
  // floating base's free joint counts 6.
  int num_rates() const { return static_cast<int>(bodies.size()); }
  // Configuration numbers (the length of q; nq): num_rates(), plus 1 with a floating base
  // (its quaternion).
  int num_positions() const { return num_rates() + (floating ? 1 : 0); }
  [[deprecated("num_joints() counts joint rates (a free joint 6): use num_rates()")]]
  int num_joints() const { return num_rates(); }
  // The rates of a floating base's free joint (bodies 0 to 5), 0 without one: the URDF's
  // movable joints are the rates from this index on.
  int free_joint_rates() const { return floating ? 6 : 0; }
  // The same in q: the free joint's seven numbers q[0..6], 0 without one.
  int free_joint_positions() const { return floating ? 7 : 0; }
  // Where joint i's position is in q: q[i], or q[i + 1] behind a floating base's quaternion
  // (i >= free_joint_rates(); the free joint's own numbers are q[0..6]).
  int position_index(int joint) const { return floating && joint >= 6 ? joint + 1 : joint; }
  int num_links() const { return static_cast<int>(links.size()); }
  // The loop joints' constraint columns, all loops together.
  int num_loop_columns() const;
  bool has_tip() const { return !tip_name.empty(); }
  const Link& tip() const { return links.back(); }  // when has_tip()

  // Set the rotor (armature) inertia of a movable joint, by index; checked.
  void set_rotor_inertia(int joint, double value);
  int joint_index(const std::string& joint_name) const;  // -1 if absent
  int link_index(const std::string& link_name) const;    // -1 if absent
};

}  // namespace achd
