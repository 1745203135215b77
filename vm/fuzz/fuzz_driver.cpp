// Drives LLVMFuzzerTestOneInput without libFuzzer (GCC builds, CTest), for the bytecode, Meld source
// and world-file targets alike:
//   DRIVER [--mutate] FILE|DIR...      replay each file (a directory: each file in it); --mutate also
//                                      feeds every truncated prefix and three single-byte changes per
//                                      byte, so that a small seed corpus exercises the error paths.
//   DRIVER --random SECONDS [--seed S] [--out DIR] [--timeout T] FILE|DIR...
//                                      random mutations of the seeds (byte flips, inserted, deleted and
//                                      repeated ranges, splices of two seeds) for SECONDS of CPU time.
// Every input must return within the timeout (default 30 s): a hang writes `hang-N` to DIR (default
// the current folder) and aborts; a crash under the sanitizers writes `crash-N` first (the death
// callback). The last line says how many inputs ran.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::size_t runs = 0;
const std::vector<std::uint8_t>* current = nullptr;
std::string outDir = ".";

// Writes the input being run (async-signal-safe: open/write/close only).
void saveCurrent(const char* kind) {
  if (!current) return;
  char path[4096];
  std::snprintf(path, sizeof path, "%s/%s-%zu", outDir.c_str(), kind, runs);
  const int fd = ::open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return;
  const std::size_t n = current->size();
  for (std::size_t done = 0; done < n;) {
    const ssize_t w = ::write(fd, current->data() + done, n - done);
    if (w <= 0) break;
    done += std::size_t(w);
  }
  ::close(fd);
  const char msg[] = "fuzz driver: input saved\n";
  (void)!::write(2, msg, sizeof msg - 1);
}

void onAlarm(int) {
  const char msg[] = "fuzz driver: an input ran past the timeout (a hang)\n";
  (void)!::write(2, msg, sizeof msg - 1);
  saveCurrent("hang");
  std::_Exit(3);
}

#if defined(__SANITIZE_ADDRESS__)
void onDeath() { saveCurrent("crash"); }
#else
// Without the sanitizers' death callback: save the input, then die of the same signal.
void onCrashSignal(int sig) {
  saveCurrent("crash");
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}
#endif

unsigned timeoutSeconds = 30;

void feed(const std::vector<std::uint8_t>& bytes) {
  current = &bytes;
  ::alarm(timeoutSeconds);
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
  ::alarm(0);
  current = nullptr;
  ++runs;
}

std::vector<std::uint8_t> readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void replay(const std::vector<std::uint8_t>& bytes, bool mutate) {
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

// One random change of `b` (which may come out empty); `other` is a second seed for splices.
void mutateOnce(std::vector<std::uint8_t>& b, const std::vector<std::uint8_t>& other, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n ? std::size_t(rng() % n) : 0; };
  static const std::uint8_t interesting[] = {0,   1,   0x7f, 0x80, 0xff, '(', ')', ',', '.',  '[', ']', '<',
                                             '>', '"', '@',  '-',  '!',  '0', '9', ' ', '\n', '/', '*', '|'};
  switch (rng() % 7) {
    case 0:  // flip a bit
      if (!b.empty()) b[pick(b.size())] ^= std::uint8_t(1u << (rng() % 8));
      break;
    case 1:  // an interesting byte
      if (!b.empty()) b[pick(b.size())] = interesting[pick(sizeof interesting)];
      break;
    case 2: {  // insert a byte
      b.insert(b.begin() + std::ptrdiff_t(pick(b.size() + 1)), interesting[pick(sizeof interesting)]);
      break;
    }
    case 3: {  // delete a range
      if (b.empty()) break;
      const std::size_t at = pick(b.size()), n = 1 + pick(std::min<std::size_t>(16, b.size() - at));
      b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + n));
      break;
    }
    case 4: {  // repeat a range
      if (b.empty() || b.size() > (1u << 20)) break;
      const std::size_t at = pick(b.size()), n = 1 + pick(std::min<std::size_t>(64, b.size() - at));
      const std::vector<std::uint8_t> piece(b.begin() + std::ptrdiff_t(at),
                                            b.begin() + std::ptrdiff_t(at + n));
      b.insert(b.begin() + std::ptrdiff_t(pick(b.size() + 1)), piece.begin(), piece.end());
      break;
    }
    case 5: {  // splice: the head of b, the tail of another seed
      if (other.empty()) break;
      const std::size_t keep = pick(b.size() + 1), from = pick(other.size());
      b.resize(keep);
      b.insert(b.end(), other.begin() + std::ptrdiff_t(from), other.end());
      break;
    }
    default:  // a random 32-bit little-endian value (counts and ids in bytecode)
      if (b.size() >= 4) {
        const std::size_t at = pick(b.size() - 3) & ~std::size_t(3);
        const std::uint32_t v = std::uint32_t(rng() % 3 == 0 ? rng() : rng() % 300);
        std::memcpy(b.data() + at, &v, 4);
      }
      break;
  }
}

double cpuSeconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  bool mutate = false;
  double randomSeconds = 0;
  std::uint64_t seed = 1;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--mutate") {
      mutate = true;
    } else if (arg == "--random" && i + 1 < argc) {
      randomSeconds = std::atof(argv[++i]);
    } else if (arg == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--out" && i + 1 < argc) {
      outDir = argv[++i];
      std::error_code ec;  // made here: the crash handler can only open files, not make folders
      std::filesystem::create_directories(outDir, ec);
    } else if (arg == "--timeout" && i + 1 < argc) {
      timeoutSeconds = unsigned(std::atoi(argv[++i]));
    } else if (std::filesystem::is_directory(arg)) {
      for (const auto& e : std::filesystem::directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
    } else {
      files.push_back(arg);
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr,
                 "usage: %s [--mutate | --random SECONDS [--seed S]] [--out DIR] [--timeout T] FILE|DIR...\n",
                 argv[0]);
    return 2;
  }
  std::signal(SIGALRM, onAlarm);
#if defined(__SANITIZE_ADDRESS__)
  __sanitizer_set_death_callback(onDeath);
#else
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, onCrashSignal);
#endif
  std::vector<std::vector<std::uint8_t>> seeds;
  for (const auto& f : files) seeds.push_back(readFile(f));
  if (randomSeconds <= 0) {
    for (const auto& s : seeds) replay(s, mutate);
    std::printf("%zu inputs from %zu files: no crash\n", runs, files.size());
    return 0;
  }
  std::mt19937_64 rng(seed);
  const double start = cpuSeconds();
  while (cpuSeconds() - start < randomSeconds) {
    std::vector<std::uint8_t> input = seeds[rng() % seeds.size()];
    const int changes = 1 + int(rng() % 8);
    for (int k = 0; k < changes; ++k) mutateOnce(input, seeds[rng() % seeds.size()], rng);
    feed(input);
  }
  std::printf("%zu random inputs from %zu seeds in %.0f s of CPU (seed %llu): no crash, no hang\n", runs,
              seeds.size(), cpuSeconds() - start, (unsigned long long)seed);
  return 0;
}
