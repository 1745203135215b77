// vsim-ide's command line: vsim's run options (the same run as `vsim` with the same options), the
// world optional, plus the IDE's own options for pictures without a window.
#pragma once

#include <QSize>
#include <string>
#include <vector>

#include "options.hpp"
#include "simcore/time.hpp"

namespace ide {

struct IdeOptions {
  vsim::Options run;       // run.world empty: the IDE starts without a world
  std::string screenshot;  // --screenshot: render at --until (or the end) into this PNG and exit
  QSize size{1024, 768};   // --size WxH of the screenshot
  std::string framesDir;   // --frames DIR: a PNG every --every of simulated time, without a window
  simcore::SimTime frameEvery = 100 * simcore::kMillisecond;
  int frameTimes = 0;      // --frame-time N: also draw N frames offscreen and print the time per frame
  bool runAtOnce = false;  // --run: start the run when the window opens
  std::uint32_t select = 0xFFFFFFFFu;  // --select ID: the block the inspector shows
  std::vector<std::string> profiles;   // --profile-view FILE.json (repeatable): open in the profile view
};

// Throws vsim::UsageError.
IdeOptions parseIdeOptions(int argc, char** argv);
const char* ideUsageText();

}  // namespace ide
