#include "cosim/util/long_quotes.h"

namespace cosim::util {

std::string cutInput(std::string_view text, std::size_t max) {
  if (text.size() <= max) return std::string(text);
  return std::string(text.substr(0, max)) + "... (" + std::to_string(text.size()) +
         " characters in all)";
}

namespace {
// [begin, end) of the span to keep whole or cut: a quoted span ('...'), else a run of
// characters without white space.
std::size_t spanEnd(std::string_view m, std::size_t i) {
  if (m[i] == '\'') {
    const auto close = m.find('\'', i + 1);
    if (close != std::string_view::npos) return close + 1;
  }
  std::size_t j = i;
  while (j < m.size() && m[j] != ' ' && m[j] != '\n' && m[j] != '\t') ++j;
  return j == i ? i + 1 : j;
}
}  // namespace

std::string cutLongQuotes(std::string_view message, std::size_t max) {
  std::string out;
  out.reserve(message.size() < 4 * max ? message.size() : 4 * max);
  for (std::size_t i = 0; i < message.size();) {
    const std::size_t end = spanEnd(message, i);
    const std::string_view span = message.substr(i, end - i);
    // (max + 5: quotes and the "..." of a span cut already stay as they are)
    if (span.size() <= max + 5) {
      out += span;
    } else if (span.front() == '\'' && span.back() == '\'') {
      out += '\'' + cutInput(span.substr(1, span.size() - 2), max) + '\'';
    } else {
      out += cutInput(span, max);
    }
    i = end;
  }
  return out;
}

}  // namespace cosim::util
