#include "app/compare_command.h"

#include <cstdio>

#include "compare/image_compare.h"
#include "output/exr_io.h"
#include "output/pfm_io.h"
#include "util/error.h"

namespace mixtrace {

int runCompare(const CompareOptions& options) {
  if (options.errorOnly) {
    std::printf("relMSE %.6g\n", relativeMseOfExrFiles(options.a, options.b));
    if (!options.errorMap.empty()) {
      const Image a = readExr(options.a), b = readExr(options.b);
      const std::vector<double> errors = relativeSquaredErrors(a, b);
      writePfmGray(options.errorMap, a.width, a.height, std::vector<float>(errors.begin(), errors.end()));
    }
    return kCompareExitAgree;
  }
  if (!options.errorMap.empty()) throw Error("--error-map needs --error-only");
  const ComparisonResult result = compareExrFiles(options.a, options.b, options.alpha, options.maxFailFraction);
  if (!options.reportJson.empty()) writeComparisonJson(options.reportJson, result, options.a, options.b);
  if (!options.quiet) {
    std::printf("%s\n", result.summary().c_str());
    std::fflush(stdout);
  }
  if (!result.agree) return kCompareExitDiffer;
  return result.inconclusive ? kCompareExitInconclusive : kCompareExitAgree;
}

}  // namespace mixtrace
