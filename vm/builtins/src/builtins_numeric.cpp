// Numeric built-ins of §5.6: sigmoid, randint, the log-space belief-propagation helpers on float
// lists and float structs, truncate, float2int, intpower, fabs.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "builtins_util.hpp"
#include "meldvm/plain_libm.hpp"

namespace meldvm::builtins {

namespace {

// Reads a float list into ctx-owned storage `out` (cleared first).
void readFloats(Value list, std::vector<double>& out) {
  out.clear();
  for (; !list.isNil(); list = listTail(list)) out.push_back(listHead(list).asFloat());
}

Value floatList(BuiltinContext& ctx, TypeId listType, std::span<const double> xs) {
  ListBuilder lb(ctx.heap, listType);
  for (double x : xs) lb.push(Value::fromFloat(x));
  return lb.finish();
}

// a (x) b element-wise over two float lists, stopping at the shorter one.
template <class Op>
Value zipFloats(BuiltinContext& ctx, Value a, Value b, TypeId listType, Op op) {
  ListBuilder lb(ctx.heap, listType);
  for (; !a.isNil() && !b.isNil(); a = listTail(a), b = listTail(b))
    lb.push(Value::fromFloat(op(listHead(a).asFloat(), listHead(b).asFloat())));
  return lb.finish();
}

template <class Op>
Value zipStructs(BuiltinContext& ctx, std::string_view fn, Value a, Value b, Op op) {
  const auto x = tupleItems(a), y = tupleItems(b);
  if (x.size() != y.size()) throw error(fn, "structs of different sizes");
  Value result;
  Value* out = ctx.heap.makePlainTuple(objectType(a), std::uint32_t(x.size()), result);
  for (std::size_t i = 0; i < x.size(); ++i) out[i] = Value::fromFloat(op(x[i].asFloat(), y[i].asFloat()));
  return result;
}

// The helpers take float lists copied into doubles (ctx.numbers) and float structs' items in place.
double toDouble(double x) { return x; }
double toDouble(Value v) { return v.asFloat(); }

// write(i, x_i - max - log(sum_j exp(x_j - max))); x_i is read before write(i, ...).
template <class T, class Write>
void normalizeEach(std::span<const T> xs, Write&& write) {
  if (xs.empty()) return;
  double mx = toDouble(xs[0]);
  for (const T& x : xs) mx = std::max(mx, toDouble(x));
  double sum = 0;
  for (const T& x : xs) sum += plainExp(toDouble(x) - mx);
  const double lsum = plainLog(sum);
  for (std::size_t i = 0; i < xs.size(); ++i) write(i, toDouble(xs[i]) - mx - lsum);
}

void checkConvolution(std::string_view fn, std::size_t matrix, std::size_t vector) {
  if (matrix != vector * vector)
    throw error(
        fn, "matrix has " + std::to_string(matrix) + " entries, expected " + std::to_string(vector * vector));
}

// Arguments whose exponentials are normal doubles with room to spare: a formula rewritten with
// fewer exponentials (the exponential of a sum as a product, or of a difference) rounds a little
// differently but neither overflows nor underflows where the definition does not.
constexpr double kModerate = 300;

template <class T>
bool allModerate(std::span<const T> xs) {
  for (const T& x : xs)
    if (!(std::fabs(toDouble(x)) <= kModerate)) return false;
  return true;
}

// log(f e^b + (1 - f) e^a), as a + log((1 - f) + f e^(b - a)) when a and b are moderate: one
// exponential instead of two (belief propagation damps every message it sends).
double dampOne(double a, double b, double f) {
  if (std::fabs(a) <= kModerate && std::fabs(b) <= kModerate)
    return a + plainLog((1.0 - f) + f * plainExp(b - a));
  return plainLog(f * plainExp(b) + (1.0 - f) * plainExp(a));
}

// exp of each entry of m, from ctx's cache when m is the matrix of the last call; null when m has
// an entry that is not moderate.
template <class T>
const double* matrixExponentials(BuiltinContext& ctx, std::span<const T> m) {
  // The same bits as the last matrix (a float's Value is its double's bits): one memcmp, where
  // comparing the entries one by one was 2 % of belief-propagation-50's instructions. (The cache
  // holds moderate entries only, so equal bits are never NaNs.)
  static_assert(sizeof(T) == sizeof(double));
  std::vector<double>& last = ctx.convolveMatrix;
  if (last.size() == m.size() &&
      (m.empty() || std::memcmp(last.data(), m.data(), m.size() * sizeof(double)) == 0))
    return ctx.convolveMatrixExp.data();
  if (!allModerate(m)) return nullptr;
  last.resize(m.size());
  ctx.convolveMatrixExp.resize(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) {
    last[i] = toDouble(m[i]);
    ctx.convolveMatrixExp[i] = plainExp(last[i]);
  }
  return ctx.convolveMatrixExp.data();
}

// out_i = log sum_j exp(M[i*n + j] + v_j), n = |v| = |out|, M has n*n entries (checkConvolution).
// A sum that underflows to 0 counts as the smallest normal double, as in the established VM: a
// very unlikely row gives about -708, not -inf. With moderate entries (all but such extremes),
// exp(M_ij + v_j) is taken as exp(M_ij) exp(v_j), M's exponentials kept from call to call.
template <class T>
void convolveInto(BuiltinContext& ctx, std::span<const T> m, std::span<const T> v, Value* out) {
  const std::size_t n = v.size();
  constexpr std::size_t kMaxCached = 16;  // vectors of up to this many entries: exp(v_j) on the stack
  const double* expM = n <= kMaxCached && allModerate(v) ? matrixExponentials(ctx, m) : nullptr;
  if (expM) {
    double expV[kMaxCached];
    for (std::size_t j = 0; j < n; ++j) expV[j] = plainExp(toDouble(v[j]));
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0;
      for (std::size_t j = 0; j < n; ++j) sum += expM[i * n + j] * expV[j];
      out[i] = Value::fromFloat(plainLog(sum));
    }
    return;
  }
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (std::size_t j = 0; j < n; ++j) sum += plainExp(toDouble(m[i * n + j]) + toDouble(v[j]));
    if (sum == 0) sum = std::numeric_limits<double>::min();
    out[i] = Value::fromFloat(plainLog(sum));
  }
}

}  // namespace

Value sigmoid(BuiltinContext&, std::span<const Value> a, TypeId) {
  return Value::fromFloat(1.0 / (1.0 + plainExp(-a[0].asFloat())));
}

Value randint(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  const std::int32_t n = a[0].asInt();
  if (n <= 0) throw error("randint", "bound must be positive, got " + std::to_string(n));
  if (!ctx.rng) throw error("randint", "no random stream in the context");
  return Value::fromInt(std::int32_t(ctx.rng->next() % std::uint64_t(n)));
}

Value normalize(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  readFloats(a[0], ctx.numbers);
  std::vector<double>& xs = ctx.numbers;
  normalizeEach(std::span<const double>(xs), [&](std::size_t i, double x) { xs[i] = x; });
  return floatList(ctx, result, xs);
}

Value damp(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  const double f = a[2].asFloat();
  return zipFloats(ctx, a[0], a[1], result, [f](double x, double y) { return dampOne(x, y, f); });
}

Value divide(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  return zipFloats(ctx, a[0], a[1], result, [](double x, double y) { return x - y; });
}

Value addfloatlists(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  return zipFloats(ctx, a[0], a[1], result, [](double x, double y) { return x + y; });
}

Value convolve(BuiltinContext& ctx, std::span<const Value> a, TypeId result) {
  std::vector<double>& buf = ctx.numbers;  // [M..., v...]
  readFloats(a[0], buf);
  const std::size_t mn = buf.size();
  for (Value l = a[1]; !l.isNil(); l = listTail(l)) buf.push_back(listHead(l).asFloat());
  const std::span<const double> all(buf);
  checkConvolution("convolve", mn, all.size() - mn);
  ctx.scratch.resize(all.size() - mn);
  convolveInto(ctx, all.first(mn), all.subspan(mn), ctx.scratch.data());
  return ctx.heap.makeList(result, ctx.scratch);
}

Value residual(BuiltinContext&, std::span<const Value> a, TypeId) {
  double sum = 0;
  std::size_t n = 0;
  for (Value x = a[0], y = a[1]; !x.isNil() && !y.isNil(); x = listTail(x), y = listTail(y), ++n)
    sum += std::fabs(plainExp(listHead(x).asFloat()) - plainExp(listHead(y).asFloat()));
  return Value::fromFloat(n == 0 ? 0.0 : sum / double(n));
}

Value truncate(BuiltinContext&, std::span<const Value> a, TypeId) {
  // floor(x * 10^n) / 10^n in single precision, widened back to double.
  const float p = std::pow(10.0f, float(a[1].asInt()));
  const float r = std::floor(float(a[0].asFloat()) * p) / p;
  return Value::fromFloat(double(r));
}

Value float2int(BuiltinContext&, std::span<const Value> a, TypeId) {
  return Value::fromInt(floatToInt(a[0].asFloat()));
}

Value intpower(BuiltinContext&, std::span<const Value> a, TypeId) {
  // a^b with 32-bit wrap-around (the product of b factors, by squaring: the same value as the
  // established VM's repeated multiplication, in log b steps); a non-positive exponent gives 1.
  std::int32_t r = 1, base = a[0].asInt();
  for (std::int32_t e = a[1].asInt(); e > 0; e >>= 1) {
    if (e & 1) r = intMul(r, base);
    base = intMul(base, base);
  }
  return Value::fromInt(r);
}

Value fabs(BuiltinContext&, std::span<const Value> a, TypeId) {
  return Value::fromFloat(std::fabs(a[0].asFloat()));
}

Value addfloatstructs(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  return zipStructs(ctx, "addfloatstructs", a[0], a[1], [](double x, double y) { return x + y; });
}

Value dividestruct(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  return zipStructs(ctx, "dividestruct", a[0], a[1], [](double x, double y) { return x - y; });
}

Value dampstruct(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  const double f = a[2].asFloat();
  return zipStructs(ctx, "dampstruct", a[0], a[1], [f](double x, double y) { return dampOne(x, y, f); });
}

Value normalizestruct(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  const auto xs = tupleItems(a[0]);
  Value result;
  Value* out = ctx.heap.makePlainTuple(objectType(a[0]), std::uint32_t(xs.size()), result);
  normalizeEach(xs, [&](std::size_t i, double x) { out[i] = Value::fromFloat(x); });
  return result;
}

Value residualstruct(BuiltinContext&, std::span<const Value> a, TypeId) {
  const auto x = tupleItems(a[0]), y = tupleItems(a[1]);
  if (x.size() != y.size()) throw error("residualstruct", "structs of different sizes");
  if (x.empty()) return Value::fromFloat(0.0);
  double sum = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    sum += std::fabs(plainExp(x[i].asFloat()) - plainExp(y[i].asFloat()));
  return Value::fromFloat(sum / double(x.size()));
}

Value convolvestruct(BuiltinContext& ctx, std::span<const Value> a, TypeId) {
  // M: a struct of n*n floats (25 in the belief-propagation programs), v: a struct of n floats;
  // the result has v's struct type.
  const auto m = tupleItems(a[0]), v = tupleItems(a[1]);
  checkConvolution("convolvestruct", m.size(), v.size());
  Value result;
  Value* out = ctx.heap.makePlainTuple(objectType(a[1]), std::uint32_t(v.size()), result);
  convolveInto(ctx, m, v, out);
  return result;
}

}  // namespace meldvm::builtins
