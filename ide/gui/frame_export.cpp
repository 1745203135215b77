#include "frame_export.hpp"

#include <QDir>
#include <QImage>
#include <cstdio>

#include "offscreen_render.hpp"
#include "sim_controller.hpp"

namespace ide {

FrameExportResult exportFrames(const vsim::Options& run, const FrameExport& how) {
  FrameExportResult r;
  SimController controller;
  if (!controller.open(run)) {
    r.error = controller.diagnostics() + controller.error();
    r.exitCode = controller.errorCode();
    return r;
  }
  if (!QDir().mkpath(QString::fromStdString(how.folder))) {
    r.error = "cannot make the folder '" + how.folder + "'";
    r.exitCode = vsim::kExitRuntime;
    return r;
  }
  OffscreenRenderer renderer;
  QString glError;
  if (!renderer.initialize(controller.info(), how.size, glError)) {
    r.error = "cannot render: " + glError.toStdString();
    r.exitCode = vsim::kExitRuntime;
    return r;
  }
  const simcore::SimTime until = run.until.value_or(simcore::kTimeInfinity);
  std::optional<OrbitCamera> camera = how.camera;
  for (simcore::SimTime t = 0;; t += how.every) {
    const auto snap = controller.runToAndWait(std::min(t, until));
    if (snap->state == RunState::Failed) {
      r.error = "the run failed at " + simcore::formatTime(snap->now) + ": " + snap->error;
      r.exitCode = vsim::kExitRuntime;
      return r;
    }
    if (!camera) camera = initialCamera(controller.info(), *snap);
    char name[32];
    std::snprintf(name, sizeof name, "/frame-%06d.png", r.written);
    const std::string path = how.folder + name;
    if (!renderer.render(*snap, *camera).save(QString::fromStdString(path), "PNG")) {
      r.error = "cannot write '" + path + "'";
      r.exitCode = vsim::kExitRuntime;
      return r;
    }
    ++r.written;
    if (snap->state == RunState::Finished || t >= until) break;
    if (how.progress && !how.progress(r.written, snap->now)) break;
  }
  return r;
}

}  // namespace ide
