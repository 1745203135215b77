// The records shards send each other (worker threads through their channels, the simulated cores
// of `vsim --target multicore` through the simulated interconnect): a fact for a node, a
// coordination fact (§5.7) for a node, or a whole node moving to another shard (work stealing,
// set-cpu). One encoder and one decoder for both, so that a simulated chip moves exactly what
// the threads move.
#pragma once

#include <cstdint>
#include <vector>

#include "meldvm/fact_codec.hpp"
#include "meldvm/machine.hpp"

namespace meldvm {

using MailBytes = std::vector<std::uint8_t>;

// When a shard sends what it has for other shards: once this many bytes wait, or after this many
// node runs with something waiting, or when it runs out of nodes to run. The worker threads and
// the simulated chip both follow it, so the chip's node runs see the batches threads see.
struct BatchPolicy {
  static constexpr std::size_t kFlushBytes = 65536;
  static constexpr unsigned kFlushRuns = 64;
};

class ShardMail {
 public:
  explicit ShardMail(const Program& program);

  // Facts (and moving nodes) with lists go in a batch's sharing format (fact_codec.hpp): `share`
  // belongs to the batch `out` (one per destination, on the sender's heap); endBatch closes it
  // before the batch leaves.
  void putFact(MailBytes& out, ListEncoderShare& share, NodeId dest, PredId p, const Value* args,
               bool negative);
  void putCoordination(MailBytes& out, NodeId n, Opcode op, double value);
  // Node n leaves `from` with its stored facts, waiting messages and scheduling state (it must be
  // out of from's queue: Machine::unqueueToGive or pickNodesToGive). moved: by set-cpu (the taker
  // pins it and gives it just-moved).
  void putNode(MailBytes& out, ListEncoderShare& share, Machine& from, NodeId n, bool moved);
  void endBatch(MailBytes& out, ListEncoderShare& share);

  struct Taken {
    std::uint64_t facts = 0, nodes = 0;
  };
  // Applies every record of `in` to shard `to`; counts what it took. Throws RuntimeError for a
  // coordination fact whose node does not exist.
  void apply(Machine& to, const MailBytes& in, Taken& taken);

 private:
  void putLengthAndFact(MailBytes& out, ListEncoderShare& share, PredId p, const Value* args, bool negative);
  template <class Use>
  void readFact(Machine& to, ListDecoderShare& share, const MailBytes& in, std::size_t& pos, Use&& use);
  void takeNode(Machine& to, ListDecoderShare& share, NodeId n, const MailBytes& in, std::size_t& pos);

  void putScalarFact(MailBytes& out, NodeId dest, PredId p, const Value* args, bool negative);
  void readScalarFact(Machine& to, NodeId node, const MailBytes& in, std::size_t& pos);

  const Program& program_;
  // Per predicate: every field is a scalar (no heap object), so a fact for another shard travels
  // as its values' bits, without the codec: most facts that cross threads are such.
  std::vector<std::uint8_t> scalar_;
  DecodedFact fact_;          // the decoder's storage, reused
  MailBytes pendingScratch_;  // a moving node's waiting messages, until its stored facts are out
};

}  // namespace meldvm
