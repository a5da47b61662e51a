// What a written height map says about itself besides its grid: which map it is, what made it
// and when, so a file opened in Gwyddion or MountainsMap months later still tells its origin.
#pragma once

#include <ctime>
#include <string>

namespace topomill {

struct FileInfo {
  std::string title;        // which map: "topomill residual height"
  std::string description;  // the scene: its name and key settings, one line
  std::time_t created = 0;  // when the run wrote it; 0: when the file is written
};

// "topomill 0.1.0"
std::string file_creator();
// UTC in ISO 8601 with its offset, as x3p's xs:dateTime: "2026-11-24T12:40:05+00:00".
std::string iso8601_utc(std::time_t t);
// The shortest text that reads back to exactly v (0.3, not 0.29999999999999999).
std::string exact_text(double v);
// Text on one line: line breaks and NULs become spaces (a header line of CSV or gsf would end
// there, and what follows would be read as data).
std::string one_line(std::string text);
// The creation time to record: info.created, or now.
std::time_t created_time(const FileInfo& info);

}  // namespace topomill
