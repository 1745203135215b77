// The IDE's window under Xvfb, driven as a user would: open a world and its Meld program, run to
// the end, select a block and read the inspector (it must equal `vsim --dump` for that block), a
// compile error listed and underlined at its line, step/pause/restart against vsim's fingerprint,
// the Meld colouring, a saved picture of the 3D view.
#include <QDir>
#include <QListWidget>
#include <QProcess>
#include <QStandardPaths>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QTextBlock>
#include <QTextLayout>

#include "block_inspector.hpp"
#include "code_editor.hpp"
#include "console_panel.hpp"
#include "main_window.hpp"
#include "meld_highlighter.hpp"
#include "profile_view.hpp"
#include "world_view.hpp"

namespace {

const QString kSource = MELD_SOURCE_DIR;
const QString kVsim = QString(MELD_BINARY_DIR) + "/apps/vsim/vsim";

vsim::Options gradientOptions() {
  vsim::Options o;
  o.world = (kSource + "/examples/worlds/meld-gradient-tap.xml").toStdString();
  o.program = (kSource + "/examples/meld/gradient-tap.meld").toStdString();
  return o;
}

// vsim's output for the same run (stdout), with --dump.
QString vsimOutput() {
  QProcess p;
  p.start(kVsim, {kSource + "/examples/worlds/meld-gradient-tap.xml", "--program",
                  kSource + "/examples/meld/gradient-tap.meld", "--dump", "--no-progress"});
  if (!p.waitForFinished(60000) || p.exitCode() != 0) return {};
  return QString::fromUtf8(p.readAllStandardOutput());
}

QStringList dumpSection(const QString& output, int block) {
  QStringList lines;
  bool inside = false;
  for (const QString& l : output.split('\n')) {
    if (!l.isEmpty() && l[0].isDigit()) {
      inside = l == QString::number(block);
      continue;
    }
    if (inside && (l.startsWith('!') || (!l.isEmpty() && l[0].isLower()))) lines << l;
  }
  return lines;
}

QString fingerprintOf(const QString& vsimOut) {
  for (const QString& l : vsimOut.split('\n'))
    if (l.trimmed().startsWith("fingerprint")) return l.trimmed().split(' ', Qt::SkipEmptyParts).last();
  return {};
}

// Writes `text` into dir/name; its path, empty if it could not be written.
QString writeFile(const QTemporaryDir& dir, const QString& name, const QByteArray& text) {
  QFile f(dir.filePath(name));
  if (!f.open(QIODevice::WriteOnly) || f.write(text) != text.size()) return {};
  return f.fileName();
}

bool finished(ide::MainWindow& w) {
  w.poll();
  const auto s = w.controller().snapshot();
  return s && s->state == ide::RunState::Finished;
}

}  // namespace

class MainWindowTest : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings of the tests, not the user's
    reference_ = vsimOutput();
    QVERIFY2(!reference_.isEmpty(), "vsim did not run");
  }

  void inspectorShowsTheBlocksDumpSection() {
    ide::MainWindow w(gradientOptions());
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.worldView()->glError().isEmpty());
    QCOMPARE(w.editor()->path(), kSource + "/examples/meld/gradient-tap.meld");
    w.controller().run();
    QTRY_VERIFY_WITH_TIMEOUT(finished(w), 30000);
    w.selectBlock(10);
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.inspector()->headerText().contains("block 10")), 10000);
    QTRY_COMPARE_WITH_TIMEOUT((w.poll(), w.inspector()->factLines()), dumpSection(reference_, 10), 10000);
    QVERIFY(!w.inspector()->factLines().isEmpty());
    QVERIFY(w.statusText().contains(fingerprintOf(reference_)));
    w.inspector()->setFilter("dist");
    for (const QString& l : w.inspector()->factLines()) QVERIFY(l.contains("dist"));
    QVERIFY(!w.inspector()->factLines().isEmpty());
  }

  void clickingABlockSelectsIt() {
    ide::MainWindow w(gradientOptions());
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.controller().snapshot() != nullptr), 10000);
    ide::WorldView* view = w.worldView();
    const QPoint centre(view->width() / 2, view->height() / 2);
    const std::uint32_t under = view->blockAt(centre);
    QVERIFY(under != 0xFFFFFFFFu);
    QTest::mouseClick(view, Qt::LeftButton, {}, centre);
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.inspector()->headerText().contains(QString("block %1").arg(under))),
                             10000);
  }

  void stepPauseRestartGiveVsimsFingerprint() {
    ide::MainWindow w(gradientOptions());
    for (int i = 0; i < 7; ++i) w.controller().step();
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.controller().snapshot()->events == 7), 10000);
    QVERIFY(w.statusText().startsWith("paused"));
    w.controller().run(10.0);
    QTest::qWait(30);
    w.controller().pause();
    QVERIFY(w.restart());
    QCOMPARE(w.controller().snapshot()->events, std::uint64_t(0));
    w.controller().step();
    w.controller().run();
    QTRY_VERIFY_WITH_TIMEOUT(finished(w), 30000);
    QVERIFY(w.statusText().contains(fingerprintOf(reference_)));
  }

  void compileErrorIsListedAndUnderlinedAtItsLine() {
    QTemporaryDir dir;
    const QString path = writeFile(
        dir, "broken.meld",
        "include #blinkyblocks.meld\n\ntype dist(node, min int).\n\n!dist(B, D) -o !setColor2(B, Q).\n");
    QVERIFY(!path.isEmpty());
    vsim::Options o = gradientOptions();
    o.program.clear();
    ide::MainWindow w(o);
    QVERIFY(!w.openProgram(path));
    QVERIFY(w.diagnosticsList()->count() >= 1);
    const QListWidgetItem* first = w.diagnosticsList()->item(0);
    QVERIFY2(first->text().contains("broken.meld:5:"), qPrintable(first->text()));
    const auto marks = w.editor()->underlined();
    QVERIFY(!marks.empty());
    QCOMPARE(w.editor()->document()->findBlock(marks[0].first).blockNumber(), 4);
    // A click on the message puts the cursor there.
    w.editor()->goTo(1, 1);
    Q_EMIT w.diagnosticsList()->itemClicked(w.diagnosticsList()->item(0));
    QCOMPARE(w.editor()->textCursor().blockNumber(), 4);
    // The IDE keeps running: the message is in the console, the window answers.
    QVERIFY(w.console()->text().contains("errors"));
    // Fixed and saved: the run starts.
    QTextCursor edit(w.editor()->document()->findBlockByNumber(4));  // as typed: Q becomes D
    edit.setPosition(edit.position() + int(QString("!dist(B, D) -o !setColor2(B, ").size()));
    edit.deleteChar();
    edit.insertText("D");
    QVERIFY(w.editor()->document()->isModified());
    QVERIFY2(w.restart(), qPrintable(w.console()->text()));
    QCOMPARE(w.diagnosticsList()->count(), 0);
    QVERIFY(w.controller().isOpen());
  }

  void profilesTheProgramOnThreads() {
    // Run > Profile on threads: a ring of tokens (a program on its own graph) at -j 1 and -j 2 in
    // the background; the window stays live, then the profile view opens with both profiles and
    // their speedup table.
    QTemporaryDir dir;
    QString source = "type route edge(node, node).\ntype linear token(node, int).\n";
    for (int i = 0; i < 32; ++i) source += QString("!edge(@%1, @%2).\n").arg(i).arg((i + 1) % 32);
    for (int i = 0; i < 64; ++i) source += QString("token(@%1, 20).\n").arg(i % 32);
    source += "token(A, N), N > 0, !edge(A, B) -o token(B, N - 1).\n";
    const QString ring = writeFile(dir, "ring.meld", source.toUtf8());
    QVERIFY(!ring.isEmpty());
    vsim::Options o;
    ide::MainWindow w(o);
    QVERIFY(!w.profileProgram({1, 2}));  // no program yet: a message, nothing runs
    QVERIFY(w.console()->text().contains("open a Meld program first"));
    QVERIFY(w.openProgram(ring));
    QVERIFY2(w.profileProgram({1, 2}), qPrintable(w.console()->text()));
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.lastProfileWindow() != nullptr), 60000);
    auto* view = qobject_cast<ide::ProfileView*>(w.lastProfileWindow());
    QVERIFY(view);
    QCOMPARE(int(view->profiles().size()), 2);
    QCOMPARE(view->sweepTable()->rowCount(), 2);
    unsigned long long facts = 0;
    for (const ide::ThreadSummary& s : view->profiles()[1].summary) facts += s.facts;
    QCOMPARE(facts, 32ull + 64 + 64 * 20);  // edges, tokens, every hop
  }

  void stopsAProfilingRun() {
    // Run > Stop profiling: a run that would last minutes stops at once, and no window opens.
    QTemporaryDir dir;
    const QString count = writeFile(
        dir, "count.meld",
        "type linear count(node, int).\ncount(@0, 0).\ncount(A, N), N < 2000000000 -o count(A, N + 1).\n");
    QVERIFY(!count.isEmpty());
    vsim::Options o;
    ide::MainWindow w(o);
    QVERIFY(w.openProgram(count));
    QVERIFY(!w.stopProfiling());  // nothing runs yet
    QVERIFY(w.console()->text().contains("no profiling is running"));
    QVERIFY2(w.profileProgram({1, 2}), qPrintable(w.console()->text()));
    QTest::qWait(200);
    QVERIFY(w.stopProfiling());
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.console()->text().contains("Profile: stopped")), 10000);
    QVERIFY(w.lastProfileWindow() == nullptr);
  }

  void badWorldIsAMessage() {
    vsim::Options o;
    ide::MainWindow w(o);
    QVERIFY(!w.openWorld(kSource + "/no/such/world.xml"));
    QVERIFY(w.console()->text().contains("cannot open world file"));
    w.poll();
  }

  void whyTreeOfAFactAndItsRule() {
    ide::MainWindow w(gradientOptions());
    w.controller().setRecordDerivations(true);
    QVERIFY(w.restart());
    w.controller().run();
    QTRY_VERIFY_WITH_TIMEOUT(finished(w), 30000);
    w.selectBlock(10);
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.inspector()->factLines().contains("!dist(2)")), 10000);
    QVERIFY(w.inspector()->chooseFact("!dist(2)"));
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), !w.inspector()->whyRows().isEmpty()), 10000);
    // The tree vsim --why prints (tests/cli/expected), with the program named as the IDE got it.
    QFile expectedFile(kSource + "/tests/cli/expected/why-gradient.txt");
    QVERIFY(expectedFile.open(QIODevice::ReadOnly));
    QString expected = QString::fromUtf8(expectedFile.readAll());
    expected.replace("examples/meld/gradient-tap.meld", kSource + "/examples/meld/gradient-tap.meld");
    QCOMPARE(w.inspector()->whyRows().join('\n') + '\n', expected);
    // The rule of the fact: a click opens the program at its line (23).
    w.editor()->goTo(1, 1);
    w.inspector()->clickFirstWhyRow();
    QCOMPARE(w.editor()->textCursor().blockNumber(), 22);
  }

  void historyOfTheSelectedBlock() {
    ide::MainWindow w(gradientOptions());
    w.selectBlock(24);
    w.inspector()->setHistoryRecorded(true);
    w.controller().run();
    QTRY_VERIFY_WITH_TIMEOUT(finished(w), 30000);
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.inspector()->historyLines().size() > 5), 10000);
    const QStringList lines = w.inspector()->historyLines();
    QVERIFY(lines.filter("event tap").size() == 1);
    QVERIFY(lines.filter("+ !dist(0)").size() == 1);
    QVERIFY(lines.filter("+ !dist(0)")[0].startsWith("1.000000000 s"));
    w.inspector()->setFilter("dist");
    QVERIFY(!w.inspector()->historyLines().isEmpty());
    for (const QString& l : w.inspector()->historyLines()) QVERIFY(l.contains("dist"));
    w.inspector()->setHistoryRecorded(false);
  }

  void runTimeErrorsAndBadCodeAreMessages() {
    QTemporaryDir dir;
    QVERIFY(!writeFile(
                 dir, "div.meld",
                 "include #blinkyblocks.meld\ntype v(node, int).\n!at(B, X, _, _) -o !v(B, 10 / (X - X)).\n")
                 .isEmpty());
    vsim::Options o = gradientOptions();
    o.program = dir.filePath("div.meld").toStdString();
    ide::MainWindow w(o);
    w.show();
    w.controller().run();
    QTRY_VERIFY_WITH_TIMEOUT((w.poll(), w.controller().snapshot()->state == ide::RunState::Failed), 30000);
    w.poll();
    QVERIFY(w.statusText().startsWith("failed"));
    QVERIFY2(w.console()->text().contains("integer division by zero"), qPrintable(w.console()->text()));
    // The window goes on: a good program runs again.
    QVERIFY(w.openProgram(kSource + "/examples/meld/gradient-tap.meld"));
    w.controller().run();
    QTRY_VERIFY_WITH_TIMEOUT(finished(w), 30000);

    const QString badSo = writeFile(dir, "bad.so", "not a shared object");
    QVERIFY(!badSo.isEmpty());
    vsim::Options c;
    c.world = (kSource + "/examples/worlds/color-flood.xml").toStdString();
    c.code = badSo.toStdString();
    ide::MainWindow broken(c);
    QVERIFY(!broken.controller().isOpen());
    QVERIFY(broken.console()->text().contains("is not a shared object"));
    broken.poll();
    QVERIFY(broken.statusText().isEmpty());
  }

  void highlighterColoursMeld() {
    ide::CodeEditor editor;
    editor.setPlainText("type linear go(node). // c\n/* a\nb */ !go(X, 3) -o go(X, \"s\").\n");
    ide::MeldHighlighter* h = editor.highlighter();
    auto formatAt = [&](int line, int column) {
      const QTextBlock block = editor.document()->findBlockByNumber(line);
      for (const QTextLayout::FormatRange& r : block.layout()->formats())
        if (column >= r.start && column < r.start + r.length) return r.format.foreground().color();
      return QColor();
    };
    using Role = ide::MeldHighlighter::Role;
    QCOMPARE(formatAt(0, 0), h->format(Role::Keyword).foreground().color());     // type
    QCOMPARE(formatAt(0, 12), h->format(Role::Predicate).foreground().color());  // go
    QCOMPARE(formatAt(0, 15), h->format(Role::Type).foreground().color());       // node
    QCOMPARE(formatAt(0, 23), h->format(Role::Comment).foreground().color());    // c
    QCOMPARE(formatAt(1, 3), h->format(Role::Comment).foreground().color());     // a (block comment)
    QCOMPARE(formatAt(2, 0), h->format(Role::Comment).foreground().color());     // b (still inside)
    QCOMPARE(formatAt(2, 9), h->format(Role::Variable).foreground().color());    // X
    QCOMPARE(formatAt(2, 12), h->format(Role::Number).foreground().color());     // 3
    QCOMPARE(formatAt(2, 25), h->format(Role::String).foreground().color());     // "s"
  }

  void exportsFramesSeenFromTheView() {
    ide::MainWindow w(gradientOptions());
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QTemporaryDir dir;
    QCOMPARE(w.exportFrames(dir.path(), 400 * simcore::kMillisecond), 4);
    const QStringList frames = QDir(dir.path()).entryList({"frame-*.png"}, QDir::Files, QDir::Name);
    QCOMPARE(frames.size(), 4);
    QCOMPARE(QImage(dir.filePath(frames[0])).size(),
             w.worldView()->size() * w.worldView()->devicePixelRatio());
    QVERIFY(w.console()->text().contains("Exported 4 frames"));
    // The window's own run is untouched: still at its start.
    w.poll();
    QCOMPARE(w.controller().snapshot()->events, std::uint64_t(0));
  }

  void savesThe3dViewAsPng() {
    ide::MainWindow w(gradientOptions());
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.controller().run();
    QTRY_VERIFY_WITH_TIMEOUT(finished(w), 30000);
    QTemporaryDir dir;
    const QString path = dir.filePath("view.png");
    QVERIFY(w.saveScreenshot(path));
    const QImage image(path);
    QCOMPARE(image.size(), w.worldView()->size() * w.worldView()->devicePixelRatio());
    // Blocks are drawn: the centre block is red (distance 0), the picture is not one colour.
    QSet<QRgb> colours;
    for (int y = 0; y < image.height(); y += 7)
      for (int x = 0; x < image.width(); x += 7) colours.insert(image.pixel(x, y));
    QVERIFY(colours.size() > 6);
  }

 private:
  QString reference_;
};

QTEST_MAIN(MainWindowTest)
#include "qtest_main_window.moc"
