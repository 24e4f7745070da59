#include "editor_client/commands/shared_render_flags.h"

#include "editor_client/commands/enum_flags.h"
#include "lightcuts/device/limits.h"

namespace lc::client {
namespace {

// The real-time mode's budget: its cut per block and its shadow rays.
void add_realtime_flags(CLI::App& cmd, SharedRenderFlags& flags) {
    cmd.add_option("--realtime-cut", flags.realtime_cut,
                   "Real-time mode: nodes of each 8x8 block's cut, 1 to 32 (at most this many "
                   "shadow rays per pixel and frame)")
        ->capture_default_str();
    cmd.add_option("--realtime-rays", flags.realtime_rays,
                   "Real-time mode: shadow rays per pixel and frame, picked among the cut's "
                   "drawn lights by their unshadowed light (unbiased); 0 traces one per cut node")
        ->check(CLI::Range(0u, kMaxStochasticRays))
        ->capture_default_str();
}

}  // namespace

void add_shared_render_flags(CLI::App& cmd, SharedRenderFlags& flags) {
    add_realtime_flags(cmd, flags);
    cmd.add_option("--representatives", flags.representatives,
                   "Bound criterion: evaluate a cluster through the tree's representative (drawn "
                   "once for the image), one drawn per pixel with the same probabilities "
                   "(errors independent between pixels), or one drawn per pixel in proportion "
                   "to intensity x a bound of cos / d^2 at the point (importance; walk search)")
        ->transform(checked_names(kRepresentativesNames))
        ->default_str(representatives_name(flags.representatives));
    cmd.add_option("--shadows", flags.shadows,
                   "Shadow rays: auto (simulated when a surface may hide a light; the stats "
                   "JSON says why), on or off")
        ->transform(checked_names(kShadowModeNames))
        ->default_str(shadow_mode_name(flags.shadows));
    cmd.add_option("--primary", flags.primary,
                   "How the G-buffer is made: raster, rays (a compute pass: faster on GPUs that "
                   "rasterise on few units; untextured scenes), or auto (rays on a GPU for a scene "
                   "without textures, raster otherwise)")
        ->transform(checked_names(kPrimaryChoiceNames))
        ->default_str(name_in(kPrimaryChoiceNames, flags.primary));
}

}  // namespace lc::client
