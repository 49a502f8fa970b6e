// layerjkr: measured force curves - the data a fit consumes - and their CSV reader.
//
// A curve is a sequence of samples (delta_i [m], P_i [N]) in acquisition order, with
// optional times t_i [s], contact radii a_i [m] (JKR rigs measure them), weights and a segment
// label (0 = approach/loading, 1 = retract/unloading, 2 = dwell: a pause, the indenter at rest,
// which the elastic fits leave out and a relaxation law fits). delta is the approach of the indenter
// in any fixed frame: the fit's contact-point offset delta0 maps it to the model's
// approach, delta_model = delta - delta0. P is positive when repulsive.
//
// CSV forms (header row; columns in any order; extra columns are an error; each form also
// takes a time column t [s], strictly increasing - aliases time, t_s):
//   delta,P[,a][,weight][,segment]        the model's own variables
//   tip_position,force[,weight][,segment] JPK / nanite export: delta = -tip_position
//                                         (the tip moves to more negative values on approach)
//   z,deflection[,weight][,segment]       raw AFM: delta = z_sign*z - deflection_sign*d,
//                                         P = k * deflection_sign*d  (needs spring_constant)
//   z,force[,weight][,segment]            piezo and force (AFM Workshop, lab scripts):
//                                         delta = z_sign*z - P/k, P = force (needs spring_constant)
//   P,a[,weight][,segment]                a JKR rig's load and contact radius, no displacement
//                                         (delta stays empty: a fit of P against a)
//   curve,segment[,t],force,height,tip_position  `layerjkr export` of an instrument file: height is
//                                         informational; a file of several curves needs
//                                         CsvOptions::curve
// Aliases: P <-> force; a unit suffix _m / _N (delta_m, force_N, tip_position_m, ...) is
// accepted and means SI, so it cannot be combined with non-SI CsvOptions units.
// A leading UTF-8 byte-order mark is ignored (as in scene files). Limits: max_bytes, max_rows.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "layerjkr/types.hpp"

namespace layerjkr {

/// A measured force curve in SI units.
struct CurveData {
  /// approach [m], arbitrary offset; empty for (P, a) data - a rig's load against its measured
  /// contact radius, fitted as P(a) without a displacement (then `a` is required)
  std::vector<double> delta;
  std::vector<double> P;       ///< force [N], positive = repulsive
  std::vector<double> a;       ///< contact radius [m] (empty = not measured)
  std::vector<double> weight;  ///< relative weights > 0 (empty = all 1); a fit divides them by the largest, so only their ratios matter
  /// 0 approach, 1 retract, 2 dwell (empty = split at the largest delta). No approach sample
  /// follows a retract one; dwells may come anywhere (before the approach, between, after).
  std::vector<int> segment;
  /// Time of each sample [s], strictly increasing (empty = unknown): what a relaxation law or
  /// rate-dependent adhesion is fitted against (CSV column t, or read from the instrument file).
  std::vector<double> t;
  std::string source = "curve";  ///< names the curve in error messages
  /// Stiffness [N/m] of the cantilever that measured it, when known (instrument files); 0 if not.
  double spring_constant = 0.0;
  /// What the reader decided that a fit should report (FitSummary::notices), e.g. which of two
  /// different copies of a header key it used.
  std::vector<std::string> notes;

  std::size_t size() const { return P.size(); }
  /// True for (P, a) data: no displacement, the contact radius measured at every sample.
  bool radius_only() const { return delta.empty() && !a.empty(); }

  /// Throws InputError naming the source, the column and the row unless all columns
  /// have equal length, values are finite, a >= 0, weight > 0, segment in {0, 1, 2} with no
  /// approach after a retract, and t strictly increasing.
  void validate() const;

  /// Indices of the samples on `branch`, in acquisition order; dwell samples are on no branch
  /// (Branch::all is approach and retract). Without a segment column the curve is split at its
  /// largest delta (approach up to and including it); (P, a) data without one are all loading.
  std::vector<std::size_t> select(Branch branch) const;

  /// Per sample: true on the retract branch (the rule select() uses). One pass.
  std::vector<bool> retract_mask() const;
  /// How many samples are dwell (segment 2).
  std::size_t dwell_count() const;
  /// The curve without its dwell samples (the elastic fits' data); itself if it has none.
  CurveData without_dwell() const;
};

/// Units and the raw-AFM conversion for CSV input.
struct CsvOptions {
  double length_unit = 1.0;  ///< metres per length unit in the file (1e-9 for nm), > 0
  double force_unit = 1.0;   ///< newtons per force unit in the file (1e-9 for nN), > 0
  double spring_constant = 0.0;  ///< cantilever stiffness [N/m]; required for z,deflection
  /// Instrument files: the deflection sensitivity [m/V] replacing the file's (0: the file's;
  /// needed where the file gives none - to_curve_data). Vendor text exports: AFM Workshop's
  /// T-B(V) columns [m/V] and NT-MDT's deflection signal [m/A] use it. Plain CSV does not.
  double sensitivity = 0.0;
  double z_sign = 1.0;           ///< +1: z grows towards the sample; -1: it decreases
  double deflection_sign = 1.0;  ///< +1: deflection > 0 when pushed away by the sample
  int curve = -1;  ///< with a curve column: read only this curve (-1: the file must hold one)
  /// Largest file read_curve_csv reads [bytes] (default 512 MiB), > 0: a bound on memory.
  std::size_t max_bytes = std::size_t{512} << 20;
  /// Most data rows parse_curve_csv accepts (default 10^7, about 1 GB of peak memory in a fit), > 0.
  std::size_t max_rows = 10'000'000;
  /// Throws DomainError naming the first invalid field.
  void validate() const;
};

/// Parses a length/force unit pair "m,N" | "nm,nN" | "um,uN" | "nm,pN" ... into the
/// options' multipliers; throws InputError for an unknown unit.
void parse_units(const std::string& text, CsvOptions& options);

/// True if `text` (a file's first 4 KiB) begins a vendor's text export that parse_curve_csv
/// reads by its content - AFM Workshop's force-distance CSV, afmformats' tab export, NT-MDT
/// Nova's and Optics11 Chiaro's text exports - rather than a plain CSV of named columns.
bool is_vendor_curve_text(std::string_view text);

/// Parses CSV text (see the forms above). `source` names the data in errors. Throws
/// InputError for a bad header, a non-numeric or non-finite cell (naming row and
/// column), a row with the wrong number of cells, no data rows, or more than max_rows rows.
CurveData parse_curve_csv(const std::string& text, const std::string& source,
                          const CsvOptions& options = {});

/// Reads and parses a CSV file; a file over max_bytes, a directory or a device is an
/// InputError naming the path and the limit.
CurveData read_curve_csv(const std::string& path, const CsvOptions& options = {});

}  // namespace layerjkr
