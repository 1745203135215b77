// Frames of a run for a video: the run that the options describe, from its start, a PNG every
// Δt of simulated time (frame-000000.png, ...) until --until or the run's end. Used by
// `vsim-ide --frames` and by File > Export frames in the window (with the view's camera).
#pragma once

#include <QSize>
#include <functional>
#include <optional>
#include <string>

#include "options.hpp"
#include "orbit_camera.hpp"
#include "simcore/time.hpp"

namespace ide {

struct FrameExport {
  std::string folder;
  simcore::SimTime every = 100 * simcore::kMillisecond;
  QSize size{1024, 768};
  std::optional<OrbitCamera> camera;  // none: the world's <camera>, else a view of all blocks
  // Called after each frame with the count and the simulated time; false stops the export.
  std::function<bool(int, simcore::SimTime)> progress;
};

struct FrameExportResult {
  int written = 0;
  std::string error;  // empty: done (or stopped by `progress`)
  int exitCode = 0;   // vsim's exit codes, for the command line
};

FrameExportResult exportFrames(const vsim::Options& run, const FrameExport& how);

}  // namespace ide
