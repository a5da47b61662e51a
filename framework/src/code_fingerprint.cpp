#include "code_fingerprint.hpp"

#include <algorithm>
#include <boost/crc.hpp>
#include <boost/dll/runtime_symbol_info.hpp>
#include <cstdio>
#include <fstream>

namespace topomill {

namespace {
void add_file(boost::crc_32_type& crc, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    crc.process_bytes("unreadable:", 11);
    crc.process_bytes(path.data(), path.size());
    return;
  }
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
    crc.process_bytes(buffer, static_cast<std::size_t>(in.gcount()));
}
}  // namespace

std::string code_fingerprint(std::vector<std::string> libraries) {
  std::sort(libraries.begin(), libraries.end());
  boost::crc_32_type crc;
  add_file(crc, boost::dll::program_location().string());
  add_file(crc, boost::dll::this_line_location().string());
  for (const auto& library : libraries) add_file(crc, library);
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(crc.checksum()));
  return hex;
}

std::string file_checksum(const std::string& path) {
  boost::crc_32_type crc;
  add_file(crc, path);
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(crc.checksum()));
  return hex;
}

}  // namespace topomill
