// SPDX-License-Identifier: MIT
#include "frictopt/io/design_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/io/json.hpp"

namespace frictopt::io {

Eigen::VectorXd read_design_file(const std::filesystem::path& path, Eigen::Index expected_size) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(fmt::format("{}: cannot read the design file", path.string()));
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::vector<double> values;
  if (path.extension() == ".json") {
    const JsonValue json = parse_json(text);
    if (!json.is_object() || !json.contains("alpha"))
      throw InvalidInput(fmt::format("{}: expected a JSON object with an \"alpha\" array", path.string()));
    for (const JsonValue& v : json.at("alpha").as_array()) values.push_back(v.as_number());
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
                                         path.string(), line_number, word));
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
