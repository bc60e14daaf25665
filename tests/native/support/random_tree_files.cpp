// The random trees of the C++ suites (random_tree.hpp) as files, for the Node tests
// (tests/node/trees.test.mjs), so that the wasm module and the native CLI solve the same
// trees: `random_tree_files DIR SEED COUNT` writes, for k = 0 .. COUNT - 1 of
// for_random_trees(SEED, COUNT), DIR/tree<k>.urdf (tree_urdf) and DIR/case<k>.json, the
// tree's random_tree_case (random inputs and well-conditioned constraint blocks; inputs
// alone when no blocks were drawn) in the case JSON with joints and links by name, so that
// it does not depend on the loader's body order. Exit 2 with one line on stderr on error.
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "random_tree.hpp"

namespace {

using nlohmann::json;

template <typename V>
json numbers(const V& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v[i]);
  return out;
}

json case_json(const achd::Model& m, const achd::Case& c) {
  json j;
  j["q"] = json::object();
  j["qd"] = json::object();
  j["ff_torques"] = json::object();
  for (int i = 0; i < m.num_rates(); ++i) {
    const std::string& name = m.bodies[i].joint_name;
    j["q"][name] = c.q[i];
    if (c.qd.size()) j["qd"][name] = c.qd[i];
    if (c.ff_torques.size()) j["ff_torques"][name] = c.ff_torques[i];
  }
  j["gravity"] = numbers(c.gravity);
  j["f_ext"] = json::object();
  for (size_t l = 0; l < c.f_ext.size(); ++l) j["f_ext"][m.links[l].name] = numbers(c.f_ext[l]);
  j["constraints"] = json::array();
  for (const achd::ConstraintBlock& b : c.constraints) {
    json alpha = json::array();
    for (Eigen::Index k = 0; k < b.alpha.cols(); ++k) alpha.push_back(numbers(b.alpha.col(k)));
    j["constraints"].push_back(
        {{"link", m.links[b.link].name}, {"alpha", alpha}, {"beta", numbers(b.beta)}, {"point", numbers(b.point)}});
  }
  return j;
}

void write(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) throw std::runtime_error(path + ": cannot write");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc != 4) throw std::runtime_error("usage: random_tree_files DIR SEED COUNT");
    const std::string dir = argv[1];
    const unsigned seed = static_cast<unsigned>(std::stoul(argv[2]));
    const int count = std::stoi(argv[3]);
    int k = 0;
    achd::test::for_random_trees(seed, count, [&](const achd::test::RandomTree& tree, std::mt19937& rng) {
      const std::optional<achd::Case> c = achd::test::random_tree_case(rng, tree.model);
      const achd::Case inputs = c ? *c : achd::test::random_tree_inputs(rng, tree.model);
      write(dir + "/tree" + std::to_string(k) + ".urdf", achd::test::tree_urdf(tree.links));
      write(dir + "/case" + std::to_string(k) + ".json", case_json(tree.model, inputs).dump());
      ++k;
    });
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "random_tree_files: error: " << e.what() << "\n";
    return 2;
  }
}
