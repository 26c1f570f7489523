// A CSV a user brings (user_csv.h).
#include "cosim/analysis/user_csv.h"

#include <fmt/format.h>

#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {
namespace {

std::string_view trimmed(std::string_view t) {
  const auto b = t.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return t.substr(b, t.find_last_not_of(" \t\r") - b + 1);
}

constexpr std::string_view kByteOrderMark = "\xef\xbb\xbf";

}  // namespace

std::vector<std::string> userCsvCells(std::string_view line, const std::string& where) {
  std::vector<std::string> out;
  std::size_t i = 0;
  for (;;) {
    // one cell: blanks, then either "quoted text" (then blanks) or plain text up to a comma
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    std::string cell;
    if (i < line.size() && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cell += '"';
            i += 2;
            continue;
          }
          ++i;
          closed = true;
          break;
        }
        cell += line[i++];
      }
      if (!closed)
        throw InputError(where +
                         ": a double quote is left open (a cell in quotes "
                         "ends with a quote on the same line)");
      const auto comma = line.find(',', i);
      const auto rest =
          trimmed(line.substr(i, comma == std::string_view::npos ? line.npos : comma - i));
      if (!rest.empty())
        throw InputError(where + ": text " + quotedCell(rest) +
                         " after a quoted cell (a quote inside quotes is written \"\")");
      i = comma;
      cell = std::string(trimmed(cell));
    } else {
      const auto comma = line.find(',', i);
      cell = std::string(
          trimmed(line.substr(i, comma == std::string_view::npos ? line.npos : comma - i)));
      i = comma;
    }
    out.push_back(std::move(cell));
    if (i == std::string_view::npos) break;
    ++i;  // past the comma: a line ending in a comma has an empty last cell
  }
  return out;
}

UserCsv::UserCsv(const std::filesystem::path& path, std::string expected)
    : path_(path), expected_(std::move(expected)), in_(openUserFile(path, expected_)) {}

bool UserCsv::nextLine(std::string& line) {
  while (std::getline(in_, line)) {
    ++line_;
    if (line_ == 1 && line.rfind(kByteOrderMark, 0) == 0) line.erase(0, kByteOrderMark.size());
    const auto t = trimmed(line);
    if (!t.empty() && t.front() != '#') return true;
  }
  return false;
}

std::string UserCsv::where() const { return fmt::format("{}:{}", path_.string(), line_); }

const std::vector<std::string>& UserCsv::header() {
  if (have_header_) return header_;
  std::string line;
  if (!nextLine(line)) throw InputError(path_.string() + ": empty; expected " + expected_);
  header_ = userCsvCells(line, where());
  have_header_ = true;
  if (header_.size() == 1) {
    for (const char sep : {';', '\t'}) {
      if (header_[0].find(sep) == std::string::npos) continue;
      throw InputError(fmt::format(
          "{}: the header's cells are separated by {} (a spreadsheet saved in a locale with a "
          "decimal comma?); cosim reads cells separated by commas and numbers with a decimal "
          "point: save as CSV with ',' between cells and '.' in numbers",
          where(), sep == ';' ? "';'" : "tabs"));
    }
  }
  return header_;
}

bool UserCsv::next(std::vector<std::string>& cells) {
  const auto columns = header().size();
  std::string line;
  if (!nextLine(line)) return false;
  cells = userCsvCells(line, where());
  if (cells.size() != columns)
    throw InputError(fmt::format(
        "{}: {} cells, the header has {}{}", where(), cells.size(), columns,
        cells.size() > columns ? " (numbers with a decimal comma? cosim reads numbers with a "
                                 "decimal point, cells separated by commas)"
                               : ""));
  return true;
}

}  // namespace cosim::analysis
