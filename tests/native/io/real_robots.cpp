// The robots people have: every URDF of the example-robot-data collection
// (robots/example-robot-data, vendored texts) loads as a whole tree with the default
// options (which hold a joint that moves no mass), or with the one option its error line
// names (--floating for a tree with no movable joint, --inertia repair for an inertia
// that is not physical), at most 6 of the 69 needing one, or is a malformed file refused
// with a one-line error. Each robot that loads solves at a pose within its
// limits under gravity with finite results that RNEA reproduces. The user guide's table
// (docs/guide/real-robots.md) is checked row by row against what the loader does, so it
// stays true; on a mismatch the measured table is written beside the test binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "achd/achd.hpp"

namespace achd::test {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(ACHD_SOURCE_DIR) / "robots" / "example-robot-data";
const fs::path kGuide = fs::path(ACHD_SOURCE_DIR) / "docs" / "guide" / "real-robots.md";

std::vector<std::string> corpus_urdfs() {
  std::vector<std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(kCorpus))
    if (entry.is_regular_file() && entry.path().extension() == ".urdf")
      out.push_back(fs::relative(entry.path(), kCorpus).generic_string());
  std::sort(out.begin(), out.end());
  return out;
}

// How one URDF loads: the options it needed ("defaults" or the one option its error
// named), its movable joints and links (root included), its warnings; or the error.
struct Outcome {
  std::string loads_with;
  int joints = 0, links = 0, warnings = 0;
  std::string error;  // the first error (whatever loads_with then says)
  Model model;
};

Outcome load(const std::string& file) {
  Outcome out;
  const std::string path = (kCorpus / file).string();
  UrdfOptions options;
  std::vector<std::string> named;  // the options the errors named, in turn
  for (;;) {
    try {
      out.model = load_urdf_file(path, "", "", options);
      break;
    } catch (const Error& e) {
      const std::string error = e.what();
      if (out.error.empty()) out.error = error;
      if (!options.floating && error.find("--floating") != std::string::npos) {
        options.floating = true;
        named.push_back("--floating");
      } else if (options.inertia != InertiaPolicy::Repair && error.find("--inertia repair") != std::string::npos) {
        options.inertia = InertiaPolicy::Repair;
        named.push_back("--inertia repair");
      } else if (options.mimic != MimicJoints::Independent && error.find("--mimic independent") != std::string::npos) {
        options.mimic = MimicJoints::Independent;
        named.push_back("--mimic independent");
      } else {
        out.error = error;
        out.loads_with = "refused";
        return out;
      }
    }
  }
  for (const std::string& o : named) out.loads_with += (out.loads_with.empty() ? "" : " ") + o;
  if (named.empty()) out.loads_with = "defaults";
  out.joints = out.model.num_rates() - (out.model.floating ? 6 : 0);
  out.links = out.model.num_links() + 1;
  out.warnings = static_cast<int>(out.model.warnings.size());
  return out;
}

std::string table_row(const std::string& file, const Outcome& o) {
  std::ostringstream row;
  row << "| `" << file << "` | " << o.joints << " | " << o.links << " | " << o.loads_with << " | " << o.warnings
      << " |";
  return row.str();
}

// The guide's table rows by URDF: "| `file` | joints | links | loads with | warnings |".
std::map<std::string, std::string> guide_rows() {
  std::ifstream in(kGuide);
  std::map<std::string, std::string> rows;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("| `", 0) == 0) rows[line.substr(3, line.find('`', 3) - 3)] = line;
  return rows;
}

TEST(RealRobots, EveryUrdfOfTheCollectionLoadsOrNamesItsOption) {
  const std::vector<std::string> files = corpus_urdfs();
  ASSERT_EQ(files.size(), 69u) << "the vendored collection has 69 URDFs";
  const std::map<std::string, std::string> guide = guide_rows();
  std::string measured = "| URDF | joints | links | loads with | warnings |\n|---|---|---|---|---|\n";
  int with_option = 0, refused = 0, mismatched = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const Outcome o = load(file);
    const std::string row = table_row(file, o);
    measured += row + "\n";
    const auto it = guide.find(file);
    if (it == guide.end() || it->second != row) {
      ++mismatched;
      ADD_FAILURE() << "docs/guide/real-robots.md has " << (it == guide.end() ? "no row" : it->second)
                    << "\n  measured: " << row;
    }
    if (o.loads_with == "refused") {
      ++refused;
      std::printf("refused: %s\n", o.error.c_str());
      EXPECT_EQ(o.error.find('\n'), std::string::npos) << "one line: " << o.error;
      EXPECT_EQ(o.error.rfind((kCorpus / file).string() + ":", 0), 0u) << "names the file: " << o.error;
      continue;
    }
    if (o.loads_with != "defaults") {
      ++with_option;
      // The error named the option and said why, in one line.
      EXPECT_EQ(o.error.find('\n'), std::string::npos) << o.error;
    }
    // Every warning names the link or joint it is about.
    for (const std::string& w : o.model.warnings)
      EXPECT_TRUE(w.rfind("link '", 0) == 0 || w.rfind("joint '", 0) == 0) << w;

    // A solve at rest under gravity: finite, and RNEA at the solved qdd gives back
    // joint_torques (the coupled joints' torques -C^T nu_c; zero without couplings),
    // relative to the gravity torques.
    const Model& model = o.model;
    Case c = Case::zeros(model);
    c.q = default_pose(model);
    Data data(model);
    hybrid_dynamics(model, data, c);
    ASSERT_TRUE(data.qdd.allFinite());
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.num_rates());
    const Eigen::VectorXd gravity_torques = rnea(model, c.q, zero, zero, c.gravity);
    const Eigen::VectorXd tau = rnea(model, c.q, zero, data.qdd, c.gravity);
    EXPECT_LE((tau - data.joint_torques).cwiseAbs().maxCoeff(),
              1e-8 * std::max(1.0, gravity_torques.cwiseAbs().maxCoeff()));
    if (model.couplings.empty()) EXPECT_LE(data.joint_torques.cwiseAbs().maxCoeff(), 0.0);
  }
  EXPECT_EQ(guide.size(), files.size()) << "the guide's table lists every URDF once";
  if (mismatched) {
    const fs::path out = fs::path(ACHD_BINARY_DIR) / "real_robots_table.md";
    std::ofstream(out) << measured;
    ADD_FAILURE() << "the measured table is in " << out;
  }
  std::printf("%zu URDFs: %zu load with the defaults, %d with one option, %d refused\n", files.size(),
              files.size() - with_option - refused, with_option, refused);
  EXPECT_LE(with_option, 6) << "at most 6 of the 69 URDFs need an option";
  EXPECT_EQ(refused, 2) << "only the two malformed files are refused";
}

}  // namespace
}  // namespace achd::test
