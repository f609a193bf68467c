// SPDX-License-Identifier: MIT
// The full examples of docs/case-format.md parse, so the documentation cannot drift from the
// parser.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "frictopt/io/case_file.hpp"

namespace frictopt::io {
namespace {

// The ```toml blocks of a Markdown file, in order.
std::vector<std::string> toml_blocks(const std::string& markdown) {
  std::vector<std::string> blocks;
  std::istringstream lines(markdown);
  std::string line, block;
  bool inside = false;
  while (std::getline(lines, line)) {
    if (!inside && line == "```toml") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      blocks.push_back(block);
    } else if (inside) {
      block += line + "\n";
    }
  }
  return blocks;
}

TEST(CaseFormatDoc, FullExamplesParseToTheirStatedDimension) {
  std::ifstream in(std::string(FRICTOPT_SOURCE_DIR) + "/docs/case-format.md");
  ASSERT_TRUE(in) << "docs/case-format.md not found";
  std::ostringstream text;
  text << in.rdbuf();
  const std::vector<std::string> blocks = toml_blocks(text.str());
  ASSERT_EQ(blocks.size(), 2u) << "expected the full 2D and 3D examples";

  const CaseDescription c2 = parse_case(blocks[0], "case-format.md (2D example)");
  EXPECT_EQ(c2.dim(), 2);
  EXPECT_EQ(c2.body.shape.num_controls(), 15);
  EXPECT_EQ(c2.output.name, "thesis_2d");

  const CaseDescription c3 = parse_case(blocks[1], "case-format.md (3D example)");
  EXPECT_EQ(c3.dim(), 3);
  EXPECT_EQ(c3.body.shape.num_controls(), 12);
  // The documented initial design is feasible for the documented volume: the mean control
  // height equals height − volume/(a·b) (docs/theory/problem.md §6, the 3D set), up to summation
  // round-off.
  const double mean = c3.body.initial_design.mean();
  EXPECT_NEAR(mean, 1.0 - *c3.body.admissible.volume / 2.0, 1e-15);
  ASSERT_TRUE(c3.body.contact.has_value());
  EXPECT_EQ(c3.body.contact->law.vertices().size(), 8u);
  ASSERT_EQ(c3.body.dirichlet.size(), 2u);
  EXPECT_EQ(c3.body.dirichlet[1].components, (std::vector<int>{1}));
}

}  // namespace
}  // namespace frictopt::io
