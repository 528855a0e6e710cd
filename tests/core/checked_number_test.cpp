// The checked number readers refuse what would wrap, truncate or overflow, naming field and value.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "lapis/core/checked_number.h"

using namespace lapis;
using nlohmann::json;

TEST_CASE("core: text integers are whole, in range and never wrap") {
  CHECK(parse_integer("42", "n", 0, 100) == 42);
  CHECK(parse_integer("+7", "n", 0, 100) == 7);
  CHECK(parse_integer("-3", "n", -5, 5) == -3);
  CHECK(parse_index("2147483647", "vertex") == 2147483647);
  CHECK_THROWS_WITH_AS(parse_index("4294967296", "ROI entry 0"),
                       "ROI entry 0: expected an integer in [0, 2147483647], found 4294967296", InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_index("4294967301", "vertex"),
                       "vertex: expected an integer in [0, 2147483647], found 4294967301", InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_index("99999999999999999999999", "vertex"),
                       "vertex: expected an integer in [0, 2147483647], found 99999999999999999999999",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_index("-1", "vertex"), "vertex: expected an integer in [0, 2147483647], found -1",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_index("5", "vertex", 5), "vertex: expected an integer in [0, 4], found 5",
                       InvalidArgument);
  for (const char* bad : {"1.5", "1e3", "", "+", "12abc", " 1", "0x10"})
    CHECK_THROWS_AS(parse_integer(bad, "n", 0, 1000), InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_integer<IoError>("1.5", "f.txt: entry 3", 0, 9),
                       "f.txt: entry 3: expected an integer in [0, 9], found '1.5'", IoError);
}

TEST_CASE("core: text and computed numbers are finite and in range") {
  CHECK(parse_finite("1e-3", "step") == 1e-3);
  CHECK(parse_finite("+2.5", "x", 0, 3) == 2.5);
  for (const char* bad : {"1e400", "nan", "inf", "-inf", "", "1.0x", "4", "-0.5"})
    CHECK_THROWS_WITH_AS(parse_finite(bad, "x", 0, 3),
                         doctest::Contains("x: expected a finite number in [0, 3], found"), InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_finite("nan", "x"), "x: expected a finite number, found nan", InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_finite("1e999", "x"), "x: expected a finite number, found 1e999", InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_finite("0x1p3", "x"), "x: expected a finite number, found '0x1p3'", InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_finite("-0.5", "--width", 0, 1e300),
                       "--width: expected a finite number in [0, 1e+300], found -0.5", InvalidArgument);
  CHECK(check_finite(1e308, "y") == 1e308);
  CHECK_THROWS_WITH_AS(check_finite(1e308 * 10, "vertex 3 x"), "vertex 3 x: expected a finite number, found inf",
                       InvalidArgument);
  CHECK_THROWS_AS(check_finite(std::nan(""), "y"), InvalidArgument);
}

TEST_CASE("core: JSON indices are JSON integers in range, never truncated or wrapped") {
  CHECK(json_index(json::parse("175"), "source") == 175);
  CHECK(json_integer(json::parse("-4"), "n", -10, 10) == -4);
  CHECK_THROWS_WITH_AS(json_index(json::parse("4294967471"), "pairs[0].keys[0].source"),
                       "pairs[0].keys[0].source: expected an integer in [0, 2147483647], found 4294967471",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(json_index(json::parse("1.5"), "roi[0]"),
                       "roi[0]: expected an integer in [0, 2147483647], found '1.5'", InvalidArgument);
  CHECK_THROWS_WITH_AS(json_index(json::parse("5.7"), "v"), doctest::Contains("found '5.7'"), InvalidArgument);
  CHECK_THROWS_WITH_AS(json_index(json::parse("1e20"), "v"), doctest::Contains("found '1e+20'"), InvalidArgument);
  CHECK_THROWS_WITH_AS(json_index(json::parse("18446744073709551615"), "v"),
                       "v: expected an integer in [0, 2147483647], found 18446744073709551615", InvalidArgument);
  CHECK_THROWS_WITH_AS(json_index(json::parse("-9223372036854775808"), "v"),
                       "v: expected an integer in [0, 2147483647], found -9223372036854775808", InvalidArgument);
  CHECK_THROWS_AS(json_index(json::parse("\"3\""), "v"), InvalidArgument);
  CHECK_THROWS_AS(json_index(json::parse("null"), "v"), InvalidArgument);
  CHECK_THROWS_AS(json_index<IoError>(json::parse("true"), "v"), IoError);
}

TEST_CASE("core: JSON numbers are finite and in range") {
  CHECK(json_finite(json::parse("3"), "t") == 3.0);
  CHECK(json_finite(json::parse("-1e308"), "t") == -1e308);
  CHECK_THROWS_WITH_AS(json_finite(json::parse("2"), "t", 0, 1), "t: expected a finite number in [0, 1], found 2",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(json_finite(json::parse("[1]"), "t"), "t: expected a finite number, found '[1]'",
                       InvalidArgument);
  CHECK_THROWS_AS(json_finite(json(std::numeric_limits<double>::infinity()), "t"), InvalidArgument);
}
