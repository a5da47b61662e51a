// Cutter-location data as the tool path: the passes a CAM system wrote (CSV or APT CL), the ball
// centre linear between points (ToolPath::Waypoint). The file is read when the scene is, so a
// damaged one is refused (with its line and column) before anything runs.
#include <cmath>
#include <filesystem>

#include "../common/parallel_passes.hpp"
#include "cl_reader.hpp"
#include "topomill/input_files.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

class ClFile : public PathModel {
 public:
  static Schema schema() {
    Schema s;
    s.add_string("file",
                 "The cutter-location file, relative to the scene file's folder: CSV with a "
                 "header (x, y, z; optionally i, j, k and f in mm/min; a blank line ends a pass) "
                 "or APT CL (GOTO/, FEDRAT/, RAPID)")
        .is_required();
    s.add_choice("format", {"auto", "csv", "apt"},
                 "auto: from the file's extension (.csv, .txt: csv; .cl, .cls, .apt: apt), else "
                 "its first statement")
        .with_default(std::string("auto"));
    s.add_choice("point", {"centre", "tip"},
                 "What the points locate: the ball's centre, or the tool's tip (the centre is R "
                 "along the axis from it)")
        .is_required();
    PassPhase::add_keys(s, PassPhase::Anchor::first_point);
    return s;
  }

  explicit ClFile(const Params& p) : phase_(p), tip_(p.string("point") == "tip") {
    // Relative to the scene file (a --set override: to the working folder).
    const SourceRef& at = p.where("file");
    std::filesystem::path file = p.string("file");
    if (file.is_relative() && at.line > 0)
      file = std::filesystem::path(at.file).parent_path() / file;
    path_ = file.lexically_normal().string();
    const std::string format = p.string("format");
    std::string text;
    try {
      // Recorded as read: a resumed sweep reruns a case whose file changed.
      text = read_input_file(path_, cl::kMaxBytes, "cutter-location data (CSV or APT CL)");
    } catch (const InputError& e) {
      throw ParamError("file",
                       "cannot read the cutter-location file " + path_ + ": " + e.message());
    }
    try {
      data_ = cl::read_text(text, format == "csv"   ? cl::Format::Csv
                                  : format == "apt" ? cl::Format::Apt
                                                    : cl::guess_format(path_, text));
    } catch (const cl::ReadError& e) {
      throw InputError(SourceRef{path_, e.line, e.column}, "path.file", e.what());
    }
    if (data_.passes.empty())
      throw ParamError("file", "the cutter-location file " + path_ +
                                   " holds no move (a pass needs two points at least)");
  }

  std::vector<PassLine> passes(const PathRequest& rq) const override {
    std::vector<PassLine> out;
    for (std::size_t k = 0; k < data_.passes.size(); ++k) {
      PassLine l;
      l.phase = phase_.start + static_cast<double>(k) * phase_.shift;
      l.source = path_;
      const auto& points = data_.passes[k];
      for (std::size_t i = 0; i < points.size(); ++i) {
        const cl::Point& q = points[i];
        ClPoint c;
        c.at.centre = tip_ ? Vec3(q.position + rq.radius * q.axis) : q.position;
        c.at.axis = q.axis;
        // The move to the next point at its feed (the data's, else the scene's).
        const double f = i + 1 < points.size() ? points[i + 1].feed : NAN;
        c.at.speed = std::isnan(f) ? rq.feed_speed : f / 60;
        c.line = q.line;
        l.points.push_back(c);
      }
      out.push_back(std::move(l));
    }
    return out;
  }

 private:
  PassPhase phase_;
  bool tip_;
  std::string path_;
  cl::Data data_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("cl_file", "0.1.0") {
  registrar.add<topomill::PathModel, topomill::plugins::ClFile>(
      "cl_file",
      "Cutter-location data (CSV or APT CL) from a CAM system: the ball centre linear between "
      "points, passes ended by rapid moves or breaks");
}
