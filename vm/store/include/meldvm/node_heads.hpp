// The per-node list heads of a Database (one ListHead per node and table), in pages of 256
// nodes, each allocated when one of its nodes first stores a fact.
//
// Why pages: node ids are global, but a shard of a threaded run (and each core of a simulated
// chip) stores the facts of only some nodes. A dense array spent the heads of every node of the
// graph in every shard: 96 bytes per node and shard for pagerank's 8 predicates, and on a
// 256-core chip 256 copies. Unwritten pages share one page of empty heads, so a read needs no
// test; a write tests for it. A store of at most 256 nodes (a robot's machine holds one or a
// few) keeps one page of exactly its size instead.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "meldvm/fact_table.hpp"
#include "meldvm/types.hpp"

namespace meldvm {

class NodeHeads {
 public:
  explicit NodeHeads(std::uint32_t perNode) : perNode_(perNode) {}

  // Room for nodes [nodes(), nodes() + count): their heads read as empty until written. Heads
  // obtained before may move (as they did in a growing array).
  void addNodes(NodeId count);

  const ListHead* of(NodeId n) const { return pages_[n >> kShift] + std::size_t(n & kMask) * perNode_; }
  ListHead* forWrite(NodeId n) {
    ListHead* page = pages_[n >> kShift];
    if (page == empty_.get()) [[unlikely]]
      page = allocate(n >> kShift);
    return page + std::size_t(n & kMask) * perNode_;
  }

  // Where the page table is (native code finds a node's heads through it; it moves as pages are
  // added), and the layout it needs: node n's heads are page n >> kShift, node n & kMask of it.
  const ListHead* const* const* pageTableAddress() const { return &pageTable_; }
  std::uint32_t headsPerNode() const { return perNode_; }
  static constexpr std::uint32_t kShift = 8, kPageNodes = 1u << kShift, kMask = kPageNodes - 1;

  // The heads allocated (the empty page included) and the page table.
  std::size_t bytesReserved() const {
    return headsAllocated_ * sizeof(ListHead) + pages_.capacity() * sizeof(ListHead*) +
           owned_.capacity() * sizeof(owned_[0]);
  }

 private:
  // A page's heads are all written as it is made: its memory is prefaulted first (operator new,
  // then the heads constructed in place; freed with operator delete).
  struct PageFree {
    void operator()(ListHead* heads) const { ::operator delete(heads); }
  };
  using Page = std::unique_ptr<ListHead[], PageFree>;
  Page newPage(std::size_t nodes);  // empty heads, counted
  ListHead* allocate(std::size_t page);
  // Page 0 for `nodes` nodes (all of a small store, or a full page), keeping its heads.
  void resizeFirstPage(std::size_t nodes);

  std::uint32_t perNode_;
  NodeId nodes_ = 0;
  std::size_t firstPageNodes_ = 0;
  std::size_t headsAllocated_ = 0;
  Page empty_;                         // once the store has more than one page
  std::vector<ListHead*> pages_;       // empty_.get() until a node of the page is written
  const ListHead* const* pageTable_ = nullptr;  // pages_.data(), kept at a fixed address
  std::vector<Page> owned_;
};

}  // namespace meldvm
