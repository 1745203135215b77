#include "meldvm/block_runtime.hpp"

#include <cstdio>
#include <ostream>

#include "meldvm/arith.hpp"
#include "meldvm/derivation_log.hpp"
#include "meldvm/dump.hpp"

namespace meldvm {

namespace {

constexpr std::uint32_t kVisibleSimColors[12] = {0xFF0000, 0xFFA500, 0xFFFF00, 0x00FF00, 0x00FFFF, 0x0000FF,
                                                 0xFFFFFF, 0xFF00FF, 0xFFC0CB, 0xFFD700, 0xA52A2A, 0x808080};
constexpr std::uint32_t kLinearMeldColors[9] = {0xFF0000, 0xFFA500, 0xFFFF00, 0x00FF00, 0x00FFFF,
                                                0x0000FF, 0xFFFFFF, 0x800080, 0xFFC0CB};

std::uint32_t clampByte(std::int32_t v) { return std::uint32_t(v < 0 ? 0 : v > 255 ? 255 : v); }

}  // namespace

struct BlockRuntime::BlockState {
  std::int32_t neighbors;  // the count last asserted in neighborCount
  std::int32_t at[3];      // the position last asserted in at
  std::uint8_t terminated;
};

BlockRuntime::BlockRuntime(const Program& program, std::uint32_t blockCount, BlockRuntimeOptions options)
    : program_(program),
      options_(std::move(options)),
      sensing_(std::make_unique<Sensing>(checkRobotProgram(program))) {
  if (program.nodeSourceIds.size() > blockCount)
    throw BlockProgramError("the program mentions node @" + std::to_string(program.nodeSourceIds.size() - 1) +
                            " but the world has only " + std::to_string(blockCount) + " blocks");

  MachineOptions mo;
  mo.args = options_.args;
  mo.output = options_.output;
  mo.host = this;
  mo.nodes = blockCount;
  mo.native = options_.native;
  machine_ = std::make_unique<Machine>(program, mo);
  const Sensing& s = *sensing_;
  if (s.neighbor != Program::kNoPred && options_.neighborFacts)
    machine_->reserveFacts(s.neighbor, options_.neighborFacts);
  if (s.vacant != Program::kNoPred && options_.vacantFacts)
    machine_->reserveFacts(s.vacant, options_.vacantFacts);
  code_ = vs_blockcode{VS_ABI_VERSION, "meld-vm", sizeof(BlockState), &onStart, &onEvent, &onInfo, this};
}

BlockRuntime::~BlockRuntime() = default;

// ---- callbacks ----

void BlockRuntime::onStart(vs_ctx* ctx) { static_cast<BlockRuntime*>(ctx->user)->start(ctx); }
void BlockRuntime::onEvent(vs_ctx* ctx, const vs_event* ev) {
  static_cast<BlockRuntime*>(ctx->user)->event(ctx, *ev);
}

int BlockRuntime::onInfo(vs_ctx* ctx, char* text, size_t capacity) {
  const auto& self = *static_cast<const BlockRuntime*>(ctx->user);
  const Database& db = self.machine_->database();
  std::uint32_t facts = 0;
  for (PredId p = 0; p < self.program_.predicates.size(); ++p) facts += db.factCount(ctx->block, p);
  return std::snprintf(text, capacity, "Meld node @%u: %u facts", ctx->block, facts);
}

void BlockRuntime::failed(vs_ctx* ctx, const std::exception& e) {
  if (error_.empty()) error_ = e.what();
  ctx->api->trace(ctx, e.what());
}

void BlockRuntime::start(vs_ctx* ctx) {
  if (!error_.empty()) return;
  try {
    machine_->start();
    // A block added to the running world (the IDE): its node is made now, with the next id.
    while (machine_->database().nodeCount() <= ctx->block) machine_->addHostNode();
    auto& st = *static_cast<BlockState*>(ctx->state);
    st.neighbors = ctx->api->neighbor_count(ctx);
    ctx->api->position(ctx, st.at);
    ctx_ = ctx;
    assertSensors(ctx);
    runNode(ctx);
  } catch (const std::exception& e) {
    failed(ctx, e);
  }
}

void BlockRuntime::receiveSensed(NodeId n, PredId p, const Value* args, bool negative) {
  if (DerivationLog* log = machine_->derivations(); log && !negative) [[unlikely]] {
    Derivation d;
    d.kind = Derivation::Kind::Sensed;
    d.at = n;
    if (log->clock) d.time = log->clock();
    std::string text;
    appendFact(text, machine_->database(), p, args);
    log->record(n, std::move(text), std::move(d));
  }
  machine_->receive(n, p, args, negative);
}

void BlockRuntime::retractInverseRoutes(NodeId n, NodeId other) {
  // The inverse route facts at n that name `other` (`___robhgien(n, other, face)`: other has n as
  // a neighbour) were sent by `other`; the link is gone, so it cannot take them back: n does.
  const Database& db = machine_->database();
  for (PredId p = 0; p < program_.predicates.size(); ++p) {
    const PredicateDesc& d = program_.predicates[p];
    if (!d.reverseRoute || d.linear || d.arity() == 0 || d.fields[0] != TypeTable::kNode) continue;
    std::vector<Value>& stale = retracting_;
    std::vector<std::uint32_t>& copies = retractingCopies_;
    stale.clear();
    copies.clear();
    for (FactRef f = db.first(n, p); f != kNoFact; f = db.next(p, f)) {
      const Value* args = db.args(p, f);
      if (args[0].asNode() != other) continue;
      for (std::uint32_t i = 0; i < d.arity(); ++i) {
        machine_->database().heap().retain(d.fields[i], args[i]);
        stale.push_back(args[i]);
      }
      copies.push_back(db.copies(p, f));
    }
    for (std::size_t k = 0; k < copies.size(); ++k) {
      const Value* args = stale.data() + k * d.arity();
      for (std::uint32_t c = 0; c < copies[k]; ++c) machine_->receive(n, p, args, true);
      for (std::uint32_t i = 0; i < d.arity(); ++i) machine_->database().heap().release(d.fields[i], args[i]);
    }
  }
}

void BlockRuntime::recordDerivations(DerivationLog* log) {
  if (log) log->clock = [this] { return ctx_ ? std::int64_t(vs_now(ctx_)) : std::int64_t(-1); };
  machine_->recordDerivations(log);
}

void BlockRuntime::sense(NodeId n, PredId p, std::initializer_list<std::int32_t> ints, bool negative) {
  if (p == Program::kNoPred) return;
  Value args[4];
  std::size_t i = 0;
  for (std::int32_t v : ints) args[i++] = Value::fromInt(v);
  receiveSensed(n, p, args, negative);
}

void BlockRuntime::assertSensors(vs_ctx* ctx) {
  const Sensing& s = *sensing_;
  const auto& st = *static_cast<BlockState*>(ctx->state);
  const NodeId n = ctx->block;
  for (int f = 0; f < ctx->api->face_count(ctx); ++f) {
    const vs_block_id other = ctx->api->neighbor(ctx, f);
    if (other != VS_NO_BLOCK) {
      if (s.neighbor != Program::kNoPred) {
        const Value args[2] = {Value::fromNode(other), Value::fromInt(f)};
        receiveSensed(n, s.neighbor, args, false);
      }
    } else {
      sense(n, s.vacant, {f}, false);
    }
  }
  sense(n, s.neighborCount, {st.neighbors}, false);
  sense(n, s.at, {st.at[0], st.at[1], st.at[2]}, false);
}

void BlockRuntime::event(vs_ctx* ctx, const vs_event& ev) {
  auto& st = *static_cast<BlockState*>(ctx->state);
  if (!error_.empty() || st.terminated) return;
  const Sensing& s = *sensing_;
  const NodeId n = ctx->block;
  ctx_ = ctx;
  try {
    switch (ev.kind) {
      case VS_EV_MESSAGE: {
        decodeFact(static_cast<const std::uint8_t*>(ev.data), ev.size, program_.predicates,
                   machine_->database().heap(), decoded_);
        machine_->receive(n, decoded_.pred, decoded_.args.data(), decoded_.negative);
        const auto& fields = program_.predicates[decoded_.pred].fields;
        for (std::size_t i = 0; i < decoded_.args.size(); ++i)
          machine_->database().heap().release(fields[i], decoded_.args[i]);
        break;
      }
      case VS_EV_NEIGHBOR_ADDED:
      case VS_EV_NEIGHBOR_REMOVED: {
        const bool added = ev.kind == VS_EV_NEIGHBOR_ADDED;
        if (s.neighbor != Program::kNoPred) {
          const Value args[2] = {Value::fromNode(ev.other), Value::fromInt(ev.face)};
          receiveSensed(n, s.neighbor, args, !added);
        }
        if (!added) retractInverseRoutes(n, ev.other);
        sense(n, s.vacant, {ev.face}, added);
        sense(n, s.neighborCount, {st.neighbors}, true);
        st.neighbors += added ? 1 : -1;
        sense(n, s.neighborCount, {st.neighbors}, false);
        break;
      }
      case VS_EV_TAP:
        sense(n, s.tap, {}, false);
        break;
      case VS_EV_SENSOR:
        sense(n, s.accel, {ev.values[0]}, false);
        sense(n, s.shake, {ev.values[0], ev.values[1], ev.values[2]}, false);
        break;
      case VS_EV_MOBILE:  // values[0]: the mobile; values[1]: 1 it came over, 0 it left
        sense(n, s.mobileOver, {ev.values[0]}, ev.values[1] == 0);
        break;
      case VS_EV_MOTION_END:
        ctx->api->position(ctx, st.at);
        sense(n, s.at, {st.at[0], st.at[1], st.at[2]}, false);
        break;
      case VS_EV_TIMER: {
        if (ev.tag >= delayed_.size()) return;
        const std::vector<std::uint8_t>& bytes = delayed_[ev.tag];
        decodeFact(bytes.data(), bytes.size(), program_.predicates, machine_->database().heap(), decoded_);
        freeDelayed_.push_back(std::uint32_t(ev.tag));
        if (program_.predicates[decoded_.pred].action)  // a delayed action: its time has come
          action(n, n, decoded_.pred, decoded_.args.data());
        else
          machine_->receive(n, decoded_.pred, decoded_.args.data(), decoded_.negative);
        const auto& fields = program_.predicates[decoded_.pred].fields;
        for (std::size_t i = 0; i < decoded_.args.size(); ++i)
          machine_->database().heap().release(fields[i], decoded_.args[i]);
        break;
      }
      default:
        return;
    }
    runNode(ctx);
  } catch (const std::exception& e) {
    failed(ctx, e);
  }
}

void BlockRuntime::runNode(vs_ctx* ctx) {
  // A run may give its own block new facts (an action's sensing change): run again for those.
  do {
    firedInRun_ = machine_->stats().rulesFired;
    // randint & co. draw from the block's own stream of the kernel: --seed changes them, and they
    // do not depend on the order in which blocks run.
    if (machine_->usesRandom())
      machine_->reseed((std::uint64_t(ctx->api->random_u32(ctx)) << 32) | ctx->api->random_u32(ctx));
    machine_->runNode(ctx->block);
  } while (machine_->hasWork(ctx->block) && !machine_->stopped());
}

// ---- what the machine hands over ----

bool BlockRuntime::reachable(NodeId from, NodeId to) {
  if (!ctx_ || ctx_->block != from) return false;
  for (int f = 0; f < ctx_->api->face_count(ctx_); ++f)
    if (ctx_->api->neighbor(ctx_, f) == to) return true;
  return false;
}

void BlockRuntime::transmit(NodeId from, NodeId to, PredId p, const Value* args, bool negative,
                            std::uint32_t delayMs) {
  vs_ctx* ctx = ctx_;
  const std::uint64_t fired = machine_->stats().rulesFired - firedInRun_;
  const vs_time delay = vs_time(fired) * options_.timePerRuleNs + vs_time(delayMs) * VS_MS;
  buffer_.clear();
  encodeFact(buffer_, program_.predicates, p, args, negative);
  if (to == from) {  // a delayed fact for the block itself: wait for a timer
    std::uint32_t slot;
    if (!freeDelayed_.empty()) {
      slot = freeDelayed_.back();
      freeDelayed_.pop_back();
      delayed_[slot] = buffer_;
    } else {
      slot = std::uint32_t(delayed_.size());
      delayed_.push_back(buffer_);
    }
    ctx->api->set_timer(ctx, delay, slot, nullptr);
    return;
  }
  for (int f = 0; f < ctx->api->face_count(ctx); ++f)
    if (ctx->api->neighbor(ctx, f) == to) {
      ctx->api->send(ctx, f, buffer_.data(), std::uint32_t(buffer_.size()), delay);
      messageBytes_ += buffer_.size();
      ++messages_;
      return;
    }
  throw BlockProgramError("block " + std::to_string(from) + ": fact " + program_.predicates[p].name +
                          " for block " + std::to_string(to) + ", which is no longer a neighbour");
}

void BlockRuntime::action(NodeId from, NodeId, PredId p, const Value* args) {
  vs_ctx* ctx = ctx_;
  if (!ctx || ctx->block != from) return;
  const Sensing& s = *sensing_;
  if (p == s.setcolor2) {
    const std::int32_t c = args[0].asInt();
    if (options_.palette == Palette::VisibleSim) {
      ctx->api->set_color(ctx, kVisibleSimColors[((c % 12) + 12) % 12]);
    } else if (c >= 0 && c < 9) {
      ctx->api->set_color(ctx, kLinearMeldColors[c]);
    }
  } else if (p == s.setcolor && program_.predicates[p].arity() >= 3) {
    ctx->api->set_color(
        ctx, clampByte(args[0].asInt()) << 16 | clampByte(args[1].asInt()) << 8 | clampByte(args[2].asInt()));
  } else if (p == s.moveto) {
    const std::int32_t xyz[3] = {args[0].asInt(), args[1].asInt(), args[2].asInt()};
    const int face = ctx->api->face_toward(ctx, xyz);
    if (face < 0)
      throw RuntimeError("moveTo(" + std::to_string(xyz[0]) + ", " + std::to_string(xyz[1]) + ", " +
                         std::to_string(xyz[2]) + "): not a cell next to the block");
    if (ctx->api->move(ctx, face) == VS_OK && s.at != Program::kNoPred) {
      auto& st = *static_cast<BlockState*>(ctx->state);
      sense(from, s.at, {st.at[0], st.at[1], st.at[2]}, true);  // §7.2: `at` is retracted at once
    } else {
      ctx->api->trace(ctx, "moveTo refused by the world (cell taken, no pivot, no motion, or a result that would not stand)");
    }
  } else if (p == s.senseMobile) {
    std::int32_t mobile;
    double at[3];
    if (s.mobileAt != Program::kNoPred && ctx->api->mobile_above(ctx, &mobile, at) == VS_OK) {
      const Value sensed[4] = {Value::fromInt(mobile), Value::fromFloat(at[0]), Value::fromFloat(at[1]),
                               Value::fromInt(std::int32_t(ctx->api->now(ctx) / VS_MS))};
      receiveSensed(from, s.mobileAt, sensed, false);
    }
  } else if (p == s.airJet) {
    const std::int32_t face = args[0].asInt(), ms = args[2].asInt();
    const int rc = ctx->api->air_jet(ctx, face, args[1].asFloat(), vs_time(ms) * VS_MS);
    if (rc != VS_OK)
      throw RuntimeError("airJet(" + std::to_string(face) + ", " + std::to_string(args[1].asFloat()) + ", " +
                         std::to_string(ms) + "): refused by the world (" +
                         (rc == VS_ERR_UNSUPPORTED ? "no physics here" : "bad face, power or duration") + ")");
  } else if (p == s.terminate) {
    static_cast<BlockState*>(ctx->state)->terminated = 1;
  } else if (p == s.writeString && options_.output) {
    *options_.output << stringOf(args[0]) << '\n';
  }
}

}  // namespace meldvm
