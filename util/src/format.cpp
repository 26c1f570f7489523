#include "cosim/util/format.h"

#include <fmt/format.h>

#include <cmath>

namespace cosim::util {

std::string exact(double v) { return fmt::format("{}", v); }

std::string significant(double v, int digits) { return fmt::format("{:.{}g}", v, digits); }

std::string fixed(double v, int decimals) { return fmt::format("{:.{}f}", v, decimals); }

std::string clockDuration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 60) return fmt::format("{:.0f} s", s);
  const int whole = static_cast<int>(s);
  if (s < 3600) return fmt::format("{} min {:02d} s", whole / 60, whole % 60);
  return fmt::format("{} h {:02d} min", whole / 3600, (whole % 3600) / 60);
}

}  // namespace cosim::util
