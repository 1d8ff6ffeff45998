// SPDX-License-Identifier: LGPL-3.0-or-later
// The planning app's small pure functions: base64_decode and html_escape of
// the report writer, the report's picture checks, and the grid of the small
// sweep job (sweep_request.cpp) with the CLI's messages for bad values.
#include "case_request.hpp"
#include "errors.hpp"
#include "input_error_message.hpp"
#include "report.hpp"
#include "sweep_request.hpp"
#include <functional>
#include <gtest/gtest.h>
#include <limits>

using namespace breastsim;
using nlohmann::json;

namespace
{
using fixtures::message_of;

/// RFC 4648 base64 of `bytes` with padding: the closed form the decoder inverts.
std::string base64_encode(const std::string& bytes)
{
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3)
  {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    unsigned group = 0; // 3 bytes -> 24 bits, missing bytes as zeros
    for (std::size_t k = 0; k < 3; ++k)
      group = (group << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k)
      out += k <= n ? alphabet[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

/// The numbers of one grid entry.
std::vector<double> numbers(const std::vector<Value>& values)
{
  std::vector<double> out;
  for (const auto& v : values)
    out.push_back(std::get<double>(v));
  return out;
}

const std::string png_signature = "\x89PNG\r\n\x1a\n";
} // namespace

TEST(AppBase64, Rfc4648VectorsPaddedAndUnpadded)
{
  // RFC 4648 section 10
  const std::vector<std::pair<std::string, std::string>> vectors = {
      {"", ""},         {"Zg==", "f"},         {"Zm8=", "fo"},        {"Zm9v", "foo"},
      {"Zm9vYg==", "foob"}, {"Zm9vYmE=", "fooba"}, {"Zm9vYmFy", "foobar"}};
  for (const auto& [text, bytes] : vectors)
  {
    EXPECT_EQ(app::base64_decode(text), bytes) << text;
    std::string unpadded = text;
    while (!unpadded.empty() && unpadded.back() == '=')
      unpadded.pop_back();
    EXPECT_EQ(app::base64_decode(unpadded), bytes) << unpadded;
  }
  // '+' = 62, '/' = 63: 111110 111111 111110 111111 = 0xfb 0xff 0xbf
  EXPECT_EQ(app::base64_decode("+/+/"), "\xfb\xff\xbf");
  EXPECT_EQ(app::base64_decode("iVBORw0KGgo="), png_signature);
}

TEST(AppBase64, EveryByteValueAtEveryOffset)
{
  std::string all;
  for (int b = 0; b < 256; ++b)
    all += static_cast<char>(b);
  for (std::size_t shift = 0; shift < 3; ++shift) // 256 - shift bytes: all three remainders mod 3
  {
    const std::string bytes = all.substr(shift);
    EXPECT_EQ(app::base64_decode(base64_encode(bytes)), bytes) << shift;
  }
}

TEST(AppBase64, RefusedWithTheReason)
{
  const std::string length = "not base64: its length is impossible";
  const std::string character = "not base64: a character outside A-Z, a-z, 0-9, +, /";
  const std::string padding = "not base64: '=' padding that does not complete a group of 4 characters";
  // 4k + 1 characters cannot come from any bytes
  for (const char* text : {"Z", "Zm9vY", "Zm9vYmFyZ", "Zm9vY="})
    EXPECT_EQ(message_of([&] { app::base64_decode(text); }), length) << text;
  for (const char* text : {"Zm9-", "Zm9_", "Zm 9", "Zm9\n", "Zm=v", "Z===", "Zm9v\xc3\xa9", "not base64!"})
    EXPECT_EQ(message_of([&] { app::base64_decode(text); }), character) << text;
  for (const char* text : {"Zg=", "Zm9vYg=", "Zm9v=", "Zg==="})
    EXPECT_EQ(message_of([&] { app::base64_decode(text); }), padding) << text;
}

TEST(AppHtmlEscape, TheFiveCharactersAndNothingElse)
{
  EXPECT_EQ(app::html_escape(""), "");
  EXPECT_EQ(app::html_escape("standing: before | after, 60 mm"), "standing: before | after, 60 mm");
  EXPECT_EQ(app::html_escape("<script>alert('x') & \"y\"</script>"),
            "&lt;script&gt;alert(&#39;x&#39;) &amp; &quot;y&quot;&lt;/script&gt;");
  EXPECT_EQ(app::html_escape("χ² ≈ 1 cm³"), "χ² ≈ 1 cm³"); // UTF-8 bytes pass unchanged
  EXPECT_EQ(app::html_escape("&amp;"), "&amp;amp;");       // each call escapes once
  EXPECT_EQ(app::html_escape(std::string("a\0b", 3)), std::string("a\0b", 3));
}

TEST(AppReportPictures, PngOnlyAtMostEightShortCaptions)
{
  const std::string png = base64_encode(png_signature + "rest of the file");
  const json one = {{"caption", "standing: before | after"}, {"png", png}};
  const auto pictures = app::report_pictures({{"pictures", {one, one}}, {"calibration", nullptr}});
  ASSERT_EQ(pictures.size(), 2u);
  EXPECT_EQ(pictures[1].caption, "standing: before | after");
  EXPECT_EQ(pictures[1].png_base64, png);
  EXPECT_TRUE(app::report_pictures(json::object()).empty());

  const auto refused = [](const json& request) { return message_of([&] { app::report_pictures(request); }); };
  EXPECT_EQ(refused({{"pictures", json::array({one, one, one, one, one, one, one, one, one})}}),
            "pictures: an array of at most 8 pictures");
  EXPECT_EQ(refused({{"pictures", {{{"caption", std::string(201, 'x')}, {"png", png}}}}}),
            "pictures[0].caption: 201 characters, allowed at most 200");
  EXPECT_EQ(refused({{"pictures", {{{"caption", std::string(200, 'x')}, {"png", png}}}}}), "");
  EXPECT_EQ(refused({{"pictures", {one, {{"caption", "x"}, {"png", base64_encode("GIF89a")}}}}}),
            "pictures[1].png: not a PNG file");
  EXPECT_EQ(refused({{"pictures", {{{"caption", "x"}, {"png", "Zm9-"}}}}}),
            "pictures[0].png: not base64: a character outside A-Z, a-z, 0-9, +, /");
  EXPECT_EQ(refused({{"pictures", {{{"caption", "x"}, {"png", png}, {"src", "/etc/passwd"}}}}}),
            "pictures[0]: an object {\"caption\": text, \"png\": base64}");
  EXPECT_EQ(refused({{"pictures", {{{"caption", 1}, {"png", png}}}}}),
            "pictures[0]: an object {\"caption\": text, \"png\": base64}");
  EXPECT_EQ(refused({{"script", 1}}), "unknown field 'script' in the report request: allowed pictures, calibration");
  EXPECT_EQ(refused(json::array()), "the report request must be an object {\"pictures\": [...], \"calibration\": id or null}");
}

TEST(AppSweepGrid, ShortNamesAndCaseKeysGiveTheCliGrid)
{
  const Config base = app::case_from_overrides(json::object());
  const json vary = {{"h", {0.02, 0.025, 0.03}}, {"a", {25, 30, 35}}};
  const auto grid = app::sweep_grid(vary, base);
  ASSERT_EQ(grid.size(), 2u); // in the order of the names: a, h
  EXPECT_EQ(grid[0].first, "incision.a_deg");
  EXPECT_EQ(numbers(grid[0].second), (std::vector<double>{25, 30, 35}));
  EXPECT_EQ(grid[1].first, "incision.h");
  EXPECT_EQ(numbers(grid[1].second), (std::vector<double>{0.02, 0.025, 0.03}));
  EXPECT_EQ(app::sweep_size(vary), 9u);
  // the same grid as `breastsim sweep --vary a=25,30,35 --vary h=0.02,0.025,0.03`
  EXPECT_EQ(grid[0].second, sweep_values(base, "incision.a_deg", "25,30,35"));
  EXPECT_EQ(grid[1].second, sweep_values(base, "incision.h", "0.02,0.025,0.03"));

  const json keys = {{"incision.s", {0.018, 0.1 + 0.2 - 0.28}}, {"d", {0.045}}};
  const auto by_key = app::sweep_grid(keys, base);
  ASSERT_EQ(by_key.size(), 2u);
  EXPECT_EQ(by_key[0].first, "incision.d");
  EXPECT_EQ(by_key[1].first, "incision.s");
  // every double survives the request's text form exactly
  EXPECT_EQ(numbers(by_key[1].second), (std::vector<double>{0.018, 0.1 + 0.2 - 0.28}));
  EXPECT_EQ(app::sweep_size(keys), 2u);
  EXPECT_EQ(app::sweep_size({{"a", {30}}}), 1u);
}

TEST(AppSweepGrid, OutOfRangeValuesWithTheCliMessages)
{
  const Config base = app::case_from_overrides(json::object());
  const auto refused = [&](const json& vary) { return message_of([&] { app::sweep_grid(vary, base); }); };
  // the messages `breastsim sweep --vary` gives for these values
  EXPECT_EQ(refused({{"a", {25, 95}}}), "key 'incision.a_deg' = 95 is out of range: allowed (0, 90) deg");
  EXPECT_EQ(refused({{"a", {0}}}), "key 'incision.a_deg' = 0 is out of range: allowed (0, 90) deg");
  EXPECT_EQ(refused({{"h", {0}}}), "key 'incision.h' = 0 is out of range: allowed (0, 0.5] m");
  EXPECT_EQ(refused({{"s", {-0.01}}}), "key 'incision.s' = -0.01 is out of range: allowed [0, 0.5] m");
  EXPECT_EQ(refused({{"a", {30}}, {"d", {0.02, 0.6}}}), "key 'incision.d' = 0.6 is out of range: allowed [0, 0.5] m");
  EXPECT_NE(refused({{"a", {std::numeric_limits<double>::infinity()}}}).find("incision.a_deg"), std::string::npos);
  // the bounds themselves where the range is closed
  EXPECT_EQ(refused({{"s", {0, 0.5}}, {"d", {0, 0.5}}}), "");
}

TEST(AppSweepGrid, MalformedRequestsNameTheField)
{
  Config base = app::case_from_overrides(json::object());
  const auto refused = [&](const json& vary) { return message_of([&] { app::sweep_grid(vary, base); }); };
  const std::string shape = "vary: an object of 1 to 2 of a, s, h, d with their values, such as "
                            "{\"a\": [25, 30, 35], \"h\": [0.02, 0.025, 0.03]}";
  EXPECT_EQ(refused(json::object()), shape);
  EXPECT_EQ(refused(json::array({25, 30})), shape);
  EXPECT_EQ(refused({{"a", {30}}, {"s", {0.02}}, {"h", {0.025}}}), shape);
  EXPECT_EQ(refused({{"tissue.mu", {300}}}), "vary: 'tissue.mu' is not one of the incision's a, s, h, d");
  EXPECT_NE(refused({{"x", {1}}}).find("'x'"), std::string::npos);
  EXPECT_EQ(refused({{"a", {25}}, {"incision.a_deg", {30}}}), "vary: incision.a_deg is named twice");
  EXPECT_EQ(refused({{"a", json::array()}}), "vary.a: an array of 1 to 3 numbers");
  EXPECT_EQ(refused({{"a", {20, 25, 30, 35}}}), "vary.a: an array of 1 to 3 numbers");
  EXPECT_EQ(refused({{"a", 30}}), "vary.a: an array of 1 to 3 numbers");
  EXPECT_EQ(refused({{"a", {"30"}}}), "vary.a: \"30\" is not a number");
  EXPECT_EQ(refused({{"h", {true}}}), "vary.h: true is not a number");
  base.set("postures.names", std::vector<std::string>{"supine"});
  EXPECT_EQ(refused({{"a", {30}}}), "key 'postures.names': the sweep reports the standing breast, so the "
                                    "postures must include standing (theta = 0)");
}
