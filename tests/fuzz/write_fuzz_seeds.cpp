// Writes the seed corpora the recorded test data does not hold as they are:
//   OUT/messages, OUT/frames: one encoded message of every kind, as a frame
//       body and as a framed stream (the recorded channels carry no frames);
//   OUT/scene, OUT/result: the payloads of the scene and result channel dumps
//       under DATA/replay, behind the byte that picks the fuzzers' piece size;
//   OUT/geometry, OUT/environment: small geometry and environment channels
//       (a lit box, a 4 x 2 map, a sun and sky), behind the same byte.
// The dumps and glTF files themselves are seeds as they are (scripts/fuzz.sh).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "protocol/codec.h"
#include "protocol/dump.h"
#include "protocol/environment_records.h"
#include "protocol/geometry_channel.h"
#include "protocol/frame_decoder.h"

namespace {

std::vector<lc::Message> sample_messages() {
    return {
        lc::HelloMsg{lc::kProtocolVersion, "editor_client", "token"},
        lc::HelloAckMsg{lc::kProtocolVersion, "lightmass_server"},
        lc::OpenChannelMsg{1, "scene.channel", 720},
        lc::WriteChannelMsg{1, 0, std::vector<uint8_t>(40, 7)},
        lc::CloseChannelMsg{1},
        lc::BakeRequestMsg{3, "scene.channel", lc::BuilderKind::kAgglomerative, 42,
                           lc::RepresentativeRule::kThesisFirst, lc::PairingMode::kExact, 64},
        // Every field, the indirect light's included (issue 27's limits).
        lc::BakeRequestMsg{4, "scene.channel", lc::BuilderKind::kOptimalPair, 7,
                           lc::RepresentativeRule::kIntensity, lc::PairingMode::kAuto, 0, "env.channel", 3000,
                           "geom.channel", 4096,
                           lc::IndirectRequest{lc::IndirectMethod::kVpl, 65535, 1000, 0.25f, 0.01f}},
        lc::ProgressMsg{3, "pairing", 37.5f},
        lc::WarningMsg{3, "two lights share a position"},
        lc::ErrorMsg{3, lc::ErrorCode::kInvalidScene, "light 4: intensity is negative"},
        lc::CancelMsg{3},
        lc::BakeDoneMsg{3, "result.channel", 7, 4, 1.5, 2.25, 2.0, false},
    };
}

void write(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

}  // namespace

// Channel payloads behind a piece-size byte: 37 and 255 (pieces of a few
// hundred and a few thousand bytes; byte-sized pieces would make every
// execution of a 20 KB channel thousands of pushes).
int write_channel_seeds(const std::filesystem::path& data, const std::filesystem::path& out) {
    std::filesystem::create_directories(out / "scene");
    std::filesystem::create_directories(out / "result");
    int index = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(data / "replay")) {
        const std::string name = entry.path().filename().string();
        const bool scene = name.ends_with(".scene.dump");
        if (!scene && !name.ends_with(".lcut.dump")) continue;
        lc::Result<lc::ChannelDump> dump = lc::read_dump(entry.path());
        if (!dump) {
            std::fprintf(stderr, "%s\n", dump.error().c_str());
            return 1;
        }
        for (uint8_t piece : {uint8_t(37), uint8_t(255)}) {
            std::vector<uint8_t> seed = {piece};
            seed.insert(seed.end(), dump->payload.begin(), dump->payload.end());
            write(out / (scene ? "scene" : "result") / (std::to_string(index++)), seed);
        }
    }
    return 0;
}

namespace {

void write_behind_piece_bytes(const std::filesystem::path& dir, const std::vector<uint8_t>& payload, int& index) {
    std::filesystem::create_directories(dir);
    for (uint8_t piece : {uint8_t(3), uint8_t(37)}) {
        std::vector<uint8_t> seed = {piece};
        seed.insert(seed.end(), payload.begin(), payload.end());
        write(dir / std::to_string(index++), seed);
    }
}

// A quad lit by an emissive triangle, one degenerate triangle among them.
lc::SceneGeometry sample_geometry() {
    lc::SceneGeometry g;
    g.materials.push_back({glm::vec3(0.73f), glm::vec3(0.0f), 0.0f, 1.0f});
    g.materials.push_back({glm::vec3(0.5f), glm::vec3(4.0f, 3.0f, 2.0f), 0.0f, 0.5f});
    auto triangle = [](glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material) {
        lc::SurfaceTriangle t;
        t.positions[0] = a;
        t.positions[1] = b;
        t.positions[2] = c;
        t.normals[0] = t.normals[1] = t.normals[2] = glm::vec3(0, 1, 0);
        t.material = material;
        return t;
    };
    g.triangles.push_back(triangle({0, 0, 0}, {1, 0, 1}, {1, 0, 0}, 0));
    g.triangles.push_back(triangle({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, 0));
    g.triangles.push_back(triangle({0.2f, 1, 0.2f}, {0.8f, 1, 0.2f}, {0.5f, 1, 0.8f}, 1));
    return g;
}

void write_surface_seeds(const std::filesystem::path& out) {
    int index = 0;
    write_behind_piece_bytes(out / "geometry", lc::encode_geometry_channel(sample_geometry()), index);
    write_behind_piece_bytes(out / "geometry", lc::encode_geometry_channel(lc::SceneGeometry{}), index);
    // With the optional mask sections: a 5 x 3 mask over the floor's second
    // triangle and a see-through 1 x 1 over the emitter.
    lc::SceneGeometry masked = sample_geometry();
    masked.masks.push_back(lc::SurfaceMask{5, 3, {0x5A5Au}});
    masked.masks.push_back(lc::SurfaceMask{1, 1, {0u}});
    masked.masked_triangles.push_back(lc::MaskedTriangle{1, 0, {{0, 0}, {0, 1}, {1, 1}}});
    masked.masked_triangles.push_back(lc::MaskedTriangle{2, 1, {{0, 0}, {1, 0}, {0.5f, 1}}});
    write_behind_piece_bytes(out / "geometry", lc::encode_geometry_channel(masked), index);
    lc::Environment map;
    map.map.width = 4;
    map.map.height = 2;
    for (int i = 0; i < 8; ++i) map.map.texels.push_back(glm::vec3(float(i), 1.0f, 0.5f));
    map.intensity = 2.0f;
    map.rotation_deg = 30.0f;
    write_behind_piece_bytes(out / "environment", lc::encode_environment_channel(map), index);
    lc::Environment sky;
    sky.sky = lc::SkyParameters{30.0f, 40.0f, 3.0f};
    write_behind_piece_bytes(out / "environment", lc::encode_environment_channel(sky), index);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s DATA_DIR OUT_DIR\n", argv[0]);
        return 2;
    }
    const std::filesystem::path dir = argv[2];
    if (write_channel_seeds(argv[1], dir) != 0) return 1;
    write_surface_seeds(dir);
    std::filesystem::create_directories(dir / "messages");
    std::filesystem::create_directories(dir / "frames");
    std::vector<uint8_t> stream = {0};  // frame_decoder_fuzz: first byte is the piece size
    int index = 0;
    for (const lc::Message& message : sample_messages()) {
        const std::string name = std::to_string(index++) + "_" + lc::message_name(message);
        write(dir / "messages" / name, lc::encode_message(message));
        std::vector<uint8_t> framed = {uint8_t(index)};
        const std::vector<uint8_t> frame = lc::encode_frame(message);
        framed.insert(framed.end(), frame.begin(), frame.end());
        write(dir / "frames" / name, framed);
        stream.insert(stream.end(), frame.begin(), frame.end());
    }
    write(dir / "frames" / "all_messages", stream);
    return 0;
}
