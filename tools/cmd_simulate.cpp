// achd simulate SCENE.json [--out traj.csv]: runs a scene, writes the trajectory as CSV
// (t, q..., qd..., and on a chain the tip's x y z qx qy qz qw; a floating base's q as
// ROOT_x ROOT_y ROOT_z ROOT_qx ROOT_qy ROOT_qz ROOT_qw, its qd as ROOT_vx ... ROOT_wz)
// and prints a JSON summary on stdout. With
// --out -, the CSV goes to stdout instead of the summary.
// Runs longer than a second show progress on stderr; Ctrl-C stops the run (exit 130).
// A failed or interrupted run says on stderr how far it got (t, steps) and leaves no
// file under the --out name (output_file.hpp).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "achd/names.hpp"
#include "args.hpp"
#include "commands.hpp"
#include "output_file.hpp"
#include "progress.hpp"
#include "urdf_options.hpp"
#include "scene_json.hpp"

namespace achd::cli {
namespace {

std::string csv_header(const Model& model) {
  std::string out = "t";
  const int first = model.free_joint_rates();  // the free joint's bodies: named below
  if (model.floating)
    for (const char* c : {"x", "y", "z", "qx", "qy", "qz", "qw"}) out += ",q_" + model.root_name + "_" + c;
  for (int i = first; i < model.num_rates(); ++i) out += ",q_" + model.bodies[i].joint_name;
  if (model.floating)
    for (const char* c : {"vx", "vy", "vz", "wx", "wy", "wz"}) out += ",qd_" + model.root_name + "_" + c;
  for (int i = first; i < model.num_rates(); ++i) out += ",qd_" + model.bodies[i].joint_name;
  return out + (model.has_tip() ? ",x,y,z,qx,qy,qz,qw\n" : "\n");
}

// 17 significant digits: the doubles round-trip exactly.
void append(std::string& row, double x, char separator) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  row.append(buf, static_cast<std::size_t>(n));
  row += separator;
}

void csv_row(std::string& row, const Simulator& sim) {
  row.clear();
  append(row, sim.t, ',');
  for (Eigen::Index i = 0; i < sim.q.size(); ++i) append(row, sim.q[i], ',');
  if (!sim.model().has_tip()) {
    for (Eigen::Index i = 0; i < sim.qd.size(); ++i) append(row, sim.qd[i], i + 1 < sim.qd.size() ? ',' : '\n');
    return;
  }
  for (Eigen::Index i = 0; i < sim.qd.size(); ++i) append(row, sim.qd[i], ',');
  const Transform tip = sim.tip_pose();
  const Eigen::Quaterniond r(tip.R);
  for (double x : {tip.p.x(), tip.p.y(), tip.p.z(), r.x(), r.y(), r.z()}) append(row, x, ',');
  append(row, r.w(), '\n');
}

std::string seconds(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", x);
  return buf;
}

}  // namespace

int cmd_simulate(int argc, char** argv) {
  const Args args(argc, argv, {"--out", "--integrator", "--rtol", "--atol"}, {});
  if (args.positional().size() != 1) throw Error("simulate: expected one scene file, see `achd help`");
  Scene scene = load_scene(args.positional()[0]);
  print_warnings(scene.model, scene.urdf);
  // The integrator and its tolerances, over the scene's.
  if (args.has("--integrator")) scene.options.integrator = integrator_from_name(args.get("--integrator"), "--integrator");
  for (const auto& [name, value] : {std::pair<const char*, double*>{"--rtol", &scene.options.rtol},
                                    {"--atol", &scene.options.atol}}) {
    if (!args.has(name)) continue;
    *value = args.number(name, 0);
    if (!(*value > 0)) throw Error(std::string(name) + " must be > 0, got " + args.get(name));
  }
  const std::int64_t steps = scene.steps();
  Simulator sim(scene.model, scene.options);
  start_scene(scene, sim);

  // Before the output file exists: from here on SIGINT, SIGTERM and SIGHUP unwind the
  // run, which removes the file's temporary file, instead of ending the process.
  catch_interrupt();
  std::unique_ptr<OutputFile> csv;
  std::string row;
  if (args.has("--out")) {
    csv = std::make_unique<OutputFile>(args.get("--out"));
    csv->write(csv_header(scene.model));
    csv_row(row, sim);
    csv->write(row);
  }
  // For a failed or interrupted run: what became of --out.
  const auto no_file = [&] { return csv && !csv->direct() ? "; no file written to " + csv->path() : std::string(); };
  Progress progress([&](std::int64_t done) {
    char percent[32];
    std::snprintf(percent, sizeof percent, "%.1f", 100.0 * static_cast<double>(done) / static_cast<double>(steps));
    return "simulate " + scene.source + ": t = " + seconds(sim.t) + " s of " + seconds(scene.duration) + " s (" +
           std::to_string(done) + " of " + std::to_string(steps) + " steps, " + percent + "%)";
  });

  const bool conserves = scene.conserves_energy();
  const double E0 = sim.energy();
  double max_kinetic = sim.kinetic_energy(), max_energy_error = 0;
  std::vector<std::int64_t> hits(scene.model.num_rates(), 0);
  double step_ns = 0;
  try {
    for (std::int64_t s = 0; s < steps; ++s) {
      const auto t0 = std::chrono::steady_clock::now();
      try {
        sim.step(scene.dt);
      } catch (const Error& e) {
        throw Error(scene.source + ": " + e.what() + "; the run stopped after " + std::to_string(sim.steps_taken()) +
                    " of " + std::to_string(steps) + " steps" + no_file());
      }
      step_ns += std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
      for (int i : sim.limit_hits()) ++hits[i];
      max_kinetic = std::max(max_kinetic, sim.kinetic_energy());
      if (conserves) max_energy_error = std::max(max_energy_error, std::abs(sim.energy() - E0));
      if (csv) {
        csv_row(row, sim);
        csv->write(row);
      }
      progress.step();
    }
  } catch (const Interrupted& e) {
    throw Interrupted(e.what() + no_file(), e.signal());
  }

  nlohmann::ordered_json out;
  out["scene"] = scene.source;
  out["urdf"] = scene.urdf;
  out["integrator"] = integrator_name(scene.options.integrator);
  out["dt"] = scene.dt;
  out["steps"] = steps;
  out["t"] = sim.t;  // = steps * dt exactly (Simulator::t)
  out["wall_ns_per_step"] = steps ? step_ns / static_cast<double>(steps) : 0.0;
  out["friction_velocity"] = scene.options.solver.friction_velocity;
  out["substeps"] = sim.substeps();
  out["rejected_substeps"] = sim.rejected_substeps();
  out["stiff_substeps"] = sim.stiff_substeps();
  if (conserves && max_kinetic > 0) out["energy_drift"] = max_energy_error / max_kinetic;
  else out["energy_drift"] = nullptr;
  out["energy"] = {{"initial", E0}, {"final", sim.energy()}, {"max_kinetic", max_kinetic}};
  // held_drift: the tip's held directions; link_held_drift: every link's, by link name
  // (while followed: released intervals excluded); released_s and link_released_s: how
  // long each direction that was ever released was not followed.
  nlohmann::ordered_json drift = nlohmann::ordered_json::object(), link_drift = nlohmann::ordered_json::object();
  nlohmann::ordered_json released = nlohmann::ordered_json::object(), link_released = nlohmann::ordered_json::object();
  for (const LinkDirections& set : sim.direction_sets()) {
    nlohmann::ordered_json d = nlohmann::ordered_json::object(), r = nlohmann::ordered_json::object();
    const auto res = sim.max_residuals(set.link);
    const auto seconds = sim.released_seconds(set.link);
    for (int k = 0; k < kNumDirections; ++k) {
      if (set.held.mode[k] == DirectionMode::Hold) d[direction_name(k)] = res[k];
      if (seconds[k] > 0) r[direction_name(k)] = seconds[k];
    }
    const std::string& name = scene.model.links[set.link].name;
    const bool tip = scene.model.has_tip() && set.link == scene.model.num_links() - 1;
    if (!d.empty()) {
      if (tip) drift = d;
      link_drift[name] = d;
    }
    if (!r.empty()) {
      if (tip) released = r;
      link_released[name] = r;
    }
  }
  out["held_drift"] = drift;
  out["link_held_drift"] = link_drift;
  out["released_s"] = released;
  out["link_released_s"] = link_released;
  // loop_drift: each loop joint's largest closure error (m or rad), by loop name;
  // loop_released_s: how long each of its directions that was ever released was not followed
  if (!scene.model.loops.empty()) {
    out["loop_drift"] = nlohmann::ordered_json::object();
    nlohmann::ordered_json loop_released = nlohmann::ordered_json::object();
    for (size_t l = 0; l < scene.model.loops.size(); ++l) {
      const std::string& name = scene.model.loops[l].name;
      out["loop_drift"][name] = sim.loop_drift(static_cast<int>(l));
      const auto seconds = sim.loop_released_seconds(static_cast<int>(l));
      for (int k = 0; k < kNumDirections; ++k)
        if (seconds[k] > 0) loop_released[name][direction_name(k)] = seconds[k];
    }
    out["loop_released_s"] = loop_released;
  }
  nlohmann::ordered_json limit = nlohmann::ordered_json::object();
  for (int i = 0; i < scene.model.num_rates(); ++i)
    if (hits[i]) limit[scene.model.bodies[i].joint_name] = hits[i];
  out["limit_hits"] = limit;  // joint -> number of steps that ended at or past a limit
  nlohmann::ordered_json events = nlohmann::ordered_json::array();
  for (const DirectionEvent& e : sim.events()) {
    nlohmann::ordered_json j = {{"t", e.t}, {"step", e.step}};
    if (e.loop >= 0) j["loop"] = scene.model.loops[e.loop].name;
    else j["link"] = scene.model.links[e.link].name;
    j["direction"] = direction_name(e.direction);
    j["kind"] = kDirectionEventKindNames[static_cast<int>(e.kind)];
    j["sigma_min"] = e.sigma_min;
    j["unmet"] = e.unmet;
    j["effort_ratio"] = e.effort_ratio;
    events.push_back(j);
  }
  out["events"] = events;  // direction events (Simulator::events())
  if (sim.events_not_kept()) out["events_not_kept"] = sim.events_not_kept();
  if (csv) csv->commit();
  if (!csv || csv->path() != "-") std::cout << out.dump(2) << "\n";
  return 0;
}

}  // namespace achd::cli
