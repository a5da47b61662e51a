#include "atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <streambuf>
#include <vector>

#include "interrupt.hpp"

namespace topomill {

namespace {

// Bytes gathered before each write(2), and so between two checks of the stop flag.
constexpr std::size_t kFlushBytes = 1 << 16;

// The mode a file created with 0666 gets under this process's umask (mkstemp gives 0600).
mode_t created_mode() {
  static const mode_t mode = static_cast<mode_t>(0666 & ~process_umask());
  return mode;
}

// A new file beside `path`, created exclusively and hidden: ".<name>.partial.XXXXXX".
struct Staging {
  std::string name;
  int fd = -1;
  explicit Staging(const std::string& path) {
    const std::filesystem::path p(path);
    const std::string t =
        (p.parent_path() / ("." + p.filename().string() + kStagingSuffix + "XXXXXX")).string();
    std::vector<char> tmpl(t.begin(), t.end());
    tmpl.push_back('\0');
    fd = mkostemp(tmpl.data(), O_CLOEXEC);
    if (fd < 0)
      throw std::filesystem::filesystem_error("cannot write '" + path + "'", path,
                                              std::error_code(errno, std::generic_category()));
    name = tmpl.data();
    fchmod(fd, created_mode());
  }
  ~Staging() {
    if (fd >= 0) close(fd);
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
};

// An output stream's buffer on a file descriptor: each flush checks for a stop request first.
class FdBuf : public std::streambuf {
 public:
  FdBuf(int fd, std::string path) : fd_(fd), path_(std::move(path)), buf_(kFlushBytes) {
    setp(buf_.data(), buf_.data() + buf_.size());
  }

 protected:
  int_type overflow(int_type c) override {
    flush_buffer();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override {
    flush_buffer();
    return 0;
  }

 private:
  void flush_buffer() {
    throw_if_interrupted();
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) {
        throw_if_interrupted();
        continue;
      }
      if (n <= 0)
        throw std::runtime_error("writing '" + path_ + "' failed: " + std::strerror(errno) +
                                 " (disk full?)");
      p += n;
    }
    setp(buf_.data(), buf_.data() + buf_.size());
  }
  int fd_;
  std::string path_;
  std::vector<char> buf_;
};

}  // namespace

unsigned process_umask() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Umask:", 0) == 0)
      return static_cast<unsigned>(std::stoul(line.substr(6), nullptr, 8));
  return 022;
}

void write_atomically_to(const std::string& path,
                         const std::function<void(const std::string&)>& write) {
  Staging staged(path);
  try {
    close(staged.fd);
    staged.fd = -1;
    write(staged.name);
    throw_if_interrupted();
    std::filesystem::rename(staged.name, path);
  } catch (...) {
    std::remove(staged.name.c_str());
    throw;
  }
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  Staging staged(path);
  try {
    FdBuf buf(staged.fd, path);
    std::ostream out(&buf);
    // The buffer's errors (a stop request, a full disk) leave the stream as they were thrown.
    out.exceptions(std::ios::badbit);
    write(out);
    out.flush();
    if (close(staged.fd) != 0) {
      staged.fd = -1;
      throw std::runtime_error("writing '" + path + "' failed: " + std::strerror(errno));
    }
    staged.fd = -1;
    std::filesystem::rename(staged.name, path);
  } catch (...) {
    std::remove(staged.name.c_str());
    throw;
  }
}

}  // namespace topomill
