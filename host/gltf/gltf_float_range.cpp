// Finite doubles from the file that float cannot hold. JSON numbers are doubles, the renderer
// computes in float: 1e39 would turn into infinity after the conversion and then into black or
// NaN pixels with exit 0, so such a value is refused with the property's name instead.
#include <cfloat>
#include <cmath>
#include <sstream>

#include "gltf/gltf_internal.h"

namespace mixtrace {
namespace gltf {

bool fitsInFloat(double value) { return std::fabs(value) <= double(FLT_MAX); }

float checkedFloat(const LoadContext& ctx, double value, const std::string& property) {
  if (std::isfinite(value) && !fitsInFloat(value)) {
    std::ostringstream text;
    text << property << " " << value << " does not fit in a float (at most " << FLT_MAX << ")";
    ctx.fail(text.str());
  }
  return float(value);
}

void checkFitsInFloat(const LoadContext& ctx, const std::vector<double>& values, const std::string& property) {
  for (size_t i = 0; i < values.size(); ++i) checkedFloat(ctx, values[i], property + "[" + std::to_string(i) + "]");
}

}  // namespace gltf
}  // namespace mixtrace
