#include "cl_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>

#include "topomill/interrupt.hpp"

namespace topomill::plugins::cl {

namespace {

// Lines parsed between two looks at the stop flag, less one (a mask).
constexpr int kLinesPerStopCheck = (1 << 14) - 1;

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}
bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// A field of a line: its text, trimmed, and the 1-based column where it starts.
struct Field {
  std::string text;
  int column;
};

// Splits `line` at `sep`, trimming each field; `first` is the column of line[0].
std::vector<Field> split(const std::string& line, char sep, int first = 1) {
  std::vector<Field> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = std::min(line.find(sep, start), line.size());
    std::size_t a = start, b = end;
    while (a < b && blank(line[a])) ++a;
    while (b > a && blank(line[b - 1])) --b;
    out.push_back({line.substr(a, b - a), first + static_cast<int>(a)});
    if (end == line.size()) return out;
    start = end + 1;
  }
}

// A finite number, the whole field (a leading + allowed), or a ReadError naming it.
double number(const Field& f, int line, const char* what) {
  const char* b = f.text.data();
  const char* e = b + f.text.size();
  if (b != e && *b == '+') ++b;
  double v = 0;
  const auto r = std::from_chars(b, e, v);
  if (f.text.empty() || r.ec != std::errc() || r.ptr != e || !std::isfinite(v))
    throw ReadError(line, f.column,
                    "'" + f.text.substr(0, 40) + "' is not a number: expected " + what +
                        " as a finite decimal number");
  return v;
}

Eigen::Vector3d unit_axis(const Eigen::Vector3d& a, int line, int column) {
  const double n = a.norm();
  if (!(n > 0))
    throw ReadError(line, column, "the tool axis (i, j, k) is zero: expected a direction");
  return a / n;
}

// Lines without their end-of-line, numbered from 1.
template <class F>
void for_each_line(const std::string& text, F&& f) {
  std::size_t start = 0;
  int line = 1;
  while (start < text.size()) {
    if ((line & kLinesPerStopCheck) == 0) throw_if_interrupted();  // 256 MiB parse in seconds
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string s = text.substr(start, end - start);
    if (!s.empty() && s.back() == '\r') s.pop_back();
    f(s, line++);
    start = end + 1;
  }
}

// Collects passes: a point joins the current pass (unless it repeats the last); a break closes
// it (a single point is no pass: there is no move).
class Passes {
 public:
  explicit Passes(Data& d) : d_(d) {}
  void add(const Point& p) {
    if (++count_ > kMaxPoints)
      throw ReadError(p.line, 1,
                      "more than " + std::to_string(kMaxPoints) +
                          " points: expected fewer (a patch needs the passes near it only)");
    // A point repeated (CAM output has them, around a feed change) is no move: left out.
    if (!current_.empty() && current_.back().position == p.position &&
        current_.back().axis == p.axis)
      return;
    current_.push_back(p);
  }
  void end() {
    if (current_.size() >= 2) d_.passes.push_back(std::move(current_));
    current_.clear();
  }

 private:
  Data& d_;
  std::vector<Point> current_;
  std::size_t count_ = 0;
};

Data read_csv(const std::string& text) {
  Data d;
  Passes passes(d);
  std::vector<std::string> names;  // the header's, lower case
  std::map<std::string, std::size_t> column;
  for_each_line(text, [&](const std::string& raw, int line) {
    const auto first = raw.find_first_not_of(" \t");
    if (first == std::string::npos) return passes.end();  // a blank line: a marked break
    if (raw[first] == '#') return;                        // a comment
    const std::vector<Field> fields = split(raw, ',');
    if (names.empty()) {
      static const std::array<const char*, 7> known{"x", "y", "z", "i", "j", "k", "f"};
      for (const Field& f : fields) {
        std::string name = f.text;
        for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (std::find(known.begin(), known.end(), name) == known.end())
          // Not quoted: a file that is no CL data at all (a scene may name any file) keeps
          // its first line to itself.
          throw ReadError(line, f.column,
                          "column " + std::to_string(names.size() + 1) +
                              " of the header is not a name topomill knows: expected x, y, z "
                              "(mm), optionally i, j, k (the tool axis) and f (feed, mm/min), "
                              "separated by commas");
        if (column.count(name))
          throw ReadError(line, f.column, "column '" + name + "' appears twice in the header");
        column[name] = names.size();
        names.push_back(name);
      }
      for (const char* need : {"x", "y", "z"})
        if (!column.count(need))
          throw ReadError(
              line, 1, std::string("the header has no column '") + need + "': expected x, y and z");
      const int axes = static_cast<int>(column.count("i") + column.count("j") + column.count("k"));
      if (axes != 0 && axes != 3)
        throw ReadError(line, 1, "the header has some of i, j, k: expected all three or none");
      d.has_axis = axes == 3;
      return;
    }
    if (fields.size() != names.size()) {
      const int at = fields.size() > names.size() ? fields[names.size()].column
                                                  : static_cast<int>(raw.size()) + 1;
      throw ReadError(line, at,
                      "a row of " + std::to_string(fields.size()) + " values: expected " +
                          std::to_string(names.size()) + ", one per column of the header");
    }
    auto value = [&](const char* name, const char* what) {
      return number(fields[column.at(name)], line, what);
    };
    Point p{{value("x", "x (mm)"), value("y", "y (mm)"), value("z", "z (mm)")},
            Eigen::Vector3d::UnitZ(),
            NAN,
            line};
    if (d.has_axis)
      p.axis = unit_axis({value("i", "i"), value("j", "j"), value("k", "k")}, line,
                         fields[column.at("i")].column);
    if (column.count("f")) {
      p.feed = value("f", "the feed f (mm/min)");
      if (!(p.feed > 0))
        throw ReadError(
            line, fields[column.at("f")].column,
            "a feed of " + fields[column.at("f")].text + " mm/min: expected more than 0");
    }
    passes.add(p);
  });
  if (names.empty())
    throw ReadError(1, 1, "no header: expected a first line naming the columns (x, y, z, ...)");
  passes.end();
  return d;
}

// FEDRAT's arguments: the rate and its unit (MMPM, the default, or IPM), in mm/min.
double feed_rate(const std::vector<Field>& args, int line) {
  double rate = NAN, unit = 1;
  for (const Field& a : args) {
    const std::string u = upper(a.text);
    if (u == "MMPM")
      unit = 1;
    else if (u == "IPM")
      unit = 25.4;
    else
      rate = number(a, line, "the feed rate (or MMPM, IPM)");
  }
  if (!(rate > 0))
    throw ReadError(line, args.empty() ? 1 : args[0].column,
                    "FEDRAT without a rate above 0: expected FEDRAT/ f (mm/min)");
  return rate * unit;
}

// A statement topomill does not follow: refused. Named only when it is APT's own word: a file that
// is no CL data at all (a scene may name any file) keeps its first line to itself.
[[noreturn]] void refuse_word(const std::string& w, int column, int line) {
  static const std::vector<std::string> apt_words{
      "CIRCLE", "GOFWD",  "GOLFT", "GORGT", "GOBACK", "GOUP",  "GODOWN", "GODLTA", "INDIRV",
      "INDIRP", "CUTCOM", "CYCLE", "PSIS",  "DNTCUT", "THICK", "ARCSLP", "PIVOTZ", "ROTABL"};
  const bool known = std::find(apt_words.begin(), apt_words.end(), w) != apt_words.end();
  throw ReadError(line, column,
                  (known ? w + " is" : std::string("this is")) +
                      " not a statement topomill follows: expected GOTO, FROM, FEDRAT, "
                      "RAPID, UNITS, TLAXIS, END-OF-PATH, FINI, END (motion in straight "
                      "lines), or one that does not move the tool (PARTNO, CUTTER, SPINDL, "
                      "COOLNT, ...); circles (CIRCLE, GOFWD) and cutter compensation are not "
                      "followed");
}

// APT statements: a line, or lines joined where one ends in '$' (a continuation); "$$" starts a
// comment. Each character keeps its column, for messages (on the first line of the statement).
Data read_apt(const std::string& text) {
  Data d;
  Passes passes(d);
  double scale = 1;                                 // UNITS/INCHES: 25.4
  double feed = NAN;                                // mm/min, from FEDRAT
  bool rapid = false;                               // the next motion is a rapid move
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // modal: TLAXIS, or the last GOTO's
  std::string statement;                            // joined over continuation lines
  int statement_line = 0;
  // Words that move the tool along paths topomill does not follow are refused; these say
  // nothing about the motion and are passed over.
  static const std::vector<std::string> ignored{
      "PARTNO", "PPRINT", "CUTTER", "TLDATA", "LOADTL", "SELECT", "TOOLNO", "SPINDL", "COOLNT",
      "MACHIN", "PAINT",  "DISPLY", "TPRINT", "OPSKIP", "INSERT", "CLRSRF", "SEQNO",  "STOP",
      "OPSTOP", "DELAY",  "TITLE",  "REMARK", "MULTAX", "AUTOPS", "INTOL",  "OUTTOL", "TOOL PATH"};
  auto handle = [&](const std::string& s, int line) {
    const std::size_t slash = s.find('/');
    const Field word = split(s.substr(0, std::min(slash, s.size())), '\0').front();
    const std::string w = upper(word.text);
    const std::vector<Field> args =
        slash == std::string::npos ? std::vector<Field>{}
                                   : split(s.substr(slash + 1), ',', static_cast<int>(slash) + 2);
    if (w == "GOTO" || w == "FROM") {
      if (args.size() != 3 && args.size() != 6)
        throw ReadError(line, word.column,
                        w + " with " + std::to_string(args.size()) +
                            " values: expected x, y, z or x, y, z, i, j, k");
      Point p{{number(args[0], line, "x"), number(args[1], line, "y"), number(args[2], line, "z")},
              axis,
              feed,
              line};
      p.position *= scale;
      if (args.size() == 6) {
        axis = p.axis = unit_axis(
            {number(args[3], line, "i"), number(args[4], line, "j"), number(args[5], line, "k")},
            line, args[3].column);
        d.has_axis = true;
      }
      // A rapid move or the start point ends the pass before it: the point starts the next.
      if (rapid || w == "FROM") passes.end(), rapid = false;
      passes.add(p);
    } else if (w == "FEDRAT") {
      feed = feed_rate(args, line);
    } else if (w == "RAPID") {
      rapid = true;
    } else if (w == "UNITS") {
      const std::string u = args.empty() ? "" : upper(args[0].text);
      if (u != "MM" && u != "INCHES")
        throw ReadError(line, args.empty() ? 1 : args[0].column,
                        "UNITS/" + (args.empty() ? std::string() : args[0].text) +
                            ": expected UNITS/MM or UNITS/INCHES");
      scale = u == "MM" ? 1 : 25.4;
    } else if (w == "TLAXIS") {
      if (args.size() != 3)
        throw ReadError(line, word.column,
                        "TLAXIS with " + std::to_string(args.size()) + " values: expected i, j, k");
      axis = unit_axis(
          {number(args[0], line, "i"), number(args[1], line, "j"), number(args[2], line, "k")},
          line, args[0].column);
      d.has_axis = d.has_axis || axis != Eigen::Vector3d::UnitZ();
    } else if (w == "END-OF-PATH" || w == "FINI" || w == "END") {
      passes.end();
    } else if (std::find(ignored.begin(), ignored.end(), w) == ignored.end()) {
      refuse_word(w, word.column, line);
    }
  };
  bool open = false;  // the statement continues on the next line
  for_each_line(text, [&](const std::string& raw, int line) {
    std::string s = raw.substr(0, std::min(raw.find("$$"), raw.size()));
    while (!s.empty() && blank(s.back())) s.pop_back();
    const bool continues = !s.empty() && s.back() == '$';
    if (continues) s.pop_back();
    if (!open) {
      statement = s, statement_line = line;  // its columns are the line's
    } else {
      const std::size_t a = s.find_first_not_of(" \t");
      statement += " " + (a == std::string::npos ? std::string() : s.substr(a));
    }
    open = continues;
    if (!open && statement.find_first_not_of(" \t") != std::string::npos)
      handle(statement, statement_line);
  });
  if (open)
    throw ReadError(statement_line, 1, "the statement continues ('$') past the end of the file");
  passes.end();
  return d;
}

}  // namespace

Data read_text(const std::string& text, Format format) {
  if (format == Format::Auto) format = guess_format("", text);
  return format == Format::Csv ? read_csv(text) : read_apt(text);
}

Format guess_format(const std::string& path, const std::string& text) {
  const std::size_t dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : upper(path.substr(dot + 1));
  if (ext == "CSV" || ext == "TXT") return Format::Csv;
  if (ext == "CL" || ext == "CLS" || ext == "APT" || ext == "APTSOURCE") return Format::Apt;
  // The first word: APT statements carry a '/' or are one of a few words; a CSV header does not.
  const std::size_t a = text.find_first_not_of(" \t\r\n");
  const std::string head = upper(text.substr(a == std::string::npos ? 0 : a, 16));
  for (const char* w : {"GOTO", "FROM", "PARTNO", "$$", "FEDRAT", "RAPID", "UNITS", "TOOL PATH",
                        "MULTAX", "CUTTER", "LOADTL", "TLDATA"})
    if (head.rfind(w, 0) == 0) return Format::Apt;
  return Format::Csv;
}

}  // namespace topomill::plugins::cl
