#include "io/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include "interrupt.hpp"
#include "topomill/error.hpp"

namespace fs = std::filesystem;

namespace topomill {

namespace {
// The pid the holder wrote into the lock file ("" when unreadable).
std::string holder_of(int fd) {
  char buf[32] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  std::string s = n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// Whether `fd` is a file a run may have made: regular, with no other name (a hard link planted
// at .lock would have its bytes replaced by the pid).
bool own_lock_file(int fd) {
  struct stat st {};
  return fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_nlink == 1;
}

// Whether `fd` is still the file at `path` (a holder that gave up may have removed it).
bool same_file(int fd, const std::string& path) {
  struct stat a {
  }, b{};
  return fstat(fd, &a) == 0 && lstat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}
}  // namespace

OutputLock::OutputLock(const std::string& dir, SourceRef where, std::string option, bool wait)
    : dir_(dir), file_((fs::path(dir) / ".lock").string()) {
  for (;;) {
    std::error_code ec;
    const bool existed = fs::exists(dir_, ec);
    if (existed && !fs::is_directory(dir_, ec))
      throw InputError(where, option,
                       "'" + dir_ + "' is not a directory: expected a directory to write into");
    fs::create_directories(dir_, ec);
    if (ec)
      throw InputError(where, option,
                       "cannot create the output directory '" + dir_ + "': " + ec.message());
    created_ = created_ || !existed;
    // Never through a link planted at .lock: the pid below would be written into its target.
    fd_ = open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    if (fd_ < 0 && errno == ELOOP)
      throw InputError(where, option,
                       "'" + file_ +
                           "' is a symbolic link: expected the directory's own lock file or "
                           "nothing (remove the link; someone may have planted it)");
    if (fd_ < 0)
      throw InputError(
          where, option,
          "cannot write into the output directory '" + dir_ + "': " + std::strerror(errno));
    if (!own_lock_file(fd_)) {
      close(fd_);
      fd_ = -1;
      throw InputError(where, option,
                       "'" + file_ +
                           "' is not a lock file topomill made (not a regular file, or linked "
                           "from elsewhere): expected it absent or a run's lock; "
                           "remove it");
    }
    int rc;
    while ((rc = flock(fd_, wait ? LOCK_EX : LOCK_EX | LOCK_NB)) != 0 && errno == EINTR)
      if (stop_flag().load()) break;
    if (rc != 0) {
      const int err = errno;
      const std::string holder = holder_of(fd_);
      close(fd_);
      fd_ = -1;
      throw_if_interrupted();
      if (err == EWOULDBLOCK)
        throw InputError(where, option,
                         "the output directory '" + dir_ + "' is in use by another topomill run" +
                             (holder.empty() ? std::string() : " (pid " + holder + ")") +
                             ": expected a directory no run is writing; wait for it, choose "
                             "another directory, or pass --wait");
      throw InputError(where, option,
                       "cannot lock the output directory '" + dir_ + "': " + std::strerror(err));
    }
    if (same_file(fd_, file_)) break;
    close(fd_);  // the previous holder removed the directory it had made: start again
    fd_ = -1;
  }
  // The pid is a courtesy for the next run's message; the lock holds without it.
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd_, 0) == 0) {
    [[maybe_unused]] const ssize_t n = pwrite(fd_, pid.data(), pid.size(), 0);
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  if (created_ && !keep_) {
    // Removed while still held, so that no other run can have taken it in between.
    std::error_code ec;
    fs::remove(file_, ec);
    fs::remove(dir_, ec);  // only if empty
  }
  close(fd_);
}

}  // namespace topomill
