// `coulomb urdf info FILE [--json] [--floating]` and `coulomb urdf dynamics FILE --state S.json`
// (docs/urdf.md): what a URDF becomes, and its forward dynamics for a check against another tool.
#include <coulomb/io/UrdfReport.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "Commands.hpp"

namespace coulomb::cli {
namespace {

struct UrdfArguments {
  std::string file;
  std::string statePath;
  std::vector<std::string> packagePath;
  bool json = false;
  bool floating = false;
  bool noMeshes = false;
};

engine::io::UrdfOptions optionsFrom(const UrdfArguments& a) {
  engine::io::UrdfOptions options;
  options.base = a.floating ? engine::io::UrdfBase::Floating : engine::io::UrdfBase::Fixed;
  options.loadCollisionMeshes = !a.noMeshes;
  for (const std::string& folder : a.packagePath) options.packagePath.emplace_back(folder);
  return options;
}

void addCommonOptions(CLI::App* command, const std::shared_ptr<UrdfArguments>& a) {
  command->add_option("file", a->file, "URDF file")->required();
  command->add_option("--package-path", a->packagePath,
                      "folder searched for package:// and relative meshes (repeatable; also "
                      "COULOMB_PACKAGE_PATH=dir1:dir2, then the URDF's folder)");
  command->add_flag("--no-meshes", a->noMeshes, "do not read collision meshes");
}

void runInfo(const UrdfArguments& a) {
  const engine::io::UrdfModel model = engine::io::loadUrdfFile(a.file, optionsFrom(a));
  std::cout << (a.json ? engine::io::urdfInfoJson(model) : engine::io::urdfInfoText(model));
}

void runDynamics(const UrdfArguments& a) {
  const engine::io::UrdfModel model =
      engine::io::loadUrdfFile(a.file, engine::io::urdfDynamicsOptions(optionsFrom(a)));
  std::ifstream in(a.statePath);
  if (!in) throw CommandError(a.statePath + ": cannot open the state file");
  std::ostringstream text;
  text << in.rdbuf();
  const engine::io::UrdfJointState state =
      engine::io::parseUrdfJointState(text.str(), a.statePath, model);
  std::cout << engine::io::urdfDynamicsJson(model, state);
}

}  // namespace

void registerUrdfCommands(CLI::App& app) {
  CLI::App* urdf = app.add_subcommand("urdf", "Inspect URDF robots (docs/urdf.md)");
  urdf->require_subcommand(1);

  auto info = std::make_shared<UrdfArguments>();
  CLI::App* infoCommand = urdf->add_subcommand(
      "info", "Print the tree a URDF becomes: bodies, joints, DOFs, masses, shapes, warnings");
  addCommonOptions(infoCommand, info);
  infoCommand->add_flag("--json", info->json, "print JSON (with \"dofs\" and \"joints\" in order)");
  infoCommand->add_flag("--floating", info->floating, "floating base instead of a fixed one");
  infoCommand->callback([info] { runInfo(*info); });

  auto dynamics = std::make_shared<UrdfArguments>();
  CLI::App* dynamicsCommand = urdf->add_subcommand(
      "dynamics",
      "Forward dynamics (fixed base, no damping) at a state given by joint name, with the "
      "file's inertias as written (only tensors the algorithm cannot use are repaired, and named): "
      "prints joints, qddot, mass_matrix, bias_forces, inertias as JSON");
  addCommonOptions(dynamicsCommand, dynamics);
  dynamicsCommand
      ->add_option("--state", dynamics->statePath,
                   "JSON {\"q\": {\"joint\": value}, \"qdot\": {...}, \"tau\": {...}, "
                   "\"gravity\": [gx, gy, gz]}; missing joints are zero")
      ->required();
  dynamicsCommand->callback([dynamics] { runDynamics(*dynamics); });
}

}  // namespace coulomb::cli
