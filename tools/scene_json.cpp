#include "scene_json.hpp"

#include <cmath>
#include <filesystem>

#include "achd/names.hpp"
#include "achd/srdf.hpp"
#include "case_json.hpp"
#include "json_file.hpp"
#include "json_text.hpp"
#include "loops_json.hpp"
#include "printable.hpp"
#include "read_text_file.hpp"

namespace achd::cli {
namespace {

using nlohmann::json;

double number(const json& v, const std::string& field) {
  if (!v.is_number()) throw Error(field + " must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw Error(field + " is not finite");
  return x;
}

std::string text(const json& v, const std::string& field) {
  if (!v.is_string()) throw Error(field + " must be a string");
  return v.get<std::string>();
}

Eigen::VectorXd vector(const json& v, const std::string& field, int n) {
  if (!v.is_array() || static_cast<int>(v.size()) != n)
    throw Error(field + " must be an array of " + std::to_string(n) + " numbers");
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) out[i] = number(v[i], field + "[" + std::to_string(i) + "]");
  return out;
}

void only_known(const json& j, const std::string& where, std::initializer_list<const char*> known) {
  for (const auto& item : j.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || item.key() == k;
    if (!ok) throw Error("unknown field '" + where + printable(item.key()) + "'");
  }
}

std::uint32_t effects(const json& j) {
  if (!j.is_object()) throw Error("effects must be an object of booleans");
  std::uint32_t bits = kAllEffects;  // a missing key keeps its effect on
  for (const auto& item : j.items()) {
    const EffectName* e = nullptr;
    for (const EffectName& k : kEffectNames)
      if (item.key() == k.name) e = &k;
    if (!e) throw Error("unknown field 'effects." + printable(item.key()) + "'");
    if (!item.value().is_boolean()) throw Error("effects." + printable(item.key()) + " must be true or false");
    if (item.value().get<bool>()) bits |= e->bit;
    else bits &= ~e->bit;
  }
  return bits;
}

Integrator integrator(const json& v) { return integrator_from_name(text(v, "integrator"), "integrator"); }

SingularityPolicy policy(const json& v) {
  const std::string s = text(v, "policy");
  for (int k = 0; k < 3; ++k)
    if (s == kSingularityPolicyNames[k]) return static_cast<SingularityPolicy>(k);
  throw Error("policy: expected 'truncate', 'damped' or 'variable_damping', got '" + printable(s) + "'");
}

LimitPolicy limits(const json& v) {
  const std::string s = text(v, "limits");
  for (int k = 0; k < 3; ++k)
    if (s == kLimitPolicyNames[k]) return static_cast<LimitPolicy>(k);
  throw Error("limits: expected 'report', 'clamp' or 'ignore', got '" + printable(s) + "'");
}

// The start pose q0 of a floating base: its orientation quaternion
// q[3..6] must not be zero (the numbers are finite already). Named here, since a zero
// quaternion would otherwise surface later as a NaN blamed on whatever used it first
// (a held direction of a foot).
void check_quaternion(const Eigen::VectorXd& q, const Model& model, const std::string& field) {
  if (model.floating && !(q.segment<4>(3).lpNorm<Eigen::Infinity>() > 0))
    throw Error(field + "[3..6]: the floating base's orientation quaternion (qx, qy, qz, qw) is zero");
}

const json& required(const json& j, const char* field) {
  if (!j.contains(field)) throw Error(std::string("missing required field '") + field + "'");
  return j[field];
}

// A required field of an object in the scene, `where` naming the object.
const json& required_in(const json& j, const char* field, const std::string& where) {
  if (!j.contains(field)) throw Error(where + ": missing required field '" + field + "'");
  return j[field];
}

// "directions": {"z": "hold", "y": 0.5, ...} (`prefix` names the object in messages).
void directions(const json& j, const std::string& prefix, std::array<DirectionMode, kNumDirections>& modes,
                std::array<double, kNumDirections>& setpoints) {
  if (!j.is_object()) throw Error(prefix + "directions must be an object (x y z rx ry rz)");
  for (const auto& item : j.items()) {
    const int k = index_of_direction(item.key());
    const std::string field = prefix + "directions." + printable(item.key());
    if (k < 0) throw Error("unknown field '" + field + "' (directions are x y z rx ry rz)");
    const json& v = item.value();
    if (v.is_number()) {
      modes[k] = DirectionMode::Accelerate;
      setpoints[k] = number(v, field);
    } else if (v.is_string() && (v == "hold" || v == "free")) {
      modes[k] = v == "hold" ? DirectionMode::Hold : DirectionMode::Free;
    } else {
      throw Error(field + " must be \"hold\", \"free\" or a number (classical acceleration)");
    }
  }
}

// "direction_weights": {"z": {"w_fext": 0, "w_ff": 1}, ...}, each weight in [0, 1]
// (default 1; Simulator::set_direction_weights).
void direction_weights(const json& j, const std::string& prefix, std::array<double, kNumDirections>& w_fext,
                       std::array<double, kNumDirections>& w_ff) {
  if (!j.is_object()) throw Error(prefix + "direction_weights must be an object (x y z rx ry rz)");
  for (const auto& item : j.items()) {
    const int k = index_of_direction(item.key());
    const std::string field = prefix + "direction_weights." + printable(item.key());
    if (k < 0) throw Error("unknown field '" + field + "' (directions are x y z rx ry rz)");
    if (!item.value().is_object()) throw Error(field + " must be an object {\"w_fext\": w, \"w_ff\": w}");
    for (const auto& w : item.value().items()) {
      if (w.key() != "w_fext" && w.key() != "w_ff") throw Error("unknown field '" + field + "." + printable(w.key()) + "'");
      const double value = number(w.value(), field + "." + w.key());
      if (!(value >= 0 && value <= 1)) throw Error(field + "." + printable(w.key()) + " must be in [0, 1]");
      (w.key() == "w_fext" ? w_fext : w_ff)[k] = value;
    }
  }
}

// "link_directions": [{"link": NAME, "directions": {...}, "point": [x, y, z],
// "direction_weights": {...}}], one entry per link.
void link_directions(const json& j, Scene& s) {
  if (!j.is_array()) throw Error("link_directions must be an array of {link, directions, point, direction_weights}");
  for (size_t e = 0; e < j.size(); ++e) {
    const std::string where = "link_directions[" + std::to_string(e) + "]";
    const json& item = j[e];
    if (!item.is_object()) throw Error(where + " must be an object {link, directions, point, direction_weights}");
    only_known(item, where + ".", {"link", "directions", "point", "direction_weights"});
    const std::string name = text(required_in(item, "link", where), where + ".link");
    Scene::LinkSet set;
    set.link = s.model.link_index(name);
    if (set.link < 0)
      throw Error(where + ".link: no link '" + printable(name) + "' after the root link '" + s.model.root_name + "'");
    for (const Scene::LinkSet& other : s.link_directions)
      if (other.link == set.link) throw Error(where + ".link: link '" + printable(name) + "' is listed twice");
    if (item.contains("point")) set.point = vector(item["point"], where + ".point", 3);
    if (item.contains("directions")) directions(item["directions"], where + ".", set.modes, set.setpoints);
    if (item.contains("direction_weights"))
      direction_weights(item["direction_weights"], where + ".", set.w_fext, set.w_ff);
    s.link_directions.push_back(set);
  }
}

// Gains: one number for every joint (a floating base's free joint: 0), or one per joint.
Eigen::VectorXd gains(const json& j, const std::string& field, const Model& model) {
  const int n = model.num_rates();
  Eigen::VectorXd g = j.is_number() ? Eigen::VectorXd::Constant(n, number(j, field)) : vector(j, field, n);
  if (j.is_number() && model.floating) g.head(6).setZero();
  return g;
}

// "joint_control": {"target": a pose as q0 (default q0), then "kp": gains, "kd": gains, or
// "frequency": Hz, "damping_ratio": zeta (JointControl), and "feedforward": "hold" or
// "none" (default)}; the simulator checks the values (Simulator::set_joint_control).
void joint_control(const json& j, Scene& s) {
  if (!j.is_object()) throw Error("joint_control must be an object {target, kp, kd} or {target, frequency, damping_ratio}");
  only_known(j, "joint_control.", {"target", "kp", "kd", "frequency", "damping_ratio", "feedforward"});
  s.joint_control = true;
  s.control.target = j.contains("target") ? vector(j["target"], "joint_control.target", s.model.num_positions()) : s.q0;
  if (j.contains("frequency") || j.contains("damping_ratio")) {
    if (j.contains("kp") || j.contains("kd"))
      throw Error("joint_control: give kp and kd, or frequency and damping_ratio, not both");
    s.control.frequency = number(required_in(j, "frequency", "joint_control"), "joint_control.frequency");
    s.control.damping_ratio =
        j.contains("damping_ratio") ? number(j["damping_ratio"], "joint_control.damping_ratio") : 1.0;
  } else {
    s.control.kp = gains(required_in(j, "kp", "joint_control"), "joint_control.kp", s.model);
    s.control.kd = j.contains("kd") ? gains(j["kd"], "joint_control.kd", s.model)
                                    : Eigen::VectorXd::Zero(s.model.num_rates());
  }
  if (j.contains("feedforward")) {
    const std::string ff = text(j["feedforward"], "joint_control.feedforward");
    if (ff != "hold" && ff != "none")
      throw Error("joint_control.feedforward: expected 'hold' or 'none', got '" + ff + "'");
    s.control.hold = ff == "hold";
  }
}

// "prescribed": [{"joint": NAME, "motion": KIND, "position", "velocity", "amplitude",
// "frequency", "phase"}]: the parameters a kind reads (joint_motion.hpp), absent = 0.
void prescribed(const json& j, Scene& s) {
  if (!j.is_array()) throw Error("prescribed must be an array of {joint, motion, ...} objects");
  for (size_t k = 0; k < j.size(); ++k) {
    const std::string where = "prescribed[" + std::to_string(k) + "]";
    const json& item = j[k];
    if (!item.is_object()) throw Error(where + " must be an object {joint, motion, ...}");
    only_known(item, where + ".", {"joint", "motion", "position", "velocity", "amplitude", "frequency", "phase"});
    const std::string name = text(required_in(item, "joint", where), where + ".joint");
    const int i = s.model.joint_index(name);
    if (i < 0) throw Error(where + ".joint: no movable joint '" + printable(name) + "' between the root and the tip");
    for (const auto& [other, motion] : s.prescribed)
      if (other == i) throw Error(where + ".joint: joint '" + printable(name) + "' is prescribed twice");
    const std::string kind = text(required_in(item, "motion", where), where + ".motion");
    JointMotion m;
    int found = -1;
    for (int c = 0; c < 3; ++c)
      if (kind == kMotionKindNames[c]) found = c;
    if (found < 0) throw Error(where + ".motion: expected 'constant', 'ramp' or 'sine', got '" + printable(kind) + "'");
    m.kind = static_cast<MotionKind>(found);
    for (auto [field, out] : {std::pair<const char*, double*>{"position", &m.position}, {"velocity", &m.velocity},
                              {"amplitude", &m.amplitude}, {"frequency", &m.frequency}, {"phase", &m.phase}})
      if (item.contains(field)) *out = number(item[field], where + "." + field);
    validate(m, where + ": ");
    s.prescribed.emplace_back(i, m);
  }
}

void f_ext(const json& j, Scene& s) {
  if (!j.is_object()) throw Error("f_ext must be an object {link name: [fx, fy, fz, tx, ty, tz]}");
  s.f_ext.assign(s.model.num_links(), Vector6::Zero());
  for (const auto& item : j.items()) {
    const int l = s.model.link_index(item.key());
    if (l < 0) throw Error("f_ext." + printable(item.key()) + ": no link of that name after the root");
    s.f_ext[l] = vector(item.value(), "f_ext." + item.key(), 6);
  }
}

double positive(const json& j, const char* field) {
  const double x = number(j, field);
  if (!(x > 0)) throw Error(std::string(field) + " must be > 0");
  return x;
}



}  // namespace

Integrator integrator_from_name(const std::string& name, const std::string& field) {
  for (Integrator i : kIntegrators)
    if (name == integrator_name(i)) return i;
  std::string names;
  for (Integrator i : kIntegrators) names += std::string(names.empty() ? "'" : ", '") + integrator_name(i) + "'";
  throw Error(field + ": expected one of " + names + ", got '" + printable(name) + "'");
}

std::int64_t Scene::steps() const { return steps_for_duration(duration, dt); }

bool Scene::conserves_energy() const {
  const std::uint32_t e = options.effects;
  if (!(e & kVelocityProducts) || options.limits == LimitPolicy::Clamp) return false;
  for (const Body& b : model.bodies)
    if (((e & kDamping) && b.damping != 0) || ((e & kFriction) && b.friction != 0)) return false;
  if (ff_torques.size() && ff_torques.cwiseAbs().maxCoeff() != 0) return false;
  if (!prescribed.empty()) return false;
  if (e & kExternalWrenches)
    for (const Vector6& f : f_ext)
      if (f.cwiseAbs().maxCoeff() != 0) return false;
  if (joint_control && (control.hold || control.frequency != 0 || control.kp.cwiseAbs().maxCoeff() != 0 ||
                        control.kd.cwiseAbs().maxCoeff() != 0))
    return false;
  if (e & kConstraints) {
    for (DirectionMode m : modes)
      if (m == DirectionMode::Accelerate) return false;
    for (const LinkSet& set : link_directions)
      for (DirectionMode m : set.modes)
        if (m == DirectionMode::Accelerate) return false;
  }
  return true;
}

std::string resolve_scene_path(const std::string& path, const std::string& scene_file, const std::string& field) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  if (p.is_absolute()) return path;
  for (fs::path dir = fs::absolute(scene_file).parent_path();; dir = dir.parent_path()) {
    if (fs::exists(dir / p)) return (dir / p).lexically_normal().string();
    if (dir == dir.root_path() || dir.empty()) break;
  }
  throw Error(field + ": '" + printable(path) + "' not found from the scene's directory or any parent");
}

Scene parse_scene(const std::string& text_in, const std::string& source) {
  Scene s;
  s.source = source;
  try {
    const json j = parse_json_text(text_in);  // duplicate keys refused
    if (!j.is_object()) throw Error("the scene must be a JSON object");
    only_known(j, "", {"description", "urdf", "root", "tip", "q0", "qd0", "effects", "directions", "direction_weights",
                       "integrator", "dt", "duration", "gravity", "limits", "friction_velocity",
                       "stabilisation_frequency", "stabilisation_damping", "ff_torques", "f_ext",
                       "rotor_inertia", "mimic", "inertia", "srdf", "pose", "rtol", "atol", "policy",
                       "singular_region", "max_damping", "prescribed", "floating", "link_directions",
                       "joint_control", "loops"});
    if (j.contains("description")) text(j["description"], "description");
    s.urdf = resolve_scene_path(text(required(j, "urdf"), "urdf"), source);
    s.root = text(required(j, "root"), "root");
    if (j.contains("tip")) s.tip = text(j["tip"], "tip");  // without one: the whole tree
    UrdfOptions urdf_options;
    if (j.contains("mimic")) urdf_options.mimic = mimic_joints_from_name(text(j["mimic"], "mimic"), "mimic");
    if (j.contains("floating")) {
      if (!j["floating"].is_boolean()) throw Error("floating must be true or false");
      urdf_options.floating = j["floating"].get<bool>();
    }
    if (j.contains("inertia"))
      urdf_options.inertia = inertia_policy_from_name(text(j["inertia"], "inertia"), "inertia");
    // loops: the loop joints, or the path of a loops file (resolved as urdf is)
    if (j.contains("loops") && j["loops"].is_string()) {
      const std::string path = resolve_scene_path(text(j["loops"], "loops"), source, "loops");
      urdf_options.loops = parse_loops(read_json_file(path, "a loops file"), path);
    } else if (j.contains("loops")) {
      urdf_options.loops = loop_specs(j["loops"], "loops");
    }
    s.model = load_urdf_file(s.urdf, s.root, s.tip, urdf_options);
    const int n = s.model.num_rates();
    // q0: given, or the SRDF's pose ("srdf": a path resolved as urdf is, "pose": a
    // group_state name), or the default pose (every joint at 0 or mid-limits).
    if (j.contains("srdf") != j.contains("pose")) throw Error("srdf and pose go together: the file and the state's name");
    if (j.contains("srdf") && j.contains("q0")) throw Error("give q0 or srdf and pose, not both");
    if (j.contains("srdf")) {
      const std::string srdf = resolve_scene_path(text(j["srdf"], "srdf"), source, "srdf");
      const std::string text_of = read_text_file(srdf, kMaxUrdfFileBytes, "an SRDF file");
      s.q0 = srdf_pose_q(s.model, find_srdf_pose(read_srdf_poses(text_of, srdf), text(j["pose"], "pose"), srdf));
    } else {
      s.q0 = j.contains("q0") ? vector(j["q0"], "q0", s.model.num_positions()) : default_pose(s.model);
      check_quaternion(s.q0, s.model, "q0");
    }
    s.qd0 = j.contains("qd0") ? vector(j["qd0"], "qd0", n) : Eigen::VectorXd::Zero(n);
    s.ff_torques = j.contains("ff_torques") ? vector(j["ff_torques"], "ff_torques", n)
                                            : Eigen::VectorXd::Zero(n);
    if (j.contains("rotor_inertia")) {
      const Eigen::VectorXd r = vector(j["rotor_inertia"], "rotor_inertia", n);
      for (int i = 0; i < n; ++i) {
        if (r[i] < 0) throw Error("rotor_inertia[" + std::to_string(i) + "] must be >= 0");
        s.model.set_rotor_inertia(i, r[i]);
      }
    }
    if (j.contains("f_ext")) f_ext(j["f_ext"], s);
    if (j.contains("effects")) s.options.effects = effects(j["effects"]);
    if (j.contains("directions") || j.contains("direction_weights")) {
      if (!s.model.has_tip())
        throw Error(std::string(j.contains("directions") ? "directions" : "direction_weights") +
                    ": the tip's directions need a tip (the scene loads a whole tree): use link_directions");
      if (j.contains("directions")) directions(j["directions"], "", s.modes, s.setpoints);
      if (j.contains("direction_weights")) direction_weights(j["direction_weights"], "", s.w_fext, s.w_ff);
    }
    if (j.contains("link_directions")) link_directions(j["link_directions"], s);
    if (j.contains("joint_control")) joint_control(j["joint_control"], s);
    if (j.contains("prescribed")) prescribed(j["prescribed"], s);
    if (j.contains("integrator")) s.options.integrator = integrator(j["integrator"]);
    if (j.contains("limits")) s.options.limits = limits(j["limits"]);
    if (j.contains("gravity")) s.options.gravity = vector(j["gravity"], "gravity", 3);
    s.dt = j.contains("dt") ? positive(j["dt"], "dt") : kDefaultSceneDt;
    s.duration = number(required(j, "duration"), "duration");
    if (s.duration < 0) throw Error("duration must be >= 0");
    s.steps();  // a whole number of steps that can be run, else an error naming it
    if (j.contains("friction_velocity"))
      s.options.solver.friction_velocity = positive(j["friction_velocity"], "friction_velocity");
    if (j.contains("stabilisation_frequency"))
      s.options.stabilisation_frequency = positive(j["stabilisation_frequency"], "stabilisation_frequency");
    if (j.contains("policy")) s.options.solver.policy = policy(j["policy"]);
    if (j.contains("singular_region"))
      s.options.solver.singular_region = positive(j["singular_region"], "singular_region");
    if (j.contains("max_damping")) s.options.solver.max_damping = positive(j["max_damping"], "max_damping");
    if (j.contains("stabilisation_damping"))
      s.options.stabilisation_damping = positive(j["stabilisation_damping"], "stabilisation_damping");
    if (j.contains("rtol")) s.options.rtol = positive(j["rtol"], "rtol");
    if (j.contains("atol")) s.options.atol = positive(j["atol"], "atol");
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  return s;
}

Scene load_scene(const std::string& path) { return parse_scene(read_json_file(path, "a scene file"), path); }

void start_scene(const Scene& scene, Simulator& sim) {
  sim.reset(scene.q0, scene.qd0);
  sim.ff_torques = scene.ff_torques;
  sim.f_ext = scene.f_ext;
  if (scene.model.has_tip())
    for (int k = 0; k < kNumDirections; ++k) {
      sim.set_direction_weights(k, scene.w_fext[k], scene.w_ff[k]);
      if (scene.modes[k] != DirectionMode::Free) sim.set_direction(k, scene.modes[k], scene.setpoints[k]);
    }
  for (size_t e = 0; e < scene.link_directions.size(); ++e) {
    const Scene::LinkSet& set = scene.link_directions[e];
    try {
      sim.set_direction_point(set.link, set.point);
      for (int k = 0; k < kNumDirections; ++k) {
        sim.set_direction_weights(set.link, k, set.w_fext[k], set.w_ff[k]);
        if (set.modes[k] != DirectionMode::Free) sim.set_direction(set.link, k, set.modes[k], set.setpoints[k]);
      }
    } catch (const Error& err) {
      throw Error(scene.source + ": link_directions[" + std::to_string(e) + "]: " + err.what());
    }
  }
  // After the held directions: a prescribed joint jumps onto its trajectory as an impulse
  // they respect (Simulator::prescribe), so the scene starts with them at rest.
  for (const auto& [joint, motion] : scene.prescribed) sim.prescribe(joint, motion);
  if (scene.joint_control) {
    try {
      sim.set_joint_control(scene.control);
    } catch (const Error& err) {
      throw Error(scene.source + ": " + err.what());
    }
  }
}

}  // namespace achd::cli
