// The number formats of the project, each named for its purpose. Plain text (the report's HTML
// forms are analysis/display_units.h).
#pragma once

#include <string>

namespace cosim::util {

// A number written to be read again (records, checkpoints, a value quoted back to the user): the
// shortest text that reads back as the same double ("0.1", "1e-05", "0.30000000000000004").
std::string exact(double v);

// A number for people: `digits` significant digits, as printf's %g ("0.0123", "1.23e+05").
std::string significant(double v, int digits);

// A number with a fixed count of decimals ("12.35" for 12.345 with 2).
std::string fixed(double v, int decimals);

// A wall-clock duration for a progress line: "42 s", "3 min 05 s", "2 h 07 min"; "?" when
// negative or not finite.
std::string clockDuration(double seconds);

}  // namespace cosim::util
