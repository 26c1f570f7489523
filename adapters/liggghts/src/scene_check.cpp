#include "cosim/liggghts/scene_check.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "cosim/liggghts/adapter_options.h"
#include "cosim/util/errors.h"

namespace cosim::liggghts {

namespace fs = std::filesystem;

std::optional<std::string> timestepMismatch(const std::string& script, double dt, double cfd_dt,
                                            unsigned dem_steps) {
  if (!(cfd_dt > 0) || dem_steps == 0) return std::nullopt;
  const double wanted = cfd_dt / dem_steps;
  if (std::abs(dt - wanted) <= 1e-9 * wanted) return std::nullopt;
  const double steps = cfd_dt / dt;
  std::string hint;
  if (std::abs(steps - std::round(steps)) < 1e-6 && steps >= 1)
    hint = fmt::format(" or set coupling.dem_steps: {:.0f} in the scenario", std::round(steps));
  return fmt::format(
      "LIGGGHTS script {}: `timestep {:.6g}` does not match the coupling: coupling.dt {:.6g} s / "
      "coupling.dem_steps {} = {:.6g} s per DEM step. Write `timestep {:.6g}` in the script{}",
      script, dt, cfd_dt, dem_steps, wanted, wanted, hint);
}

namespace {

// The script's logical lines (a trailing & continues a line, # starts a comment), with the
// number of the line each starts on.
std::vector<std::pair<int, std::vector<std::string>>> commands(std::istream& in) {
  std::vector<std::pair<int, std::vector<std::string>>> out;
  std::string logical;
  int start = 0, number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (logical.empty()) start = number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    const auto last = line.find_last_not_of(" \t\r");
    if (last != std::string::npos && line[last] == '&') {
      logical += line.substr(0, last) + " ";
      continue;
    }
    logical += line;
    std::istringstream words(logical);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (!w.empty()) out.emplace_back(start, std::move(w));
    logical.clear();
  }
  return out;
}

// A file a command reads, when it is named literally (not through a LIGGGHTS variable).
std::optional<std::string> fileRead(const std::vector<std::string>& w) {
  auto literal = [](const std::string& s) -> std::optional<std::string> {
    if (s.find('$') != std::string::npos || s.find('*') != std::string::npos) return std::nullopt;
    return s;
  };
  if ((w[0] == "include" || w[0] == "read_data" || w[0] == "read_restart") && w.size() > 1)
    return literal(w[1]);
  if (w[0] == "fix" && w.size() > 3 && w[3].rfind("mesh/surface", 0) == 0) {
    for (std::size_t i = 4; i + 1 < w.size(); ++i)
      if (w[i] == "file") return literal(w[i + 1]);
  }
  return std::nullopt;
}

}  // namespace

void checkScene(const cosim::wire::Welcome& welcome) {
  const AdapterOptions options = AdapterOptions::parse(welcome.config_yaml());
  const fs::path dir = welcome.workdir().empty() ? fs::current_path() : fs::path(welcome.workdir());
  const fs::path script = dir / options.script;
  std::ifstream in(script);
  if (!in) {
    throw InputError(
        "scenario file, participants.<particles>.options.script: the LIGGGHTS "
        "script '" +
        options.script +
        "' is not in the participant's files: folder (the path is relative "
        "to that folder)");
  }
  const bool resuming = !welcome.restart_from().empty();
  std::optional<double> last_dt;
  for (const auto& [line, w] : commands(in)) {
    const std::string where = fmt::format("LIGGGHTS script {}, line {}", options.script, line);
    if (const auto file = fileRead(w)) {
      // A resume replaces the box creation by the checkpoint's restart file
      if (resuming && (w[0] == "read_data" || w[0] == "read_restart")) continue;
      if (!fs::exists(dir / *file))
        throw InputError(fmt::format(
            "{}: `{}` reads '{}', which is not in the participant's files: folder (paths in the "
            "script are relative to that folder)",
            where, w[0] == "fix" ? "fix " + w[1] + " ... " + w[3] : w[0], *file));
    }
    // Friction coefficients: LIGGGHTS takes a negative one and the bed blows up steps later
    // with a speed that looks like an unstable time step.
    if (w[0] == "fix" && w.size() > 5 && w[3] == "property/global" &&
        (w[4] == "coefficientFriction" || w[4] == "coefficientRollingFriction")) {
      // values follow the style (peratomtype, or peratomtypepair and the number of types)
      const std::size_t first = w[5] == "peratomtypepair" ? 7 : 6;
      for (std::size_t i = first; i < w.size(); ++i) {
        char* end = nullptr;
        const double v = std::strtod(w[i].c_str(), &end);
        if (end == w[i].c_str() || *end != '\0') continue;  // a LIGGGHTS variable, or a keyword
        if (!(v >= 0) || !std::isfinite(v))
          throw InputError(fmt::format(
              "{}: `fix {} ... {}` has the value {}: a friction coefficient must be a finite "
              "number >= 0 (e.g. 0.52); in a templated script it comes from the "
              "scene's parameters",
              where, w[1], w[4], w[i]));
      }
    }
    if (w[0] == "timestep" && w.size() > 1 && w[1].find('$') == std::string::npos) {
      char* end = nullptr;
      const double dt = std::strtod(w[1].c_str(), &end);
      if (end == w[1].c_str() || *end != '\0' || !(dt > 0) || !std::isfinite(dt))
        throw InputError(
            fmt::format("{}: `timestep {}`: expected a positive number of "
                        "seconds",
                        where, w[1]));
      last_dt = dt;  // the last one set is the one the coupled run steps with
    }
  }
  if (last_dt) {
    if (const auto why =
            timestepMismatch(options.script, *last_dt, welcome.cfd_dt(), welcome.dem_steps()))
      throw InputError(*why);
  }
}

}  // namespace cosim::liggghts
