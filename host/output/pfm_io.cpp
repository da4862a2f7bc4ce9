#include "output/pfm_io.h"

#include <sstream>

#include "output/atomic_file.h"
#include "util/error.h"

namespace mixtrace {

void writePfmGray(const std::string& path, int width, int height, const std::vector<float>& values) {
  if (values.size() != size_t(width) * size_t(height)) throw Error("internal: PFM size mismatch");
  std::ostringstream out;
  // A negative scale marks little-endian data (every machine this runs on).
  out << "Pf\n" << width << " " << height << "\n-1.0\n";
  for (int y = height - 1; y >= 0; --y)
    out.write(reinterpret_cast<const char*>(values.data() + size_t(y) * width), std::streamsize(sizeof(float)) * width);
  writeFileAtomically(path, out.str());
}

}  // namespace mixtrace
