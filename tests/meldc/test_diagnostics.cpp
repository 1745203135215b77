#define BOOST_TEST_MODULE meldc_diagnostics
#include <boost/test/unit_test.hpp>

#include "test_support.hpp"

using namespace meldc;

BOOST_AUTO_TEST_CASE(format_with_source_line_and_caret) {
  SourceManager sources;
  std::ostringstream out;
  Diagnostics diag(sources, out);
  uint32_t f = sources.add("dir/x.meld", "type a(node).\n  a(A) -o b(A).\n");
  diag.error(SourceLoc{f, 2, 11}, "unknown predicate 'b'");
  BOOST_TEST(out.str() ==
             "dir/x.meld:2:11: error: unknown predicate 'b'\n"
             "  a(A) -o b(A).\n"
             "          ^\n");
  BOOST_TEST(diag.errorCount() == 1);
}

BOOST_AUTO_TEST_CASE(tabs_are_kept_in_the_caret_line) {
  SourceManager sources;
  std::ostringstream out;
  Diagnostics diag(sources, out);
  uint32_t f = sources.add("t.meld", "\ta(A)\n");
  diag.warning(SourceLoc{f, 1, 3}, "w");
  BOOST_TEST(out.str() == "t.meld:1:3: warning: w\n\ta(A)\n\t ^\n");
  BOOST_TEST(diag.warningCount() == 1);
  BOOST_TEST(diag.errorCount() == 0);
}

BOOST_AUTO_TEST_CASE(position_at_end_of_file) {
  SourceManager sources;
  std::ostringstream out;
  Diagnostics diag(sources, out);
  uint32_t f = sources.add("t.meld", "a(A)");
  diag.error(SourceLoc{f, 1, 5}, "e");
  BOOST_TEST(out.str() == "t.meld:1:5: error: e\na(A)\n    ^\n");
}

BOOST_AUTO_TEST_CASE(missing_dot_points_after_the_statement) {
  Parsed p("type a(node).\ntype b(node).\na(A) -o b(A)\na(A) -o b(A).\n");
  BOOST_TEST(!p.ok());
  BOOST_TEST(p.errors().rfind("t.meld:3:13: error: expected", 0) == 0, p.errors());
}

BOOST_AUTO_TEST_CASE(several_syntax_errors_in_one_run) {
  Parsed p("type a(node).\na(A) -o b(A) c.\na(A) -o -o.\na(A) -o b(A).\n");
  BOOST_TEST(!p.program.has_value());
  BOOST_TEST(p.diag.errorCount() >= 2, p.errors());
}

BOOST_AUTO_TEST_CASE(helpful_operator_messages) {
  Parsed ne("a(A, X), X != 1 -o b(A).\n");
  BOOST_TEST(ne.errors().find("writes 'not equal' as '<>'") != std::string::npos, ne.errors());
  Parsed eq("a(A, X), X == 1 -o b(A).\n");
  BOOST_TEST(eq.errors().find("single '='") != std::string::npos, eq.errors());
  Parsed neg("a(A, X) -o b(A, -X).\n");
  BOOST_TEST(neg.errors().find("no unary minus") != std::string::npos, neg.errors());
}

BOOST_AUTO_TEST_CASE(lexical_errors) {
  Parsed s("const a = \"abc.\n");
  BOOST_TEST(s.errors().find("unterminated string") != std::string::npos, s.errors());
  Parsed c("type a(node). /* never closed\n");
  BOOST_TEST(c.errors().find("unterminated comment") != std::string::npos, c.errors());
}

BOOST_AUTO_TEST_CASE(invalid_utf8_is_an_error_not_a_crash) {
  Parsed p("type a(node).\n// caf\xe9\n");
  BOOST_TEST(!p.program.has_value());
  BOOST_TEST(p.errors().find("t.meld:2:7: error: the file is not valid UTF-8 text") != std::string::npos,
             p.errors());
}
