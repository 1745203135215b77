#include "ide_options.hpp"

#include <cstdlib>
#include <string_view>
#include <vector>

namespace ide {

namespace {

QSize parseSize(std::string_view text) {
  const auto x = text.find('x');
  const std::string w(text.substr(0, x)), h(x == std::string_view::npos ? "" : text.substr(x + 1));
  char *endW = nullptr, *endH = nullptr;
  const long width = std::strtol(w.c_str(), &endW, 10), height = std::strtol(h.c_str(), &endH, 10);
  if (w.empty() || h.empty() || *endW || *endH || width < 16 || height < 16 || width > 8192 || height > 8192)
    throw vsim::UsageError("--size wants WIDTHxHEIGHT in pixels (16 to 8192), like 800x600, got '" +
                           std::string(text) + "'");
  return QSize(int(width), int(height));
}

int parseFrames(std::string_view text) {
  const std::string s(text);
  char* end = nullptr;
  const long n = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end || n < 1 || n > 100000)
    throw vsim::UsageError("--frame-time wants a number of frames from 1 to 100000, got '" + s + "'");
  return int(n);
}

}  // namespace

IdeOptions parseIdeOptions(int argc, char** argv) {
  IdeOptions o;
  bool sizeGiven = false, everyGiven = false;
  // The IDE's own options are taken out; the rest is vsim's command line.
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    std::string_view name = arg, inlineValue;
    bool hasInline = false;
    if (arg.substr(0, 2) == "--" && arg.find('=') != std::string_view::npos) {
      name = arg.substr(0, arg.find('='));
      inlineValue = arg.substr(arg.find('=') + 1);
      hasInline = true;
    }
    if (name == "--run") {
      if (hasInline) throw vsim::UsageError("--run takes no value");
      o.runAtOnce = true;
      continue;
    }
    if (name != "--screenshot" && name != "--size" && name != "--frame-time" && name != "--select" &&
        name != "--frames" && name != "--every" && name != "--profile-view") {
      rest.push_back(argv[i]);
      continue;
    }
    if (!hasInline && i + 1 >= argc) throw vsim::UsageError(std::string(name) + " needs a value");
    const std::string_view value = hasInline ? inlineValue : std::string_view(argv[++i]);
    if (name == "--profile-view") {
      if (value.empty()) throw vsim::UsageError("--profile-view needs a file written by meld --profile");
      o.profiles.emplace_back(value);
    } else if (name == "--screenshot") {
      if (value.empty()) throw vsim::UsageError("--screenshot needs a file name");
      o.screenshot = value;
    } else if (name == "--size") {
      o.size = parseSize(value);
      sizeGiven = true;
    } else if (name == "--frames") {
      if (value.empty()) throw vsim::UsageError("--frames needs a folder");
      o.framesDir = value;
    } else if (name == "--every") {
      const auto t = simcore::parseDuration(value);
      if (!t || *t <= 0)
        throw vsim::UsageError("--every wants a positive duration like 100ms, got '" + std::string(value) +
                               "'");
      o.frameEvery = *t;
      everyGiven = true;
    } else if (name == "--select") {
      const std::string v(value);
      char* end = nullptr;
      const unsigned long id = std::strtoul(v.c_str(), &end, 10);
      if (v.empty() || *end || id >= 0xFFFFFFFFul)
        throw vsim::UsageError("--select wants a block id, got '" + v + "'");
      o.select = std::uint32_t(id);
    } else {
      o.frameTimes = parseFrames(value);
    }
  }
  o.run = vsim::parseOptions(int(rest.size()), rest.data(), /*worldRequired=*/false);
  if (o.run.help || o.run.version) return o;
  const bool headless = !o.screenshot.empty() || !o.framesDir.empty();
  if (!o.screenshot.empty() && !o.framesDir.empty())
    throw vsim::UsageError("give --screenshot or --frames, not both");
  if ((sizeGiven && !headless) || (o.frameTimes && o.screenshot.empty()))
    throw vsim::UsageError("--size goes with --screenshot or --frames, --frame-time with --screenshot");
  if (everyGiven && o.framesDir.empty()) throw vsim::UsageError("--every goes with --frames");
  if (headless && o.run.world.empty()) throw vsim::UsageError("--screenshot and --frames need a world file");
  return o;
}

const char* ideUsageText() {
  return R"(usage: vsim-ide [WORLD.xml] [--program PROG.meld|PROG.mbc | --code LIB.so] [vsim's run options]
       vsim-ide WORLD.xml [...] --screenshot OUT.png [--size WxH] [--until T]
       vsim-ide WORLD.xml [...] --frames DIR [--every T] [--until T] [--size WxH]

The IDE: the Meld program's editor, the 3D world and the inspector of the selected block side by
side, with the console below. It runs exactly the run that vsim runs with the same options (same
events, same fingerprint), in a thread of its own; the window draws snapshots of it.

In the window:
  --run                 start the run at once (at the speed chosen last time)
  --select ID           show block ID in the inspector
  --profile-view F.json open a profile that `meld -j N --profile F.json` wrote: per-thread
                        timelines, busy/idle/steal summary; repeat it with the profiles of
                        one program at several thread counts for their speedup table
  --why FACT@BLOCK      record derivations, run, and show why the fact exists when the run
                        ends, like --why 'dist(2)@10' (a click on a fact in the inspector does
                        the same once Run > Record derivations is on)

Pictures without a window:
  --screenshot OUT.png  run to --until T (or to the end), render the 3D view as it is then into
                        OUT.png and exit 0; no window is shown (needs an X display: xvfb-run -a)
  --size WxH            the picture's size in pixels (default 1024x768)
  --frame-time N        also draw N frames and print the mean time per frame
  --frames DIR          a picture every --every of simulated time (default 100ms) from 0 to
                        --until T (or to the end), DIR/frame-000000.png on, then exit; make a
                        video with e.g. ffmpeg -i DIR/frame-%06d.png out.mp4
  --every T             the simulated time between two frames (a duration: 50ms, 0.5s, ...)

Run options (as vsim; see vsim --help): --code, --program, -I DIR, --target, --until, --seed,
  --fes, --link-rate, --link-latency, --link-jitter, --motion-time, --tap ID@T, --time-per-rule,
  --palette visiblesim|lm. The console's trace filter takes vsim --trace's syntax.

Exit status: 0 ok; 1 the run failed, or a picture could not be written; 2 bad command line;
  3 bad world, program or block code (1 and 3: screenshot and frames modes; the window shows
  such errors and keeps running).
)";
}

}  // namespace ide
