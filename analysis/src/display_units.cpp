// Display units and unbreakable number text of the report (display_units.h).
#include "cosim/analysis/display_units.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstring>
#include <utility>

namespace cosim::analysis {

namespace {
struct Step {
  const char* name;
  const char* ascii;
  double si;
};
constexpr std::array<Step, 7> kMass = {{{"kg", "kg", 1.0},
                                        {"g", "g", 1e-3},
                                        {"mg", "mg", 1e-6},
                                        {"µg", "ug", 1e-9},
                                        {"ng", "ng", 1e-12},
                                        {"pg", "pg", 1e-15},
                                        {"fg", "fg", 1e-18}}};
// No pm: a coating below a nanometre reads as a fraction of a nm (an atomic layer is ~0.3 nm).
constexpr std::array<Step, 4> kLength = {
    {{"m", "m", 1.0}, {"mm", "mm", 1e-3}, {"µm", "um", 1e-6}, {"nm", "nm", 1e-9}}};

template <std::size_t N>
DisplayUnit choose(const std::array<Step, N>& steps, double typical) {
  const Step* pick = &steps.front();
  if (std::isfinite(typical) && typical > 0) {
    pick = &steps.back();
    for (const auto& s : steps) {
      if (typical / s.si >= 1.0) {
        pick = &s;
        break;
      }
    }
  }
  return {pick->name, pick->ascii, pick->si};
}

// Removes the zeros after the last significant decimal (and a bare decimal point).
std::string trimZeros(std::string s) {
  if (s.find('.') == std::string::npos) return s;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

// "995900" -> "995&#8239;900" (groups of three digits before the decimal point).
std::string groupThousands(const std::string& s) {
  const auto dot = s.find('.');
  const std::string whole = s.substr(0, dot);
  const std::string rest = dot == std::string::npos ? "" : s.substr(dot);
  if (whole.size() <= 4) return s;  // 1234 reads fine; 12 345 is grouped
  std::string out;
  for (std::size_t i = 0; i < whole.size(); ++i) {
    if (i > 0 && (whole.size() - i) % 3 == 0) out += "&#8239;";
    out += whole[i];
  }
  return out + rest;
}
}  // namespace

DisplayUnit massUnitFor(double typical_kg) { return choose(kMass, typical_kg); }
DisplayUnit lengthUnitFor(double typical_m) { return choose(kLength, typical_m); }

std::string htmlNumber(double v, int digits) {
  if (!std::isfinite(v)) return "&ndash;";
  if (digits < 1) digits = 1;
  const std::string sign = std::signbit(v) && v != 0 ? "&minus;" : "";
  const double a = std::abs(v);
  if (a == 0) return "0";
  // Round to the significant digits first: 9.9996 with 4 digits is 10, not 10.000.
  const std::string e = fmt::format("{:.{}e}", a, digits - 1);
  const double rounded = std::stod(e);
  const int exponent = static_cast<int>(std::floor(std::log10(rounded)));
  if (rounded >= 1e-4 && rounded < 1e7) {
    const int decimals = std::max(0, digits - 1 - exponent);
    return sign + groupThousands(trimZeros(fmt::format("{:.{}f}", rounded, decimals)));
  }
  const auto epos = e.find('e');
  const std::string mantissa = trimZeros(e.substr(0, epos));
  const int ex = std::stoi(e.substr(epos + 1));
  return sign + mantissa + "&times;10<sup>" + (ex < 0 ? "&minus;" : "") +
         std::to_string(std::abs(ex)) + "</sup>";
}

std::string textNumber(double v, int digits) {
  std::string s = htmlNumber(v, digits);
  const std::pair<const char*, const char*> entities[] = {{"&#8239;", "\u202f"},
                                                          {"&minus;", "\u2212"},
                                                          {"&times;10<sup>", "\u00d710^"},
                                                          {"</sup>", ""},
                                                          {"&ndash;", "\u2013"}};
  for (const auto& [from, to] : entities) {
    for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at)) {
      s.replace(at, std::strlen(from), to);
      at += std::strlen(to);
    }
  }
  return s;
}

std::string htmlQuantity(double value_si, const DisplayUnit& unit, int digits) {
  if (!std::isfinite(value_si)) return "&ndash;";
  return htmlNumber(unit.of(value_si), digits) + "&nbsp;" + unit.name;
}

std::string htmlDuration(double s) {
  if (!std::isfinite(s)) return "&ndash;";
  if (std::abs(s) < 1.0) return htmlNumber(1e3 * s, 3) + "&nbsp;ms";
  if (std::abs(s) > 120.0) return htmlNumber(s / 60.0, 3) + "&nbsp;min";
  return htmlNumber(s, 3) + "&nbsp;s";
}

std::string htmlFixed(double v, int decimals) {
  if (!std::isfinite(v)) return "&ndash;";
  const std::string s = fmt::format("{:.{}f}", std::abs(v), std::max(0, decimals));
  const bool zero = s.find_first_not_of("0.") == std::string::npos;  // no "-0.0"
  return (v < 0 && !zero ? "&minus;" : "") + s;
}

std::string htmlPercent(double share, int decimals) {
  if (!std::isfinite(share)) return "&ndash;";
  return htmlFixed(100.0 * share, decimals) + "&nbsp;%";
}

namespace {
constexpr const char* kTextNbsp = "\u00a0";
}  // namespace

std::string textPercent(double share, int digits) {
  if (!std::isfinite(share)) return "\u2013";
  return textNumber(100.0 * share, digits) + kTextNbsp + "%";
}

std::string textDuration(double s) {
  if (!std::isfinite(s)) return "\u2013";
  if (std::abs(s) < 1.0) return textNumber(1e3 * s, 3) + kTextNbsp + "ms";
  if (std::abs(s) > 120.0) return textNumber(s / 60.0, 3) + kTextNbsp + "min";
  return textNumber(s, 3) + kTextNbsp + "s";
}

std::string textQuantity(double value_si, const DisplayUnit& unit, int digits) {
  if (!std::isfinite(value_si)) return "\u2013";
  return textNumber(unit.of(value_si), digits) + kTextNbsp + unit.name;
}

}  // namespace cosim::analysis
