// achd accuracy SCENE.json [--out DIR] [--quick]: the accuracy-versus-time study of a
// scene (accuracy_study.hpp). Writes DIR/accuracy.{csv,json,svg} and prints the JSON on
// stdout. A study that lasts more than a second shows progress on stderr; Ctrl-C stops
// it (exit 130) before any file is written; a study beyond kMaxStudySteps is refused.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "accuracy_report.hpp"
#include "args.hpp"
#include "commands.hpp"
#include "output_file.hpp"
#include "progress.hpp"
#include "urdf_options.hpp"

namespace achd::cli {

int cmd_accuracy(int argc, char** argv) {
  const Args args(argc, argv, {"--out"}, {"--quick"});
  if (args.positional().size() != 1) throw Error("accuracy: expected one scene file, see `achd help`");
  const Scene scene = load_scene(args.positional()[0]);
  print_warnings(scene.model, scene.urdf);
  const StudyConfig config = default_config(scene, args.has("--quick"));
  const double planned = planned_steps(scene, config);
  catch_interrupt();
  Progress progress([&](std::int64_t done) {
    // The plan is an estimate: a reference refined further (its error above a tenth of
    // the best row's) or an adaptive row's substeps can take more, and a percentage past
    // 100 would say nothing.
    char text[96];
    if (static_cast<double>(done) <= planned)
      std::snprintf(text, sizeof text, "%lld of about %.0f steps (%.0f%%)", static_cast<long long>(done), planned,
                    100.0 * static_cast<double>(done) / planned);
    else
      std::snprintf(text, sizeof text, "%lld steps, past the %.0f planned", static_cast<long long>(done), planned);
    return "accuracy " + scene.source + ": " + text;
  });
  Study study;
  try {
    study = run_study(scene, config, [&](std::int64_t steps) { progress.step(steps); });
  } catch (const Error& e) {
    throw Error(scene.source + ": " + e.what());
  } catch (const Interrupted& e) {
    throw Interrupted(e.what() + std::string(args.has("--out") ? "; no file written to " + args.get("--out") : ""),
                      e.signal());
  }
  const nlohmann::ordered_json json = study_json(study);
  if (args.has("--out")) {
    const std::filesystem::path dir = args.get("--out");
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error("--out: cannot create directory " + dir.string() + ": " + ec.message());
    // All three written before any is renamed into place.
    const std::string title = "Accuracy versus cost: " + std::filesystem::path(scene.source).stem().string();
    const std::pair<const char*, std::string> files[] = {{"accuracy.csv", study_csv(study)},
                                                         {"accuracy.json", json.dump(2) + "\n"},
                                                         {"accuracy.svg", render_svg(study_plot(study, title))}};
    std::vector<std::unique_ptr<OutputFile>> out;
    for (const auto& [name, text] : files) {
      out.push_back(std::make_unique<OutputFile>((dir / name).string()));
      out.back()->write(text);
    }
    for (auto& file : out) file->commit();
  }
  std::cout << json.dump(2) << "\n";
  return 0;
}

}  // namespace achd::cli
