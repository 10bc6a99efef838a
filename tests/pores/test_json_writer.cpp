// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// JSON writer of the pore tool: exact escaping and layout, non-finite numbers as null, and a
// round trip of awkward strings and numbers through Python's json module (the project's TAPMC_PYTHON).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "tapmc_pores/json_writer.h"

namespace {

using tapmc::pores::json_string;
using tapmc::pores::JsonWriter;

TEST(JsonWriter, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(json_string("plain"), "\"plain\"");
  EXPECT_EQ(json_string("a\"b\\c/d"), "\"a\\\"b\\\\c/d\"");
  EXPECT_EQ(json_string("\b\f\n\r\t"), "\"\\b\\f\\n\\r\\t\"");
  EXPECT_EQ(json_string(std::string("\x01\x1f\x7f", 3)), "\"\\u0001\\u001f\x7f\"");
  EXPECT_EQ(json_string(std::string("a\0b", 3)), "\"a\\u0000b\"");
}

TEST(JsonWriter, KeepsValidUtf8AndReplacesInvalidBytes) {
  EXPECT_EQ(json_string("caf\xc3\xa9 \xe6\x97\xa5 \xf0\x9f\x98\x80"), "\"caf\xc3\xa9 \xe6\x97\xa5 \xf0\x9f\x98\x80\"");
  EXPECT_EQ(json_string("\xff"), "\"\\ufffd\"");                  // never a UTF-8 byte
  EXPECT_EQ(json_string("\xc3"), "\"\\ufffd\"");                  // truncated sequence
  EXPECT_EQ(json_string("\xc0\xaf"), "\"\\ufffd\\ufffd\"");       // overlong '/'
  EXPECT_EQ(json_string("\xed\xa0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // surrogate U+D800
  EXPECT_EQ(json_string("\xf4\x90\x80\x80"), "\"\\ufffd\\ufffd\\ufffd\\ufffd\"");  // beyond U+10FFFF
}

TEST(JsonWriter, SeparatorsLineBreaksAndNonFiniteNumbers) {
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object().key("n").value(3).key("x").value(0.1).break_line(1).key("list").begin_array();
  json.break_line(2).value(std::numeric_limits<double>::quiet_NaN());
  json.break_line(2).value(std::numeric_limits<double>::infinity());
  json.break_line(2).begin_object().key("s").value("q\"").key("b").value(true).end_object();
  json.end_array().key("empty").array(std::vector<double>{}).key("v").array(std::vector<double>{1.5, -2e-300});
  json.end_object();
  EXPECT_EQ(out.str(),
            "{\"n\": 3, \"x\": 0.1,\n \"list\": [\n  null,\n  null,\n  {\"s\": \"q\\\"\", \"b\": true}], "
            "\"empty\": [], \"v\": [1.5, -2e-300]}");
}

TEST(JsonWriter, NumbersCarryTwelveSignificantDigits) {
  EXPECT_EQ(tapmc::pores::number_text(1.0 / 3.0), "0.333333333333");
  EXPECT_EQ(tapmc::pores::number_text(123456789012345.0), "1.23456789012e+14");
  EXPECT_EQ(tapmc::pores::number_text(-0.0), "-0");
}

// Every string and number written, read back by Python's json module: strings byte for byte (as
// UTF-8, invalid bytes as U+FFFD), numbers to 12 digits, non-finite as None.
TEST(JsonWriter, RoundTripsThroughPythonJson) {
  const char* python = TAPMC_PYTHON;  // the project's Python (CMake: TAPMC_PYTHON)
  if (std::FILE* probe = std::fopen(python, "r")) std::fclose(probe);
  else GTEST_SKIP() << python << " not found";
  std::vector<std::string> strings = {"", "plain", "quote \" backslash \\ slash /", "tab\tnew\nline\rcr",
                                      "caf\xc3\xa9 \xf0\x9f\x98\x80", std::string("nul\0byte", 8), "bad \xff byte"};
  std::string all_controls;
  for (int c = 1; c < 32; ++c) all_controls += static_cast<char>(c);
  strings.push_back(all_controls);
  const std::vector<double> numbers = {0.0, -1.5, 1.0 / 3.0, 6.02214076e23, -4.9e-324, 1.7976931348623157e308,
                                       std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity()};
  const std::string path = ::testing::TempDir() + "tapmc_json_round_trip.json";
  {
    std::ofstream file(path);
    JsonWriter json(file);
    json.begin_object().key("strings").array(strings).key("numbers").array(numbers).end_object();
  }
  // Python prints each string as UTF-8 hex and each number with repr (None for null).
  const std::string command = std::string(python) +
                              " -c \"import json, sys; d = json.load(open(sys.argv[1], encoding='utf-8'));"
                              " [print(s.encode('utf-8').hex()) for s in d['strings']];"
                              " [print(repr(x)) for x in d['numbers']]\" " +
                              path;
  std::FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  ASSERT_EQ(pclose(pipe), 0) << output;
  std::istringstream lines(output);
  for (std::string expected : strings) {
    const auto bad = expected.find('\xff');
    if (bad != std::string::npos) expected.replace(bad, 1, "\xef\xbf\xbd");  // U+FFFD in UTF-8
    std::string hex;
    for (unsigned char c : expected) {
      static const char* kHex = "0123456789abcdef";
      hex += kHex[c >> 4];
      hex += kHex[c & 15];
    }
    std::string line;
    ASSERT_TRUE(std::getline(lines, line));
    EXPECT_EQ(line, hex);
  }
  for (double x : numbers) {
    std::string line;
    ASSERT_TRUE(std::getline(lines, line));
    if (!std::isfinite(x)) {
      EXPECT_EQ(line, "None");
    } else {
      const double back = std::strtod(line.c_str(), nullptr);  // stod refuses subnormals
      EXPECT_NEAR(back, x, 5e-12 * std::abs(x)) << line;
    }
  }
  std::remove(path.c_str());
}

}  // namespace
