// vsim-ide without a window: --screenshot (the run to the requested time, then one picture) and
// --frames (a picture every Δt of simulated time, to make a video of).
#pragma once

#include "ide_options.hpp"

namespace ide {

// Returns the exit status (ide_options.cpp's --help lists them); messages go to stderr.
int runHeadless(const IdeOptions& options);

}  // namespace ide
