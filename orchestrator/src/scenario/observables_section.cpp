#include "scenario/observables_section.h"

namespace cosim::orchestrator {

const std::vector<KeySpec>& observableKeys() {
  static const std::vector<KeySpec> k = {
      {"quantity", "required",
       "particles.<field>[.x|y|z].<mean|min|max|std|cv|sum>, series.<column>.<mean|final|min|max> "
       "or totals.<name>"},
      {"reference", "none", "the exact value, usually a ${expression} of the parameters"},
      {"after", "the start", "series: only rows with t >= after [s]"},
  };
  return k;
}

ObservablesSection parseObservables(const YAML::Node& obs, const Context& ctx) {
  ObservablesSection out;
  if (!obs) return out;
  if (!obs.IsMap())
    ctx.fail(obs, "observables", "expected a map name: { quantity: ..., reference: ... }");
  for (const auto& kv : obs) {
    const std::string name = ctx.keyName(kv.first, "observables");
    const std::string key = "observables." + name;
    const YAML::Node o = kv.second;
    if (!o.IsMap()) ctx.fail(o, key, "expected a map { quantity: ..., reference: ... }");
    ctx.allowOnly(o, key, observableKeys());
    ObservableSpec spec;
    spec.name = name;
    spec.quantity = ctx.text(o["quantity"], key + ".quantity");
    spec.where = ctx.where(o["quantity"], key + ".quantity");
    try {
      checkQuantity(spec.quantity);
    } catch (const std::exception& e) {
      ctx.fail(o["quantity"], key + ".quantity", e.what());
    }
    if (o["reference"]) spec.reference = ctx.number(o["reference"], key + ".reference");
    if (o["after"]) spec.after = ctx.number(o["after"], key + ".after");
    out.push_back(spec);
  }
  return out;
}

}  // namespace cosim::orchestrator
