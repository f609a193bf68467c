// SPDX-License-Identifier: MIT
// JSON values: building, writing, reading back; key order; NaN as null; type errors.
#include "frictopt/io/json.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "frictopt/core/error.hpp"
#include "frictopt/io/file_error.hpp"

namespace frictopt::io {
namespace {

JsonValue sample_summary() {
  JsonValue s;
  s["status"] = "converged";
  s["iterations"] = 12;
  s["kkt_residual"] = 1.0 / 3.0;
  s["not_computed"] = std::nan("");
  const Eigen::VectorXd alpha = Eigen::VectorXd::LinSpaced(3, 0.0, 0.1);
  s["alpha"] = alpha;
  s["flags"] = JsonValue::Array{true, nullptr, "x"};
  s["nested"]["given"] = "automatic";
  return s;
}

TEST(JsonValue, WritesMembersInInsertionOrderWithExactReals) {
  const std::string text = to_json_string(sample_summary(), -1);
  EXPECT_EQ(text,
            "{\"status\":\"converged\",\"iterations\":12,\"kkt_residual\":0.3333333333333333,"
            "\"not_computed\":null,\"alpha\":[0.0,0.05,0.1],\"flags\":[true,null,\"x\"],"
            "\"nested\":{\"given\":\"automatic\"}}");
}

TEST(JsonValue, RoundTripsThroughTextExceptNanWhichBecomesNull) {
  const JsonValue original = sample_summary();
  const JsonValue back = parse_json(to_json_string(original));
  EXPECT_TRUE(back.at("not_computed").is_null());
  EXPECT_EQ(back.at("kkt_residual").as_number(), 1.0 / 3.0) << "reals must read back exactly";
  EXPECT_EQ(back.at("iterations").as_integer(), 12);
  EXPECT_EQ(back.at("nested").at("given").as_string(), "automatic");
  JsonValue expected = original;
  expected["not_computed"] = nullptr;
  EXPECT_EQ(back, expected);
}

TEST(JsonValue, WrongTypeAccessAndBadTextAreInvalidInput) {
  JsonValue v = 3;
  EXPECT_THROW((void)v.as_string(), InvalidInput);
  EXPECT_THROW(v["key"], InvalidInput);
  EXPECT_THROW(v.push_back(1), InvalidInput);
  EXPECT_THROW((void)sample_summary().at("missing"), InvalidInput);
  EXPECT_THROW((void)parse_json("{\"a\": }"), InvalidInput);
  EXPECT_THROW((void)to_json_string(JsonValue("\xff\xfe")), InvalidInput);
}

TEST(WriteJson, WritesAFileEndingInANewline) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("frictopt_json_" + std::to_string(::getpid()) + ".json");
  write_json(file, sample_summary());
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str().back(), '\n');
  EXPECT_EQ(parse_json(text.str()).at("status").as_string(), "converged");
  std::filesystem::remove(file);
  // A missing directory is the file system's refusal (exit 5), not bad input.
  EXPECT_THROW(write_json("/nonexistent/dir/x.json", JsonValue()), FileSystemError);
}

}  // namespace
}  // namespace frictopt::io
