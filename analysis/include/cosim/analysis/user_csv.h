// Reading a CSV a user brings: a measurement exported by an instrument's software or saved from a
// spreadsheet (the measured FT4 energy of `cosim ft4 calibrate`, the measured PIV profiles of
// `cosim piv-compare`). Cells are separated by commas and numbers have a decimal point.
//
// Accepted, because spreadsheets write them: a UTF-8 byte-order mark before the header, Windows
// line ends, blanks around cells, cells in double quotes (a comma inside them is text; "" is one
// quote), blank lines and lines starting with '#' (comments).
// Refused with the file and line, because they cannot be read unambiguously: a header whose
// cells are separated by ';' or tabs (a spreadsheet in a locale with a decimal comma), a row
// with another number of cells than the header (a decimal comma splits one number into two
// cells), a quote left open at the end of a line.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace cosim::analysis {

// The cells of one line of a user's CSV: split at commas outside double quotes, each trimmed of
// blanks and carriage returns, quotes removed. Throws std::runtime_error starting with `where`
// when a quote is left open.
std::vector<std::string> userCsvCells(std::string_view line, const std::string& where);

class UserCsv {
 public:
  // Opens path (openUserFile: a folder, a missing or unreadable file is named as such);
  // `expected` says what file was expected there, for the messages.
  UserCsv(const std::filesystem::path& path, std::string expected);

  // The header's cells: the first line that is neither blank nor a comment. Throws when the file
  // has none ("empty") or when its cells are separated by ';' or tabs.
  const std::vector<std::string>& header();

  // The next data row's cells, as many as the header's (else throws, naming the line and, for
  // more cells than the header, a decimal comma as the likely cause); false at the end.
  bool next(std::vector<std::string>& cells);

  // "path:line" of the line read last, for the messages of the reader that interprets the cells.
  std::string where() const;
  const std::filesystem::path& path() const { return path_; }

 private:
  bool nextLine(std::string& line);

  std::filesystem::path path_;
  std::string expected_;
  std::ifstream in_;
  std::size_t line_ = 0;
  bool have_header_ = false;
  std::vector<std::string> header_;
};

}  // namespace cosim::analysis
