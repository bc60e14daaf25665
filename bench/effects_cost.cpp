// What each effect costs (issue 4): KUKA LWR 4 from its default pose, effect sets from
// "gravity only, at rest" to "everything on, 6 constraints", each timed as one
// hybrid_dynamics solve and as one RK4 step of the Simulator (4 solves + the held
// directions' kinematics), in one run. Prints Google Benchmark's table, then a markdown
// table with the increment of each row over the previous one.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "achd/achd.hpp"
#include "achd/simulator.hpp"

namespace {

using namespace achd;

struct EffectSet {
  const char* name;
  std::uint32_t effects;
  bool moving;  // qd != 0
  int nc;       // held directions x, y, z, rx, ry, rz, in that order
};

const std::uint32_t kG = kGravity, kV = kVelocityProducts, kW = kExternalWrenches, kD = kDamping,
                    kF = kFriction, kR = kRotorInertia, kC = kConstraints;

const EffectSet kSets[] = {
    {"gravity, at rest", kG, false, 0},
    {"gravity, moving, no velocity products", kG, true, 0},
    {"+ velocity products", kG | kV, true, 0},
    {"+ damping", kG | kV | kD, true, 0},
    {"+ friction", kG | kV | kD | kF, true, 0},
    {"+ rotor inertia", kG | kV | kD | kF | kR, true, 0},
    {"+ external wrenches (every link)", kG | kV | kD | kF | kR | kW, true, 0},
    {"+ 1 constraint (z)", kAllEffects, true, 1},
    {"+ 3 constraints (x y z)", kAllEffects, true, 3},
    {"everything on, 6 constraints", kAllEffects, true, 6},
};
static_assert((kC & kAllEffects) != 0, "constraints are part of kAllEffects");

struct Robot {
  Model model;
  Eigen::VectorXd q0, qd0;
  std::vector<Vector6> f_ext;
};

Robot lwr() {
  Robot r{load_urdf_file(ACHD_ROBOTS_DIR "/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7"),
          Eigen::VectorXd(7), Eigen::VectorXd(7), {}};
  for (int i = 0; i < 7; ++i) r.model.set_rotor_inertia(i, 0.05);
  r.q0 << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  r.qd0 << 0.4, -0.3, 0.5, 0.2, -0.6, 0.7, -0.2;
  Vector6 w;
  w << 1, -2, 0.5, 0.1, 0.2, -0.1;
  r.f_ext.assign(r.model.num_links(), w);
  return r;
}

// One solve: the held directions of the simulator as a Case (alpha columns, beta = 0).
void solve(benchmark::State& st, const Robot& r, const EffectSet& s) {
  Case c = Case::zeros(r.model);
  c.q = r.q0;
  c.qd = s.moving ? r.qd0 : Eigen::VectorXd::Zero(7);
  if (s.effects & kExternalWrenches) c.f_ext = r.f_ext;
  c.alpha.setZero(6, s.nc);
  for (int k = 0; k < s.nc; ++k) c.alpha(k, k) = 1;
  c.beta.setZero(s.nc);
  Options o;
  o.effects = s.effects;
  Data d(r.model);
  for (auto _ : st) {
    hybrid_dynamics(r.model, d, c, o);
    benchmark::DoNotOptimize(d.qdd.data());
  }
}

// One RK4 step from the same state every time (the state is restored, 14 copies).
void step(benchmark::State& st, const Robot& r, const EffectSet& s) {
  SimulatorOptions o;
  o.effects = s.effects;
  o.limits = LimitPolicy::Ignore;
  Simulator sim(r.model, o);
  const Eigen::VectorXd qd = s.moving ? r.qd0 : Eigen::VectorXd::Zero(7);
  sim.reset(r.q0, qd);
  if (s.effects & kExternalWrenches) sim.f_ext = r.f_ext;
  for (int k = 0; k < s.nc; ++k) sim.set_direction(k, DirectionMode::Hold);
  for (auto _ : st) {
    sim.q = r.q0;
    sim.qd = qd;
    sim.step(1e-3);
    benchmark::DoNotOptimize(sim.q.data());
  }
}

class Collector : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, double> ns;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) ns[run.benchmark_name()] = run.GetAdjustedCPUTime();
    ConsoleReporter::ReportRuns(runs);
  }
};

}  // namespace

int main(int argc, char** argv) {
  const Robot robot = lwr();
  int row = 0;
  for (const EffectSet& s : kSets) {
    char id[8];
    std::snprintf(id, sizeof id, "%02d", row++);
    benchmark::RegisterBenchmark((std::string("solve/") + id).c_str(),
                                 [&robot, &s](benchmark::State& st) { solve(st, robot, s); });
    benchmark::RegisterBenchmark((std::string("rk4_step/") + id).c_str(),
                                 [&robot, &s](benchmark::State& st) { step(st, robot, s); });
  }
  benchmark::Initialize(&argc, argv);
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);

  std::printf("\nKUKA LWR 4 (7 joints), CPU ns, one run:\n\n");
  std::printf("| effect set | ns per solve | + over previous | ns per RK4 step |\n");
  std::printf("| --- | ---: | ---: | ---: |\n");
  double previous = 0;
  row = 0;
  for (const EffectSet& s : kSets) {
    char id[8];
    std::snprintf(id, sizeof id, "%02d", row);
    const double solve_ns = collector.ns[std::string("solve/") + id];
    const double step_ns = collector.ns[std::string("rk4_step/") + id];
    if (solve_ns > 0)
      std::printf("| %s | %.0f | %+.0f | %.0f |\n", s.name, solve_ns, row ? solve_ns - previous : 0.0, step_ns);
    previous = solve_ns;
    ++row;
  }
  return 0;
}
