#include "app/compare_command.h"

#include <cstdio>

#include "compare/image_compare.h"

namespace mixtrace {

int runCompare(const CompareOptions& options) {
  if (options.errorOnly) {
    std::printf("relMSE %.6g\n", relativeMseOfExrFiles(options.a, options.b));
    return kCompareExitAgree;
  }
  const ComparisonResult result = compareExrFiles(options.a, options.b, options.alpha, options.maxFailFraction);
  if (!options.reportJson.empty()) writeComparisonJson(options.reportJson, result, options.a, options.b);
  if (!options.quiet) {
    std::printf("%s\n", result.summary().c_str());
    std::fflush(stdout);
  }
  return result.agree ? kCompareExitAgree : kCompareExitDiffer;
}

}  // namespace mixtrace
