// SPDX-License-Identifier: MIT
#include "frictopt/io/design_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/io/json.hpp"
#include "input_file.hpp"

namespace frictopt::io {

Eigen::VectorXd read_design_file(const std::filesystem::path& path, Eigen::Index expected_size) {
  // A design is a few hundred numbers; 64 MiB is far beyond any and bounds what is read.
  const std::string text = detail::read_input_file(path, "the design file", std::size_t{64} << 20);
  std::vector<double> values;
  if (path.extension() == ".json") {
    JsonValue json;
    try {
      json = parse_json(text);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: the design file is not valid JSON ({})", path.string(), e.what()));
    }
    if (!json.is_object() || !json.contains("alpha") || !json.at("alpha").is_array())
      throw InvalidInput(fmt::format("{}: expected a JSON object with an \"alpha\" array", path.string()));
    const JsonValue::Array& alpha = json.at("alpha").as_array();
    for (std::size_t i = 0; i < alpha.size(); ++i) {
      if (!alpha[i].is_integer() && !alpha[i].is_real())
        throw InvalidInput(fmt::format("{}: alpha[{}] is not a number; expected control heights in metres",
                                       path.string(), i));
      values.push_back(alpha[i].as_number());
    }
  } else {
    std::istringstream lines(text);
    std::string line;
    int line_number = 0;
    while (std::getline(lines, line)) {
      ++line_number;
      if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
      for (char& ch : line)
        if (ch == ',' || ch == ';' || ch == '\t') ch = ' ';
      std::istringstream words(line);
      std::string word;
      while (words >> word) {
        try {
          std::size_t used = 0;
          values.push_back(std::stod(word, &used));
          if (used != word.size()) throw std::invalid_argument(word);
        } catch (const std::exception&) {
          throw InvalidInput(fmt::format("{}:{}: '{}' is not a number; expected control heights in metres",
                                         path.string(), line_number, detail::printable_excerpt(word, 40)));
        }
      }
    }
  }
  if (static_cast<Eigen::Index>(values.size()) != expected_size)
    throw InvalidInput(fmt::format("{}: has {} control heights; expected {} (the case's control net)", path.string(),
                                   values.size(), expected_size));
  return Eigen::Map<const Eigen::VectorXd>(values.data(), expected_size);
}

}  // namespace frictopt::io
