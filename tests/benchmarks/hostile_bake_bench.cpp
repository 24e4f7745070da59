// Issue 27's hostile client against a running lightmass_server (scripts/
// fault_test.sh hostile starts the server, samples its memory and reads these
// lines). One scenario per run:
//   vpl-deep       1,000 paths of 65,535 bounces in a white furnace
//   radiosity      about 2 million patches and 1,000 point lights
//   vpl-huge       10^9 light paths in a black furnace; with --small, a
//                  20-light bake is timed on a second connection meanwhile
//   environment    an 8192 x 4096 environment map, 100,000 lights
//   area           4,194,304 area-light samples of one emissive triangle
//   area-fit       400,000 samples: a bake that fits 512 MB, run to the end
//                  (its peak RSS checks the estimate it was admitted by)
//   vpl-fit        100,000 paths of 3 bounces in a white furnace, to the end
//   silent-channel opens a 200 MB channel, sends 2 bytes, goes silent
//   points         --size point lights, no geometry, to the end (a tree
//                  builder's peak: scripts/fault_test.sh footprint)
// --size N scales a scenario for the footprint calibration: area and
// area-fit's samples, vpl-fit's paths, radiosity's point lights (with
// --patch-size), the environment map's width (height half of it), points'
// lights; --builder optimal-pair|agglomerative|lbvh picks the tree builder,
// --exact pairs every optimal-pair level exactly.
// A bake is cancelled --cancel-after-ms after its first stage past "queued"
// (0: not cancelled); the line gives the stage it was in and how long the
// Cancel took to come back as an error. Prints one CSV row:
//   scenario,outcome,stage,cancel_ms,small_idle_ms,small_busy_ms,detail
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "editor_client/bake/bake_client.h"
#include "lightcuts/seeded_mixer.h"
#include "protocol/asio.h"
#include "protocol/channel_name.h"
#include "protocol/codec.h"
#include "tests/indirect_scenes.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
constexpr lc::Guid kSceneGuid{0x48617374u, 0x696c6521u, 0x1u, 0x2u};

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// `count` point lights inside the box [0.5, 3.5]^3, from `seed`.
std::vector<lc::SceneLight> point_lights(uint32_t count, uint64_t seed) {
    lc::SplitMix64 random(seed);
    std::vector<lc::SceneLight> lights(count);
    for (uint32_t i = 0; i < count; ++i) {
        lc::SceneLight& light = lights[i];
        const uint8_t id[4] = {uint8_t(i), uint8_t(i >> 8), uint8_t(i >> 16), uint8_t(i >> 24)};
        light.guid = lc::Guid::from_bytes(id);
        light.type = lc::LightType::kPoint;
        for (int axis = 0; axis < 3; ++axis) light.position[axis] = float(0.5 + 3.0 * random.uniform());
        light.intensity = 1.0f;
    }
    return lights;
}

struct Scenario {
    std::vector<lc::SceneLight> lights;
    lc::client::BakeClientOptions options;
};

// What --size, --patch-size and --builder change; 0: the scenario's own value.
struct Knobs {
    uint32_t size = 0;
    float patch_size = 0.0f;
    lc::BuilderKind builder = lc::BuilderKind::kOptimalPair;
    lc::PairingMode pairing = lc::PairingMode::kAuto;
};

Scenario make_scenario(const std::string& name, const std::string& server, const Knobs& knobs) {
    Scenario s;
    s.options.builder = knobs.builder;
    s.options.pairing = knobs.pairing;
    auto sized = [&](uint32_t otherwise) { return knobs.size != 0 ? knobs.size : otherwise; };
    s.options.server = server;
    s.options.timeout_seconds = 900.0;
    s.lights = point_lights(4, 9);
    const glm::vec3 white(1.0f), black(0.0f), none(0.0f);
    if (name == "vpl-fit") {
        s.options.geometry =
            std::make_shared<const lc::SceneGeometry>(lc::test::closed_box({white, none}, 4.0f));
        s.options.indirect = {lc::IndirectMethod::kVpl, 3, sized(100000)};
    } else if (name == "vpl-deep" || name == "vpl-huge") {
        s.options.geometry = std::make_shared<const lc::SceneGeometry>(
            lc::test::closed_box({name == "vpl-deep" ? white : black, none}, 4.0f));
        s.options.indirect = name == "vpl-deep"
                                 ? lc::IndirectRequest{lc::IndirectMethod::kVpl, 65535, 1000}
                                 : lc::IndirectRequest{lc::IndirectMethod::kVpl, 1, 1000000000};
    } else if (name == "radiosity") {
        s.lights = point_lights(sized(1000), 9);
        s.options.geometry =
            std::make_shared<const lc::SceneGeometry>(lc::test::closed_box({glm::vec3(0.5f), none}, 4.0f));
        const float patch_size = knobs.patch_size > 0.0f ? knobs.patch_size : 0.0141f;
        s.options.indirect = {lc::IndirectMethod::kRadiosity, 1, 1, patch_size, 0.01f};
    } else if (name == "environment") {
        auto environment = std::make_shared<lc::Environment>();
        environment->map.width = sized(8192);
        environment->map.height = environment->map.width / 2;
        environment->map.texels.assign(size_t(environment->map.width) * environment->map.height,
                                       glm::vec3(0.5f));
        s.options.environment = environment;
        s.options.environment_lights = 100000;
    } else if (name == "area" || name == "area-fit") {
        lc::SceneGeometry panel;
        panel.materials.push_back({glm::vec3(0.5f), glm::vec3(1.0f)});
        panel.triangles.push_back(lc::test::flat_triangle({0, 2, 0}, {1, 2, 0}, {0, 2, 1}, 0));
        s.options.geometry = std::make_shared<const lc::SceneGeometry>(std::move(panel));
        s.options.area_lights = sized(name == "area" ? lc::kMaxAreaLights : 400000);
    } else if (name == "points") {
        s.lights = point_lights(sized(65536), 11);
    }
    return s;
}

// Opens a channel, sends two bytes of it, says nothing more: how long until the server hangs up.
int silent_channel(const std::string& server) {
    const size_t colon = server.rfind(':');
    lc::asio::io_context io;
    lc::tcp::socket socket(io);
    boost::system::error_code ec;
    socket.connect(
        {lc::asio::ip::make_address(server.substr(0, colon)), uint16_t(std::stoi(server.substr(colon + 1)))},
        ec);
    if (ec) return std::fprintf(stderr, "connect: %s\n", ec.message().c_str()), 1;
    for (const lc::Message& message :
         {lc::Message(lc::HelloMsg{lc::kProtocolVersion, "hostile", ""}),
          lc::Message(lc::OpenChannelMsg{1, lc::scene_channel_name(kSceneGuid), uint64_t{200} << 20}),
          lc::Message(lc::WriteChannelMsg{1, 0, std::vector<uint8_t>(2, 0)})}) {
        const std::vector<uint8_t> frame = lc::encode_frame(message);
        lc::asio::write(socket, lc::asio::buffer(frame), ec);
    }
    const auto start = Clock::now();
    std::vector<uint8_t> sink(4096);
    while (!ec && ms_since(start) < 120000) socket.read_some(lc::asio::buffer(sink), ec);
    std::printf("silent-channel,%s,,,,,closed %.0f ms after going silent\n", ec ? "closed" : "open",
                ms_since(start));
    return 0;
}

struct Flags {
    int cancel_after_ms = 0;
    bool small = false;
    Knobs knobs;
};

// The flags after HOST:PORT SCENARIO; unknown ones are ignored.
Flags parse_flags(int argc, char** argv) {
    Flags flags;
    for (int i = 3; i < argc; ++i) {
        const bool has_value = i + 1 < argc;
        if (!std::strcmp(argv[i], "--cancel-after-ms") && has_value)
            flags.cancel_after_ms = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--small"))
            flags.small = true;
        else if (!std::strcmp(argv[i], "--size") && has_value)
            flags.knobs.size = uint32_t(std::strtoul(argv[++i], nullptr, 10));
        else if (!std::strcmp(argv[i], "--exact"))
            flags.knobs.pairing = lc::PairingMode::kExact;
        else if (!std::strcmp(argv[i], "--patch-size") && has_value)
            flags.knobs.patch_size = std::strtof(argv[++i], nullptr);
        else if (!std::strcmp(argv[i], "--builder") && has_value) {
            const std::string builder = argv[++i];
            flags.knobs.builder = builder == "lbvh"            ? lc::BuilderKind::kLbvh
                                  : builder == "agglomerative" ? lc::BuilderKind::kAgglomerative
                                                               : lc::BuilderKind::kOptimalPair;
        }
    }
    return flags;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr,
                     "usage: %s HOST:PORT SCENARIO [--cancel-after-ms N] [--small] [--size N] "
                     "[--patch-size S] [--builder optimal-pair|agglomerative|lbvh] [--exact]\n",
                     argv[0]);
        return 2;
    }
    const std::string server = argv[1], name = argv[2];
    const Flags flags = parse_flags(argc, argv);
    const int cancel_after_ms = flags.cancel_after_ms;
    const bool small = flags.small;
    const Knobs& knobs = flags.knobs;
    if (name == "silent-channel") return silent_channel(server);
    auto small_bake_ms = [&] {
        lc::client::BakeClientOptions quick;
        quick.server = server;
        const auto t0 = Clock::now();
        auto little = lc::client::bake_lights(point_lights(20, 3), kSceneGuid, quick);
        return little.ok() ? ms_since(t0) : -2.0;
    };
    double small_idle_ms = -1.0;
    if (small) {
        small_bake_ms();  // warm: the first connection's costs are not the bake's
        small_idle_ms = small_bake_ms();
    }
    Scenario s = make_scenario(name, server, knobs);
    std::mutex mutex;
    std::string stage = "queued";
    std::atomic<bool> started{false}, cancel{false};
    lc::client::BakeWaker waker;
    s.options.on_progress = [&](const lc::ProgressMsg& progress) {
        std::lock_guard lock(mutex);
        stage = progress.stage;
        if (stage != "queued") started = true;
    };
    s.options.cancel = &cancel;
    s.options.waker = &waker;
    lc::Result<lc::client::BakeOutcome> outcome = lc::make_error("not run");
    std::atomic<bool> done{false};
    Clock::time_point finished_at;
    std::thread bake([&] {
        outcome = lc::client::bake_lights(s.lights, kSceneGuid, s.options);
        finished_at = Clock::now();
        done = true;
    });
    while (!started && !done) std::this_thread::sleep_for(1ms);
    double small_busy_ms = -1.0;
    if (small && !done) small_busy_ms = small_bake_ms();
    double cancel_ms = -1.0;
    std::string cancelled_in;
    if (cancel_after_ms > 0) {
        const auto until = Clock::now() + std::chrono::milliseconds(cancel_after_ms);
        while (!done && Clock::now() < until) std::this_thread::sleep_for(1ms);
        if (!done) {
            {
                std::lock_guard lock(mutex);
                cancelled_in = stage;
            }
            const auto t0 = Clock::now();
            cancel = true;
            waker.wake();
            bake.join();
            cancel_ms = std::chrono::duration<double, std::milli>(finished_at - t0).count();
        }
    }
    if (bake.joinable()) bake.join();
    std::string detail =
        outcome.ok() ? std::to_string(outcome->tree.leaf_count) + " leaves" : outcome.error();
    for (char& c : detail)
        if (c == ',' || c == '\n') c = ';';
    std::printf("%s,%s,%s,%.1f,%.1f,%.1f,%s\n", name.c_str(), outcome.ok() ? "baked" : "refused-or-stopped",
                cancelled_in.c_str(), cancel_ms, small_idle_ms, small_busy_ms, detail.c_str());
    return 0;
}
