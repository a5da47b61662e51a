#include "io/read_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "interrupt.hpp"
#include "resources.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace {
// What measuring a map takes at its peak, per point: measured 121 bytes for --parameters all on
// a 2049 x 2049 map without missing points (the ACF's field padded 1.5x each way, its spectrum
// and sums; the PSD is held within 2^22 padded values), and about 55 more with missing points
// (the ACF counts each lag's pairs by a second transform).
constexpr double kBytesPerPoint = 180;
}  // namespace

std::uint64_t readable_bytes() {
  return static_cast<std::uint64_t>(0.9 * static_cast<double>(available_memory()));
}

namespace {
// Bytes read between two checks of the stop flag.
constexpr std::size_t kReadChunk = std::size_t{1} << 20;

std::string kind_of(mode_t mode) {
  return S_ISDIR(mode) ? "is a directory" : "is not a regular file (a device or a pipe)";
}

// An open descriptor that closes itself.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) close(fd);
  }
};

// The size of the file `st` describes, which must be a regular file of at most `max_bytes`
// (`status` is stat's or fstat's return; errno tells why it failed).
std::uint64_t checked_size(int status, const struct stat& st, const std::string& path,
                           std::uint64_t max_bytes, const std::string& what) {
  if (status != 0)
    throw InputError(SourceRef{path}, "",
                     std::string("cannot read the file: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw InputError(SourceRef{path}, "", kind_of(st.st_mode) + ": expected " + what);
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes)
    throw InputError(SourceRef{path}, "",
                     "the file is " + format_bytes(static_cast<double>(size)) + ", more than the " +
                         format_bytes(static_cast<double>(max_bytes)) + " allowed: expected " +
                         what);
  return size;
}
}  // namespace

std::uint64_t regular_file_size(const std::string& path, std::uint64_t max_bytes,
                                const std::string& what) {
  struct stat st {};
  const int status = stat(path.c_str(), &st);
  return checked_size(status, st, path, max_bytes, what);
}

std::string read_file_bounded(const std::string& path, std::uint64_t max_bytes,
                              const std::string& what) {
  // Opened without waiting (a FIFO would block an open for reading until a writer came), then
  // the descriptor itself is checked: the file read is the file checked.
  const Fd file{open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0)
    throw InputError(SourceRef{path}, "",
                     std::string("cannot read the file: ") + std::strerror(errno));
  struct stat st {};
  const int status = fstat(file.fd, &st);
  const std::uint64_t size = checked_size(status, st, path, max_bytes, what);
  // Exactly as many bytes as its size said (a file that grows meanwhile is read to that size,
  // one that shrinks to its end), a chunk at a time.
  std::string bytes(size, '\0');
  std::size_t got = 0;
  while (got < bytes.size()) {
    throw_if_interrupted();
    const ssize_t n = read(file.fd, bytes.data() + got, std::min(kReadChunk, bytes.size() - got));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw InputError(SourceRef{path}, "",
                       std::string("cannot read the file: ") + std::strerror(errno));
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  bytes.resize(got);
  return bytes;
}

void check_map_memory(const std::string& path, double points) {
  const double need = points * kBytesPerPoint;
  const double available = static_cast<double>(available_memory());
  if (need <= 0.9 * available) return;
  throw InputError(SourceRef{path}, "",
                   "the map has " + format_number(points) +
                       " points: reading and measuring it "
                       "needs about " +
                       format_bytes(need) + ", and " + format_bytes(available) +
                       " are available (TOPOMILL_MEMORY_LIMIT sets the limit)");
}

}  // namespace topomill
