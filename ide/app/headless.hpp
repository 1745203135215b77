// vsim-ide --screenshot: the run to the requested time, then one picture, without a window.
#pragma once

#include "ide_options.hpp"

namespace ide {

// Returns the exit status (ide_options.cpp's --help lists them); messages go to stderr.
int takeScreenshot(const IdeOptions& options);

}  // namespace ide
