#include "scenario/reference.h"

#include <cctype>
#include <sstream>
#include <stdexcept>

#include "cosim/models/drag/undisturbed_velocity.h"
#include "cosim/models/registry.h"
#include "cosim/util/adapter_options.h"
#include "scenario.h"

namespace cosim::orchestrator {

namespace {

std::string names(const std::vector<std::string>& list) {
  std::string out;
  for (const auto& n : list) out += (out.empty() ? "`" : ", `") + n + "`";
  return out.empty() ? "(none)" : out;
}

void table(std::ostream& os, const std::string& prefix, const std::vector<KeySpec>& keys) {
  os << util::optionsTable(keys, "key", prefix) << "\n";
}

const KeySpec& topLevel(const std::string& name) {
  for (const auto& k : topLevelKeys())
    if (k.name == name) return k;
  throw std::logic_error("scenario reference: no top-level key '" + name + "'");
}

// "## `coupling`" and its meaning from the top-level declaration
void heading(std::ostream& os, const std::string& name) {
  const KeySpec& top = topLevel(name);
  std::string doc = top.doc;
  if (!doc.empty()) doc[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(doc[0])));
  os << "## `" << name << "`\n\n" << doc << " (default: " << top.default_value << ").\n\n";
}

void section(std::ostream& os, const std::string& name, const std::vector<KeySpec>& keys) {
  heading(os, name);
  table(os, name + ".", keys);
}

}  // namespace

std::string scenarioReference() {
  std::ostringstream os;
  os << "# Scenario key reference\n\n"
        "<!-- Made by `cosim reference > docs/scenario-reference.md` from the declarations in\n"
        "orchestrator/src/scenario.cpp and orchestrator/src/scenario/*_section.cpp; edit those, "
        "not\n"
        "this page (a test compares the two). -->\n\n"
        "Every key a `scenario.yaml` may hold, with its default and what it means, as the code "
        "that\n"
        "reads it declares it; `cosim reference` prints this page for the build you have. A key\n"
        "not listed is an error naming the file and line. How the file is read (`extends`,\n"
        "`${expressions}`, `--set`, `--unset`) and worked examples: "
        "[scenario.md](scenario.md).\n\n";

  os << "## The top level\n\n";
  table(os, "", topLevelKeys());

  os << "## `parameters`\n\n"
        "`NAME: VALUE`, or `NAME: { value: ..., min: ..., max: ..., doc: ..., show: ... }` for a\n"
        "parameter with the range the scene holds for:\n\n";
  table(os, "parameters.NAME.", parameterKeys());

  heading(os, "participants");
  os << "Each of `participants.particles` and `participants.fluid`:\n\n";
  table(os, "participants.NAME.", ParticipantSpec::keys());
  os << "`participants.NAME.slurm` (with `launch: slurm`):\n\n";
  table(os, "participants.NAME.slurm.", SlurmLaunch::keys());
  os << "`participants.NAME.options` is the adapter's own: [openfoam.md](openfoam.md) "
        "(`openfoam`),\n"
        "[liggghts.md](liggghts.md) (`liggghts`), [models.md](models.md) (the analytic "
        "adapters).\n\n";

  section(os, "coupling", CouplingSection::keys());
  section(os, "constants", ConstantsSection::keys());
  section(os, "models", ModelsSection::keys());
  os << "`models.drag`, beside the law's own parameters:\n\n";
  table(os, "models.drag.", ModelsSection::dragKeys());
  const auto& r = models::Registry::instance();
  os << "The names this build knows (`cosim models`; a plugin adds its own), their parameters in\n"
        "[models.md](models.md):\n\n"
        "| key | names |\n|---|---|\n"
        "| `models.drag.law` | "
     << names(r.dragNames()) << " |\n| `models.drag.undisturbed_velocity` | "
     << names(models::undisturbedVelocityNames()) << " |\n| `models.forces[].law` | "
     << names(r.forceNames()) << " |\n| `models.mass_transfer.law` | "
     << names(r.massTransferNames()) << " |\n| `models.coating_zone.shape` | "
     << names(r.zoneNames()) << " |\n\n";
  section(os, "output", OutputSection::keys());
  section(os, "checkpoint", CheckpointSection::keys());
  section(os, "transport", TransportSection::keys());
  section(os, "checks", ChecksSection::keys());
  heading(os, "observables");
  os << "Each `observables.NAME: { quantity: ..., reference: ..., after: ... }`:\n\n";
  table(os, "observables.NAME.", observableKeys());
  return os.str();
}

}  // namespace cosim::orchestrator
