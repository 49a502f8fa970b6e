// Stage A of the two-model approach (discrete.hpp): flat-punch load steps to S_k.
#include <algorithm>
#include <cmath>
#include <map>

#include "core/line_fit.hpp"
#include "io/csv_rows.hpp"
#include "io/read_file.hpp"
#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {

FlatPunchData parse_flat_punch_csv(const std::string& text, const std::string& source) {
  auto fail = [&](const std::string& what) { throw InputError(source + ": " + what); };
  detail::CsvRows rows(text);
  std::vector<std::string_view> cells;
  if (!rows.next(cells)) fail("is empty (expected the header a,delta,P)");
  std::map<std::string, std::size_t> column;
  for (std::size_t c = 0; c < cells.size(); ++c) column[std::string(cells[c])] = c;
  if (cells.size() != 3 || !column.count("a") || !column.count("delta") || !column.count("P"))
    fail("the header must name exactly the columns a, delta and P (SI units)");
  FlatPunchData d;
  d.source = source;
  double v[3];
  while (rows.next(cells)) {
    if (cells.size() != 3) fail("line " + std::to_string(rows.line()) + " has " + std::to_string(cells.size()) + " cells, not 3");
    for (std::size_t c = 0; c < 3; ++c)
      if (!detail::parse_finite(cells[c], v[c]))
        fail("line " + std::to_string(rows.line()) + ": '" + std::string(cells[c]) + "' is not a finite number");
    const double a = v[column["a"]];
    if (!(a > 0.0)) fail("line " + std::to_string(rows.line()) + ": radius a = " + format_double(a) + " must be > 0");
    d.a.push_back(a);
    d.delta.push_back(v[column["delta"]]);
    d.P.push_back(v[column["P"]]);
  }
  if (d.a.empty()) fail("has a header but no data rows");
  return d;
}

FlatPunchData read_flat_punch_csv(const std::string& path) {
  return parse_flat_punch_csv(detail::read_file(path, "the flat-punch data"), path);
}

FlatPunchStiffness fit_flat_punch(const FlatPunchData& data, double linearity_tolerance) {
  if (!(linearity_tolerance > 0.0) || !std::isfinite(linearity_tolerance))
    throw DomainError("fit_flat_punch", "linearity_tolerance", linearity_tolerance, "finite and > 0");
  auto fail = [&](const std::string& what) { throw InputError(data.source + ": " + what); };
  if (data.delta.size() != data.a.size() || data.P.size() != data.a.size()) fail("columns of different lengths");
  std::map<double, std::vector<std::size_t>> steps;  // radius -> its samples
  for (std::size_t i = 0; i < data.a.size(); ++i) steps[data.a[i]].push_back(i);
  if (steps.size() < 4)
    fail(std::to_string(steps.size()) + " radii; the stiffness S(a) needs load steps at 4 or more radii");
  FlatPunchStiffness out;
  for (const auto& [a, idx] : steps) {
    const std::string at = "radius a = " + format_double(a) + " m";
    if (idx.size() < 2) fail(at + " has one load step; a slope needs two or more");
    const detail::LineFit line = detail::fit_line(data.delta, data.P, idx);
    if (!(line.sxx > 0.0)) fail(at + ": every load step has the same delta");
    const double S = line.slope;
    if (!(S > 0.0)) fail(at + ": the force does not grow with delta (slope " + format_double(S) + " N/m)");
    const auto [lo, hi] = std::minmax_element(idx.begin(), idx.end(), [&](auto i, auto j) { return data.delta[i] < data.delta[j]; });
    const double span = data.delta[*hi] - data.delta[*lo];
    const double nonlinearity = std::sqrt(line.rss / static_cast<double>(idx.size())) / (S * span);
    if (nonlinearity > linearity_tolerance)
      fail(at + ": P(delta) is not linear (rms deviation " + format_double(nonlinearity) +
           " of the force range, tolerance " + format_double(linearity_tolerance) +
           "): the flat-punch stiffness is not defined there (Condition 2 of the paper)");
    out.a.push_back(a);
    out.S.push_back(S);
    out.S_stderr.push_back(line.slope_stderr);
    out.nonlinearity.push_back(nonlinearity);
  }
  for (std::size_t k = 1; k < out.S.size(); ++k)
    if (!(out.S[k] > out.S[k - 1]))
      fail("the stiffness does not grow with the radius: S = " + format_double(out.S[k]) + " N/m at a = " +
           format_double(out.a[k]) + " m after " + format_double(out.S[k - 1]) + " N/m at a = " +
           format_double(out.a[k - 1]) + " m");
  return out;
}

}  // namespace layerjkr
