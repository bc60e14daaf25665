// Google Benchmark: hybrid_dynamics() on the robots of robots/index.json and on generated
// chains of 7, 50, 200 and 1000 links, with 0, 1, 3 and 6 constraints and every input
// nonzero; with KDL found, KDL's ChainHdSolver_Vereshchagin on the same problems.
#include <benchmark/benchmark.h>

#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "random_chain.hpp"
#ifdef ACHD_HAVE_KDL
#include "kdl_problem.hpp"
#endif

namespace {

using namespace achd;

struct Problem {
  std::string name, urdf;  // urdf: XML text
  std::string root, tip;
  Model model;
  Case c;
};

void register_problem(const std::shared_ptr<Problem>& p) {
  const int nc = p->c.num_constraints();
  const std::string suffix = p->name + "/nc:" + std::to_string(nc);
  benchmark::RegisterBenchmark(("achd/" + suffix).c_str(), [p](benchmark::State& st) {
    Data d(p->model);
    for (auto _ : st) {
      hybrid_dynamics(p->model, d, p->c);
      benchmark::DoNotOptimize(d.qdd.data());
    }
    st.counters["ns_per_link"] = benchmark::Counter(
        static_cast<double>(st.iterations()) * p->model.num_rates(),
        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  });
#ifdef ACHD_HAVE_KDL
  benchmark::RegisterBenchmark(("kdl/" + suffix).c_str(), [p](benchmark::State& st) {
    cli::KdlProblem k(p->urdf, true, p->root, p->tip, p->c);
    for (auto _ : st) k.solve();
  });
#endif
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = bench::robots_dir();
  const nlohmann::json index = nlohmann::json::parse(read(dir + "/index.json"));
  for (const auto& r : index["robots"]) {
    if (!r.contains("tip")) continue;  // the chains: a tree entry has no tip
    const std::string file = r["urdf"].get<std::string>();
    const std::string urdf = read(dir + "/" + file.substr(file.rfind('/') + 1));
    const Model m = load_urdf_string(urdf, r["root"], r["tip"]);
    for (int nc : {0, 1, 3, 6}) {
      Case c = bench::random_case(m, nc, 1);
      for (int i = 0; i < m.num_rates(); ++i) c.q[i] = r["q0"][i].get<double>();
      register_problem(std::make_shared<Problem>(Problem{r["name"], urdf, r["root"], r["tip"], m, c}));
    }
  }
  for (int links : {7, 50, 200, 1000}) {
    const std::string urdf = bench::random_chain_urdf(links, 1);
    const std::string tip = "link" + std::to_string(links);
    const Model m = load_urdf_string(urdf, "link0", tip);
    for (int nc : {0, 1, 3, 6})
      register_problem(std::make_shared<Problem>(
          Problem{"chain" + std::to_string(links), urdf, "link0", tip, m, bench::random_case(m, nc, 2)}));
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
