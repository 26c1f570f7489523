// Observables: named numbers a scenario asks to be measured at the end of a run, each with an
// optional reference (an analytic ${expression} of the parameters). They go into summary.json
// and are what `cosim study` compares across variants.
//
//   observables:
//     v_terminal: { quantity: particles.velocity.z.mean, reference:
//     "${-(rho_p-rho_f)*9.81*d^2/(18*mu)}" } dp_bed:     { quantity: series.pressure_drop.mean,
//     after: 0.2 }
//
// quantity grammar:
//   particles.<field>[.x|.y|.z].<mean|min|max|std|cv|sum>   over the final particle state
//   series.<column>.<mean|final|min|max>                     over time-series rows with t >= after
//   totals.<name>                                            accumulated run totals
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosim/analysis/summary.h"
#include "cosim/link/particle_data.h"

namespace cosim::orchestrator {

struct ObservableSpec {
  std::string name;
  std::string quantity;
  std::optional<double> reference;
  double after = -1e300;  // series: only rows with t >= after
  std::string where;      // "FILE:LINE" or "FILE: --set ..." of its quantity (for messages)
};

// A quantity that has no value for this run's outcome (no particle left for a mean, a CV of
// values whose mean is 0): the run is not wrong, the number just does not exist.
class UndefinedQuantity : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One observable's value as measured at the end of a run (as summary.json records it).
using analysis::ObservableValue;

// Throws std::runtime_error naming the quantity when it cannot be evaluated, UndefinedQuantity
// when the run's outcome leaves it without a value.
double evaluateQuantity(const std::string& quantity, const link::ParticleData& state,
                        const std::vector<double>& series_time,
                        const std::map<std::string, std::vector<double>>& series,
                        const std::map<std::string, double>& totals, double after);

// Checks the grammar (used at scenario validation).
void checkQuantity(const std::string& quantity);

std::optional<double> relativeError(double value, std::optional<double> reference);

}  // namespace cosim::orchestrator
