#pragma once
#include "session/options.h"

namespace mixtrace {

// `mixtrace compare A.exr B.exr`: loads both renders with their variances, runs compareImages,
// prints the one-line summary to stdout (unless quiet) and writes the JSON report when asked.
// Returns kCompareExitAgree or kCompareExitDiffer; throws mixtrace::Error for input errors
// (main turns those into kCompareExitError for this command).
int runCompare(const CompareOptions& options);

}  // namespace mixtrace
