#pragma once
// The regression guard (issue 12 item 5): a short benchmark subset whose error metrics (never a
// time) must stay within a committed threshold file, bench/guard_thresholds.json. Each entry
// names what to run (a scene with a solver and a step count, a conformance case, or an fc3d
// problem of the --corpus folder), one metric, the value measured when the file was written and
// a margin: the guard fails when the metric exceeds max(measured * margin, floor).
#include <string>

namespace coulomb::cli {

/// Runs every entry of `thresholdFile`, prints one line each (value, limit, verdict) and throws
/// CommandError listing the entries that got worse. fc3d problems are read from `corpus`.
/// `update` rewrites the file's "measured" values with this run's (margins and floors kept).
void runBenchGuard(const std::string& thresholdFile, const std::string& corpus, bool update);

}  // namespace coulomb::cli
