// achd simulate SCENE.json [--out traj.csv]: runs a scene, writes the trajectory as CSV
// (t, q..., qd..., tip x y z qx qy qz qw) and prints a JSON summary on stdout.
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "args.hpp"
#include "commands.hpp"
#include "scene_json.hpp"

namespace achd::cli {
namespace {

void csv_header(std::ostream& out, const Model& model) {
  out << "t";
  for (const Body& b : model.bodies) out << ",q_" << b.joint_name;
  for (const Body& b : model.bodies) out << ",qd_" << b.joint_name;
  out << ",x,y,z,qx,qy,qz,qw\n";
}

void csv_row(std::ostream& out, const Simulator& sim) {
  out << sim.t;
  for (Eigen::Index i = 0; i < sim.q.size(); ++i) out << ',' << sim.q[i];
  for (Eigen::Index i = 0; i < sim.qd.size(); ++i) out << ',' << sim.qd[i];
  const Transform tip = sim.tip_pose();
  const Eigen::Quaterniond r(tip.R);
  out << ',' << tip.p.x() << ',' << tip.p.y() << ',' << tip.p.z() << ',' << r.x() << ',' << r.y()
      << ',' << r.z() << ',' << r.w() << '\n';
}

}  // namespace

int cmd_simulate(int argc, char** argv) {
  const Args args(argc, argv, {"--out"}, {});
  if (args.positional().size() != 1) throw Error("simulate: expected one scene file, see `achd help`");
  const Scene scene = load_scene(args.positional()[0]);
  Simulator sim(scene.model, scene.options);
  start_scene(scene, sim);

  std::ofstream csv;
  if (args.has("--out")) {
    csv.open(args.get("--out"));
    if (!csv) throw Error(args.get("--out") + ": cannot write file");
    csv.precision(17);
    csv_header(csv, scene.model);
    csv_row(csv, sim);
  }
  const bool conserves = scene.conserves_energy();
  const double E0 = sim.energy();
  double max_kinetic = sim.kinetic_energy(), max_energy_error = 0;
  std::vector<int> hits(scene.model.num_joints(), 0);
  double step_ns = 0;
  const int steps = scene.steps();
  for (int s = 0; s < steps; ++s) {
    const auto t0 = std::chrono::steady_clock::now();
    sim.step(scene.dt);
    step_ns += std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    for (int i : sim.limit_hits()) ++hits[i];
    max_kinetic = std::max(max_kinetic, sim.kinetic_energy());
    if (conserves) max_energy_error = std::max(max_energy_error, std::abs(sim.energy() - E0));
    if (csv.is_open()) csv_row(csv, sim);
  }

  nlohmann::ordered_json out;
  out["scene"] = scene.source;
  out["urdf"] = scene.urdf;
  out["integrator"] = integrator_name(scene.options.integrator);
  out["dt"] = scene.dt;
  out["steps"] = steps;
  out["t"] = sim.t;
  out["wall_ns_per_step"] = steps ? step_ns / steps : 0.0;
  out["friction_velocity"] = sim.friction_velocity(scene.dt);
  if (conserves && max_kinetic > 0) out["energy_drift"] = max_energy_error / max_kinetic;
  else out["energy_drift"] = nullptr;
  out["energy"] = {{"initial", E0}, {"final", sim.energy()}, {"max_kinetic", max_kinetic}};
  nlohmann::ordered_json drift = nlohmann::ordered_json::object();
  const auto r = sim.max_residuals();
  for (int k = 0; k < kNumDirections; ++k)
    if (sim.direction_mode(k) == DirectionMode::Hold) drift[direction_name(k)] = r[k];
  out["held_drift"] = drift;
  nlohmann::ordered_json limit = nlohmann::ordered_json::object();
  for (int i = 0; i < scene.model.num_joints(); ++i)
    if (hits[i]) limit[scene.model.bodies[i].joint_name] = hits[i];
  out["limit_hits"] = limit;  // joint -> number of steps that ended at or past a limit
  std::cout << out.dump(2) << "\n";
  return 0;
}

}  // namespace achd::cli
