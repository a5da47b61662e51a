// One writer per output directory. Two runs into one directory used to stage into the same
// `.incomplete/` and seal a result mixing both; now the first takes OUT/.lock (an flock, which the
// kernel releases when the holder dies, so a killed run leaves no stale lock) for as long as it
// runs, and a second is refused with exit 2 naming the directory and the holder's pid, or waits
// for it when asked (--wait).
#pragma once

#include <string>

#include "topomill/error.hpp"

namespace topomill {

class OutputLock {
 public:
  // Creates `dir` if needed and locks it. `where` and `option` say where the user gave the
  // directory (the command line's --out, or a scene's [output] dir), for messages; `wait` blocks
  // until the holder is done (a stop request still ends the wait). Throws InputError when the
  // directory cannot be made or is busy.
  OutputLock(const std::string& dir, SourceRef where, std::string option, bool wait);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  // Keeps the directory when the lock is released: call once something was written into it.
  // Until then, a directory this lock created is removed again on release (a refused run leaves
  // nothing behind).
  void keep() { keep_ = true; }

 private:
  std::string dir_, file_;
  int fd_ = -1;
  bool created_ = false, keep_ = false;
};

}  // namespace topomill
