// Precursor mass balance over a run, like the paper's Table 3:
//   expected coating = in - out - (held_end - held_start)
//   error            = expected - obtained       (obtained = coated_end - coated_start)
//   error %          = 100 error / expected
// From a time series (time_series.h, cumulative columns): in, out, held and coated are read
// from the last row. If the first row has in = out = 0 it is the initial state and gives
// held_start and coated_start; otherwise the run is taken to start with no precursor in the gas
// and no coating credited. With a precursor_removed column the table also shows what the fluid's
// sink removed, and `pending` what was removed but not yet credited at the last row.
#pragma once

#include <string>

#include "cosim/analysis/time_series.h"

namespace cosim::analysis {

struct MassBalance {
  double precursor_in = 0;                  // [kg]
  double precursor_out = 0;                 // [kg]
  double held_start = 0, held_end = 0;      // [kg] precursor in the gas
  double held_change = 0;                   // [kg]
  double expected_coating = 0;              // [kg]
  double coated_start = 0, coated_end = 0;  // [kg] on the particles
  double obtained_coating = 0;              // [kg]
  double error = 0;                         // [kg] expected - obtained
  double error_percent = 0;                 // [%]; NaN when expected = 0
  bool has_removed = false;                 // the time series has precursor_removed
  double removed = 0;                       // [kg] taken from the gas by the sink (fluid side)
  double pending = 0;           // [kg] removed - obtained: not yet credited at the last row
  std::string initial_state;    // where held_start/coated_start came from, in words
  std::string obtained_source;  // where the coating on particles was read, in words
};

MassBalance massBalance(double in, double out, double held_start, double held_end,
                        double coated_start, double coated_end);

// Throws std::runtime_error naming the file and the missing column.
MassBalance massBalance(const TimeSeries& series);

// The same balance with the coating read on the particles themselves (e.g. the sums of
// coating_mass over the first and last snapshot of particles.h5): the paper's "obtained
// coating", and an end-to-end check that every credit reached a particle.
MassBalance withParticleCoating(const MassBalance& b, double coated_start, double coated_end,
                                const std::string& source);

}  // namespace cosim::analysis
