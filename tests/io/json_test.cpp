// The JSON module: every value type, key order kept, escapes, strict grammar, errors that name the
// line or key, and the layout the files are written in.
#include "io/json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/input_error.hpp"

namespace msislab::io {
namespace {

TEST(Json, ParsesEveryValueTypeInOrder) {
  const Json v = parse_json(
      "{\"b\": 1.5, \"a\": [true, false, null], \"s\": \"x\\\"y\\\\z\\n\\u00e9\", "
      "\"o\": {\"n\": -2e-3}, \"big\": 1093455413.9}",
      "t.json");
  ASSERT_TRUE(v.is_object());
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v.begin().key(), "b");
  EXPECT_EQ(std::next(v.begin()).key(), "a");
  EXPECT_EQ(v.at("b").get<double>(), 1.5);
  const Json& a = v.at("a");
  ASSERT_EQ(a.size(), 3u);
  EXPECT_TRUE(a[0].get<bool>());
  EXPECT_TRUE(a[1].is_boolean());
  EXPECT_FALSE(a[1].get<bool>());
  EXPECT_TRUE(a[2].is_null());
  EXPECT_EQ(v.at("s").get<std::string>(), "x\"y\\z\n\xc3\xa9");
  EXPECT_EQ(v.at("o").at("n").get<double>(), -2e-3);
  EXPECT_EQ(v.at("big").get<double>(), 1093455413.9);
  EXPECT_FALSE(v.contains("missing"));
}

void expect_error(const std::string& text, const std::string& word) {
  try {
    parse_json(text, "f.json");
    ADD_FAILURE() << "no error for " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
  }
}

TEST(Json, RejectsMalformedText) {
  expect_error("{\"a\": 1,\n\"b\": }", "f.json:2: syntax error");
  expect_error("{\"a\": 1} x", "f.json:1: syntax error");
  expect_error("[1, 2", "unexpected end of input");
  expect_error("\"abc", "missing closing quote");
  expect_error("{\"a\": nan}", "invalid literal");
  expect_error("", "unexpected end of input");
  // What the hand-written reader used to let through.
  expect_error("{\"a\": 01}", "f.json:1:");
  expect_error("{\"a\": 1.}", "f.json:1:");
  expect_error("{\"a\": 1,}", "f.json:1:");
  // Found by fuzzing (tests/fuzz/findings): a number beyond a double's range escaped as
  // nlohmann's out_of_range instead of an InputError.
  expect_error("{\"a\": 1,\n\"b\": 1e999}", "f.json:2: number 1e999 is out of range");
  expect_error("-4.4E1462197744", "f.json:1: number -4.4E1462197744 is out of range");
}

TEST(Json, ObjectAccessorsNameTheKey) {
  const Json v = parse_json("{\"n\": \"text\", \"o\": {\"x\": null}, \"k\": 2.5}", "m.json");
  const JsonObject root(v, "m.json");
  EXPECT_FALSE(root.object("o").number_or_null("x").has_value());
  EXPECT_FALSE(root.object("o").has_value("x"));
  EXPECT_TRUE(root.object("o").has("x"));
  try {
    root.number("n");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "m.json: key 'n': expected a number, got a string");
  }
  try {
    root.object("o").string("y");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "m.json: key 'o.y': missing");
  }
  try {
    root.integer("k", 0, 10);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "m.json: key 'k': expected a whole number in [0, 10], got 2.5");
  }
}

TEST(Json, LayoutExpandsTheOuterLevelsOnly) {
  Json doc = Json::object();
  doc["name"] = "a\"b";
  doc["n"] = 3;
  doc["x"] = 0.1;
  doc["nan"] = std::nan("");
  doc["list"] = {1, 2};
  doc["inner"] = {{"p", 1.0}, {"q", Json()}};
  doc["empty"] = Json::object();
  doc["rows"] = {{{"k", 1}}, {{"k", 2}}};
  EXPECT_EQ(format_json(doc),
            "{\n  \"name\": \"a\\\"b\",\n  \"n\": 3,\n  \"x\": 0.1,\n  \"nan\": null,\n"
            "  \"list\": [1, 2],\n  \"inner\": {\"p\": 1, \"q\": null},\n  \"empty\": {},\n"
            "  \"rows\": [{\"k\": 1}, {\"k\": 2}]\n}\n");
  EXPECT_EQ(format_json(doc.at("rows"), {1, {}}), "[\n  {\"k\": 1},\n  {\"k\": 2}\n]\n");
  EXPECT_EQ(format_json(Json::object({{"rows", doc.at("rows")}}), {1, {"rows"}}),
            "{\n  \"rows\": [\n    {\"k\": 1},\n    {\"k\": 2}\n  ]\n}\n");
  EXPECT_EQ(format_json(Json::object({{"m", {{"a", {1}}}}}), {2, {}}),
            "{\n  \"m\": {\n    \"a\": [1]\n  }\n}\n");
  EXPECT_EQ(format_json(Json::array(), {1, {}}), "[\n]\n");
  EXPECT_EQ(format_json(doc, {0, {}}).find('\n'), format_json(doc, {0, {}}).size() - 1);
  // What is written reads back.
  const Json back = parse_json(format_json(doc), "back.json");
  EXPECT_EQ(back.at("name"), "a\"b");
  EXPECT_TRUE(back.at("nan").is_null());
  EXPECT_EQ(back.at("x").get<double>(), 0.1);
}

}  // namespace
}  // namespace msislab::io
