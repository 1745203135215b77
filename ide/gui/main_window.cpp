#include "main_window.hpp"

#include <QApplication>
#include <QCloseEvent>
#include <QComboBox>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QGuiApplication>
#include <QLabel>
#include <QListWidget>
#include <QMessageBox>
#include <QScreen>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>
#include <QTimer>
#include <QVBoxLayout>
#include <sstream>

#include "block_inspector.hpp"
#include "code_editor.hpp"
#include "console_panel.hpp"
#include "diagnostics.hpp"
#include "meld_program.hpp"
#include "world_view.hpp"

namespace ide {

namespace {

constexpr double kDrawShare = 0.2;

}  // namespace

MainWindow::MainWindow(const vsim::Options& options, const StartActions& start, QWidget* parent)
    : QMainWindow(parent),
      options_(options),
      editor_(new CodeEditor),
      diagnostics_(new QListWidget),
      editorPane_(new QWidget),
      view_(new WorldView),
      inspector_(new BlockInspector),
      console_(new ConsolePanel),
      splitter_(new QSplitter(Qt::Horizontal)),
      speed_(new QComboBox),
      status_(new QLabel),
      timer_(new QTimer(this)) {
  setWindowTitle("vsim-ide");
  buildLayout();
  buildFileMenu();
  buildRunActions();
  buildBlockActions();
  QSettings settings;
  restoreGeometry(settings.value("window/geometry").toByteArray());
  restoreState(settings.value("window/state").toByteArray());
  splitter_->restoreState(settings.value("window/splitter").toByteArray());
  speed_->setCurrentIndex(settings.value("run/speed", 1).toInt());

  connect(timer_, &QTimer::timeout, this, &MainWindow::poll);
  timer_->start(33);
  if (options_.world.empty()) {
    showSession();
    return;
  }
  if (!options_.program.empty()) {
    QString error;
    if (!editor_->load(QString::fromStdString(options_.program), error)) console_->appendMessage(error);
  }
  whyAtEnd_ = !options_.why.empty();
  controller_.setRecordDerivations(whyAtEnd_);
  if (!restart()) return;
  if (start.select != simcore::kNoBlock) selectBlock(start.select);
  if (start.run || whyAtEnd_) controller_.run(chosenSpeed());
}

MainWindow::~MainWindow() = default;

void MainWindow::buildLayout() {
  auto* paneLayout = new QVBoxLayout(editorPane_);
  paneLayout->setContentsMargins(0, 0, 0, 0);
  auto* editorSplit = new QSplitter(Qt::Vertical);
  editorSplit->addWidget(editor_);
  editorSplit->addWidget(diagnostics_);
  editorSplit->setStretchFactor(0, 5);
  editorSplit->setStretchFactor(1, 1);
  paneLayout->addWidget(editorSplit);
  diagnostics_->setToolTip("meldc's messages: click one to go there");
  splitter_->addWidget(editorPane_);
  splitter_->addWidget(view_);
  splitter_->addWidget(inspector_);
  splitter_->setStretchFactor(0, 2);
  splitter_->setStretchFactor(1, 3);
  splitter_->setStretchFactor(2, 1);
  splitter_->setSizes({380, 580, 440});
  setCentralWidget(splitter_);
  auto* dock = new QDockWidget("Console", this);
  dock->setObjectName("console");
  dock->setWidget(console_);
  addDockWidget(Qt::BottomDockWidgetArea, dock);
  resizeDocks({dock}, {180}, Qt::Vertical);
  statusBar()->addWidget(status_, 1);
  // 1400x900, or most of a smaller screen (restoreGeometry overrides it with the last run's).
  const QSize screen =
      QGuiApplication::primaryScreen() ? QGuiApplication::primaryScreen()->availableSize() : QSize(1400, 900);
  resize(std::min(1400, screen.width() * 95 / 100), std::min(900, screen.height() * 95 / 100));

  connect(view_, &WorldView::blockClicked, this, &MainWindow::selectBlock);
  connect(inspector_, &BlockInspector::factChosen, this,
          [this](std::uint32_t block, const QString& fact) { controller_.why(block, fact.toStdString()); });
  connect(inspector_, &BlockInspector::historyToggled, this, [this](bool on) { controller_.setHistory(on); });
  connect(inspector_, &BlockInspector::sourceClicked, this,
          [this](const QString& file, int line) { showSource(file, line, 1); });
  connect(diagnostics_, &QListWidget::itemClicked, this, [this](QListWidgetItem* item) {
    showSource(item->data(Qt::UserRole).toString(), item->data(Qt::UserRole + 1).toInt(),
               item->data(Qt::UserRole + 2).toInt());
  });
  connect(console_, &ConsolePanel::traceFilterChanged, this, [this](const QString& filter) {
    try {
      controller_.setTraceFilter(filter.toStdString());
      console_->setFilterError({});
    } catch (const std::exception& e) {
      console_->setFilterError(e.what());
    }
  });
}

void MainWindow::showSource(const QString& file, int line, int column) {
  if (QFileInfo(file).canonicalFilePath() != QFileInfo(editor_->path()).canonicalFilePath()) {
    // Never drop the user's edits for a jump.
    if (editor_->document()->isModified())
      return console_->appendMessage("Save the program first: " + file + ":" + QString::number(line) +
                                     " is in another file.");
    QString error;
    if (!editor_->load(file, error)) return console_->appendMessage(error);
  }
  editor_->goTo(line, column);
}

double MainWindow::chosenSpeed() const { return speed_->currentData().toDouble(); }

bool MainWindow::openWorld(const QString& path) {
  options_.world = path.toStdString();
  // The world's own block program runs, unless a Meld program is open in the editor.
  options_.code.clear();
  if (options_.program.empty()) editor_->clear();
  addRecent("recent/worlds", path);
  return restart();
}

bool MainWindow::openProgram(const QString& path) {
  if (!path.endsWith(".mbc")) {
    QString error;
    if (!editor_->load(path, error)) {
      console_->appendMessage(error);
      return false;
    }
  }
  options_.program = path.toStdString();
  options_.code.clear();
  addRecent("recent/programs", path);
  return options_.world.empty() ? compile() : restart();
}

bool MainWindow::compile() {
  if (editor_->path().isEmpty() || !editor_->path().endsWith(".meld")) return true;
  QString error;
  if (editor_->document()->isModified() && !editor_->save(error)) {
    console_->appendMessage(error);
    return false;
  }
  std::ostringstream messages;
  bool ok = true;
  try {
    vsim::loadMeldProgram(editor_->path().toStdString(), options_.includeDirs, &messages);
  } catch (const vsim::ProgramLoadError& e) {
    ok = false;
    if (messages.str().empty()) messages << e.what() << '\n';
  }
  showDiagnostics(QString::fromStdString(messages.str()));
  if (ok) statusBar()->showMessage("compiled " + QFileInfo(editor_->path()).fileName() + ": no errors", 4000);
  return ok;
}

void MainWindow::showDiagnostics(const QString& text) {
  const std::vector<Diagnostic> list = parseDiagnostics(text);
  diagnostics_->clear();
  for (const Diagnostic& d : list) {
    auto* item = new QListWidgetItem(QString("%1:%2:%3: %4: %5")
                                         .arg(QFileInfo(d.file).fileName())
                                         .arg(d.line)
                                         .arg(d.column)
                                         .arg(d.severity, d.message));
    item->setForeground(d.severity == "error" ? QColor(0xb0, 0, 0) : QColor(0x90, 0x60, 0));
    item->setData(Qt::UserRole, d.file);
    item->setData(Qt::UserRole + 1, d.line);
    item->setData(Qt::UserRole + 2, d.column);
    diagnostics_->addItem(item);
  }
  editor_->setDiagnostics(list);
  if (!text.isEmpty() && list.empty()) console_->appendMessage(text.trimmed());
}

bool MainWindow::restart() {
  if (options_.world.empty()) return compile();
  if (!compile()) {
    console_->appendMessage("The program has errors: the run was not restarted.");
    return false;
  }
  selected_ = simcore::kNoBlock;
  const bool ok = controller_.open(options_);
  if (!ok) {
    showDiagnostics(QString::fromStdString(controller_.diagnostics()));
    console_->appendMessage("Cannot start the run: " + QString::fromStdString(controller_.error()));
  } else {
    console_->appendMessage(QString("--- %1 with %2 (%3 blocks)")
                                .arg(QString::fromStdString(controller_.info().worldPath),
                                     QString::fromStdString(controller_.info().codePath))
                                .arg(controller_.info().blockCount));
  }
  showSession();
  return ok;
}

void MainWindow::showSession() {
  const bool open = controller_.isOpen();
  const SessionInfo info = open ? controller_.info() : SessionInfo{};
  // A C BlockCode has no program to show: the world and the inspector only.
  editorPane_->setVisible(!open || info.meld);
  if (open && info.meld && editor_->path().isEmpty() && info.codePath.size() > 5 &&
      info.codePath.compare(info.codePath.size() - 5, 5, ".meld") == 0) {
    QString error;
    editor_->load(QString::fromStdString(info.codePath), error);
  }
  view_->setSession(info);
  view_->setSnapshot(open ? controller_.snapshot() : nullptr);
  inspector_->setSession(info);
  setWindowTitle(
      open ? QString("vsim-ide — %1").arg(QFileInfo(QString::fromStdString(info.worldPath)).fileName())
           : QString("vsim-ide"));
  shownSerial_ = shownSession_ = 0;
  poll();
}

void MainWindow::selectBlock(std::uint32_t block) {
  selected_ = block;
  controller_.select(block);
  view_->setSelected(block);
}

void MainWindow::poll() {
  takeProfiles();
  console_->append(controller_.takeConsoleLines());
  // Fastest runs: draw at most a fifth of the time (a software renderer shares the kernel's
  // cores), and ask for no snapshot in between (each one costs the kernel a copy of the world).
  if (drawingFastest_ && chosenSpeed() == 0 && !view_->readyForFrame(kDrawShare)) return;
  const auto snap = controller_.snapshot();
  if (!snap) {
    status_->setText(controller_.error().empty()
                         ? "No world: File > Open world."
                         : "Not running: " + QString::fromStdString(controller_.error()));
    return;
  }
  if (snap->serial == shownSerial_ && snap->session == shownSession_) return;
  drawingFastest_ = snap->state == RunState::Running;
  const bool failedNow =
      snap->state == RunState::Failed && shownSession_ == snap->session && shownSerial_ != 0;
  shownSerial_ = snap->serial;
  shownSession_ = snap->session;
  view_->setSnapshot(snap);
  if (snap->selected.id == selected_) inspector_->show(snap->selected);
  if (snap->why) {
    if (snap->why->block != selected_ && snap->why->block != simcore::kNoBlock) selectBlock(snap->why->block);
    inspector_->showWhy(*snap->why);
  }
  if (whyAtEnd_ && (snap->state == RunState::Finished || snap->state == RunState::Failed)) {
    whyAtEnd_ = false;
    for (const std::string& spec : options_.why) controller_.why(spec);
  }
  status_->setText(statusText());
  if (failedNow && !snap->error.empty())
    console_->appendMessage("Run failed: " + QString::fromStdString(snap->error));
}

QString MainWindow::statusText() const {
  const auto snap = controller_.snapshot();
  if (!snap) return {};
  QString text = QString("%1   t = %2   events %3   %4 events/s")
                     .arg(runStateName(snap->state))
                     .arg(QString::fromStdString(simcore::formatTime(snap->now)))
                     .arg(snap->events)
                     .arg(snap->eventsPerSecond, 0, 'f', 0);
  if (snap->state == RunState::Finished)
    text += QString("   fingerprint %1").arg(snap->fingerprint, 16, 16, QChar('0'));
  if (snap->state == RunState::Failed) text += "   " + QString::fromStdString(snap->error);
  return text;
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (editor_->document()->isModified()) {
    const auto answer = QMessageBox::question(this, "vsim-ide", "Save the program before closing?",
                                              QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
    if (answer == QMessageBox::Cancel) return event->ignore();
    QString error;
    if (answer == QMessageBox::Save && !editor_->save(error)) {
      QMessageBox::warning(this, "vsim-ide", error);
      return event->ignore();
    }
  }
  QSettings settings;
  settings.setValue("window/geometry", saveGeometry());
  settings.setValue("window/state", saveState());
  settings.setValue("window/splitter", splitter_->saveState());
  settings.setValue("run/speed", speed_->currentIndex());
  event->accept();
}

}  // namespace ide
