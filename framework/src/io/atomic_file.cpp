#include "atomic_file.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace topomill {

void write_atomically_to(const std::string& path,
                         const std::function<void(const std::string&)>& write) {
  const std::string tmp = path + ".partial";
  try {
    write(tmp);
    std::filesystem::rename(tmp, path);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  write_atomically_to(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write '" + path + "'");
    write(out);
    out.flush();
    if (!out) throw std::runtime_error("writing '" + path + "' failed (disk full?)");
  });
}

}  // namespace topomill
