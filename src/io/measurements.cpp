// SPDX-License-Identifier: MIT
#include "frictopt/io/measurements.hpp"

#include <fmt/format.h>

#include <charconv>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

#include "atomic_file.hpp"
#include "input_file.hpp"
#include "text_input.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::io {
namespace {

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string_view> split(std::string_view s, char separator) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const auto pos = s.find(separator, start);
    out.push_back(trim(s.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start)));
    if (pos == std::string_view::npos) break;
    start = pos + 1;
  }
  return out;
}

// A whole field as a double (no trailing characters), or nullopt.
std::optional<double> to_double(std::string_view text) {
  if (text.empty()) return std::nullopt;
  if (text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<int> to_int(std::string_view text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

constexpr std::string_view kHeader = "quantity,location,value,sigma";

}  // namespace

void parse_location(study::Measurement& m, std::string_view location, const std::string& where) {
  if (study::is_total(m.quantity)) {
    if (!location.empty() && location != "all")
      throw InvalidInput(fmt::format("{}: location = \"{}\"; expected \"all\" or empty for the sum {}", where,
                                     detail::printable_excerpt(location, 40), study::to_string(m.quantity)));
  } else if (location.starts_with("x=")) {
    const std::vector<std::string_view> coords = split(location.substr(2), ';');
    Eigen::VectorXd x(static_cast<Eigen::Index>(coords.size()));
    for (std::size_t k = 0; k < coords.size(); ++k) {
      const auto v = to_double(coords[k]);
      if (!v || !std::isfinite(*v))
        throw InvalidInput(fmt::format("{}: location = \"{}\": coordinate {} = \"{}\"; expected a number [m]", where,
                                       detail::printable_excerpt(location, 40), k + 1, detail::printable_excerpt(coords[k], 40)));
      x(static_cast<Eigen::Index>(k)) = *v;
    }
    if (x.size() < 1 || x.size() > 2)
      throw InvalidInput(fmt::format("{}: location = \"{}\"; expected x=x1 (2D) or x=x1;x2 (3D)", where, detail::printable_excerpt(location, 40)));
    m.point = x;
  } else {
    const auto node = to_int(location);
    if (!node || *node < 0)
      throw InvalidInput(fmt::format("{}: location = \"{}\"; expected a contact-node index >= 0 or a point "
                                     "x=x1;x2 on the contact surface",
                                     where, detail::printable_excerpt(location, 40)));
    m.node = *node;
  }
}

std::vector<study::Measurement> read_measurements(const std::filesystem::path& path) {
  // A regular file only (a FIFO is refused without waiting), of at most 256 MiB (millions of
  // rows; more would not fit the identification's dense Jacobian anyway).
  const std::string content = detail::read_input_file(path, "the measurement file", std::size_t{256} << 20);
  std::istringstream in(content);
  std::vector<study::Measurement> out;
  std::string line;
  int number = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string_view text = trim(number == 1 ? detail::without_bom(line) : std::string_view(line));
    if (text.empty() || text.front() == '#') continue;
    const std::string where = fmt::format("{}:{}", path.string(), number);
    const std::vector<std::string_view> fields = split(text, ',');
    if (!header_seen) {
      std::string joined;
      for (std::string_view f : fields) joined += (joined.empty() ? "" : ",") + std::string(f);
      // The line is echoed only as a bounded, printable excerpt: the file may be anything.
      if (joined != kHeader)
        throw InvalidInput(fmt::format("{}: header \"{}\"; expected \"{}\"", where,
                                       detail::printable_excerpt(joined, 60), kHeader));
      header_seen = true;
      continue;
    }
    if (fields.size() != 4)
      throw InvalidInput(fmt::format("{}: {} fields; expected 4 ({})", where, fields.size(), kHeader));
    study::Measurement m;
    m.label = where;
    try {
      m.quantity = study::parse_measured_quantity(fields[0]);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: {}", where, e.what()));
    }
    parse_location(m, fields[1], where);
    const auto value = to_double(fields[2]);
    if (!value || !std::isfinite(*value))
      throw InvalidInput(fmt::format("{}: value = \"{}\"; expected a finite number", where, detail::printable_excerpt(fields[2], 40)));
    m.value = *value;
    const auto sigma = to_double(fields[3]);
    if (!sigma || !(*sigma > 0) || !std::isfinite(*sigma))
      throw InvalidInput(fmt::format("{}: sigma = \"{}\"; expected a standard deviation > 0", where, detail::printable_excerpt(fields[3], 40)));
    m.sigma = *sigma;
    out.push_back(std::move(m));
    if (out.size() > study::kMaxMeasurements)
      throw InvalidInput(fmt::format("{}: measurement {}; expected at most {} measurements in the file "
                                     "(docs/case-format.md, \"Size limits\")",
                                     where, out.size(), study::kMaxMeasurements));
  }
  if (!header_seen) throw InvalidInput(fmt::format("{}: empty measurement file; expected the header \"{}\"", path.string(), kHeader));
  if (out.empty()) throw InvalidInput(fmt::format("{}: no measurements after the header", path.string()));
  return out;
}

study::IdentificationExperiment experiment_loads(const IdentificationExperimentSetup& setup) {
  study::IdentificationExperiment e;
  e.name = setup.name;
  e.load_scale = setup.load_scale;
  e.dirichlet_scale = setup.dirichlet_scale;
  e.force_scale = setup.force_scale;
  e.orientation = setup.orientation;
  return e;
}

std::vector<study::IdentificationExperiment> identification_experiments(const IdentificationSetup& setup,
                                                                      std::string_view origin) {
  std::vector<study::IdentificationExperiment> out;
  for (const IdentificationExperimentSetup& x : setup.experiments) {
    if (!x.has_measurements())
      throw InvalidInput(fmt::format(
          "{}: [identification] gives no measurements; expected measurements = \"file.csv\" (a CSV, "
          "docs/identification.md) or [[identification.measurement]] tables in the case, or, from Python, "
          "identify(case, measurements=[...]) or experiments=[...]",
          origin));
    study::IdentificationExperiment e = experiment_loads(x);
    if (x.measurements) e.measurements = read_measurements(*x.measurements);
    e.measurements.insert(e.measurements.end(), x.inline_measurements.begin(), x.inline_measurements.end());
    out.push_back(std::move(e));
  }
  return out;
}

void write_measurements(const std::filesystem::path& path, const std::vector<study::Measurement>& measurements,
                        const std::string& comment) {
  std::ostringstream text;
  if (!comment.empty()) text << "# " << comment << '\n';
  text << kHeader << '\n';
  for (const study::Measurement& m : measurements) {
    std::string location;
    if (study::is_total(m.quantity)) location = "all";
    else if (m.point) {
      location = "x=";
      for (Eigen::Index k = 0; k < m.point->size(); ++k) location += fmt::format("{}{}", k ? ";" : "", (*m.point)(k));
    } else location = std::to_string(m.node);
    text << fmt::format("{},{},{},{}\n", study::to_string(m.quantity), location, m.value, m.sigma);
  }
  detail::write_file_atomically(path, text.str());
}

}  // namespace frictopt::io
