// Runs a fuzz target over saved inputs without libFuzzer, so that every build (gcc included)
// replays the seed corpus and the regression inputs as an ordinary test. Arguments are files or
// directories (searched recursively, `--ext .toml` keeps one extension).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::string ext;
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--ext" && i + 1 < argc) {
      ext = argv[++i];
      continue;
    }
    if (fs::is_directory(a)) {
      for (const auto& e : fs::recursive_directory_iterator(a))
        if (e.is_regular_file() && (ext.empty() || e.path().extension() == ext))
          files.push_back(e.path());
    } else if (fs::exists(a)) {
      files.push_back(a);
    } else {
      std::cerr << "replay: no such input '" << a << "'\n";
      return 2;
    }
  }
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
    std::cout << f.string() << "\n" << std::flush;  // the last line names a crashing input
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::cout << files.size() << " inputs replayed\n";
  return files.empty() ? 1 : 0;
}
