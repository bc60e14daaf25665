// bench_trees: what trees and constraint blocks cost, every number a ratio of two solves
// timed side by side in one run (interleaved rounds, medians of per-round ratios):
//   - the quadruped holding its four feet in 3D (m = 12) over its unconstrained solve;
//   - the dual-arm torso holding both hands in 6D (m = 12) over its unconstrained solve;
//   - the quadruped's feet held pairwise together (relative blocks, m = 6) over two of its
//     feet held (m = 6);
//   - the Delta robot closed by its five loop joints (m = 15) over its open tree;
//   - with a floating base: the quadruped on its four feet in 3D and the humanoid (30
//     joints) on its two soles in 6D (m = 12 each), over their unconstrained solves;
//   - a random tree of 200 bodies over one of 100, both with four blocks of 3 columns
//     on their deepest links (cost linear in n at fixed m);
//   - an unconstrained random tree over a random chain with as many joints;
//   - the quadruped with 60 massless frames on fixed joints added over the quadruped, both
//     solved without link outputs (Data::set_link_outputs({})): frames that carry nothing
//     cost nothing.
// Prints a markdown table, then one JSON line.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "random_chain.hpp"
#include "random_tree.hpp"
#include "scene_json.hpp"
#include "timing.hpp"

namespace {

using namespace achd;

std::string read(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Median per-round ratio t(a) / t(b), and both medians, of two solves timed side by side.
struct Ratio {
  double a_ns, b_ns, ratio;
};

// link_outputs false: both solves compute no link's acceleration.
Ratio side_by_side(const Model& ma, const Case& ca, const Model& mb, const Case& cb, bool link_outputs = true) {
  Data da(ma), db(mb);
  if (!link_outputs) {
    da.set_link_outputs({});
    db.set_link_outputs({});
  }
  const std::vector<std::function<void()>> fns = {[&] { hybrid_dynamics(ma, da, ca); },
                                                  [&] { hybrid_dynamics(mb, db, cb); }};
  std::vector<long> iterations;
  for (const auto& f : fns) iterations.push_back(cli::calibrate_iterations(f, 5e6));
  const std::vector<std::vector<double>> ns = cli::sample_ns(fns, iterations, 51);
  return {cli::median(ns[0]), cli::median(ns[1]), cli::median_ratio(ns[0], ns[1])};
}

// The robot's index.json default pose, every other input of random_tree_inputs.
Case robot_case(const Model& m, const nlohmann::json& entry, std::mt19937& rng) {
  Case c = test::random_tree_inputs(rng, m);
  c.gravity = Vector3(0, 0, -9.81);
  for (int i = 0; i < m.num_rates(); ++i) c.q[i] = entry["q0"][i].get<double>();  // model order
  return c;
}

// Blocks of `columns` unit columns (the first `columns` of the identity: 3 = the point's
// position, 6 = its pose) at the origins of `links`.
Case held(const Model& m, Case c, const std::vector<std::string>& links, int columns) {
  for (const std::string& name : links) {
    ConstraintBlock b;
    b.link = m.link_index(name);
    b.alpha = ConstraintMatrix::Identity(6, columns);
    b.beta = ConstraintVector::Zero(columns);
    c.constraints.push_back(b);
  }
  return c;
}

// The URDF with `frames` massless links added, each on a fixed joint below one of the
// robot's links (in turn), at an offset and a turn of its own.
std::string with_frames(const std::string& urdf, const Model& m, int frames) {
  std::string added;
  for (int k = 0; k < frames; ++k) {
    const std::string name = "frame_" + std::to_string(k);
    const int parent = k % (m.num_links() + 1);
    added += "<joint name=\"" + name + "_joint\" type=\"fixed\"><parent link=\"" +
             (parent ? m.links[parent - 1].name : m.root_name) + "\"/><child link=\"" + name +
             "\"/><origin xyz=\"0.01 " + std::to_string(0.01 * (k % 10)) + " -0.02\" rpy=\"0.1 0 " +
             std::to_string(0.1 * k) + "\"/></joint><link name=\"" + name + "\"/>\n";
  }
  const std::size_t end = urdf.rfind("</robot>");
  return urdf.substr(0, end) + added + urdf.substr(end);
}

}  // namespace

int main() {
  const std::string robots = bench::robots_dir();
  const nlohmann::json index = nlohmann::json::parse(read(robots + "/index.json"));
  auto entry = [&](const std::string& name) {
    for (const auto& r : index["robots"])
      if (r["name"] == name) return r;
    throw std::runtime_error("robots/index.json has no " + name);
  };
  std::mt19937 rng(15);
  struct Line {
    std::string measure, target;
    Ratio r;
    double limit;
  };
  std::vector<Line> lines;

  for (const auto& [name, links, columns] :
       std::vector<std::tuple<std::string, std::vector<std::string>, int>>{
           {"quadruped", {"lf_foot", "rf_foot", "lh_foot", "rh_foot"}, 3},
           {"dual_arm_torso", {"left_hand", "right_hand"}, 6}}) {
    const nlohmann::json e = entry(name);
    const Model m = load_urdf_string(read(robots + "/../" + e["urdf"].get<std::string>()), e["root"], "");
    const Case free = robot_case(m, e, rng), constrained = held(m, free, links, columns);
    lines.push_back({name + " holding " + std::to_string(links.size()) + " links (m = " +
                         std::to_string(constrained.num_constraints()) + ") / unconstrained",
                     "<= 2", side_by_side(m, constrained, m, free), 2});
  }

  // Relative blocks: the quadruped's front feet held together in 3D and its hind feet
  // likewise (two relative blocks, m = 6) over its two front feet held in 3D (two blocks
  // on one link each, m = 6). (Six relative columns between the front feet alone would be
  // singular: no joint of this quadruped turns one foot about z relative to the other.)
  {
    const nlohmann::json e = entry("quadruped");
    const Model m = load_urdf_string(read(robots + "/../" + e["urdf"].get<std::string>()), e["root"], "");
    const Case free = robot_case(m, e, rng), absolute = held(m, free, {"lf_foot", "rf_foot"}, 3);
    Case relative = held(m, free, {"lf_foot", "lh_foot"}, 3);
    relative.constraints[0].link_b = m.link_index("rf_foot");
    relative.constraints[1].link_b = m.link_index("rh_foot");
    lines.push_back({"quadruped, feet held pairwise together (two relative blocks, m = 6) / two feet held (m = 6)",
                     "<= 1.5", side_by_side(m, relative, m, absolute), 1.5});
  }

  // Loop joints: the Delta robot at its scene's closed start pose with its five spherical
  // loops (m = 15) over its open tree (the same URDF loaded without them, the same inputs).
  {
    const cli::Scene scene = cli::load_scene(robots + "/scenes/delta_pd.json");
    const Model& closed = scene.model;
    const Model open = load_urdf_file(scene.urdf, scene.root, "");
    Case c = test::random_tree_inputs(rng, open);
    c.gravity = Vector3(0, 0, -9.81);
    c.q = scene.q0;
    lines.push_back({"Delta robot, its five loop joints (m = " + std::to_string(closed.num_loop_columns()) +
                         ") / its open tree",
                     "<= 2", side_by_side(closed, c, open, c), 2});
  }

  // Floating bases (a free joint above the root link): the quadruped on its four feet in 3D
  // and the humanoid (30 joints, 36 rates) on its two soles in 6D, m = 12 each.
  for (const auto& [name, links, columns] :
       std::vector<std::tuple<std::string, std::vector<std::string>, int>>{
           {"quadruped", {"lf_foot", "rf_foot", "lh_foot", "rh_foot"}, 3},
           {"humanoid", {"l_sole", "r_sole"}, 6}}) {
    const nlohmann::json e = entry(name);
    UrdfOptions options;
    options.floating = true;
    const Model m = load_urdf_string(read(robots + "/../" + e["urdf"].get<std::string>()), e["root"], "", options);
    Case free = test::random_tree_inputs(rng, m);
    free.gravity = Vector3(0, 0, -9.81);
    free.q = Eigen::VectorXd::Zero(m.num_positions());
    free.q[2] = 0.5;  // the root 0.5 m up, upright: [x, y, z, qx, qy, qz, qw]
    free.q[6] = 1;
    for (int i = 0; i + 7 < m.num_positions(); ++i) free.q[7 + i] = e["q0"][i].get<double>();
    const Case constrained = held(m, free, links, columns);
    lines.push_back({name + ", floating, holding " + std::to_string(links.size()) + " links (m = " +
                         std::to_string(constrained.num_constraints()) + ") / unconstrained",
                     "<= 2", side_by_side(m, constrained, m, free), 2});
  }

  // Four blocks of 3 columns (m = 12, as the quadruped's feet) on the four deepest links
  // (on distinct bodies) of random trees of 200 and 100 bodies; a tree whose blocks are
  // not well conditioned is drawn again.
  std::vector<Model> trees;
  std::vector<Case> cases;
  for (int n : {200, 100}) {
    for (int attempt = 0;; ++attempt) {
      if (attempt == 20) throw std::runtime_error("no well-conditioned blocks on 20 random trees of " + std::to_string(n));
      test::RandomTree t = test::random_tree(rng, n);
      const Model& m = t.model;
      std::vector<int> depth(m.num_rates());
      for (int i = 0; i < m.num_rates(); ++i) depth[i] = m.bodies[i].parent < 0 ? 1 : depth[m.bodies[i].parent] + 1;
      std::vector<int> order(m.num_links());
      for (int l = 0; l < m.num_links(); ++l) order[l] = l;
      auto link_depth = [&](int l) { return m.links[l].body < 0 ? 0 : depth[m.links[l].body]; };
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return link_depth(a) > link_depth(b); });
      std::vector<int> held, bodies;
      for (int l : order)
        if (held.size() < 4 && m.links[l].body >= 0 &&
            std::find(bodies.begin(), bodies.end(), m.links[l].body) == bodies.end()) {
          held.push_back(l);
          bodies.push_back(m.links[l].body);
        }
      std::optional<Case> c = test::with_blocks_on(rng, m, test::random_tree_inputs(rng, m), held, 3, 1e8);
      if (!c) continue;
      trees.push_back(m);
      cases.push_back(*c);
      break;
    }
  }
  lines.push_back({"random tree, 200 bodies / 100 bodies, four blocks of 3 (m = 12)", "<= 2.3",
                   side_by_side(trees[0], cases[0], trees[1], cases[1]), 2.3});

  // An unconstrained random tree against a random chain with as many joints.
  test::RandomTree tree = test::random_tree(rng, 60), chain = test::random_tree(rng, 60, true);
  lines.push_back({"random tree / random chain, 60 joints, unconstrained", "<= 1.3",
                   side_by_side(tree.model, test::random_tree_inputs(rng, tree.model), chain.model,
                                test::random_tree_inputs(rng, chain.model)),
                   1.3});

  // Links that carry nothing: the quadruped with 60 massless frames on fixed joints (sensor
  // and marker frames) over the quadruped, the same inputs, no link outputs asked for.
  {
    const nlohmann::json e = entry("quadruped");
    const std::string urdf = read(robots + "/../" + e["urdf"].get<std::string>());
    const Model m = load_urdf_string(urdf, e["root"], "");
    const Model framed = load_urdf_string(with_frames(urdf, m, 60), e["root"], "");
    Case c = robot_case(m, e, rng);
    c.f_ext.clear();  // no wrench on any link (one per link would differ between the two)
    lines.push_back({"quadruped with 60 massless fixed frames (" + std::to_string(framed.num_links()) +
                         " links) / without (" + std::to_string(m.num_links()) + "), no link outputs",
                     "<= 1.02", side_by_side(framed, c, m, c, false), 1.02});
  }

  nlohmann::json out;
  std::printf("| measure | ns | reference ns | ratio | target |\n|---|---|---|---|---|\n");
  for (const Line& l : lines) {
    std::printf("| %s | %.0f | %.0f | %.3f | %s |\n", l.measure.c_str(), l.r.a_ns, l.r.b_ns, l.r.ratio,
                l.target.c_str());
    out["rows"].push_back({{"measure", l.measure}, {"ns", l.r.a_ns}, {"reference_ns", l.r.b_ns},
                           {"ratio", l.r.ratio}, {"limit", l.limit}});
  }
  std::printf("\n%s\n", out.dump().c_str());
  return 0;
}
