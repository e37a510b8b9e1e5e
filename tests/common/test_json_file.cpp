// JSON input helpers: load_json_file refuses missing, non-JSON and oversized files, and the
// require_* helpers' errors name the file, the JSON path and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "common/json_file.hpp"
#include "tests/common/common_test_util.hpp"

namespace a3::common {
namespace {

using nlohmann::json;

class JsonFileTest : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto path = dir_.path() / name;
    std::ofstream out(path, std::ios::binary);
    out << text;
    return path;
  }
  test::TempDir dir_;
};

// Runs fn, expects an InputError whose message contains every one of `parts`.
template <typename Fn>
void expect_input_error(Fn fn, std::initializer_list<std::string> parts) {
  try {
    fn();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const auto& part : parts) {
      EXPECT_NE(what.find(part), std::string::npos) << "'" << part << "' not in: " << what;
    }
  }
}

TEST_F(JsonFileTest, LoadsAValidFile) {
  const auto path = write("vehicle.json", R"({"rotor": {"k_f": 1.5e-5, "count": 4}, "name": "x"})");
  const json j = load_json_file(path);
  EXPECT_DOUBLE_EQ(j["rotor"]["k_f"].get<double>(), 1.5e-5);
  EXPECT_EQ(j["name"], "x");
}

TEST_F(JsonFileTest, MissingFileNamesThePath) {
  const auto path = dir_.path() / "nope.json";
  expect_input_error([&] { load_json_file(path); }, {path.string(), "cannot read"});
}

TEST_F(JsonFileTest, DirectoryIsNotAFile) {
  expect_input_error([&] { load_json_file(dir_.path()); }, {dir_.path().string()});
}

TEST_F(JsonFileTest, NonJsonFileNamesThePathAndWhere) {
  const auto path = write("broken.json", "{\"a\": 1,\n \"b\": }");
  expect_input_error([&] { load_json_file(path); }, {path.string(), "not valid JSON", "byte 15"});
  const auto text = write("notes.json", "this is not json");
  expect_input_error([&] { load_json_file(text); }, {text.string(), "not valid JSON"});
  const auto empty = write("empty.json", "");
  expect_input_error([&] { load_json_file(empty); }, {empty.string(), "not valid JSON"});
}

TEST_F(JsonFileTest, OversizedFileIsRefusedBeforeParsing) {
  const std::string text = "[" + std::string(98, ' ') + "]";  // 100 bytes of valid JSON
  const auto path = write("big.json", text);
  expect_input_error([&] { load_json_file(path, 99); },
                     {path.string(), "100 bytes", "limit of 99"});
  EXPECT_NO_THROW(load_json_file(path, 100)) << "exactly at the limit is fine";
  EXPECT_TRUE(load_json_file(path, 100).is_array());
}

TEST(JsonFields, RequireNumber) {
  const json rotor = json::parse(R"({"k_f": 2.5, "count": 4, "name": "x", "n": null})");
  EXPECT_DOUBLE_EQ(require_number(rotor, "k_f", "vehicle.json: /rotor"), 2.5);
  EXPECT_DOUBLE_EQ(require_number(rotor, "count", "vehicle.json: /rotor"), 4.0);
  expect_input_error([&] { require_number(rotor, "name", "vehicle.json: /rotor"); },
                     {"vehicle.json: /rotor/name: expected a number, got string"});
  expect_input_error([&] { require_number(rotor, "n", "vehicle.json: /rotor"); },
                     {"vehicle.json: /rotor/n: expected a number, got null"});
  expect_input_error([&] { require_number(rotor, "k_m", "vehicle.json: /rotor"); },
                     {"vehicle.json: /rotor/k_m: missing"});
  const json not_finite = {{"x", std::numeric_limits<double>::infinity()}};
  expect_input_error([&] { require_number(not_finite, "x", "a.json: "); },
                     {"a.json: /x: not a finite number"});
}

TEST(JsonFields, NotAnObjectIsReported) {
  const json array = json::parse("[1, 2]");
  expect_input_error([&] { require_number(array, "k", "s.json: /wind"); },
                     {"s.json: /wind: expected an object, got array"});
  expect_input_error([&] { require_string(json(3), "k", "s.json: /x"); },
                     {"s.json: /x: expected an object, got number"});
}

TEST(JsonFields, NumberOr) {
  const json o = json::parse(R"({"a": 1.25, "s": "text"})");
  EXPECT_DOUBLE_EQ(number_or(o, "a", 9.0, "f.json: "), 1.25);
  EXPECT_DOUBLE_EQ(number_or(o, "missing", 9.0, "f.json: "), 9.0);
  // Present but of the wrong type is an error, not the fallback.
  expect_input_error([&] { number_or(o, "s", 9.0, "f.json: /o"); },
                     {"f.json: /o/s: expected a number, got string"});
}

TEST(JsonFields, RequireStringObjectArray) {
  const json j = json::parse(R"({"name": "uav-1", "rotor": {"k": 1}, "list": [1, 2], "n": 5})");
  EXPECT_EQ(require_string(j, "name", "r.json: "), "uav-1");
  EXPECT_EQ(require_object(j, "rotor", "r.json: ").at("k"), 1);
  EXPECT_EQ(require_array(j, "list", "r.json: ").size(), 2u);
  // Returned by reference into the document, not a copy.
  EXPECT_EQ(&require_object(j, "rotor", "r.json: "), &j.at("rotor"));

  expect_input_error([&] { require_string(j, "n", "r.json: /top"); },
                     {"r.json: /top/n: expected a string, got number"});
  expect_input_error([&] { require_object(j, "list", "r.json: /top"); },
                     {"r.json: /top/list: expected an object, got array"});
  expect_input_error([&] { require_array(j, "rotor", "r.json: /top"); },
                     {"r.json: /top/rotor: expected an array, got object"});
  expect_input_error([&] { require_array(j, "absent", "r.json: /top"); },
                     {"r.json: /top/absent: missing"});
}

TEST_F(JsonFileTest, FileAndFieldErrorsTogether) {
  // The pattern every loader follows: the file name goes into `where`.
  const auto path = write("vehicle.json", R"({"rotor": {"k_f": "fast"}})");
  const json doc = load_json_file(path);
  const std::string where = path.filename().string() + ": /rotor";
  expect_input_error(
      [&] { require_number(require_object(doc, "rotor", "vehicle.json: "), "k_f", where); },
      {"vehicle.json: /rotor/k_f: expected a number, got string"});
}

}  // namespace
}  // namespace a3::common
