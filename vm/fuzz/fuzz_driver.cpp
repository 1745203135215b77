// Replays inputs through LLVMFuzzerTestOneInput without libFuzzer (GCC builds, CTest): each file
// named on the command line, or each file of a named directory. With --mutate it also feeds every
// truncated prefix and every single-byte change (three patterns per byte) of each input, so that a
// small seed corpus already exercises the reader's error paths.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::size_t runs = 0;

void feed(const std::vector<std::uint8_t>& bytes) {
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
  ++runs;
}

void replay(const std::filesystem::path& file, bool mutate) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  feed(bytes);
  if (!mutate) return;
  for (std::size_t n = 0; n < bytes.size(); ++n)
    feed(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + n));
  std::vector<std::uint8_t> changed = bytes;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (std::uint8_t x : {0x01, 0x80, 0xff}) {
      changed[i] = std::uint8_t(bytes[i] ^ x);
      feed(changed);
    }
    changed[i] = bytes[i];
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool mutate = false;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--mutate") {
      mutate = true;
    } else if (std::filesystem::is_directory(arg)) {
      for (const auto& e : std::filesystem::directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
    } else {
      files.push_back(arg);
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s [--mutate] FILE|DIR...\n", argv[0]);
    return 2;
  }
  for (const auto& f : files) replay(f, mutate);
  std::printf("%zu inputs from %zu files: no crash\n", runs, files.size());
  return 0;
}
