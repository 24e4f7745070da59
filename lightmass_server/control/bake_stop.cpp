#include "lightmass_server/control/bake_stop.h"

namespace lc::bake {

Error BakeStop::reason(const std::string& stage) const {
    if (!cancelled() && deadline_passed())
        return make_error(stage + " stopped: the bake ran past " + limit_text_, ErrorKind::kFailed);
    return make_error(stage + " cancelled", ErrorKind::kCancelled);
}

}  // namespace lc::bake
