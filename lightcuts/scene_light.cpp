#include "lightcuts/scene_light.h"

namespace lc {

const char* light_type_name(LightType type) {
    switch (type) {
        case LightType::kPoint: return "point";
        case LightType::kSpot: return "spot";
        case LightType::kDirectional: return "directional";
        case LightType::kOriented: return "oriented";
    }
    return "unknown";
}

}  // namespace lc
