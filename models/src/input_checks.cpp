#include "cosim/models/input_checks.h"

#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <tuple>

#include "cosim/util/format.h"

namespace cosim::models {

namespace {

[[noreturn]] void fail(const std::string& owner, const std::string& field, std::size_t i, double v,
                       const std::string& expected) {
  throw ModelError(owner + ": field '" + field + "' of parcel " + std::to_string(i) + " is " +
                   util::significant(v, 6) + "; expected " + expected +
                   " (the value came from the adapter that provides this field: check its "
                   "case set-up, or report it as an adapter bug)");
}

enum class Rule { finite, positive, voidage, fraction };

struct FieldRule {
  const char* name;
  const double* ParcelBatch::*member;
  unsigned components;
  Rule rule;
};

const FieldRule kRules[] = {
    {"position", &ParcelBatch::position, 3, Rule::finite},
    {"velocity", &ParcelBatch::velocity, 3, Rule::finite},
    {"radius", &ParcelBatch::radius, 1, Rule::positive},
    {"fluid_velocity", &ParcelBatch::fluid_velocity, 3, Rule::finite},
    {"voidage", &ParcelBatch::voidage, 1, Rule::voidage},
    {"fluid_density", &ParcelBatch::fluid_density, 1, Rule::positive},
    {"fluid_viscosity", &ParcelBatch::fluid_viscosity, 1, Rule::positive},
    {"pressure_gradient", &ParcelBatch::pressure_gradient, 3, Rule::finite},
    {"precursor_fraction", &ParcelBatch::precursor_fraction, 1, Rule::fraction},
    {"cell_size", &ParcelBatch::cell_size, 1, Rule::positive},
};

constexpr double kVoidageRoundOff = 1e-9;

}  // namespace

void validateConstants(const std::string& owner, const SceneConstants& c) {
  if (!(std::isfinite(c.cg) && c.cg >= 1.0)) {
    throw ModelError(owner +
                     ": constant 'cg' (coarse-graining factor, constants.cg in the "
                     "scenario) is " +
                     util::significant(c.cg, 6) + "; expected a finite number >= 1");
  }
  if (!(c.min_voidage > 0.0 && c.min_voidage <= 1.0)) {
    throw ModelError(owner +
                     ": constant 'min_voidage' (constants.min_voidage in the scenario) "
                     "is " +
                     util::significant(c.min_voidage, 6) +
                     "; expected a number in (0, 1], typically 0.1 to 0.4");
  }
  if (!(std::isfinite(c.schmidt) && c.schmidt > 0.0)) {
    throw ModelError(owner + ": constant 'schmidt' (constants.schmidt in the scenario) is " +
                     util::significant(c.schmidt, 6) +
                     "; expected a finite number > 0 (1 for the paper's gas)");
  }
  for (double g : c.gravity) {
    if (!std::isfinite(g)) {
      throw ModelError(owner +
                       ": constant 'gravity' (constants.gravity in the scenario) has a "
                       "non-finite component; expected 3 finite numbers [m/s2]");
    }
  }
}

void checkInputs(const std::string& owner, const std::vector<std::string>& fields,
                 const ParcelBatch& p, const SceneConstants& c) {
  (void)c;
  static_assert(std::size(kRules) <= std::tuple_size_v<decltype(ParcelBatch::checked)>);
  if (p.checked_lost != p.lost || p.checked_n != p.n) {
    p.checked.fill(nullptr);
    p.checked_lost = p.lost;
    p.checked_n = p.n;
  }
  for (const auto& f : fields) {
    const FieldRule* rule = nullptr;
    for (const auto& r : kRules) {
      if (f == r.name) rule = &r;
    }
    if (rule == nullptr) {
      throw ModelError(owner + ": declares unknown field '" + f + "' (a bug in the model)");
    }
    const double* v = p.*(rule->member);
    if (p.n > 0 && v == nullptr) {
      throw ModelError(owner + ": needs field '" + f +
                       "' but the batch does not carry it (the orchestrator must request every "
                       "field in requiredFields() from the adapters)");
    }
    const auto index = static_cast<std::size_t>(rule - kRules);
    if (v != nullptr && p.checked[index] == v) continue;  // found valid for an earlier law
    // One pass per rule, parcel by parcel (the rule chosen once, not per value)
    const std::size_t k = rule->components;
    auto scan = [&](auto ok, const char* expected) {
      for (std::size_t i = 0; i < p.n; ++i) {
        if (p.isLost(i)) continue;
        for (std::size_t j = 0; j < k; ++j) {
          if (!ok(v[i * k + j])) fail(owner, f, p.first + i, v[i * k + j], expected);
        }
      }
    };
    switch (rule->rule) {
      case Rule::finite:
        scan([](double x) { return std::isfinite(x); }, "a finite number");
        break;
      case Rule::positive:
        scan([](double x) { return std::isfinite(x) && x > 0.0; }, "a finite number > 0");
        break;
      case Rule::voidage:
        scan([](double x) { return x > 0.0 && x <= 1.0 + kVoidageRoundOff; },
             "a voidage in (0, 1]");
        break;
      case Rule::fraction:
        scan([](double x) { return x >= 0.0 && x <= 1.0; }, "a mass fraction in [0, 1]");
        break;
    }
    p.checked[index] = v;
  }
}

void checkOutputs(const std::string& owner, const char* what, const double* values,
                  std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) {
      throw ModelError(owner + ": computed a non-finite " + what + " (" +
                       util::significant(values[i], 6) + ") at index " + std::to_string(i) +
                       "; the inputs passed the checks, so this is a bug in the law: report it "
                       "with the scenario");
    }
  }
}

}  // namespace cosim::models
