#pragma once
// The accuracy study as tables (CSV, JSON) and as the error-versus-cost plot.
#include <string>

#include <nlohmann/json.hpp>

#include "accuracy_study.hpp"
#include "svg_plot.hpp"

namespace achd::cli {

// One row per run: kind, integrator, setting, dt_s, steps, stable, status, error_q_rad,
// error_qd_rad_s, change_q_rad, energy_drift, held_drift_m, held_drift_rad, substeps,
// stiff_substeps, rejected_substeps, ns_per_step, cpu_s_per_sim_s, order, pareto,
// resolved_by_reference (integrator rows, as the JSON's: false when the error is below
// 1000 x the reference's own), failure. Unstable and diverged runs have empty errors and
// say why in failure.
std::string study_csv(const Study& study);
// The configuration, the reference and its self-check, and the same rows.
nlohmann::ordered_json study_json(const Study& study);
// log-log error (rad) against cost (s per simulated s), one line per integrator,
// stable runs only; unstable and diverged ones are named in notes.
LogLogPlot study_plot(const Study& study, const std::string& title);

}  // namespace achd::cli
