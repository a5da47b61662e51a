// Files are written under a temporary name in the same directory and renamed when complete, so a
// crash or a kill never leaves a file that looks whole.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace topomill {

// Calls `write` with a stream on "<path>.partial", then renames it to `path`. On any failure the
// partial file is removed and an exception naming `path` is thrown.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// For writers that need a file name (libpng): `write` receives the temporary path.
void write_atomically_to(const std::string& path,
                         const std::function<void(const std::string&)>& write);

}  // namespace topomill
