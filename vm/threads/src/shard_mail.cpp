#include "meldvm/shard_mail.hpp"

#include <cstring>
#include <string>

namespace meldvm {

namespace {

// A record: its kind (u8), the node (u32), then
// - a fact: the predicate with the negative flag in its top bit (u32), then its arguments' bits
//   (u64 each). A boxed argument (string, list, struct, array, set) is a pointer into the sender's
//   heap, shared (Heap::share) and holding one reference that the record hands to the receiver
//   (a sent fact's is the sender's own, a moving node's waiting message's its mailbox's, a moving
//   node's stored fact's its own; the receiver's mailbox or store takes it over where it can, so
//   that a value crossing threads changes its count once at most);
// - a coordination fact: the opcode (u32) and the value (f64);
// - a moving node (kMigrate): its scheduling state (f64 priority, f64 default priority, u8
//   static), its waiting messages as the chain of their mailbox chunks (u32 first, u32 last, u32
//   words used in the last: Mailboxes::Chain; the chunks and the messages' references go with
//   it, and the messages' boxed values are shared), u8 1 if set-cpu moved it (0: stolen), and its
//   stored facts (u32 count; each u32 copies and a fact as above).
// Native byte order: the bytes never leave the process.
enum RecordKind : std::uint8_t { kFact = 0, kCoordination = 1, kMigrate = 2 };
constexpr std::uint32_t kNegativeBit = 0x80000000u;
// A fact's bytes after its kind and node: the predicate word, then one u64 per argument.
constexpr std::size_t factBytes(std::uint32_t arity) { return 4 + 8 * std::size_t(arity); }
// Written once the node is given: priority, default priority (f64), static (u8), the chain (3 u32).
constexpr std::size_t kStateBytes = 29;

template <class T>
void put(MailBytes& out, T v) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof(T));
}
template <class T>
T get(const MailBytes& in, std::size_t& pos) {
  T v;
  std::memcpy(&v, in.data() + pos, sizeof(T));
  pos += sizeof(T);
  return v;
}

// The nodes of the fact records of a batch ahead of the one being applied, in one walk: the
// node `kFar` records ahead goes to far(node), the one `kNear` ahead to near(node). A record of
// another kind stops the walk until the reader has passed it.
class FactsAhead {
 public:
  static constexpr std::uint32_t kFar = 8, kNear = 4;
  FactsAhead(const MailBytes& in, const PredicateTable& preds) : in_(in), preds_(preds) {}
  // The reader is at the fact record that starts at `pos`.
  template <class Far, class Near>
  void keepAhead(std::size_t pos, Far&& far, Near&& near) {
    if (at_ <= pos) {  // the start, or just past a record of another kind
      at_ = pos;
      lead_ = 0;
    } else {
      --lead_;  // the reader's record was fetched
    }
    while (lead_ < kFar && at_ < in_.size() && in_[at_] == kFact) {
      NodeId node;
      std::uint32_t predWord;
      std::memcpy(&node, in_.data() + at_ + 1, 4);
      std::memcpy(&predWord, in_.data() + at_ + 5, 4);
      far(node);
      if (lead_ < kNear) near(node);  // (at the start of a run of fact records)
      ring_[(seen_++) % kFar] = node;
      at_ += 5 + factBytes(preds_[predWord & ~kNegativeBit].arity());  // kind, node, fact
      ++lead_;
    }
    // The record kNear ahead of the reader, each in turn.
    if (lead_ > kNear) near(ring_[(seen_ - (lead_ - kNear)) % kFar]);
  }

 private:
  const MailBytes& in_;
  const PredicateTable& preds_;
  std::size_t at_ = 0;      // the next record to fetch
  std::uint32_t lead_ = 0;  // records fetched from the reader's on
  std::uint64_t seen_ = 0;  // records fetched in all
  NodeId ring_[kFar] = {};  // the last kFar records' nodes
};

}  // namespace

ShardMail::ShardMail(const Program& program) : program_(program), boxed_(program.predicates.size()) {
  const PredicateTable& preds = program.predicates;
  for (PredId p = 0; p < preds.size(); ++p)
    for (std::uint32_t i = 0; i < preds[p].arity(); ++i)
      if (preds.types().boxed(preds[p].fields[i])) boxed_[p].push_back(i);
}

void ShardMail::handOver(Heap& heap, PredId p, const Value* args, bool adopt,
                         std::vector<Object*>* shareLater) {
  for (std::uint32_t i : boxed_[p]) {  // the record's references, handed over with it
    const TypeId t = program_.predicates[p].fields[i];
    if (!shareLater)
      heap.share(t, args[i]);
    else if (!args[i].isNil())
      shareLater->push_back(args[i].asObject());
    if (!adopt) heap.retain(t, args[i]);
  }
}

namespace {

void writeFact(std::uint8_t* w, PredId p, std::uint32_t arity, const Value* args, bool negative) {
  const std::uint32_t predWord = p | (negative ? kNegativeBit : 0);
  std::memcpy(w, &predWord, 4);
  for (std::uint32_t i = 0; i < arity; ++i) {
    const std::uint64_t bits = args[i].bits();
    std::memcpy(w + 4 + 8 * std::size_t(i), &bits, 8);
  }
}

}  // namespace

void ShardMail::putArgs(MailBytes& out, Heap& heap, PredId p, const Value* args, bool negative, bool adopt,
                        std::vector<Object*>* shareLater) {
  handOver(heap, p, args, adopt, shareLater);
  const std::uint32_t arity = program_.predicates[p].arity();
  const std::size_t at = out.size();
  out.resize(at + factBytes(arity));  // one resize for the whole fact
  writeFact(out.data() + at, p, arity, args, negative);
}

// Every fact a thread sends to another's node comes this way: the record written with one resize.
void ShardMail::putFact(MailBytes& out, Heap& heap, NodeId dest, PredId p, const Value* args, bool negative) {
  if (!boxed_[p].empty()) handOver(heap, p, args, /*adopt=*/true, nullptr);
  const std::uint32_t arity = program_.predicates[p].arity();
  const std::size_t at = out.size();
  out.resize(at + 5 + factBytes(arity));
  std::uint8_t* w = out.data() + at;
  w[0] = kFact;
  std::memcpy(w + 1, &dest, 4);
  writeFact(w + 5, p, arity, args, negative);
}

template <class Use>
void ShardMail::readFact(Machine& to, const MailBytes& in, std::size_t& pos, Use&& use) {
  const auto predWord = get<std::uint32_t>(in, pos);
  const PredId p = predWord & ~kNegativeBit;
  const std::uint32_t arity = program_.predicates[p].arity();
  args_.resize(arity);
  for (std::uint32_t i = 0; i < arity; ++i) args_[i] = Value::fromBits(get<std::uint64_t>(in, pos));
  auto release = [&] {  // the references the record brought, unless use() took them over
    for (std::uint32_t i : boxed_[p]) to.heap().release(program_.predicates[p].fields[i], args_[i]);
  };
  bool adopted;
  try {
    adopted = use(p, args_.data(), (predWord & kNegativeBit) != 0);
  } catch (...) {  // use() took nothing over
    release();
    throw;
  }
  if (!adopted) release();
}

void ShardMail::putCoordination(MailBytes& out, NodeId n, Opcode op, double value) {
  put<std::uint8_t>(out, kCoordination);
  put<std::uint32_t>(out, n);
  put<std::uint32_t>(out, std::uint32_t(op));
  put<double>(out, value);
}

void ShardMail::putNode(MailBytes& out, Machine& from, NodeId n, bool moved) {
  put<std::uint8_t>(out, kMigrate);
  put<std::uint32_t>(out, n);
  const std::size_t stateAt = out.size();
  out.resize(stateAt + kStateBytes);
  put<std::uint8_t>(out, moved ? 1 : 0);
  const std::size_t storedAt = out.size();
  put<std::uint32_t>(out, 0);
  std::uint32_t stored = 0;
  toShare_.clear();  // (nothing reads the record before the move ends: shared at the end)
  Heap& heap = from.heap();
  const Machine::GivenNode given = from.giveNode(
      n,
      [&](PredId p, const Value* args, std::uint32_t copies) {
        put<std::uint32_t>(out, copies);
        putArgs(out, heap, p, args, false, /*adopt=*/false, &toShare_);  // retained while private
        ++stored;
      },
      [&](PredId p, const Value* args) {
        for (std::uint32_t i : boxed_[p])
          if (!args[i].isNil()) toShare_.push_back(args[i].asObject());
      });
  heap.shareAll(toShare_);
  clearBuffer(toShare_);
  std::memcpy(out.data() + storedAt, &stored, sizeof stored);
  std::uint8_t* state = out.data() + stateAt;
  std::memcpy(state, &given.state.prio, 8);
  std::memcpy(state + 8, &given.state.defaultPrio, 8);
  state[16] = given.state.isStatic ? 1 : 0;
  const std::uint32_t chain[3] = {given.waiting.first, given.waiting.last, given.waiting.used};
  std::memcpy(state + 17, chain, sizeof chain);
}

void ShardMail::apply(Machine& to, const MailBytes& in, Taken& taken) {
  // A batch names nodes at random: their mailbox entries are fetched 8 facts ahead, and the ends
  // of their mailboxes (whose address is in the entry) 4 ahead, as Machine::postAll does.
  FactsAhead ahead(in, program_.predicates);
  for (std::size_t pos = 0; pos < in.size();) {
    const std::size_t start = pos;
    const auto kind = get<std::uint8_t>(in, pos);
    const NodeId node = get<std::uint32_t>(in, pos);
    if (kind == kFact) {
      ahead.keepAhead(
          start, [&](NodeId n) { to.prefetchPost(n); }, [&](NodeId n) { to.prefetchPostTail(n); });
      ++taken.facts;
      readFact(to, in, pos, [&](PredId p, const Value* args, bool negative) {
        to.receive(node, p, args, negative, /*adopt=*/true);
        return true;
      });
    } else if (kind == kMigrate) {
      takeNode(to, node, in, pos);
      ++taken.nodes;
    } else {
      const auto op = Opcode(get<std::uint32_t>(in, pos));
      const double value = get<double>(in, pos);
      if (!to.holdsNode(node))
        throw RuntimeError("coordination fact for node @" + std::to_string(node) + ", which does not exist");
      to.coordinateOwned(op, node, value);
    }
  }
}

void ShardMail::takeNode(Machine& to, NodeId n, const MailBytes& in, std::size_t& pos) {
  SerialScheduler::Carried state{};
  state.prio = get<double>(in, pos);
  state.defaultPrio = get<double>(in, pos);
  state.isStatic = get<std::uint8_t>(in, pos) != 0;
  Mailboxes::Chain waiting;
  waiting.first = get<std::uint32_t>(in, pos);
  waiting.last = get<std::uint32_t>(in, pos);
  waiting.used = get<std::uint32_t>(in, pos);
  const bool moved = get<std::uint8_t>(in, pos) != 0;
  to.takeNode(n, state, waiting);
  for (std::uint32_t i = 0, count = get<std::uint32_t>(in, pos); i < count; ++i) {
    const auto copies = get<std::uint32_t>(in, pos);
    readFact(to, in, pos,
             [&](PredId p, const Value* args, bool) { return to.takeStoredFact(n, p, args, copies); });
  }
  if (moved) to.settleMovedNode(n);
  to.takeNodeDone(n);
}

}  // namespace meldvm
