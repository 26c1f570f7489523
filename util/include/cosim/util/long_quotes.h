// Messages that quote what a user or a peer gave ('value') keep the quote readable: a quoted
// span longer than a few lines is cut, and the message says how long it was.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace cosim::util {

inline constexpr std::size_t kQuotedInputShown = 200;  // characters of a quoted input shown

// `text` itself when at most `max` characters, else its first `max` and
// "... (N characters in all)".
std::string cutInput(std::string_view text, std::size_t max = kQuotedInputShown);

// `message` with every span between single quotes, and every run without spaces, longer than
// `max` characters cut as cutInput does.
std::string cutLongQuotes(std::string_view message, std::size_t max = kQuotedInputShown);

}  // namespace cosim::util
