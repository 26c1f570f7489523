#include "SceneCheck.h"

#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cosim/link/fields.h"

namespace cosim::foam {
namespace fs = std::filesystem;

namespace {

std::string textOf(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Whether `name` stands in `text` as a whole OpenFOAM word (a patch's name in a boundary file or
// a blockMeshDict). Loose on purpose: a name that is there is never refused.
bool hasWord(const std::string& text, const std::string& name) {
  std::size_t at = 0;
  auto wordChar = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == ':' ||
           c == '-';
  };
  while ((at = text.find(name, at)) != std::string::npos) {
    const bool before = at == 0 || !wordChar(text[at - 1]);
    const std::size_t end = at + name.size();
    const bool after = end >= text.size() || !wordChar(text[end]);
    if (before && after) return true;
    at = end;
  }
  return false;
}

}  // namespace

int subdomainsOf(const fs::path& dict) {
  std::smatch m;
  const std::string text = textOf(dict);
  if (std::regex_search(text, m, std::regex(R"(numberOfSubdomains\s+(\d+)\s*;)"))) {
    return std::stoi(m[1]);
  }
  return -1;
}

void checkCase(const AdapterSettings& settings, int ranks, const fs::path& dir) {
  if (!fs::exists(dir / "system/controlDict")) {
    throw std::runtime_error(
        "cosimFoam: no system/controlDict in " + dir.string() +
        ": the fluid participant's `files:` folder must be an OpenFOAM case (system/, "
        "constant/, 0/; see docs/openfoam.md)");
  }
  const bool haveMesh =
      fs::exists(dir / "constant/polyMesh/faces") || fs::exists(dir / "constant/polyMesh/faces.gz");
  const bool blockMesh = settings.mesh == "blockMesh" || (settings.mesh == "auto" && !haveMesh);
  if (blockMesh && !fs::exists(dir / "system/blockMeshDict")) {
    throw std::runtime_error("cosimFoam: " + dir.string() +
                             " has no mesh (constant/polyMesh) and no system/blockMeshDict to "
                             "make one");
  }
  if (!blockMesh && !haveMesh) {
    throw std::runtime_error("cosimFoam: options.mesh is 'existing' but " + dir.string() +
                             "/constant/polyMesh has no mesh");
  }
  if (ranks > 1) {
    if (!fs::exists(dir / "system/decomposeParDict")) {
      throw std::runtime_error("cosimFoam: running on " + std::to_string(ranks) +
                               " MPI ranks needs system/decomposeParDict in " + dir.string());
    }
    const int n = subdomainsOf(dir / "system/decomposeParDict");
    if (n != ranks) {
      throw std::runtime_error(
          "cosimFoam: system/decomposeParDict numberOfSubdomains is " + std::to_string(n) +
          " but the participant runs on " + std::to_string(ranks) +
          " MPI ranks (scenario key participants.<fluid>.mpi): make them equal");
    }
  }
  // The patches the options name: in the mesh's boundary file, or in the blockMeshDict that
  // makes the mesh (the run checks them again against the mesh itself)
  const fs::path names =
      blockMesh ? dir / "system/blockMeshDict" : dir / "constant/polyMesh/boundary";
  if (!fs::exists(names)) return;
  const std::string text = textOf(names);
  for (const auto& [key, list] : {std::pair{"inlet_patches", &settings.gas.inlet_patches},
                                  std::pair{"outlet_patches", &settings.gas.outlet_patches}}) {
    for (const auto& patch : *list) {
      if (!hasWord(text, patch)) {
        throw std::runtime_error("scenario file, participants.<fluid>.options." + std::string(key) +
                                 ": no patch '" + patch + "' in " +
                                 fs::relative(names, dir).string() +
                                 " of the case; give the names of the mesh's inlet and outlet "
                                 "patches (docs/openfoam.md)");
      }
    }
  }
}

void checkScene(const cosim::wire::Welcome& welcome, int ranks) {
  for (const auto& name : welcome.send()) {
    if (name == field::precursor_fraction && !welcome.species()) {
      throw std::runtime_error(
          "the scene asks cosimFoam for precursor_fraction but has no mass transfer: no "
          "precursor is solved");
    }
  }
  const AdapterSettings settings = parseAdapterSettings(welcome.config_yaml(), welcome.species());
  checkCase(settings, ranks,
            welcome.workdir().empty() ? fs::current_path() : fs::path(welcome.workdir()));
}

}  // namespace cosim::foam
