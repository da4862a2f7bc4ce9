#include "app/compare_command.h"

#include <cstdio>

#include "compare/image_compare.h"
#include "output/exr_io.h"
#include "output/output_paths.h"
#include "output/pfm_io.h"
#include "util/error.h"

namespace mixtrace {
namespace {

// Before reading the images: the outputs must be writable and overwrite neither image.
void checkCompareOutputs(const CompareOptions& o) {
  std::vector<NamedFile> outputs;
  if (!o.reportJson.empty()) outputs.push_back({"--json", o.reportJson});
  if (!o.errorMap.empty()) outputs.push_back({"--error-map", o.errorMap});
  checkNoSharedFiles(outputs, {{"image A", o.a}, {"image B", o.b}});
  for (const NamedFile& output : outputs) checkWritableOutput(output);
}

}  // namespace

int runCompare(const CompareOptions& options) {
  checkCompareOutputs(options);
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
