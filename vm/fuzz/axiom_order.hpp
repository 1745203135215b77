// The one other encoding of a program the `.mbc` reader takes on purpose: axiom blocks of literal
// facts before the others. meldc wrote them so before the writer put them after the others (where
// the reader numbers them), and such files still load. The fuzz entry point checks that a file it
// does not get back byte for byte from the writer differs only so.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "meldvm/bytecode_internal.hpp"

namespace meldfuzz {

namespace axiom_order {

// The sections of a file (the header checked apart): tag and bytes.
struct Section {
  std::uint32_t tag;
  std::span<const std::uint8_t> bytes;
};

inline std::optional<std::uint32_t> wordAt(std::span<const std::uint8_t> b, std::size_t at) {
  if (at + 4 > b.size()) return std::nullopt;
  std::uint32_t w;
  std::memcpy(&w, b.data() + at, 4);
  return w;
}

inline std::optional<std::vector<Section>> sections(std::span<const std::uint8_t> file) {
  std::vector<Section> out;
  for (std::size_t at = 12; at < file.size();) {
    const auto tag = wordAt(file, at), len = wordAt(file, at + 4);
    if (!tag || !len || at + 8 + *len > file.size()) return std::nullopt;
    out.push_back({*tag, file.subspan(at + 8, *len)});
    at += 8 + *len;
  }
  return out;
}

// Skips a length-prefixed item at `at` (a string: bytes padded to 4; word lists: `unit` words each).
inline std::optional<std::size_t> skip(std::span<const std::uint8_t> b, std::size_t at, bool string,
                                       std::size_t unit = 1) {
  const auto n = wordAt(b, at);
  if (!n) return std::nullopt;
  const std::size_t bytes = string ? (*n + 3) / 4 * 4 : std::size_t(*n) * 4 * unit;
  if (at + 4 + bytes > b.size()) return std::nullopt;
  return at + 4 + bytes;
}

using Bytes = std::string_view;
inline Bytes bytesOf(std::span<const std::uint8_t> b, std::size_t from, std::size_t to) {
  return {reinterpret_cast<const char*>(b.data()) + from, to - from};
}

// The axioms section: each node's block number, and each block's bytes.
struct Axioms {
  std::vector<std::uint32_t> nodeBlocks;
  std::vector<Bytes> blocks;
};
inline std::optional<Axioms> axioms(std::span<const std::uint8_t> s) {
  Axioms a;
  const auto nodes = wordAt(s, 0);
  if (!nodes) return std::nullopt;
  for (std::uint32_t n = 0; n < *nodes; ++n) {
    const auto b = wordAt(s, 4 + 4 * std::size_t(n));
    if (!b) return std::nullopt;
    a.nodeBlocks.push_back(*b);
  }
  std::size_t at = 4 + 4 * std::size_t(*nodes);
  const auto count = wordAt(s, at);
  if (!count) return std::nullopt;
  at += 4;
  for (std::uint32_t i = 0; i < *count; ++i) {
    const std::size_t from = at;
    auto next = skip(s, at, true);                                                     // label
    if (next) next = skip(s, *next, false);                                            // register types
    if (next) next = *next + 4 <= s.size() ? std::optional(*next + 4) : std::nullopt;  // slots
    if (next) next = skip(s, *next, false);                                            // code
    if (!next) return std::nullopt;
    at = *next;
    a.blocks.push_back(bytesOf(s, from, at));
  }
  if (at != s.size()) return std::nullopt;
  return a;
}

// The sources section: the bytes before the axiom blocks' line tables, and those tables.
inline std::optional<std::pair<Bytes, std::vector<Bytes>>> sourceTables(std::span<const std::uint8_t> s,
                                                                        std::size_t blocksBefore,
                                                                        std::size_t axiomBlocks) {
  const auto files = wordAt(s, 0);
  if (!files) return std::nullopt;
  std::optional<std::size_t> at = 4;
  for (std::uint32_t f = 0; f < *files && at; ++f) at = skip(s, *at, true);
  for (std::size_t b = 0; b < blocksBefore && at; ++b) at = skip(s, *at, false, 3);
  if (!at) return std::nullopt;
  std::pair<Bytes, std::vector<Bytes>> out{bytesOf(s, 0, *at), {}};
  for (std::size_t b = 0; b < axiomBlocks; ++b) {
    const std::size_t from = *at;
    at = skip(s, from, false, 3);
    if (!at) return std::nullopt;
    out.second.push_back(bytesOf(s, from, *at));
  }
  if (*at != s.size()) return std::nullopt;
  return out;
}

}  // namespace axiom_order

// Whether `data` is `canonical` (the writer's bytes for the program `data` holds) but for the order
// of its axiom blocks: the same header and sections, and in the axioms and sources sections the
// same blocks with the same line tables, permuted, each node naming the same block.
inline bool sameButAxiomOrder(std::span<const std::uint8_t> data, std::span<const std::uint8_t> canonical,
                              std::size_t blocksBeforeAxioms) {
  using namespace axiom_order;
  if (data.size() != canonical.size() || data.size() < 12 ||
      !std::equal(data.begin(), data.begin() + 12, canonical.begin()))
    return false;
  const auto ds = sections(data), cs = sections(canonical);
  if (!ds || !cs || ds->size() != cs->size()) return false;
  std::optional<Axioms> da, ca;
  for (std::size_t i = 0; i < ds->size(); ++i) {
    const Section &d = (*ds)[i], &c = (*cs)[i];
    if (d.tag != c.tag) return false;
    if (d.tag == meldvm::detail::kSecAxioms) {
      da = axioms(d.bytes);
      ca = axioms(c.bytes);
      if (!da || !ca || da->blocks.size() != ca->blocks.size() ||
          da->nodeBlocks.size() != ca->nodeBlocks.size())
        return false;
    } else if (d.tag != meldvm::detail::kSecSources) {
      if (!std::equal(d.bytes.begin(), d.bytes.end(), c.bytes.begin(), c.bytes.end())) return false;
    }
  }
  if (!da) return false;
  const std::size_t n = da->blocks.size();
  std::vector<std::pair<Bytes, Bytes>> dp(n), cp(n);  // (block, line table: none before version 3)
  for (std::size_t b = 0; b < n; ++b) {
    dp[b].first = da->blocks[b];
    cp[b].first = ca->blocks[b];
  }
  for (std::size_t i = 0; i < ds->size(); ++i)  // (the tags of both were compared above)
    if ((*ds)[i].tag == meldvm::detail::kSecSources) {
      const auto dt = sourceTables((*ds)[i].bytes, blocksBeforeAxioms, n),
                 ct = sourceTables((*cs)[i].bytes, blocksBeforeAxioms, n);
      if (!dt || !ct || dt->first != ct->first) return false;
      for (std::size_t b = 0; b < n; ++b) {
        dp[b].second = dt->second[b];
        cp[b].second = ct->second[b];
      }
    }
  for (std::size_t node = 0; node < da->nodeBlocks.size(); ++node) {
    const std::uint32_t d = da->nodeBlocks[node], c = ca->nodeBlocks[node];
    if ((d < n) != (c < n) || (d >= n && d != c) || (d < n && dp[d] != cp[c])) return false;
  }
  std::sort(dp.begin(), dp.end());
  std::sort(cp.begin(), cp.end());
  return dp == cp;
}

}  // namespace meldfuzz
