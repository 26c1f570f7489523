// The units a report shows its numbers in, and number text that never breaks across lines.
// One mass unit for every coating mass on a page (per parcel, per real grain, totals, the mass
// balance, a1 and a2), chosen from the mean coating per parcel; one length unit for the layer
// thickness. report.json and the CSV tables stay in SI units (kg, m); docs/analysis.md section 8.
#pragma once

#include <string>

namespace cosim::analysis {

struct DisplayUnit {
  std::string name;   // as shown: "ng", "µg", "nm", ...
  std::string ascii;  // for file names and plain text: "ng", "ug", "nm", ...
  double si = 1.0;    // one unit in SI (kg or m): 1e-12 for ng
  double of(double value_si) const { return value_si / si; }
};

// The unit in which `typical_kg` reads between 1 and 1000 (kg, g, mg, µg, ng, pg, fg; fg below
// it, kg above it and when typical_kg is not a positive number).
DisplayUnit massUnitFor(double typical_kg);
// The same for a length (m, mm, µm, nm; nm below it).
DisplayUnit lengthUnitFor(double typical_m);

// A number for an HTML page: `digits` significant digits, plain notation from 1e-4 to below 1e7
// (thousands grouped by narrow no-break spaces), else m&times;10<sup>e</sup>; a minus sign
// that does not allow a line break after it; "&ndash;" when not finite. Nothing in it lets a
// browser break the line.
std::string htmlNumber(double v, int digits = 4);
// The same as plain UTF-8 text (for sentences and JSON): narrow no-break spaces, U+2212 minus,
// "1.23×10^-5" (with the minus sign).
std::string textNumber(double v, int digits = 4);
// v in `unit` followed by a no-break space and the unit's name ("12.3&nbsp;ng").
std::string htmlQuantity(double value_si, const DisplayUnit& unit, int digits = 4);
// A duration in the unit a reader expects, 3 significant digits: ms below 1 s, min above
// 2 min ("250&nbsp;ms", "1.5&nbsp;s", "20&nbsp;min").
std::string htmlDuration(double seconds);
// A number with a fixed count of decimals (a position in mm to 0.1, a count to 0), &minus; for
// a negative one, "&ndash;" when not finite.
std::string htmlFixed(double v, int decimals);
// A share as a percentage with `decimals` decimals ("12.50&nbsp;%"), never "-0.00 %".
std::string htmlPercent(double share, int decimals = 2);
// For sentences in plain UTF-8 text (the verdict): `digits` significant digits and a no-break
// space before the unit; "\u2013" when not finite.
std::string textPercent(double share, int digits = 3);  // "12.3 %"
std::string textDuration(double seconds);               // ms below 1 s, min above 2 min
std::string textQuantity(double value_si, const DisplayUnit& unit, int digits = 3);

}  // namespace cosim::analysis
