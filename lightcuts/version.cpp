#include "lightcuts/version.h"

#include "lightcuts_version.h"  // configured into the build folder (cmake/version.h.in)

namespace lc {

const char* const kVersion = LC_PROJECT_VERSION;

}  // namespace lc
