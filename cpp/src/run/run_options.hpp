// The options of a dynamic run: the times a run can resolve, and the check
// of every option against the model and the method.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "lagmb/errors.hpp"
#include "lagmb/integrators/methods.hpp"
#include "lagmb/model/model.hpp"
#include "lagmb/options.hpp"

namespace lagmb {

/// Times closer than kTimeResolution max(|t|, 1 s) are one time to a run
/// (about 45 units in the last place of t): an end time, an advance or an
/// output interval shorter than that is refused.
constexpr double kTimeResolution = 1e-14;
inline double shortest_span(double t0, double t1) {
  return kTimeResolution * std::max({std::abs(t0), std::abs(t1), 1.0});
}

/// The latest time a run reaches, |t| <= 1e9 s (about 32 years): near t the
/// integrators' smallest step is about 100 eps |t| (2e-5 s here; IDA's
/// bound), so much later a mechanism's motion cannot be resolved.
constexpr double kLatestTime = 1e9;
/// ModelError "who: what = t ..." unless |t| <= kLatestTime.
inline void check_time(double t, const std::string& who, const char* what) {
  if (!(std::abs(t) <= kLatestTime))
    throw ModelError(who + ": " + what + " = " + to_text(t) + " is beyond the times a run can resolve, |t| <= " +
                     to_text(kLatestTime) + " s (the integrators' smallest step there is 100 eps |t|)");
}

/// The options every dynamic run takes (tolerances, method, bounds, start);
/// ModelError beginning with "who: " for one that is wrong. Returns the
/// method (formulation "auto": choose_method's).
const Method& validate_run_options(const Model& model, const SimulationOptions& o, const std::string& who);

}  // namespace lagmb
