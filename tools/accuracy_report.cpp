// Tables and plot of an accuracy study.
#include "accuracy_report.hpp"

#include "achd/names.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace achd::cli {
namespace {

// One colour per achd::kIntegrators entry (names.hpp), in its order.
const char* const kColors[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e"};
static_assert(sizeof kColors / sizeof kColors[0] == sizeof kIntegrators / sizeof kIntegrators[0],
              "a colour per integrator");

// 17 significant digits, empty for NaN/Inf (CSV).
std::string cell(double v) {
  if (!std::isfinite(v)) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// A CSV field: quoted, with its quotes doubled, when it holds a comma, quote or newline.
std::string text_cell(const std::string& t) {
  if (t.find_first_of(",\"\n") == std::string::npos) return t;
  std::string q = "\"";
  for (char c : t) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// A finite number or null.
nlohmann::ordered_json value(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

}  // namespace

std::string study_csv(const Study& study) {
  // false: the error is below 1000 x the reference's own (round-off territory).
  const auto resolved = [&](const StudyRun& r) { return r.stable && r.error_q >= 1e3 * study.reference.self_error_q; };
  std::ostringstream o;
  o << "kind,integrator,setting,dt_s,steps,stable,status,error_q_rad,error_qd_rad_s,change_q_rad,energy_drift,"
       "held_drift_m,held_drift_rad,substeps,stiff_substeps,rejected_substeps,ns_per_step,cpu_s_per_sim_s,order,pareto,"
       "resolved_by_reference,failure\n";
  for (const StudyRun& r : study.runs) {
    const bool s = r.stable;
    o << r.kind << ',' << r.integrator << ',' << r.setting << ',' << cell(r.dt) << ',' << r.steps << ','
      << (s ? "true" : "false") << ',' << r.status << ',' << (s ? cell(r.error_q) : "") << ',' << (s ? cell(r.error_qd) : "")
      << ',' << (r.kind == "integrator" || !s ? "" : cell(r.change_q)) << ',' << cell(r.energy_drift) << ','
      << (s ? cell(r.held_drift_linear) : "") << ',' << (s ? cell(r.held_drift_angular) : "") << ','
      << r.substeps << ',' << r.stiff_substeps << ',' << r.rejected_substeps << ','
      << cell(r.ns_per_step) << ',' << cell(r.cpu_s_per_sim_s) << ',' << cell(r.order) << ','
      << (r.pareto ? "true" : "false") << ','
      << (r.kind != "integrator" ? "" : resolved(r) ? "true" : "false") << ',' << text_cell(r.failure) << '\n';
  }
  return o.str();
}

nlohmann::ordered_json study_json(const Study& study) {
  nlohmann::ordered_json j;
  j["scene"] = study.scene;
  j["duration_s"] = study.config.duration;
  j["error_measure"] = "max_i |q_i(T) - q_ref,i(T)| (rad); error_qd: max_i |qd_i(T) - qd_ref,i(T)| (rad/s)";
  j["cost_measure"] = "CPU time of the simulating thread per output step, median of " +
                      std::to_string(study.config.timing_repeats) + " interleaved rounds (each runs every " +
                      "configuration in turn) of up to " + std::to_string(study.config.timing_steps) +
                      " steps from the scene's start";
  j["unstable_when"] = "status unstable: the state became NaN/Inf or the solver refused it; "
                      "status diverged: finite but error_q > 1 rad";
  j["friction_velocity"] = study.friction_velocity;
  j["stabilisation_frequency"] = study.stabilisation_frequency;
  const Reference& ref = study.reference;
  double smallest = INFINITY;
  for (const StudyRun& r : study.runs)
    if (r.kind == "integrator" && r.stable) smallest = std::min(smallest, r.error_q);
  int resolved = 0, stable = 0;  // stable ladder errors >= 1000 x the reference's own
  for (const StudyRun& r : study.runs)
    if (r.kind == "integrator" && r.stable) {
      ++stable;
      resolved += r.error_q >= 1e3 * ref.self_error_q;
    }
  j["reference"] = {{"integrator", "rk4"},
                    {"dt_s", ref.dt},
                    {"halvings", ref.halvings},  // of the study's reference_dt (refine_reference)
                    {"self_error_q_rad", ref.self_error_q},
                    {"self_error_qd_rad_s", ref.self_error_qd},
                    {"smallest_error_q_rad", value(smallest)},
                    {"self_error_over_smallest", value(ref.self_error_q / smallest)},
                    {"errors_above_1000x_self_error", std::to_string(resolved) + " of " + std::to_string(stable)}};
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const StudyRun& r : study.runs) {
    nlohmann::ordered_json row;
    row["kind"] = r.kind;
    row["integrator"] = r.integrator;
    if (!r.setting.empty()) row["setting"] = r.setting;
    row["dt_s"] = r.dt;
    row["steps"] = r.steps;
    row["stable"] = r.stable;
    row["status"] = r.status;
    if (!r.stable) row["failure"] = r.failure;
    row["error_q_rad"] = r.stable ? value(r.error_q) : nullptr;
    row["error_qd_rad_s"] = r.stable ? value(r.error_qd) : nullptr;
    if (r.kind != "integrator") row["change_q_rad"] = r.stable ? value(r.change_q) : nullptr;
    row["energy_drift"] = value(r.energy_drift);
    row["held_drift_m"] = r.stable ? value(r.held_drift_linear) : nullptr;
    row["held_drift_rad"] = r.stable ? value(r.held_drift_angular) : nullptr;
    row["substeps"] = r.substeps;  // up to the failed step when not ok
    row["stiff_substeps"] = r.stiff_substeps;
    row["rejected_substeps"] = r.rejected_substeps;
    row["ns_per_step"] = r.ns_per_step;
    row["cpu_s_per_sim_s"] = r.cpu_s_per_sim_s;
    if (r.kind == "integrator") {
      // false: the error is below 1000 x the reference's own (round-off territory).
      row["resolved_by_reference"] = r.stable && r.error_q >= 1e3 * ref.self_error_q;
      row["order"] = value(r.order);
      row["pareto"] = r.pareto;
    }
    runs.push_back(row);
  }
  j["runs"] = runs;
  j["study_wall_s"] = study.wall_seconds;
  return j;
}

LogLogPlot study_plot(const Study& study, const std::string& title) {
  LogLogPlot plot;
  plot.title = title;
  plot.x_label = "cost: CPU time per simulated second (s/s)";
  plot.y_label = "error: max |q(T) - q_ref(T)| (rad)";
  plot.x_marker = 1;
  plot.x_marker_label = "real time";
  // Runs not plotted, by status: "explicit_euler 10, 5 ms; rk4 10 ms; dormand_prince rtol 0.001".
  std::map<std::string, std::string> left_out;
  for (std::size_t k = 0; k < sizeof kColors / sizeof kColors[0]; ++k) {
    std::map<std::string, std::string> steps;
    PlotSeries s;
    s.name = integrator_name(kIntegrators[k]);
    s.color = kColors[k];
    bool any = false;
    for (const StudyRun& r : study.runs) {
      if (r.kind != "integrator" || r.integrator != s.name) continue;
      any = true;
      const bool resolved = r.error_q >= 1e3 * study.reference.self_error_q;
      // Fixed steps: dt in ms; Dormand-Prince: its rtol.
      const std::string label =
          (r.setting.empty() ? short_number(r.dt * 1e3) : r.setting) + (resolved ? "" : "*");
      if (r.stable && r.error_q > 0) s.points.push_back({r.cpu_s_per_sim_s, r.error_q, label, r.pareto});
      else if (!r.stable) steps[r.status] += (steps[r.status].empty() ? "" : ", ") + (r.setting.empty() ? short_number(r.dt * 1e3) : r.setting);
    }
    const bool adaptive = s.name == integrator_name(Integrator::DormandPrince);  // listed by rtol, not ms
    for (const auto& [status, list] : steps)
      left_out[status] += (left_out[status].empty() ? "" : "; ") + s.name + " " + list + (adaptive ? "" : " ms");
    if (any) plot.series.push_back(s);  // the study's integrators only
  }
  const Reference& ref = study.reference;
  plot.notes.push_back("Labels: time step in ms (dormand_prince: its rtol, output step the largest). Scene " + study.scene + ", " + short_number(study.config.duration) +
                       " s simulated; reference RK4 at " + short_number(ref.dt * 1e3) + " ms.");
  plot.notes.push_back("Reference self-check: halving its step changes q(T) by " + short_number(ref.self_error_q) +
                       " rad (* marks errors below 1000 x that).");
  plot.notes.push_back("Cost: CPU time of the simulating thread, median of " +
                       std::to_string(study.config.timing_repeats) + " interleaved rounds.");
  plot.notes.push_back("Every run: friction smoothing " + short_number(study.friction_velocity) +
                       " rad/s, Baumgarte frequency " + short_number(study.stabilisation_frequency) +
                       " rad/s (the scene's, at every step).");
  if (left_out.count("unstable"))
    plot.notes.push_back("Unstable (a step failed: NaN/Inf, or the solver or the substep control refused it), not plotted: " +
                         left_out["unstable"] + ".");
  if (left_out.count("diverged"))
    plot.notes.push_back("Diverged (finite, error > 1 rad), not plotted: " + left_out["diverged"] + ".");
  if (!left_out.empty()) plot.notes.push_back("Why each failed: the failure column of accuracy.csv.");
  return plot;
}

}  // namespace achd::cli
