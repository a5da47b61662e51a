// Cutter-location data as written by CAM systems: the CSV form (a header naming x, y, z and
// optionally i, j, k and f) and the APT CL text form (GOTO/, FEDRAT/, RAPID). Reading only: what
// the points mean (tip or centre, the default feed) is the plugin's (cl_file.cpp).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace topomill::plugins::cl {

// A damaged or unsupported file: where (1-based line and column) and what was expected.
class ReadError : public std::runtime_error {
 public:
  ReadError(int at_line, int at_column, const std::string& message)
      : std::runtime_error(message), line(at_line), column(at_column) {}
  int line, column;
};

struct Point {
  Eigen::Vector3d position;  // mm
  Eigen::Vector3d axis;      // unit, from the tip towards the spindle; +Z when the data has none
  double feed;               // mm/min of the move to this point; NaN when the data gives none
  int line;
};

// Passes: runs of feed moves, ended by a rapid move or a marked break (a blank line in CSV;
// RAPID, END-OF-PATH, FINI or END in APT). A point repeating the one before is left out, and a
// run of a single point dropped (no move).
struct Data {
  std::vector<std::vector<Point>> passes;
  bool has_axis = false;  // the data gives the tool axis (i, j, k)
};

// Auto: from the file's name, else its first statement (guess_format).
enum class Format { Csv, Apt, Auto };

// The limits a file is held to: bytes read and points kept.
constexpr std::size_t kMaxBytes = std::size_t{256} << 20;
constexpr std::size_t kMaxPoints = std::size_t{1} << 24;

// Throws ReadError for malformed content, Interrupted on a stop request. Auto guesses from the
// first statement.
Data read_text(const std::string& text, Format format);

// The format a file's name suggests (.csv, .txt: CSV; .cl, .cls, .apt, .aptsource: APT), or
// its first statement when the name says nothing.
Format guess_format(const std::string& path, const std::string& text);

}  // namespace topomill::plugins::cl
