#include "profile_data.hpp"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <algorithm>

namespace ide {

namespace {

void addSpan(Profile& p, int tid, const QJsonObject& e) {
  const QString name = e.value("name").toString();
  ProfileSpan s{ProfileSpan::Kind::Run, e.value("ts").toDouble(), 0};
  s.endUs = s.beginUs + e.value("dur").toDouble();
  const QJsonObject args = e.value("args").toObject();
  if (name == "idle") {
    s.kind = ProfileSpan::Kind::Idle;
  } else if (name == "steal") {
    s.kind = ProfileSpan::Kind::Steal;
    s.nodeRuns = args.value("nodes taken").toVariant().toULongLong();
  } else {
    s.nodeRuns = args.value("node runs").toVariant().toULongLong();
    s.facts = args.value("facts derived").toVariant().toULongLong();
  }
  if (std::size_t(tid) >= p.threads.size()) p.threads.resize(std::size_t(tid) + 1);
  p.threads[std::size_t(tid)].push_back(s);
  p.endUs = std::max(p.endUs, s.endUs);
}

void summarize(Profile& p) {
  p.summary.assign(p.threads.size(), {});
  for (std::size_t t = 0; t < p.threads.size(); ++t) {
    auto& spans = p.threads[t];
    std::sort(spans.begin(), spans.end(), [](const auto& a, const auto& b) { return a.beginUs < b.beginUs; });
    ThreadSummary& s = p.summary[t];
    for (const ProfileSpan& x : spans) {
      const double d = x.endUs - x.beginUs;
      switch (x.kind) {
        case ProfileSpan::Kind::Run:
          s.runUs += d, s.nodeRuns += x.nodeRuns, s.facts += x.facts;
          break;
        case ProfileSpan::Kind::Idle:
          s.idleUs += d;
          break;
        case ProfileSpan::Kind::Steal:
          s.stealUs += d, s.nodesTaken += x.nodeRuns;
          break;
      }
    }
  }
}

}  // namespace

std::optional<Profile> loadProfile(const QString& path, QString& error) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) {
    error = path + ": cannot read it";
    return std::nullopt;
  }
  QJsonParseError parse{};
  const QJsonDocument doc = QJsonDocument::fromJson(f.readAll(), &parse);
  if (doc.isNull()) {
    error = path + ": not JSON (" + parse.errorString() + " at byte " + QString::number(parse.offset) + ")";
    return std::nullopt;
  }
  const QJsonArray events = doc.object().value("traceEvents").toArray();
  Profile p;
  p.path = path;
  for (const QJsonValue& v : events) {
    const QJsonObject e = v.toObject();
    const QString ph = e.value("ph").toString();
    if (ph == "M" && e.value("name").toString() == "process_name")
      p.title = e.value("args").toObject().value("name").toString();
    const int tid = e.value("tid").toInt(-1);
    if (ph == "M" && e.value("name").toString() == "thread_name" && tid >= 0 && tid < 4096) {
      if (std::size_t(tid) >= p.threads.size())
        p.threads.resize(std::size_t(tid) + 1);  // a row even without spans
      if (std::size_t(tid) >= p.laneNames.size()) p.laneNames.resize(std::size_t(tid) + 1);
      p.laneNames[std::size_t(tid)] = e.value("args").toObject().value("name").toString();
    }
    if (ph == "X" && tid >= 0 && tid < 4096) addSpan(p, tid, e);
  }
  p.simulated = p.title.startsWith("vsim multicore ");
  if ((!p.title.startsWith("meld -j ") && !p.simulated) || p.threads.empty()) {
    error = path +
            ": not a profile written by `meld --profile` or `vsim --target multicore --profile`"
            " (no worker threads or cores in it)";
    return std::nullopt;
  }
  p.laneNames.resize(p.threads.size());
  for (std::size_t t = 0; t < p.laneNames.size(); ++t)
    if (p.laneNames[t].isEmpty()) p.laneNames[t] = (p.simulated ? "core " : "worker ") + QString::number(t);
  summarize(p);
  return p;
}

std::vector<SweepRow> sweep(const std::vector<Profile>& profiles) {
  std::vector<SweepRow> rows;
  for (const Profile& p : profiles) rows.push_back({int(p.threads.size()), p.endUs / 1e6, 0, 0});
  std::stable_sort(rows.begin(), rows.end(),
                   [](const auto& a, const auto& b) { return a.threads < b.threads; });
  if (rows.empty()) return rows;
  const SweepRow base = rows.front();
  for (SweepRow& r : rows) {
    r.speedup = r.wallSeconds > 0 ? base.wallSeconds / r.wallSeconds : 0;
    r.efficiency = r.speedup * base.threads / r.threads;
  }
  return rows;
}

}  // namespace ide
