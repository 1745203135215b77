// Benchmark and placement helpers of §5.6 that the established VM ships: the tic-tac-toe scores of
// its minimax programs (ids 54, 55, 62, 63), the belief-propagation bit vectors (32, 33) and the
// grid partitions that map a cell to a thread (44-46). Their behaviour follows the established
// VM's library, which the spec lists only by signature.
#include <algorithm>
#include <cmath>

#include "builtins_util.hpp"

namespace meldvm::builtins {

namespace {

// The eight lines of a 3x3 board (cells 0..8, row by row), in the order the scores test them:
// columns, rows, then the two diagonals. The first complete line decides the score.
constexpr int kLines[8][3] = {{0, 3, 6}, {1, 4, 7}, {2, 5, 8}, {0, 1, 2},
                              {3, 4, 5}, {6, 7, 8}, {0, 4, 8}, {2, 4, 6}};

// Reads a board of at least nine int cells into `cells`.
void boardCells(std::string_view fn, std::span<const Value> items, std::int32_t* cells) {
  if (items.size() < 9) throw error(fn, "a board has 9 cells, got " + std::to_string(items.size()));
  for (int i = 0; i < 9; ++i) cells[i] = items[std::size_t(i)].asInt();
}

// 0 when no line is complete; otherwise +1 when the line belongs to rootPlayer, -1 when it
// belongs to the opponent. `player`'s lines are looked for before the other player's in each line.
int lineWinner(const std::int32_t* cells, std::int32_t player, std::int32_t rootPlayer) {
  const std::int32_t other = player == 1 ? 2 : 1;
  for (const auto& line : kLines)
    for (const std::int32_t who : {player, other})
      if (cells[line[0]] == who && cells[line[1]] == who && cells[line[2]] == who)
        return who == rootPlayer ? 1 : -1;
  return 0;
}

std::int32_t countOf(std::span<const Value> items, std::int32_t who) {
  return std::int32_t(std::count_if(items.begin(), items.end(), [&](Value v) { return v.asInt() == who; }));
}

}  // namespace

Value minimax_score(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  ctx.scratch.clear();
  for (Value l = a[0]; !l.isNil(); l = listTail(l)) ctx.scratch.push_back(listHead(l));
  std::int32_t cells[9];
  boardCells("minimax_score", ctx.scratch, cells);
  const std::int32_t root = a[2].asInt();
  if (const int w = lineWinner(cells, a[1].asInt(), root)) return Value::fromInt(w > 0 ? 200 : -100);
  // No line: an empty board scores the number of cells equal to the root player (9 when it is 0),
  // any other board 0 [the established VM's quirk: it counts only up to the first played cell].
  const bool empty = std::all_of(ctx.scratch.begin(), ctx.scratch.end(), [](Value v) { return v.asInt() == 0; });
  return Value::fromInt(empty ? countOf(ctx.scratch, root) : 0);
}

Value minimax_points(BuiltinContext&, std::span<const Value> a, TypeId) {
  std::int32_t n = 0;
  for (Value l = a[0]; !l.isNil(); l = listTail(l)) n += listHead(l).asInt() == a[1].asInt();
  return Value::fromInt(n);
}

Value minimax_score2(BuiltinContext&, std::span<const Value> a, TypeId) {
  const auto items = tupleItems(a[0]);
  std::int32_t cells[9];
  boardCells("minimax_score2", items, cells);
  const std::int32_t root = a[2].asInt();
  if (const int w = lineWinner(cells, a[1].asInt(), root)) {
    // A win counts more the more cells were played (at least 1).
    const std::int32_t played = std::max<std::int32_t>(1, std::int32_t(items.size()) - countOf(items, 0));
    return Value::fromInt(played * (w > 0 ? 200 : -100));
  }
  // A full board without a line scores the root player's cells; an unfinished one 0.
  return Value::fromInt(countOf(items, 0) > 0 ? 0 : countOf(items, root));
}

Value minimax_points2(BuiltinContext&, std::span<const Value> a, TypeId) {
  return Value::fromInt(countOf(tupleItems(a[0]), a[1].asInt()));
}

Value degeneratevector(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  // k random one-bit masks of a `bits`-bit message: bit (bits - 2 - j) with j drawn from a
  // geometric distribution (j with probability 2^-(j+1), the last value taking the rest).
  const std::int32_t k = a[0].asInt(), bits = a[1].asInt();
  if (k < 0) throw error("degeneratevector", "negative count " + std::to_string(k));
  if (bits < 2 || bits > 32) throw error("degeneratevector", "bit count " + std::to_string(bits) + " outside 2..32");
  if (!ctx.rng) throw error("degeneratevector", "no random stream");
  ListBuilder out(ctx.heap, result);
  for (std::int32_t i = 0; i < k; ++i) {
    const double u = double(ctx.rng->next() >> 11) * 0x1.0p-53;
    std::int32_t j = 0;
    for (double threshold = 0; j < bits - 2; ++j) {
      threshold += std::ldexp(1.0, -j - 1);
      if (u < threshold) break;
    }
    out.push(Value::fromInt(std::int32_t(std::uint32_t(1) << (bits - 2 - j))));
  }
  return out.finish();
}

Value demergemessages(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  // Element-wise OR of two bit-vector lists; the second must be at least as long as the first.
  ListBuilder out(ctx.heap, result);
  Value y = a[1];
  for (Value x = a[0]; !x.isNil(); x = listTail(x), y = listTail(y)) {
    if (y.isNil()) throw error("demergemessages", "the second list is shorter than the first");
    out.push(Value::fromInt(listHead(x).asInt() | listHead(y).asInt()));
  }
  return out.finish();
}

namespace {

// Thread of position `pos` among `total` cells cut into equal runs, the last thread taking the rest.
Value partitionOf(const BuiltinContext& ctx, std::int64_t pos, std::int64_t total) {
  const std::int64_t threads = ctx.sched ? ctx.sched->threadCount() : 1;
  const std::int64_t part = std::max<std::int64_t>(1, total / threads);
  return Value::fromThread(ThreadId(std::clamp<std::int64_t>(pos / part, 0, threads - 1)));
}

}  // namespace

Value partition_vertical(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  const std::int64_t x = a[0].asInt(), y = a[1].asInt(), lx = a[2].asInt(), ly = a[3].asInt();
  return partitionOf(ctx, ly * y + x, lx * ly);
}

Value partition_horizontal(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  const std::int64_t x = a[0].asInt(), y = a[1].asInt(), lx = a[2].asInt(), ly = a[3].asInt();
  return partitionOf(ctx, lx * x + y, lx * ly);
}

Value partition_grid(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  // The grid is cut into fl x fl blocks (fl about the square root of the thread count), walked in
  // a snake order (odd block rows backwards) so that neighbouring blocks go to the same thread.
  const std::int64_t x = a[0].asInt(), y = a[1].asInt(), lx = a[2].asInt(), ly = a[3].asInt();
  const std::int64_t threads = ctx.sched ? ctx.sched->threadCount() : 1;
  std::int64_t fl = std::max<std::int64_t>(1, std::llround(std::sqrt(double(threads))));
  while (fl * fl < threads && fl <= lx - 1 && fl <= ly - 1) ++fl;
  const std::int64_t height = std::max<std::int64_t>(1, std::int64_t(double(lx) / double(fl)));
  const std::int64_t width = std::max<std::int64_t>(1, std::int64_t(double(ly) / double(fl)));
  const std::int64_t blockX = std::min(fl - 1, x / height), blockY = std::min(fl - 1, y / width);
  std::int64_t inBlockY = y >= fl * width ? width - 1 : y % width;
  std::int64_t block = blockX * fl;
  if (blockX % 2 == 0) {
    block += blockY;
  } else {
    block += fl - blockY - 1;
    inBlockY = width - inBlockY - 1;
  }
  return partitionOf(ctx, block * width + inBlockY, width * fl * fl);
}

}  // namespace meldvm::builtins
