// What each effect costs (docs/performance.md's table): KUKA LWR 4 from its default pose, effect
// sets from "gravity only, at rest" to "everything on, 6 constraints", each timed as one
// hybrid_dynamics solve and as one RK4 step of the Simulator (4 solves + the held
// directions' kinematics), in one run: every row's solve and step are timed in each of 31
// interleaved rounds (thread CPU time, tools/timing.hpp), so that the shared machine's
// speed changes hit all rows alike. Prints the medians as a markdown table with the
// increment of each row over the previous one. The last rows add the drivers (prescribed joints, driver weights, virtual wrenches) to
// the 3-constraint row, each measured against that row: one prescribed joint (the solve:
// a given qdd; the step: a sine), driver weights below 1 (w_fext = w_ff = 0.5 on z), and
// virtual wrenches on every link (the solve only: the simulator takes none).
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "achd/achd.hpp"
#include "achd/simulator.hpp"
#include "timing.hpp"

namespace {

using namespace achd;

enum class Driver { None, Prescribed, Weights, Virtual };

struct EffectSet {
  const char* name;
  std::uint32_t effects;
  bool moving;  // qd != 0
  int nc;       // held directions x, y, z, rx, ry, rz, in that order
  Driver driver = Driver::None;
  int base = -1;  // the row its increment is measured against (-1: the previous one)
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
    {"3 constraints + 1 prescribed joint", kAllEffects, true, 3, Driver::Prescribed, 8},
    {"3 constraints + weights below 1 (z)", kAllEffects, true, 3, Driver::Weights, 8},
    {"3 constraints + virtual wrenches (every link)", kAllEffects, true, 3, Driver::Virtual, 8},
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
struct Solve {
  Solve(const Robot& r, const EffectSet& s) : model(r.model), c(Case::zeros(r.model)), d(r.model) {
    c.q = r.q0;
    c.qd = s.moving ? r.qd0 : Eigen::VectorXd::Zero(7);
    if (s.effects & kExternalWrenches) c.f_ext = r.f_ext;
    c.alpha.setZero(6, s.nc);
    for (int k = 0; k < s.nc; ++k) c.alpha(k, k) = 1;
    c.beta.setZero(s.nc);
    o.effects = s.effects;
    if (s.driver == Driver::Prescribed) {
      c.qdd_given = Eigen::VectorXd::Zero(7);
      c.qdd_given[0] = 0.5;
      c.prescribed.assign(7, false);
      c.prescribed[0] = true;
    }
    if (s.driver == Driver::Weights) {
      c.w_fext = c.w_ff = ConstraintVector::Ones(s.nc);
      c.w_fext[2] = c.w_ff[2] = 0.5;
    }
    if (s.driver == Driver::Virtual) c.f_virtual = r.f_ext;
  }
  void operator()() { hybrid_dynamics(model, d, c, o); }
  const Model& model;
  Case c;
  Data d;
  Options o;
};

// One RK4 step from the same state every time (the state is restored, 14 copies).
struct Step {
  Step(const Robot& r, const EffectSet& s)
      : q0(r.q0), qd0(s.moving ? r.qd0 : Eigen::VectorXd::Zero(7)), sim(r.model, options(s)) {
    sim.reset(q0, qd0);
    if (s.effects & kExternalWrenches) sim.f_ext = r.f_ext;
    if (s.driver == Driver::Prescribed) {
      JointMotion m;
      m.kind = MotionKind::Sine;
      m.position = q0[0];
      m.amplitude = 0.3;
      m.frequency = 0.5;
      sim.prescribe(0, m);
      q0 = sim.q;  // started on its trajectory
      qd0 = sim.qd;
    }
    if (s.driver == Driver::Weights) sim.set_direction_weights(2, 0.5, 0.5);
    for (int k = 0; k < s.nc; ++k) sim.set_direction(k, DirectionMode::Hold);
  }
  static SimulatorOptions options(const EffectSet& s) {
    SimulatorOptions o;
    o.integrator = Integrator::RK4;  // the column's integrator (not the simulator's default)
    o.effects = s.effects;
    o.limits = LimitPolicy::Ignore;
    return o;
  }
  void operator()() {
    sim.q = q0;
    sim.qd = qd0;
    sim.t = 0;
    sim.step(1e-3);
  }
  Eigen::VectorXd q0, qd0;
  Simulator sim;
};

}  // namespace

int main() {
  const Robot robot = lwr();
  std::vector<std::unique_ptr<Solve>> solves;
  std::vector<std::unique_ptr<Step>> steps;
  std::vector<std::function<void()>> fns;
  for (const EffectSet& s : kSets) {
    solves.push_back(std::make_unique<Solve>(robot, s));
    steps.push_back(std::make_unique<Step>(robot, s));
  }
  for (auto& f : solves) fns.push_back([p = f.get()] { (*p)(); });
  for (auto& f : steps) fns.push_back([p = f.get()] { (*p)(); });
  std::vector<long> iterations;
  for (const auto& f : fns) iterations.push_back(cli::calibrate_iterations(f, 2e6));
  const std::vector<std::vector<double>> ns = cli::sample_ns(fns, iterations, 31);
  const int rows = static_cast<int>(solves.size());
  std::printf("KUKA LWR 4 (7 joints), CPU ns, medians of 31 interleaved rounds:\n\n");
  std::printf("| effect set | ns per solve | + over previous | ns per RK4 step |\n");
  std::printf("| --- | ---: | ---: | ---: |\n");
  for (int row = 0; row < rows; ++row) {
    const double solve_ns = cli::median(ns[row]), step_ns = cli::median(ns[rows + row]);
    const int base = kSets[row].base >= 0 ? kSets[row].base : row - 1;
    const double increment = row ? solve_ns - cli::median(ns[base]) : 0.0;
    const std::string over = kSets[row].base >= 0 ? std::string(" (over row ") + std::to_string(base + 1) + ")" : "";
    if (kSets[row].driver == Driver::Virtual)  // the simulator has no virtual wrenches
      std::printf("| %s | %.0f | %+.0f%s | - |\n", kSets[row].name, solve_ns, increment, over.c_str());
    else
      std::printf("| %s | %.0f | %+.0f%s | %.0f |\n", kSets[row].name, solve_ns, increment, over.c_str(), step_ns);
  }
  return 0;
}
