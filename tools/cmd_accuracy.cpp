// achd accuracy SCENE.json [--out DIR] [--quick]: the accuracy-versus-time study of a
// scene (accuracy_study.hpp). Writes DIR/accuracy.{csv,json,svg} and prints the JSON on
// stdout.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "accuracy_report.hpp"
#include "args.hpp"
#include "commands.hpp"

namespace achd::cli {
namespace {

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out || !(out << text)) throw Error(path.string() + ": cannot write file");
}

}  // namespace

int cmd_accuracy(int argc, char** argv) {
  const Args args(argc, argv, {"--out"}, {"--quick"});
  if (args.positional().size() != 1) throw Error("accuracy: expected one scene file, see `achd help`");
  const Scene scene = load_scene(args.positional()[0]);
  const Study study = run_study(scene, default_config(scene, args.has("--quick")));
  const nlohmann::ordered_json json = study_json(study);
  if (args.has("--out")) {
    const std::filesystem::path dir = args.get("--out");
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error("--out: cannot create directory " + dir.string() + ": " + ec.message());
    write_file(dir / "accuracy.csv", study_csv(study));
    write_file(dir / "accuracy.json", json.dump(2) + "\n");
    const std::string title = "Accuracy versus cost: " + std::filesystem::path(scene.source).stem().string();
    write_file(dir / "accuracy.svg", render_svg(study_plot(study, title)));
  }
  std::cout << json.dump(2) << "\n";
  return 0;
}

}  // namespace achd::cli
