// Per-node records (`perNode` of them per node) in pages of 256 nodes, each page allocated when
// one of its nodes is first written: a Database's list heads, a scheduler's node records.
//
// Why pages: node ids are global, but a shard of a threaded run (and each core of a simulated
// chip) keeps the state of only some nodes. A dense array spent a record for every node of the
// graph in every shard (pagerank's list heads: 96 bytes per node and shard; on a 256-core chip,
// 256 copies). Unwritten pages share one page filled with the default record, so a read needs
// no test; a write tests for it. A store of at most 256 nodes (a robot world's machine, a small
// program) keeps one page of exactly its size instead.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "meldvm/value.hpp"  // NodeId

namespace meldvm {

// kPerNode: the records per node when fixed at compile time (saves a multiplication on every
// access); 0: given to the constructor.
template <class T, std::uint32_t kPerNode = 0>
class NodePages {
 public:
  // `fill`: what an unwritten record reads as.
  explicit NodePages(std::uint32_t perNode = kPerNode, T fill = T{}) : perNode_(perNode), fill_(fill) {}

  // Room for nodes [nodes(), nodes() + count), reading as `fill` until written. Records
  // obtained before may move (as they did in a growing array).
  void addNodes(NodeId count) {
    nodes_ += count;
    if (nodes_ <= kPageNodes) return resizeFirstPage(nodes_);
    if (firstPageNodes_ != 0 && firstPageNodes_ < kPageNodes) resizeFirstPage(kPageNodes);
    if (!empty_) empty_ = newPage(kPageNodes);
    const std::size_t pages = (std::size_t(nodes_) + kMask) >> kShift;
    if (pages > pages_.size()) pages_.resize(pages, empty_.get());
  }
  NodeId nodes() const { return nodes_; }

  const T* of(NodeId n) const { return pages_[n >> kShift] + std::size_t(n & kMask) * stride(); }
  T* forWrite(NodeId n) {
    T* page = pages_[n >> kShift];
    if (page == empty_.get()) [[unlikely]]
      page = allocate(n >> kShift);
    return page + std::size_t(n & kMask) * stride();
  }

  // The records allocated (the shared page included) and the page table.
  std::size_t bytesReserved() const {
    return allocated_ * sizeof(T) + pages_.capacity() * sizeof(T*) + owned_.capacity() * sizeof(owned_[0]);
  }

 private:
  static constexpr std::uint32_t kShift = 8, kPageNodes = 1u << kShift, kMask = kPageNodes - 1;
  std::uint32_t stride() const { return kPerNode != 0 ? kPerNode : perNode_; }

  std::unique_ptr<T[]> newPage(std::size_t nodes) {
    std::unique_ptr<T[]> page(new T[nodes * perNode_]);
    std::fill_n(page.get(), nodes * perNode_, fill_);
    allocated_ += nodes * perNode_;
    return page;
  }
  T* allocate(std::size_t page) {
    owned_.push_back(newPage(kPageNodes));
    pages_[page] = owned_.back().get();
    return pages_[page];
  }
  // Page 0 for `nodes` nodes (all of a small store, or a full page), keeping its records.
  void resizeFirstPage(std::size_t nodes) {
    std::unique_ptr<T[]> page = newPage(nodes);
    if (firstPageNodes_ != 0) {
      std::copy_n(pages_[0], firstPageNodes_ * perNode_, page.get());
      allocated_ -= firstPageNodes_ * perNode_;  // the old page goes
    }
    firstPageNodes_ = nodes;
    if (owned_.empty()) {
      owned_.push_back(std::move(page));
      pages_.assign(1, owned_[0].get());
    } else {
      owned_[0] = std::move(page);  // page 0 is the only page allocated so far
      pages_[0] = owned_[0].get();
    }
  }

  std::uint32_t perNode_;
  T fill_;
  NodeId nodes_ = 0;
  std::size_t firstPageNodes_ = 0;
  std::size_t allocated_ = 0;
  std::unique_ptr<T[]> empty_;  // once there is more than one page
  std::vector<T*> pages_;       // empty_.get() until a node of the page is written
  std::vector<std::unique_ptr<T[]>> owned_;
};

}  // namespace meldvm
