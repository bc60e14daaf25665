// bench_ratios: the ratio table of docs/performance.md, every number
// measured side by side in one run (achd and KDL repeats interleaved, medians). Prints a
// markdown table, then one JSON line.
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "random_chain.hpp"
#include "timing.hpp"
#ifdef ACHD_HAVE_KDL
#include "kdl_problem.hpp"
#endif

namespace {

using namespace achd;

struct Row {
  std::string problem;
  int nc;
  double achd_ns, kdl_ns;  // medians; kdl_ns = 0: not measured
  double ratio;            // median of the per-round ratios achd / KDL
  double t6_over_t0 = 0;   // nc = 6 rows: median per-round achd t(6) / t(0)
  double qdd_diff;         // max|qdd_achd - qdd_kdl| / max(1, max|qdd_kdl|): same problem?
};

// achd and KDL with 0 and 6 constraints on one chain, all four interleaved.
std::vector<Row> measure(const std::string& name, const std::string& urdf, const std::string& root,
                         const std::string& tip, const Eigen::VectorXd* q0, unsigned seed,
                         bool with_kdl) {
  const Model m = load_urdf_string(urdf, root, tip);
  std::vector<Case> cases;
  for (int nc : {0, 6}) {
    cases.push_back(bench::random_case(m, nc, seed));
    if (q0) cases.back().q = *q0;
  }
  std::vector<std::unique_ptr<Data>> data;
  std::vector<std::function<void()>> fns;
  for (const Case& c : cases) {
    data.push_back(std::make_unique<Data>(m));
    Data* d = data.back().get();
    fns.push_back([&m, d, &c] { hybrid_dynamics(m, *d, c); });
  }
#ifdef ACHD_HAVE_KDL
  std::vector<std::unique_ptr<cli::KdlProblem>> kdl;
  if (with_kdl)
    for (const Case& c : cases) {
      kdl.push_back(std::make_unique<cli::KdlProblem>(urdf, true, root, tip, c));
      cli::KdlProblem* k = kdl.back().get();
      fns.push_back([k] { k->solve(); });
    }
#else
  with_kdl = false;
#endif
  std::vector<long> iterations;
  for (const auto& f : fns) iterations.push_back(cli::calibrate_iterations(f, 5e6));
  const std::vector<std::vector<double>> ns = cli::sample_ns(fns, iterations, 51);
  std::vector<Row> rows;
  for (int k = 0; k < 2; ++k) {
    Row r{name, 6 * k, cli::median(ns[k]), 0, 0, 0, 0};
#ifdef ACHD_HAVE_KDL
    if (with_kdl) {
      r.kdl_ns = cli::median(ns[2 + k]);
      r.ratio = cli::median_ratio(ns[k], ns[2 + k]);
      const Eigen::VectorXd q = kdl[k]->qdd();
      r.qdd_diff = (data[k]->qdd - q).cwiseAbs().maxCoeff() / std::max(1.0, q.cwiseAbs().maxCoeff());
    }
#endif
    rows.push_back(r);
  }
  // t(6)/t(0) as a median of per-round ratios as well.
  rows[1].t6_over_t0 = cli::median_ratio(ns[1], ns[0]);
  return rows;
}

// ns per link at 1000 links over ns per link at 50 (no constraints), the two timed in
// the same interleaved rounds; the median of the per-round ratios.
double per_link_growth() {
  const Model m50 = load_urdf_string(bench::random_chain_urdf(50, 4), "link0", "link50");
  const Model m1000 = load_urdf_string(bench::random_chain_urdf(1000, 5), "link0", "link1000");
  const Case c50 = bench::random_case(m50, 0, 4), c1000 = bench::random_case(m1000, 0, 5);
  Data d50(m50), d1000(m1000);
  const std::vector<std::function<void()>> fns = {[&] { hybrid_dynamics(m50, d50, c50); },
                                                  [&] { hybrid_dynamics(m1000, d1000, c1000); }};
  std::vector<long> iterations;
  for (const auto& f : fns) iterations.push_back(cli::calibrate_iterations(f, 5e6));
  const std::vector<std::vector<double>> ns = cli::sample_ns(fns, iterations, 51);
  return cli::median_ratio(ns[1], ns[0]) * 50.0 / 1000.0;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

int main() {
  std::vector<Row> rows;
  auto add = [&](std::vector<Row> r) { rows.insert(rows.end(), r.begin(), r.end()); };
  // The 7-DoF arm at its index.json pose, every other input random and nonzero.
  const nlohmann::json index = nlohmann::json::parse(read(bench::robots_dir() + "/index.json"));
  for (const auto& r : index["robots"])
    if (r["name"] == "kuka_lwr4") {
      Eigen::VectorXd q0(r["q0"].size());
      for (Eigen::Index i = 0; i < q0.size(); ++i) q0[i] = r["q0"][i].get<double>();
      add(measure("kuka_lwr4", read(bench::robots_dir() + "/kuka_lwr4.urdf"), r["root"], r["tip"],
                  &q0, 1, true));
    }
  for (unsigned seed : {1u, 2u, 3u})
    add(measure("random7 seed " + std::to_string(seed), bench::random_chain_urdf(7, seed), "link0",
                "link7", nullptr, seed, true));
  for (int links : {50, 200})
    add(measure("random" + std::to_string(links), bench::random_chain_urdf(links, 4), "link0",
                "link" + std::to_string(links), nullptr, 4, true));
  add(measure("random1000", bench::random_chain_urdf(1000, 5), "link0", "link1000", nullptr, 5, false));

  nlohmann::json out;
  std::printf("| problem | nc | achd ns | KDL ns | achd/KDL | qdd rel. diff |\n|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    std::printf("| %s | %d | %.0f | %.0f | %s | %.1e |\n", r.problem.c_str(), r.nc, r.achd_ns,
                r.kdl_ns, r.kdl_ns > 0 ? std::to_string(r.ratio).substr(0, 5).c_str() : "-",
                r.qdd_diff);
    out["rows"].push_back({{"problem", r.problem}, {"nc", r.nc}, {"achd_ns", r.achd_ns},
                           {"kdl_ns", r.kdl_ns}, {"ratio", r.ratio}, {"qdd_rel_diff", r.qdd_diff}});
  }
  auto find = [&](const std::string& p, int nc) {
    for (const Row& r : rows)
      if (r.problem == p && r.nc == nc) return r;
    return Row{};
  };
  const double t7 = find("kuka_lwr4", 6).t6_over_t0;
  const double t200 = find("random200", 6).t6_over_t0;
  const double per_link = per_link_growth();
  std::printf("\n| measure | value | target |\n|---|---|---|\n");
  std::printf("| t(6)/t(0), 7-DoF arm | %.3f | <= 1.8 |\n", t7);
  std::printf("| t(6)/t(0), 200 links | %.3f | <= 1.3 |\n", t200);
  std::printf("| ns/link at 1000 / ns/link at 50 | %.3f | <= 1.2 |\n", per_link);
  out["t6_over_t0_7"] = t7;
  out["t6_over_t0_200"] = t200;
  out["ns_per_link_1000_over_50"] = per_link;
  std::printf("\n%s\n", out.dump().c_str());
  return 0;
}
