// The JSON reader: every value type, key order kept, escapes, and errors that name the line or key.
#include "io/json.hpp"

#include <gtest/gtest.h>

#include <string>

#include "io/input_error.hpp"

namespace msislab::io {
namespace {

TEST(Json, ParsesEveryValueTypeInOrder) {
  const JsonValue v = parse_json(
      "{\"b\": 1.5, \"a\": [true, false, null], \"s\": \"x\\\"y\\\\z\\n\\u00e9\", "
      "\"o\": {\"n\": -2e-3}, \"big\": 1093455413.9}",
      "t.json");
  ASSERT_EQ(v.type, JsonValue::Type::object);
  ASSERT_EQ(v.members.size(), 5u);
  EXPECT_EQ(v.members[0].first, "b");
  EXPECT_EQ(v.members[1].first, "a");
  EXPECT_EQ(v.find("b")->number, 1.5);
  const JsonValue& a = *v.find("a");
  ASSERT_EQ(a.items.size(), 3u);
  EXPECT_TRUE(a.items[0].boolean);
  EXPECT_EQ(a.items[1].type, JsonValue::Type::boolean);
  EXPECT_FALSE(a.items[1].boolean);
  EXPECT_EQ(a.items[2].type, JsonValue::Type::null);
  EXPECT_EQ(v.find("s")->text, "x\"y\\z\n\xc3\xa9");
  EXPECT_EQ(v.find("o")->find("n")->number, -2e-3);
  EXPECT_EQ(v.find("big")->number, 1093455413.9);
  EXPECT_EQ(v.find("missing"), nullptr);
}

void expect_error(const std::string& text, const std::string& word) {
  try {
    parse_json(text, "f.json");
    ADD_FAILURE() << "no error for " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

TEST(Json, RejectsMalformedText) {
  expect_error("{\"a\": 1,\n\"b\": }", "f.json:2:");
  expect_error("{\"a\": 1} x", "after the JSON value");
  expect_error("[1, 2", "expected ']'");
  expect_error("\"abc", "unterminated");
  expect_error("{\"a\": nan}", "not a JSON value");
  expect_error("", "unexpected end");
}

TEST(Json, ObjectAccessorsNameTheKey) {
  const JsonValue v = parse_json("{\"n\": \"text\", \"o\": {\"x\": null}}", "m.json");
  const JsonObject root(v, "m.json");
  EXPECT_FALSE(root.object("o").number_or_null("x").has_value());
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
}

}  // namespace
}  // namespace msislab::io
