// The window's menus and toolbar, and the actions behind them that ask the user something
// (run until, export frames) or keep the recent files.
#include <QApplication>
#include <QComboBox>
#include <QCoreApplication>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressDialog>
#include <QSettings>
#include <QStatusBar>
#include <QToolBar>
#include <sstream>

#include "code_editor.hpp"
#include "console_panel.hpp"
#include "frame_export.hpp"
#include "main_window.hpp"
#include "meld_program.hpp"
#include "profile_view.hpp"
#include "world_view.hpp"

namespace ide {

namespace {

constexpr int kMaxRecent = 8;

// Speeds offered: simulated seconds per wall second; 0 = as fast as possible.
const std::pair<const char*, double> kSpeeds[] = {{"0.1×", 0.1},   {"1× (real time)", 1},
                                                  {"10×", 10},     {"100×", 100},
                                                  {"1000×", 1000}, {"as fast as possible", 0}};

}  // namespace

template <class Slot>
QAction* MainWindow::action(const QString& text, const QKeySequence& shortcut, const QString& tip,
                            Slot slot) {
  auto* a = new QAction(text, this);
  a->setShortcut(shortcut);
  a->setToolTip(tip.isEmpty() ? text : tip);
  connect(a, &QAction::triggered, this, slot);
  return a;
}

void MainWindow::buildFileMenu() {
  QMenu* file = menuBar()->addMenu("&File");
  file->addAction("Open &world...", QKeySequence("Ctrl+Shift+O"), this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, "Open world", {}, "World files (*.xml)");
    if (!path.isEmpty()) openWorld(path);
  });
  file->addAction("&Open program...", QKeySequence::Open, this, [this] {
    const QString path =
        QFileDialog::getOpenFileName(this, "Open Meld program", {}, "Meld programs (*.meld *.mbc)");
    if (!path.isEmpty()) openProgram(path);
  });
  recentMenu_ = file->addMenu("Recent files");
  file->addAction("&Save program", QKeySequence::Save, this, [this] { compile(); });
  file->addAction("Save &world as...", this, [this] {
    const QString path =
        QFileDialog::getSaveFileName(this, "Save the world as it is now", "world.xml", "World files (*.xml)");
    if (!path.isEmpty()) controller_.saveWorld(path.toStdString());
  });
  file->addAction("Save 3D view as &PNG...", this, [this] {
    const QString path =
        QFileDialog::getSaveFileName(this, "Save the 3D view", "world.png", "PNG images (*.png)");
    if (!path.isEmpty()) saveScreenshot(path);
  });
  file->addAction("Export &frames...", this, &MainWindow::exportFramesAsked);
  file->addAction("Open p&rofiles...", this, [this] {
    const QStringList paths = QFileDialog::getOpenFileNames(
        this, "Open profiles of meld -j N (several: the speedup table)", {}, "meld --profile files (*.json)");
    if (!paths.isEmpty()) openProfiles(paths);
  });
  file->addSeparator();
  file->addAction("&Quit", QKeySequence::Quit, this, &QWidget::close);
  refreshRecentMenu();
}

QWidget* MainWindow::openProfiles(const QStringList& paths) {
  std::vector<Profile> profiles;
  for (const QString& path : paths) {
    QString error;
    std::optional<Profile> p = loadProfile(path, error);
    if (!p) {
      QMessageBox::warning(this, "Open profiles", error);
      return nullptr;
    }
    profiles.push_back(std::move(*p));
  }
  auto* window = new ProfileView(std::move(profiles), this);
  window->setWindowFlag(Qt::Window);
  window->setAttribute(Qt::WA_DeleteOnClose);
  window->setWindowTitle("Profile — " + QFileInfo(paths.front()).fileName());
  window->resize(1000, 640);
  window->show();
  return window;
}

bool MainWindow::profileProgram(const std::vector<unsigned>& threads) {
  const QString path = editor_->path();
  if (path.isEmpty() || !(path.endsWith(".meld") || path.endsWith(".mbc"))) {
    console_->appendMessage("Profile: open a Meld program first");
    return false;
  }
  if (profiler_.running()) {
    console_->appendMessage("Profile: the runs of the last profiling are still going");
    return false;
  }
  if (path.endsWith(".meld") && !compile()) return false;  // saves it; its errors are listed
  std::shared_ptr<const meldvm::Program> program;
  std::ostringstream messages;
  try {
    program = vsim::loadMeldProgram(path.toStdString(), options_.includeDirs, &messages, /*robots=*/false);
  } catch (const vsim::ProgramLoadError& e) {
    console_->appendMessage("Profile: " + QString::fromStdString(messages.str() + e.what()));
    return false;
  }
  if (profileFolder_.isEmpty()) {
    profileFolder_ =
        QDir::temp().filePath(QString("vsim-ide-profiles-%1").arg(QCoreApplication::applicationPid()));
    QDir().mkpath(profileFolder_);
  }
  QStringList counts;
  for (unsigned n : threads) counts << QString::number(n);
  profiler_.start(program, options_.programArgs, threads, profileFolder_.toStdString(),
                  QFileInfo(path).completeBaseName().toStdString());
  console_->appendMessage("Profile: running " + QFileInfo(path).fileName() + " at -j " + counts.join(", ") +
                          " (the profile window opens when the runs are over)");
  return true;
}

bool MainWindow::stopProfiling() {
  if (!profiler_.running()) {
    console_->appendMessage("Profile: no profiling is running");
    return false;
  }
  profiler_.cancel();
  return true;
}

void MainWindow::takeProfiles() {
  std::optional<ProfileRunner::Result> r = profiler_.take();
  if (!r) return;
  if (r->cancelled) {
    console_->appendMessage("Profile: stopped; no profile to show");
    return;
  }
  if (!r->error.empty()) {
    console_->appendMessage("Profile: the run failed: " + QString::fromStdString(r->error));
    return;
  }
  QStringList files;
  for (const std::string& f : r->files) files << QString::fromStdString(f);
  lastProfileWindow_ = openProfiles(files);
}

void MainWindow::buildRunActions() {
  QToolBar* bar = addToolBar("Run");
  bar->setObjectName("run");
  QMenu* run = menuBar()->addMenu("&Run");
  for (QAction* a :
       {action("Compile", QKeySequence("Ctrl+B"),
               "Save and compile the program; meldc's messages are listed "
               "under the editor",
               [this] { compile(); }),
        action("Run", QKeySequence("F5"), {}, [this] { controller_.run(chosenSpeed()); }),
        action("Pause", QKeySequence("F6"), {}, [this] { controller_.pause(); }),
        action("Step", QKeySequence("F10"), "Process one event", [this] { controller_.step(); }),
        action("Run until...", {}, {}, [this] { runUntilAsked(); }),
        action("Restart", QKeySequence("Ctrl+R"),
               "Compile the program and run the world again from the start", [this] { restart(); })}) {
    bar->addAction(a);
    run->addAction(a);
  }
  run->addSeparator();
  QAction* profile = run->addAction("Profile on threads (meld -j 1, 2, ...)");
  profile->setToolTip(
      "Run the editor's program on its own graph (as meld does) at 1 thread and every power of two up "
      "to the cores, and open the threads' timelines and the speedup table");
  connect(profile, &QAction::triggered, this, [this] { profileProgram(); });
  QAction* stopProfile = run->addAction("Stop profiling");
  stopProfile->setToolTip("Stop the profiling runs in progress (closing the window stops them too)");
  connect(stopProfile, &QAction::triggered, this, [this] { stopProfiling(); });
  QAction* record = run->addAction("Record derivations (why a fact exists)");
  record->setCheckable(true);
  record->setToolTip("The VM notes where every fact comes from; the run starts again");
  connect(record, &QAction::toggled, this, [this](bool on) {
    controller_.setRecordDerivations(on);
    restart();
  });
  for (const auto& [name, value] : kSpeeds) speed_->addItem(name, value);
  speed_->setToolTip("Simulated time per wall time");
  bar->addWidget(speed_);
  connect(speed_, &QComboBox::currentIndexChanged, this, [this] {
    const auto snap = controller_.snapshot();
    if (snap && snap->state == RunState::Running) controller_.run(chosenSpeed());
  });
}

void MainWindow::buildBlockActions() {
  QToolBar* bar = addToolBar("Block");
  bar->setObjectName("block");
  // Each acts on the selected block, if any.
  auto onSelected = [this](void (SimController::*command)(simcore::BlockId)) {
    return [this, command] {
      if (selected_ != simcore::kNoBlock) (controller_.*command)(selected_);
    };
  };
  bar->addAction(
      action("Focus", {}, "Centre the camera on the selected block", [this] { view_->focusSelected(); }));
  bar->addAction(action("Tap", {}, "Tap the selected block now", onSelected(&SimController::tap)));
  bar->addAction(action("Remove", QKeySequence::Delete,
                        "Remove the selected block from the world (while paused)",
                        onSelected(&SimController::removeBlock)));
  bar->addAction(action("Add", QKeySequence("Insert"),
                        "Add a block in the first free cell next to the selected one (while paused)",
                        onSelected(&SimController::addBlockNextTo)));
}

void MainWindow::runUntilAsked() {
  bool ok = false;
  const QString text = QInputDialog::getText(
      this, "Run until", "Simulated time (like 2.5s, 300ms, 1min):", QLineEdit::Normal, "1s", &ok);
  if (!ok) return;
  const auto t = simcore::parseDuration(text.trimmed().toStdString());
  if (!t) {
    QMessageBox::warning(this, "Run until", "Not a duration: '" + text + "' (like 2.5s, 300ms or 1min)");
    return;
  }
  controller_.runUntil(*t, chosenSpeed());
}

void MainWindow::exportFramesAsked() {
  if (!controller_.isOpen()) return;
  const QString folder = QFileDialog::getExistingDirectory(this, "Export frames into");
  if (folder.isEmpty()) return;
  bool ok = false;
  const QString every = QInputDialog::getText(
      this, "Export frames", "A frame every (simulated time):", QLineEdit::Normal, "100ms", &ok);
  if (!ok) return;
  const auto t = simcore::parseDuration(every.trimmed().toStdString());
  if (!t || *t <= 0) {
    QMessageBox::warning(this, "Export frames", "Not a positive duration: '" + every + "'");
    return;
  }
  exportFrames(folder, *t);
}

int MainWindow::exportFrames(const QString& folder, simcore::SimTime every) {
  FrameExport how;
  how.folder = folder.toStdString();
  how.every = every;
  how.size = view_->size() * view_->devicePixelRatio();
  how.camera = view_->camera();
  QProgressDialog progress("Exporting frames (the run from its start)...", "Stop", 0, 0, this);
  progress.setWindowModality(Qt::WindowModal);
  progress.setMinimumDuration(500);
  how.progress = [&](int frames, simcore::SimTime now) {
    progress.setLabelText(
        QString("%1 frames, t = %2").arg(frames).arg(QString::fromStdString(simcore::formatTime(now))));
    QApplication::processEvents();
    return !progress.wasCanceled();
  };
  const FrameExportResult r = ide::exportFrames(options_, how);
  console_->appendMessage(r.error.empty() ? QString("Exported %1 frames to %2.").arg(r.written).arg(folder)
                                          : "Frame export failed: " + QString::fromStdString(r.error));
  return r.error.empty() ? r.written : -1;
}

bool MainWindow::saveScreenshot(const QString& path) {
  const QImage image = view_->grabFramebuffer();
  if (image.isNull() || !image.save(path, "PNG")) {
    console_->appendMessage("Cannot write " + path);
    return false;
  }
  statusBar()->showMessage("saved " + path, 4000);
  return true;
}

void MainWindow::addRecent(const QString& key, const QString& path) {
  QSettings settings;
  QStringList list = settings.value(key).toStringList();
  const QString absolute = QFileInfo(path).absoluteFilePath();
  list.removeAll(absolute);
  list.prepend(absolute);
  while (list.size() > kMaxRecent) list.removeLast();
  settings.setValue(key, list);
  refreshRecentMenu();
}

void MainWindow::refreshRecentMenu() {
  recentMenu_->clear();
  QSettings settings;
  for (const QString& path : settings.value("recent/worlds").toStringList())
    recentMenu_->addAction("world: " + path, this, [this, path] { openWorld(path); });
  for (const QString& path : settings.value("recent/programs").toStringList())
    recentMenu_->addAction("program: " + path, this, [this, path] { openProgram(path); });
  recentMenu_->setEnabled(!recentMenu_->isEmpty());
}

}  // namespace ide
