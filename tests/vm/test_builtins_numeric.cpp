#define BOOST_TEST_MODULE vm_builtins_numeric
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "builtins_fixture.hpp"
#include "meldvm/plain_libm.hpp"

using namespace bitest;

BOOST_FIXTURE_TEST_SUITE(numeric, Fix)

BOOST_AUTO_TEST_CASE(sigmoid_values) {
  BOOST_CHECK_EQUAL(call("sigmoid", {F(0)}, tFloat).asFloat(), 0.5);
  BOOST_CHECK_EQUAL(show("sigmoid", {F(2)}, tFloat), "0.8808");
  BOOST_CHECK_EQUAL(show("sigmoid", {F(-2)}, tFloat), "0.1192");
  BOOST_CHECK_CLOSE(call("sigmoid", {F(2)}, tFloat).asFloat(), 0.8807970779778823, 1e-12);
}

BOOST_AUTO_TEST_CASE(randint_is_reproducible_and_in_range) {
  Rng r{0};
  ctx.rng = &r;
  // splitmix64 from state 0 gives 0xe220a8397b1dcdaf first; mod 10 = 5.
  BOOST_CHECK_EQUAL(call("randint", {I(10)}, tInt).asInt(), 5);
  BOOST_CHECK_EQUAL(Rng{0}.next(), 0xe220a8397b1dcdafull);
  BOOST_CHECK_EQUAL(call("randint", {I(1)}, tInt).asInt(), 0);
  Rng a = Rng::forThread(3), b = Rng::forThread(3), c = Rng::forThread(4);
  BOOST_CHECK_EQUAL(a.next(), b.next());
  BOOST_CHECK_NE(Rng::forThread(3).next(), c.next());
  ctx.rng = &a;
  for (int i = 0; i < 200; ++i) {
    const std::int32_t x = call("randint", {I(7)}, tInt).asInt();
    BOOST_REQUIRE(x >= 0 && x < 7);
  }
  BOOST_CHECK_THROW(call("randint", {I(0)}, tInt), RuntimeError);
  BOOST_CHECK_THROW(call("randint", {I(-4)}, tInt), RuntimeError);
  ctx.rng = nullptr;
  BOOST_CHECK_THROW(call("randint", {I(4)}, tInt), RuntimeError);
}

BOOST_AUTO_TEST_CASE(normalize_in_log_space) {
  // max 3, log(e^-2 + e^-1 + 1) = 0.4076060
  BOOST_CHECK_EQUAL(show("normalize", {floats({1, 2, 3})}, tLF), "[-2.4076,-1.4076,-0.40761]");
  BOOST_CHECK_EQUAL(show("normalize", {floats({0, 0})}, tLF), "[-0.69315,-0.69315]");
  BOOST_CHECK_EQUAL(show("normalize", {floats({-5})}, tLF), "[0]");
  BOOST_CHECK_EQUAL(show("normalize", {Value::nil()}, tLF), "[]");
}

BOOST_AUTO_TEST_CASE(damp_divide_addfloatlists) {
  // log(0.25 e^1 + 0.75 e^0) = 0.357374, log(0.25 e^0 + 0.75 e^1) = 0.827989
  BOOST_CHECK_EQUAL(show("damp", {floats({0, 1}), floats({1, 0}), F(0.25)}, tLF), "[0.35737,0.82799]");
  BOOST_CHECK_EQUAL(show("damp", {floats({0, 2}), floats({0}), F(0.5)}, tLF), "[0]");
  BOOST_CHECK_EQUAL(show("damp", {Value::nil(), floats({1}), F(0.5)}, tLF), "[]");
  BOOST_CHECK_EQUAL(show("divide", {floats({3, 1}), floats({1, 1.5})}, tLF), "[2,-0.5]");
  BOOST_CHECK_EQUAL(show("divide", {floats({1, 2, 3}), floats({1})}, tLF), "[0]");
  BOOST_CHECK_EQUAL(show("addfloatlists", {floats({1.5, 2}), floats({0.25, 1, 7})}, tLF), "[1.75,3]");
  BOOST_CHECK_EQUAL(show("addfloatlists", {floats({-1}), floats({1})}, tLF), "[0]");
  BOOST_CHECK_EQUAL(show("addfloatlists", {Value::nil(), Value::nil()}, tLF), "[]");
}

BOOST_AUTO_TEST_CASE(convolve_is_a_log_space_matrix_vector_product) {
  // out0 = log(e^(1+0) + e^(2+1)) = 3.12693, out1 = log(e^(3+0) + e^(4+1)) = 5.12693
  BOOST_CHECK_EQUAL(show("convolve", {floats({1, 2, 3, 4}), floats({0, 1})}, tLF), "[3.1269,5.1269]");
  BOOST_CHECK_EQUAL(show("convolve", {floats({0}), floats({0})}, tLF), "[0]");
  BOOST_CHECK_EQUAL(show("convolve", {Value::nil(), Value::nil()}, tLF), "[]");
  BOOST_CHECK_THROW(call("convolve", {floats({1, 2, 3}), floats({0, 1})}, tLF), RuntimeError);
  // Every e^(M + v) underflows: the sum counts as the smallest normal double (log = -708.4), not 0.
  BOOST_CHECK_EQUAL(show("convolve", {floats({-800}), floats({-100})}, tLF), "[-708.4]");
}

BOOST_AUTO_TEST_CASE(residual_is_the_mean_absolute_difference_of_exponentials) {
  // (|e^0 - e^0| + |e^0 - e^log3|) / 2 = 1
  BOOST_CHECK_CLOSE(call("residual", {floats({0, 0}), floats({0, std::log(3.0)})}, tFloat).asFloat(), 1.0,
                    1e-12);
  BOOST_CHECK_EQUAL(show("residual", {floats({std::log(2.0)}), floats({0})}, tFloat), "1");
  BOOST_CHECK_EQUAL(call("residual", {Value::nil(), Value::nil()}, tFloat).asFloat(), 0.0);
}

BOOST_AUTO_TEST_CASE(truncate_in_single_precision) {
  // floor(314.159) / 100 computed in float: 3.14f = 3.1400001049041748
  BOOST_CHECK_EQUAL(call("truncate", {F(3.14159), I(2)}, tFloat).asFloat(), double(3.14f));
  BOOST_CHECK_EQUAL(show("truncate", {F(3.14159), I(2)}, tFloat), "3.14");
  // floor(-12.5) = -13 -> -1.3f
  BOOST_CHECK_EQUAL(call("truncate", {F(-1.25), I(1)}, tFloat).asFloat(), double(-1.3f));
  BOOST_CHECK_EQUAL(show("truncate", {F(2.5), I(0)}, tFloat), "2");
  BOOST_CHECK_EQUAL(show("truncate", {F(1234.5), I(-2)}, tFloat), "1200");
}

BOOST_AUTO_TEST_CASE(float2int_intpower_fabs) {
  BOOST_CHECK_EQUAL(call("float2int", {F(3.9)}, tInt).asInt(), 3);
  BOOST_CHECK_EQUAL(call("float2int", {F(-3.9)}, tInt).asInt(), -3);
  BOOST_CHECK_EQUAL(call("float2int", {F(1e20)}, tInt).asInt(), std::numeric_limits<std::int32_t>::max());
  BOOST_CHECK_EQUAL(call("intpower", {I(2), I(10)}, tInt).asInt(), 1024);
  BOOST_CHECK_EQUAL(call("intpower", {I(-3), I(3)}, tInt).asInt(), -27);
  BOOST_CHECK_EQUAL(call("intpower", {I(5), I(0)}, tInt).asInt(), 1);
  BOOST_CHECK_EQUAL(call("intpower", {I(7), I(-1)}, tInt).asInt(), 1);
  BOOST_CHECK_EQUAL(call("intpower", {I(2), I(31)}, tInt).asInt(), std::numeric_limits<std::int32_t>::min());
  BOOST_CHECK_EQUAL(call("intpower", {I(2), I(32)}, tInt).asInt(), 0);
  BOOST_CHECK_EQUAL(call("fabs", {F(-2.5)}, tFloat).asFloat(), 2.5);
  BOOST_CHECK_EQUAL(call("fabs", {F(0.75)}, tFloat).asFloat(), 0.75);
}

BOOST_AUTO_TEST_CASE(float_struct_variants) {
  const TypeId s2 = floatStruct(2);
  BOOST_CHECK_EQUAL(show("addfloatstructs", {fstruct({1, 2}), fstruct({0.5, 0.25})}, s2), ":(1.5, 2.25)");
  BOOST_CHECK_EQUAL(show("dividestruct", {fstruct({1, 2}), fstruct({0.5, 0.25})}, s2), ":(0.5, 1.75)");
  BOOST_CHECK_EQUAL(show("normalizestruct", {fstruct({0, 0})}, s2), ":(-0.69315, -0.69315)");
  BOOST_CHECK_EQUAL(show("dampstruct", {fstruct({0, 1}), fstruct({1, 0}), F(0.25)}, s2),
                    ":(0.35737, 0.82799)");
  BOOST_CHECK_CLOSE(call("residualstruct", {fstruct({0, 0}), fstruct({0, std::log(3.0)})}, tFloat).asFloat(),
                    1.0, 1e-12);
  BOOST_CHECK_EQUAL(show("convolvestruct", {fstruct({1, 2, 3, 4}), fstruct({0, 1})}, s2),
                    ":(3.1269, 5.1269)");
  // The result of convolvestruct has the vector's type: a 25-float matrix times 5 floats.
  std::vector<Value> m(25, F(0));
  const Value mat = tuple(floatStruct(25), m);
  const TypeId s5 = floatStruct(5);
  BOOST_CHECK_EQUAL(show("convolvestruct", {mat, fstruct({0, 0, 0, 0, 0})}, s5),
                    ":(1.6094, 1.6094, 1.6094, 1.6094, 1.6094)");  // log 5
  BOOST_CHECK_EQUAL(show("convolvestruct", {fstruct({-800, -800, -800, -800}), fstruct({-100, 0})}, s2),
                    ":(-708.4, -708.4)");  // underflow: log of the smallest normal double
  BOOST_CHECK_THROW(call("addfloatstructs", {fstruct({1, 2}), fstruct({1})}, s2), RuntimeError);
  BOOST_CHECK_THROW(call("convolvestruct", {fstruct({1, 2, 3}), fstruct({0, 1})}, s2), RuntimeError);
}

namespace {

// log sum_j exp(M[i*n + j] + v_j), as the definition says it.
std::vector<double> convolution(const std::vector<double>& m, const std::vector<double>& v) {
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    double sum = 0;
    for (std::size_t j = 0; j < v.size(); ++j) sum += std::exp(m[i * v.size() + j] + v[j]);
    out.push_back(std::log(sum));
  }
  return out;
}

}  // namespace

// convolve keeps the exponentials of its last matrix (moderate entries only): every call, with the
// same matrix again, a new one, a list or a struct, an extreme vector, agrees with the definition.
BOOST_AUTO_TEST_CASE(convolve_with_the_last_matrix_kept_agrees_with_the_definition) {
  const std::vector<double> m1 = {-0.0, -2.0, -4.0, -2.0, -0.0, -2.0, -4.0, -2.0, -0.0};
  const std::vector<double> m2 = {0.5, -1.0, 2.0, -3.0, 0.25, 1.5, -0.5, 0.0, -2.5};
  const std::vector<double> mExtreme = {400, -2.0, -4.0, -2.0, -0.0, -2.0, -4.0, -2.0, -0.0};
  const std::vector<double> v1 = {-0.1, -2.3, -1.7}, v2 = {-28.4, -6.3, -0.01}, vExtreme = {-350, 0, -1};
  const TypeId s3 = floatStruct(3), s9 = floatStruct(9);
  auto asStruct = [&](const std::vector<double>& xs, TypeId t) {
    std::vector<Value> items;
    for (double x : xs) items.push_back(F(x));
    return tuple(t, items);
  };
  auto asList = [&](const std::vector<double>& xs) {
    std::vector<Value> items;
    for (double x : xs) items.push_back(F(x));
    return keep(tLF, heap.makeList(tLF, items));
  };
  struct Case {
    const std::vector<double>& m;
    const std::vector<double>& v;
    bool list;
  };
  const Case cases[] = {{m1, v1, false},       {m1, v2, false},       {m2, v1, false}, {m1, v1, true},
                        {m1, vExtreme, false}, {mExtreme, v1, false}, {m1, v2, true},  {m2, v2, true}};
  for (const Case& c : cases) {
    const std::vector<double> want = convolution(c.m, c.v);
    std::vector<double> got;
    if (c.list) {
      for (Value l = call("convolve", {asList(c.m), asList(c.v)}, tLF); !l.isNil(); l = listTail(l))
        got.push_back(listHead(l).asFloat());
    } else {
      const Value r = call("convolvestruct", {asStruct(c.m, s9), asStruct(c.v, s3)}, s3);
      for (Value x : tupleItems(r)) got.push_back(x.asFloat());
    }
    BOOST_REQUIRE_EQUAL(got.size(), want.size());
    // 1e-12 relative (the tolerance is in percent): log near 1 magnifies the sum's last bits.
    for (std::size_t i = 0; i < want.size(); ++i) BOOST_CHECK_CLOSE(got[i], want[i], 1e-10);
  }
}

// damp takes one exponential per item for moderate items, two otherwise: both agree with the
// definition, log(f e^b + (1 - f) e^a), the extremes exactly (an overflow stays infinite).
BOOST_AUTO_TEST_CASE(damp_agrees_with_the_definition) {
  const double pairs[][2] = {{-0.1, -2.3}, {-28.4, -0.01}, {3.5, -250}, {299, -299},
                             {0, 0},       {-350, -1},     {800, 1},    {-800, -700}};
  for (double f : {0.1, 0.5, 0.9}) {
    for (const auto& p : pairs) {
      const double want = std::log(f * std::exp(p[1]) + (1.0 - f) * std::exp(p[0]));
      const Value r = call("dampstruct", {fstruct({p[0]}), fstruct({p[1]}), F(f)}, floatStruct(1));
      const double got = tupleItems(r)[0].asFloat();
      if (std::isfinite(want))
        BOOST_CHECK_CLOSE(got, want, 1e-10);
      else
        BOOST_CHECK_EQUAL(got, want);
      const Value list = call("damp", {floats({p[0]}), floats({p[1]}), F(f)}, tLF);
      BOOST_CHECK_EQUAL(listHead(list).asFloat(), got);
    }
  }
}

// The built-ins' exp and log (glibc's entry points without the errno wrapper where the build found
// them) give exactly what std::exp and std::log give: the extremes, the specials and a sweep.
BOOST_AUTO_TEST_CASE(plain_exp_and_log_are_the_libm_functions) {
#if defined(__GLIBC__) && defined(__x86_64__)
  BOOST_CHECK_MESSAGE(MELD_GLIBC_MATH_ENTRIES, "glibc on x86-64, but its entry points were not found");
#endif
  const auto same = [](double a, double b) {
    return std::isnan(a) ? std::isnan(b) : a == b && std::signbit(a) == std::signbit(b);
  };
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> xs = {0.0,
                            -0.0,
                            1.0,
                            -1.0,
                            0.5,
                            709.78,
                            709.79,
                            710.0,
                            -708.39,
                            -745.13,
                            -745.14,
                            -746.0,
                            1e-310,
                            -1e-310,
                            std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::max(),
                            inf,
                            -inf,
                            std::numeric_limits<double>::quiet_NaN()};
  for (int i = -20000; i <= 20000; ++i) xs.push_back(i * 0.0371 + 1e-7 * (i % 7));
  for (int e = -1070; e <= 1023; e += 3) xs.push_back(std::ldexp(1.37, e));
  int differ = 0;
  for (double x : xs) {
    if (!same(meldvm::plainExp(x), std::exp(x))) ++differ;
    if (!same(meldvm::plainLog(x), std::log(x))) ++differ;
  }
  BOOST_CHECK_EQUAL(differ, 0);
}

BOOST_AUTO_TEST_SUITE_END()
