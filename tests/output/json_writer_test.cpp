// The JSON writer behind summary.json and `rigidity materials --json`.
#include "rigidity/json_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include "mini_json.hpp"
#include "rigidity/errors.hpp"

namespace rigidity {
namespace {

TEST(JsonWriter, StringsAreEscapedAndReadBackUnchanged) {
  const std::string tricky = std::string("quote \" backslash \\ slash / tab \t newline \n cr \r bell \a nul ") + '\0' +
                             " unit \x1f del \x7f utf-8 γ→∞";
  JsonWriter json("test");
  json.begin_object().key(tricky).text(tricky).end_object();
  const std::string text = json.take();
  const mini_json::Value doc = mini_json::parse(text);
  ASSERT_EQ(doc.object.size(), 1u);
  EXPECT_EQ(doc.object[0].first, tricky);
  EXPECT_EQ(doc.object[0].second.string, tricky);
  EXPECT_NE(text.find("\\u0000"), std::string::npos);
  EXPECT_NE(text.find("\\u001f"), std::string::npos);
}

TEST(JsonWriter, NumbersRoundTripExactly) {
  const double values[] = {0.0,
                           -0.0,
                           1.0,
                           -1.5,
                           0.1,
                           1.0 / 3.0,
                           2.0 / 3.0 * 1e-12,
                           6.02214076e23,
                           299792458.0,
                           8.987551787368176e16,
                           std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::min(),
                           std::numeric_limits<double>::denorm_min(),
                           -std::numeric_limits<double>::epsilon()};
  JsonWriter json("test");
  json.begin_array();
  for (const double v : values) json.number(v);
  json.end_array();
  const mini_json::Value doc = mini_json::parse(json.take());
  ASSERT_EQ(doc.array.size(), std::size(values));
  for (std::size_t i = 0; i < std::size(values); ++i) {
    EXPECT_EQ(doc[i].number, values[i]) << "value " << i;
    EXPECT_EQ(std::signbit(doc[i].number), values[i] < 0.0) << "value " << i;  // -0 is written as 0
  }
}

TEST(JsonWriter, ShortestFormIsShort) {
  std::string out;
  append_shortest(out, 0.1);
  EXPECT_EQ(out, "0.1");
  out.clear();
  append_shortest(out, 1.5);
  EXPECT_EQ(out, "1.5");
  out.clear();
  append_shortest(out, 2.0);
  EXPECT_EQ(out, "2");
}

TEST(JsonWriter, IntegersBooleansAndNull) {
  JsonWriter json("test");
  json.begin_object()
      .key("big")
      .integer(9007199254740993LL)
      .key("negative")
      .integer(-42)
      .key("yes")
      .boolean(true)
      .key("no")
      .boolean(false)
      .key("nothing")
      .null()
      .end_object();
  const std::string text = json.take();
  EXPECT_NE(text.find("9007199254740993"), std::string::npos);  // not rounded through a double
  const mini_json::Value doc = mini_json::parse(text);
  EXPECT_EQ(doc["negative"].number, -42.0);
  EXPECT_TRUE(doc["yes"].boolean);
  EXPECT_EQ(doc["no"].type, mini_json::Value::Type::boolean);
  EXPECT_FALSE(doc["no"].boolean);
  EXPECT_EQ(doc["nothing"].type, mini_json::Value::Type::null);
}

TEST(JsonWriter, LayoutsNestAndEmptyContainersStayValid) {
  JsonWriter json("test");
  json.begin_object();
  json.key("empty_object").begin_object().end_object();
  json.key("empty_array").begin_array().end_array();
  json.key("rows").begin_array();
  for (int i = 0; i < 3; ++i) {
    json.begin_object(JsonLayout::line);
    json.key("i").integer(i);
    json.key("list").begin_array(JsonLayout::block).text("a").text("b").end_array();  // on the row's line
    json.end_object();
  }
  json.end_array();
  json.end_object();
  const std::string text = json.take();
  EXPECT_NE(text.find("{\"i\": 1, \"list\": [\"a\", \"b\"]}"), std::string::npos) << text;
  EXPECT_NE(text.find("\"empty_object\": {}"), std::string::npos) << text;
  EXPECT_NE(text.find("\"empty_array\": []"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');
  const mini_json::Value doc = mini_json::parse(text);
  EXPECT_EQ(doc["rows"].array.size(), 3u);
  EXPECT_EQ(doc["rows"][2]["list"][1].string, "b");
}

TEST(JsonWriter, NonFiniteNumberIsRefusedWithItsPath) {
  for (const double bad :
       {std::nan(""), std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    JsonWriter json("summary.json");
    json.begin_object().key("bodies").begin_array();
    json.begin_object().key("energy").number(1.0).end_object();
    json.begin_object().key("name").text("bar");
    try {
      json.key("energy").number(bad);
      FAIL() << "a non-finite number was accepted";
    } catch (const NumericalError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("summary.json"), std::string::npos) << what;
      EXPECT_NE(what.find("bodies[1].energy"), std::string::npos) << what;
    }
  }
}

TEST(JsonWriter, MisuseIsALogicError) {
  {
    JsonWriter json("test");
    json.begin_object();
    EXPECT_THROW(json.text("no key"), std::logic_error);
  }
  {
    JsonWriter json("test");
    json.begin_array();
    EXPECT_THROW(json.key("k"), std::logic_error);
    EXPECT_THROW(json.end_object(), std::logic_error);
  }
  {
    JsonWriter json("test");
    json.begin_object();
    EXPECT_THROW((void)json.take(), std::logic_error);
  }
  {
    JsonWriter json("test");
    json.integer(1);
    EXPECT_THROW(json.integer(2), std::logic_error);
  }
}

TEST(MiniJson, RejectsWhatAWriterMightGetWrong) {
  for (const char* bad : {"[1,]", "{\"a\":1,}", "[NaN]", "[inf]", "[01]", "[\"a\nb\"]", "{\"a\":1,\"a\":2}", "[1] x",
                          "{'a':1}", "[1.]", "[.5]"}) {
    EXPECT_THROW(mini_json::parse(bad), std::runtime_error) << bad;
  }
  EXPECT_NO_THROW(mini_json::parse(" {\"a\": [1, -2.5e-3, true, null, \"\\u00e9\\ud83d\\ude00\"]} "));
}

}  // namespace
}  // namespace rigidity
