#include "meldvm/node_heads.hpp"

#include <algorithm>
#include <memory>
#include <new>
#include <type_traits>

#include "meldvm/large_allocator.hpp"

namespace meldvm {

void NodeHeads::addNodes(NodeId count) {
  nodes_ += count;
  if (nodes_ <= kPageNodes) {
    resizeFirstPage(nodes_);
    return;
  }
  if (firstPageNodes_ != 0 && firstPageNodes_ < kPageNodes) resizeFirstPage(kPageNodes);
  if (!empty_) empty_ = newPage(kPageNodes);
  const std::size_t pages = (std::size_t(nodes_) + kMask) >> kShift;
  if (pages > pages_.size()) pages_.resize(pages, empty_.get());
  pageTable_ = pages_.data();
}

NodeHeads::Page NodeHeads::newPage(std::size_t nodes) {
  static_assert(std::is_trivially_destructible_v<ListHead>);
  const std::size_t heads = nodes * perNode_;
  headsAllocated_ += heads;
  auto* page = static_cast<ListHead*>(::operator new(heads * sizeof(ListHead)));
  support::prefault(page, heads * sizeof(ListHead));
  std::uninitialized_default_construct_n(page, heads);
  return Page(page);
}

void NodeHeads::resizeFirstPage(std::size_t nodes) {
  Page page = newPage(nodes);
  if (firstPageNodes_ != 0) std::copy_n(pages_[0], firstPageNodes_ * perNode_, page.get());
  headsAllocated_ -= firstPageNodes_ * perNode_;  // the old page goes
  firstPageNodes_ = nodes;
  if (owned_.empty()) {
    owned_.push_back(std::move(page));
    pages_.assign(1, owned_[0].get());
    pageTable_ = pages_.data();
  } else {
    owned_[0] = std::move(page);  // page 0 is the first and only page allocated so far
    pages_[0] = owned_[0].get();
  }
}

ListHead* NodeHeads::allocate(std::size_t page) {
  owned_.push_back(newPage(kPageNodes));
  pages_[page] = owned_.back().get();
  return pages_[page];
}

}  // namespace meldvm
