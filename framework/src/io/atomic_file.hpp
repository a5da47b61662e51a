// Files are written under a staging name of their own in the target's directory and renamed onto
// the target when complete, so a crash or a kill never leaves a file that looks whole, and no
// path someone else prepared is ever written through: the staging file is created anew
// (O_CREAT | O_EXCL, which never follows a symbolic link, with a random suffix, so two writers
// of one target never share it), and the rename replaces the target's directory entry (a link
// planted there is replaced, never followed; a file hard-linked elsewhere keeps its bytes).
// Writing honours a stop request (SIGINT, SIGTERM, SIGHUP) at every buffer it flushes.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace topomill {

// A staging file is named ".<target's name>" + kStagingSuffix + six random characters.
inline constexpr const char* kStagingSuffix = ".partial.";

// This process's umask, read from /proc/self/status (setting the umask to read it back would let
// another thread create a file meanwhile under a umask of 0); 022 where /proc says nothing.
unsigned process_umask();

// Calls `write` with a stream on a new staging file beside `path`, then renames it to `path`. On
// any failure the staging file is removed and an exception naming `path` is thrown; a stop
// request while writing throws Interrupted.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// For writers that need a file name (libzip): `write` receives the staging file's path, a new
// empty file that this process created. It should check the stop flag itself.
void write_atomically_to(const std::string& path,
                         const std::function<void(const std::string&)>& write);

}  // namespace topomill
