// layerjkr CLI: the report schema - how the library's answers (answer.hpp) are printed.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/answer.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/provenance.hpp"

namespace layerjkr::cli {

/// The radii of an --at list, "a1,a2,...": each finite and > 0, at least one; throws
/// InputError naming the item.
std::vector<double> parse_radii(const std::string& text);

/// The keys every summary prints (summary, discrete --summary): model, profile, w, pull-off,
/// zero load, fixed grips.
nlohmann::ordered_json contact_json(const ContactSummary& s, const std::string& profile);

/// `layerjkr summary`: contact_json plus model_error_estimate, K, G (T), E_star,
/// adhesion_check (lambda, sigma0, sigma0_assumed, pull_off_error, basis; null for w = 0),
/// model_choice and warnings.
nlohmann::ordered_json summary_json(const SummaryAnswer& a);

/// `layerjkr fit --out`: the fit report's JSON keys (docs/fitting.md).
nlohmann::ordered_json report_json(const FitSummary& s, Branch branch);

/// The "provenance" of a fit report and the body of fit-map's sidecar (docs/provenance.md): the
/// library's record (provenance.hpp) with the command line that made the result.
nlohmann::ordered_json provenance_record(const Scene& scene, const FitOptions& options, const CsvOptions& csv,
                                         const std::vector<InputRecord>& inputs,
                                         const std::vector<std::string>& command_line);

/// `layerjkr curve`: CSV a,P,delta,P_H,delta_H,S,error_est with 17 significant digits.
std::string curve_csv(const CurveAnswer& c);

}  // namespace layerjkr::cli
