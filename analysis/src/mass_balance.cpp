#include "cosim/analysis/mass_balance.h"

#include <limits>
#include <stdexcept>

#include "cosim/util/errors.h"

namespace cosim::analysis {

MassBalance massBalance(double in, double out, double held_start, double held_end,
                        double coated_start, double coated_end) {
  MassBalance b;
  b.precursor_in = in;
  b.precursor_out = out;
  b.held_start = held_start;
  b.held_end = held_end;
  b.held_change = held_end - held_start;
  b.expected_coating = in - out - b.held_change;
  b.coated_start = coated_start;
  b.coated_end = coated_end;
  b.obtained_coating = coated_end - coated_start;
  b.error = b.expected_coating - b.obtained_coating;
  b.error_percent = b.expected_coating != 0 ? 100.0 * b.error / b.expected_coating
                                            : std::numeric_limits<double>::quiet_NaN();
  return b;
}

MassBalance massBalance(const TimeSeries& s) {
  const auto& in = s.at(column::precursor_in);
  const auto& out = s.at(column::precursor_out);
  const auto& held = s.at(column::precursor_held);
  const auto& coated = s.at(column::coated_mass);
  if (s.rows() == 0) throw InputError(s.source + " has no rows: no coupling step was recorded");
  const bool initialRow = in.front() == 0.0 && out.front() == 0.0;
  MassBalance b = massBalance(in.back(), out.back(), initialRow ? held.front() : 0.0, held.back(),
                              initialRow ? coated.front() : 0.0, coated.back());
  b.initial_state = initialRow
                        ? "first row (t = " + std::to_string(s.at(column::time).front()) + " s)"
                        : "assumed: no precursor in the gas and no coating at the start";
  b.obtained_source = s.source + ", column coated_mass (coating credited by the orchestrator)";
  if (s.has(column::precursor_removed)) {
    const auto& removed = s.at(column::precursor_removed);
    b.has_removed = true;
    b.removed = removed.back() - (initialRow ? removed.front() : 0.0);
    b.pending = b.removed - b.obtained_coating;
  }
  return b;
}

MassBalance withParticleCoating(const MassBalance& b, double coated_start, double coated_end,
                                const std::string& source) {
  MassBalance r = massBalance(b.precursor_in, b.precursor_out, b.held_start, b.held_end,
                              coated_start, coated_end);
  r.initial_state = b.initial_state;
  r.obtained_source = source;
  r.has_removed = b.has_removed;
  r.removed = b.removed;
  r.pending = b.has_removed ? r.removed - r.obtained_coating : 0.0;
  return r;
}

}  // namespace cosim::analysis
