#pragma once
// Scene files (robots/scenes/*.json): a robot (a chain to its tip, or a whole tree, fixed
// or floating), its initial state, the effects to simulate, held or accelerated
// directions (the tip's, and any links'), a joint PD controller, the integrator, time
// step and duration.
// Schema in docs/guide/simulation.md; every error names the scene file and the field.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "achd/achd.hpp"
#include "achd/simulator.hpp"

namespace achd::cli {

// A scene's output step when it gives no "dt": 1 ms, the page's step (the adaptive
// default integrator takes the substeps it needs within it).
constexpr double kDefaultSceneDt = 1e-3;

struct Scene {
  std::string source;  // the scene file, as given
  std::string urdf;    // the URDF path, resolved (see resolve_scene_path)
  std::string root, tip;
  Model model;
  Eigen::VectorXd q0, qd0, ff_torques;
  std::vector<Vector6> f_ext;  // empty, or one per link after the root
  SimulatorOptions options;
  std::array<DirectionMode, kNumDirections> modes{};
  std::array<double, kNumDirections> setpoints{};
  // "direction_weights": {"z": {"w_fext": 0, "w_ff": 1}}: driver priorities per direction
  std::array<double, kNumDirections> w_fext{1, 1, 1, 1, 1, 1}, w_ff{1, 1, 1, 1, 1, 1};
  // "prescribed": [{"joint": NAME, "motion": "constant" | "ramp" | "sine", ...}]: joints
  // on a trajectory (Simulator::prescribe), by joint index
  std::vector<std::pair<int, JointMotion>> prescribed;
  // "link_directions": [{"link": NAME, "directions": {...}, "point": [x, y, z],
  // "direction_weights": {...}}]: each link's own set (Simulator::set_direction(link, ...))
  struct LinkSet {
    int link = 0;
    Vector3 point = Vector3::Zero();
    std::array<DirectionMode, kNumDirections> modes{};
    std::array<double, kNumDirections> setpoints{};
    std::array<double, kNumDirections> w_fext{1, 1, 1, 1, 1, 1}, w_ff{1, 1, 1, 1, 1, 1};
  };
  std::vector<LinkSet> link_directions;
  // "joint_control": {"target": pose (default q0), "kp", "kd" or "frequency",
  // "damping_ratio", "feedforward": "hold"}
  bool joint_control = false;
  JointControl control;
  double dt = 0, duration = 0;

  // duration / dt, a whole number checked when the scene is parsed (steps_for_duration).
  std::int64_t steps() const;
  // True when nothing in the scene adds or removes energy: velocity products on, no
  // damping, friction, torques, wrenches, accelerated directions or prescribed joints,
  // limits not clamped.
  bool conserves_energy() const;
};

// Parses a scene; `source` is its file path, used for messages and to resolve "urdf".
Scene parse_scene(const std::string& text, const std::string& source);
// The Integrator named `name` (integrator_name()); an achd::Error naming `field` and the
// names otherwise.
Integrator integrator_from_name(const std::string& name, const std::string& field);
Scene load_scene(const std::string& path);

// A path in a scene is relative to the repository root: it is looked up against the
// scene file's directory and then each of its parent directories, and the first that
// holds it wins (so robots/scenes/x.json finds "robots/kuka_lwr4.urdf" from any working
// directory). Absolute paths are used as they are.
std::string resolve_scene_path(const std::string& path, const std::string& scene_file,
                               const std::string& field = "urdf");

// Puts the scene's initial state, torques, wrenches, prescribed joints (on their
// trajectories at t = 0, whatever q0 says for them) and directions (held where the tip is
// then) into `sim`.
void start_scene(const Scene& scene, Simulator& sim);

}  // namespace achd::cli
