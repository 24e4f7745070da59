#pragma once
// One bake from its inputs to the tree: the seam between the session (which
// collects the channels) and the stages that turn a scene into lights. With
// geometry, the bake builds one RayCaster (the solvers that trace rays go
// through it) and samples the emissive triangles into oriented lights; with an
// environment or sky, it samples that into directional lights; then every
// light goes to the tree builder. Each stage reports a census line.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "lightcuts/environment.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/control/bake_stop.h"
#include "lightmass_server/indirect/indirect_stage.h"
#include "lightmass_server/bake/mpi_launch_options.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/messages.h"

namespace lc::bake {

struct BakeInputs {
    // The scene channel's tree lights (classic lights already left out).
    std::shared_ptr<const std::vector<SceneLight>> lights;
    // The geometry channel's surfaces; null when the client sent none.
    std::shared_ptr<const SceneGeometry> geometry;
    uint32_t area_lights = kDefaultAreaLights;  // the area-light sample budget
    // The environment channel's map or sun and sky; null when the client sent none.
    std::shared_ptr<const Environment> environment;
    uint32_t environment_lights = 0;  // validated by the session; 0: the default
    BuildOptions build;
    IndirectOptions indirect;  // bounced light, added to the tree as oriented lights
    std::string radiosity_out;  // a radiosity bake writes its patches here (PLY); empty: not
    int raycast_threads = 1;  // Embree's build threads (results do not depend on it)
    // 0: baked in this process; N: over N MPI ranks (run_bake in mpi/bake_dispatch.h).
    uint32_t ranks = 0;
    MpiLaunchOptions mpi;
    // Cancel and deadline, polled inside every stage's loops; null: never stops.
    std::shared_ptr<BakeStop> stop;
};

// A cancelled bake returns an error of kind ErrorKind::kCancelled (a bake
// past its deadline, an error naming the deadline). The
// report's effects hold the census (area lights simulated or skipped, why).
Result<BuildResult> run_bake_in_process(const BakeInputs& inputs, const ProgressFn& progress);

}  // namespace lc::bake
