#include "meldvm/shard_mail.hpp"

#include <cstring>
#include <string>

namespace meldvm {

namespace {

// A record: its kind (u8), the node (u32), then for a fact its length (u32) and the fact as
// meldvm/fact_codec.hpp encodes it, for a coordination fact the opcode (u32) and the value (f64).
// Native byte order: the bytes never leave the process.
// A fact of a predicate with only scalar fields (kScalarFact): the node (u32), the predicate with
// the negative flag in its top bit (u32), then the arguments' bits (u64 each).
// A moving node: kMigrate, the node, its scheduling state (f64 priority, f64 default priority, u8
// static), u8 1 if set-cpu moved it (0: stolen), then its stored facts (u32 count; each u32
// copies, u32 length, the fact) and its waiting messages (u32 count; each u32 length, the fact).
// Facts are in the sharing format of fact_codec.hpp: their lists may refer to cells of lists sent
// earlier in the same batch. kEndOfBatch (the node 0) ends a batch whose facts shared lists: what
// follows refers to none of its cells.
enum RecordKind : std::uint8_t {
  kFact = 0,
  kCoordination = 1,
  kMigrate = 2,
  kScalarFact = 3,
  kEndOfBatch = 4
};
constexpr std::uint32_t kNegativeBit = 0x80000000u;
constexpr std::size_t kStateBytes = 17;  // priority, default priority (f64), static (u8)

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

}  // namespace

ShardMail::ShardMail(const Program& program) : program_(program), scalar_(program.predicates.size(), 1) {
  const PredicateTable& preds = program.predicates;
  for (PredId p = 0; p < preds.size(); ++p)
    for (TypeId t : preds[p].fields)
      if (preds.types().boxed(t)) scalar_[p] = 0;
}

void ShardMail::putLengthAndFact(MailBytes& out, ListEncoderShare& share, PredId p, const Value* args,
                                 bool negative) {
  put<std::uint32_t>(out, 0);  // the length, once known
  const std::size_t start = out.size();
  encodeFact(out, program_.predicates, p, args, negative, &share);
  const auto length = std::uint32_t(out.size() - start);
  std::memcpy(out.data() + start - sizeof length, &length, sizeof length);
}

void ShardMail::putFact(MailBytes& out, ListEncoderShare& share, NodeId dest, PredId p, const Value* args,
                        bool negative) {
  if (scalar_[p]) {
    putScalarFact(out, dest, p, args, negative);
    return;
  }
  put<std::uint8_t>(out, kFact);
  put<std::uint32_t>(out, dest);
  putLengthAndFact(out, share, p, args, negative);
}

void ShardMail::endBatch(MailBytes& out, ListEncoderShare& share) {
  if (share.empty()) return;
  put<std::uint8_t>(out, kEndOfBatch);
  put<std::uint32_t>(out, 0);
  share.reset();
}

void ShardMail::putScalarFact(MailBytes& out, NodeId dest, PredId p, const Value* args, bool negative) {
  const std::uint32_t arity = program_.predicates[p].arity();
  const std::size_t at = out.size();
  out.resize(at + 9 + 8 * std::size_t(arity));  // one resize for the whole record
  std::uint8_t* w = out.data() + at;
  const std::uint32_t predWord = p | (negative ? kNegativeBit : 0);
  w[0] = kScalarFact;
  std::memcpy(w + 1, &dest, 4);
  std::memcpy(w + 5, &predWord, 4);
  for (std::uint32_t i = 0; i < arity; ++i) {
    const std::uint64_t bits = args[i].bits();
    std::memcpy(w + 9 + 8 * std::size_t(i), &bits, 8);
  }
}

void ShardMail::readScalarFact(Machine& to, NodeId node, const MailBytes& in, std::size_t& pos) {
  const auto predWord = get<std::uint32_t>(in, pos);
  const PredId p = predWord & ~kNegativeBit;
  const std::uint32_t arity = program_.predicates[p].arity();
  fact_.args.resize(arity);
  for (std::uint32_t i = 0; i < arity; ++i) fact_.args[i] = Value::fromBits(get<std::uint64_t>(in, pos));
  to.receive(node, p, fact_.args.data(), (predWord & kNegativeBit) != 0);
}

void ShardMail::putCoordination(MailBytes& out, NodeId n, Opcode op, double value) {
  put<std::uint8_t>(out, kCoordination);
  put<std::uint32_t>(out, n);
  put<std::uint32_t>(out, std::uint32_t(op));
  put<double>(out, value);
}

void ShardMail::putNode(MailBytes& out, ListEncoderShare& share, Machine& from, NodeId n, bool moved) {
  put<std::uint8_t>(out, kMigrate);
  put<std::uint32_t>(out, n);
  const std::size_t stateAt = out.size();  // written once the node is given (giveNode returns it)
  out.resize(stateAt + kStateBytes);
  put<std::uint8_t>(out, moved ? 1 : 0);
  const std::size_t storedAt = out.size();
  put<std::uint32_t>(out, 0);
  std::uint32_t stored = 0, pending = 0;
  pendingScratch_.clear();  // the messages come after all stored facts: kept apart meanwhile
  const SerialScheduler::Carried state = from.giveNode(
      n,
      [&](PredId p, const Value* args, std::uint32_t copies) {
        put<std::uint32_t>(out, copies);
        putLengthAndFact(out, share, p, args, false);
        ++stored;
      },
      [&](PredId p, const Value* args, bool negative) {
        // Into the scratch bytes, but numbered after the stored facts' lists, as they will be read.
        putLengthAndFact(pendingScratch_, share, p, args, negative);
        ++pending;
      });
  std::memcpy(out.data() + storedAt, &stored, sizeof stored);
  put<std::uint32_t>(out, pending);
  out.insert(out.end(), pendingScratch_.begin(), pendingScratch_.end());
  std::memcpy(out.data() + stateAt, &state.prio, sizeof state.prio);
  std::memcpy(out.data() + stateAt + 8, &state.defaultPrio, sizeof state.defaultPrio);
  out[stateAt + 16] = state.isStatic ? 1 : 0;
}

// Decodes the fact at `pos` into fact_, runs use(), releases what decoding built.
template <class Use>
void ShardMail::readFact(Machine& to, ListDecoderShare& share, const MailBytes& in, std::size_t& pos,
                         Use&& use) {
  Heap& heap = to.heap();
  const auto length = get<std::uint32_t>(in, pos);
  decodeFact(in.data() + pos, length, program_.predicates, heap, fact_, &share);
  pos += length;
  const PredicateDesc& d = program_.predicates[fact_.pred];
  auto release = [&] {
    for (std::uint32_t i = 0; i < d.arity(); ++i) heap.release(d.fields[i], fact_.args[i]);
  };
  try {
    use();
  } catch (...) {
    release();
    throw;
  }
  release();
}

void ShardMail::apply(Machine& to, const MailBytes& in, Taken& taken) {
  ListDecoderShare share(to.heap());  // several batches may come one after another
  for (std::size_t pos = 0; pos < in.size();) {
    const auto kind = get<std::uint8_t>(in, pos);
    const NodeId node = get<std::uint32_t>(in, pos);
    if (kind == kScalarFact) {
      ++taken.facts;
      readScalarFact(to, node, in, pos);
    } else if (kind == kEndOfBatch) {
      share.reset();
    } else if (kind == kMigrate) {
      takeNode(to, share, node, in, pos);
      ++taken.nodes;
    } else if (kind == kCoordination) {
      const auto op = Opcode(get<std::uint32_t>(in, pos));
      const double value = get<double>(in, pos);
      if (!to.holdsNode(node))
        throw RuntimeError("coordination fact for node @" + std::to_string(node) + ", which does not exist");
      to.coordinateOwned(op, node, value);
    } else {
      ++taken.facts;
      readFact(to, share, in, pos, [&] { to.receive(node, fact_.pred, fact_.args.data(), fact_.negative); });
    }
  }
}

void ShardMail::takeNode(Machine& to, ListDecoderShare& share, NodeId n, const MailBytes& in,
                         std::size_t& pos) {
  SerialScheduler::Carried state{};
  state.prio = get<double>(in, pos);
  state.defaultPrio = get<double>(in, pos);
  state.isStatic = get<std::uint8_t>(in, pos) != 0;
  const bool moved = get<std::uint8_t>(in, pos) != 0;
  to.takeNode(n, state);
  for (std::uint32_t i = 0, count = get<std::uint32_t>(in, pos); i < count; ++i) {
    const auto copies = get<std::uint32_t>(in, pos);
    readFact(to, share, in, pos, [&] { to.takeStoredFact(n, fact_.pred, fact_.args.data(), copies); });
  }
  for (std::uint32_t i = 0, count = get<std::uint32_t>(in, pos); i < count; ++i)
    readFact(to, share, in, pos,
             [&] { to.takePendingFact(n, fact_.pred, fact_.args.data(), fact_.negative); });
  if (moved) to.settleMovedNode(n);
  to.takeNodeDone(n);
}

}  // namespace meldvm
