#include "SceneCheck.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosim/link/fields.h"
#include "cosim/util/errors.h"
#include "cosim/util/host_memory.h"

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

// The text without OpenFOAM's comments (// to the end of the line, /* ... */).
std::string withoutComments(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 2, "//") == 0) {
      i = text.find('\n', i);
      if (i == std::string::npos) break;
      out += '\n';
    } else if (text.compare(i, 2, "/*") == 0) {
      const std::size_t end = text.find("*/", i + 2);
      if (end == std::string::npos) break;
      i = end + 1;
      out += ' ';
    } else {
      out += text[i];
    }
  }
  return out;
}

// checkBlockCellCounts also refuses a mesh that cannot fit in memory before blockMesh tries to make
// it: a cell size far below what was meant (a templated case's parameter, --set cell=1e-5) would
// otherwise swap the machine to a standstill or be killed hours later. The bound is sure to fail,
// not a guess: at least kBytesPerCell per cell (OpenFOAM's mesh and the gas fields take 1-2 KB)
// against the physical memory of this host times the ranks (each rank may have a host of its own).
constexpr double kBytesPerCell = 1000;

// Every `hex (8 vertices) [zone] (nx ny nz)` of a blockMeshDict has a whole number of cells,
// at least 1, in each direction: blockMesh 1912 crashes with a segmentation fault on 0 or a
// negative count, which a templated case gets from its parameters (a cell size larger than a
// block, a block of zero or negative width).
void checkBlockCellCounts(const fs::path& dict, const fs::path& dir, int ranks) {
  const std::string text = withoutComments(textOf(dict));
  double cells = 0;
  static const std::regex hex(R"(\bhex\s*\(([^()]*)\)\s*(?:[A-Za-z_][\w.]*\s*)?\(([^()]*)\))");
  const std::string file = fs::relative(dict, dir).string();
  int block = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), hex); it != std::sregex_iterator();
       ++it) {
    ++block;
    const std::string counts = (*it)[2].str();
    std::istringstream in(counts);
    std::vector<std::string> n;
    for (std::string tok; in >> tok;) n.push_back(tok);
    const char* axis[] = {"first", "second", "third"};
    auto where = [&] {
      return "cosimFoam: " + file + ", block " + std::to_string(block) + " (hex (" +
             (*it)[1].str() + ") (" + counts + ")): ";
    };
    if (n.size() != 3)
      throw InputError(where() + "expected 3 cell counts, got " + std::to_string(n.size()));
    double block_cells = 1;
    for (int d = 0; d < 3; ++d) {
      char* end = nullptr;
      const long c = std::strtol(n[d].c_str(), &end, 10);
      if (*end != '\0' || c < 1)
        throw InputError(
            where() + "the " + axis[d] + " cell count is '" + n[d] +
            "': every block needs a whole number of cells, at least 1, in each direction. In a "
            "templated case the count comes from the scene's parameters: a cell size larger "
            "than the block, or a block of zero or negative width (check the parameters the "
            "command line changed)");
      block_cells *= static_cast<double>(c);
    }
    cells += block_cells;
  }
  const double memory = util::hostMemoryBytes() * std::max(1, ranks);
  if (memory > 0 && cells * kBytesPerCell > memory) {
    auto gb = [](double bytes) {
      std::ostringstream o;
      o.precision(3);
      o << bytes / 1e9;
      return o.str();
    };
    std::ostringstream count;
    count.precision(3);
    count << cells;
    throw InputError(
        "cosimFoam: " + file + ": the mesh would have " + count.str() + " cells, which need at " +
        "least " + gb(cells * kBytesPerCell) + " GB (about 1 KB a cell) against " + gb(memory) +
        " GB of memory (" + std::to_string(std::max(1, ranks)) + " rank(s) of this host's " +
        gb(util::hostMemoryBytes()) +
        " GB): a cell size far smaller than meant? In a templated case the counts come from the "
        "scene's parameters (check the parameters the command line changed)");
  }
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
    throw InputError("cosimFoam: no system/controlDict in " + dir.string() +
                     ": the fluid participant's `files:` folder must be an OpenFOAM case (system/, "
                     "constant/, 0/; see docs/openfoam.md)");
  }
  const bool haveMesh =
      fs::exists(dir / "constant/polyMesh/faces") || fs::exists(dir / "constant/polyMesh/faces.gz");
  const bool blockMesh = settings.mesh == "blockMesh" || (settings.mesh == "auto" && !haveMesh);
  if (blockMesh && !fs::exists(dir / "system/blockMeshDict")) {
    throw InputError("cosimFoam: " + dir.string() +
                     " has no mesh (constant/polyMesh) and no system/blockMeshDict to "
                     "make one");
  }
  if (blockMesh) checkBlockCellCounts(dir / "system/blockMeshDict", dir, ranks);
  if (!blockMesh && !haveMesh) {
    throw InputError("cosimFoam: options.mesh is 'existing' but " + dir.string() +
                     "/constant/polyMesh has no mesh");
  }
  if (ranks > 1) {
    if (!fs::exists(dir / "system/decomposeParDict")) {
      throw InputError("cosimFoam: running on " + std::to_string(ranks) +
                       " MPI ranks needs system/decomposeParDict in " + dir.string());
    }
    const int n = subdomainsOf(dir / "system/decomposeParDict");
    if (n != ranks) {
      throw InputError("cosimFoam: system/decomposeParDict numberOfSubdomains is " +
                       std::to_string(n) + " but the participant runs on " + std::to_string(ranks) +
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
        throw InputError("scenario file, participants.<fluid>.options." + std::string(key) +
                         ": no patch '" + patch + "' in " + fs::relative(names, dir).string() +
                         " of the case; give the names of the mesh's inlet and outlet "
                         "patches (docs/openfoam.md)");
      }
    }
  }
}

void checkScene(const cosim::wire::Welcome& welcome, int ranks) {
  for (const auto& name : welcome.send()) {
    if (name == field::precursor_fraction && !welcome.species()) {
      throw InputError(
          "the scene asks cosimFoam for precursor_fraction but has no mass transfer: no "
          "precursor is solved");
    }
  }
  const AdapterSettings settings = parseAdapterSettings(welcome.config_yaml(), welcome.species());
  checkCase(settings, ranks,
            welcome.workdir().empty() ? fs::current_path() : fs::path(welcome.workdir()));
}

}  // namespace cosim::foam
