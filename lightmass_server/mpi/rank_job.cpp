#include "lightmass_server/mpi/rank_job.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "lightcuts/status_macros.h"
#include "lightmass_server/bake/result_channel_file.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "protocol/environment_records.h"
#include "protocol/geometry_channel.h"

namespace lc::bake {
namespace fs = std::filesystem;

Result<std::vector<uint8_t>> read_file_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error("cannot open " + path.string());
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return make_error("cannot read " + path.string());
    return bytes;
}

Status write_file_atomically(const fs::path& path, std::span<const uint8_t> bytes) {
    const fs::path partial = path.string() + ".partial";
    {
        std::ofstream out(partial, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!out) return make_error("cannot write " + partial.string());
    }
    std::error_code ec;
    fs::rename(partial, path, ec);
    if (ec) return make_error("cannot rename " + partial.string() + ": " + ec.message());
    return Ok{};
}

namespace {

// The tree as the result channel, written a chunk at a time: never the whole channel in memory.
Status write_result_channel(const fs::path& path, const LightTree& tree) {
    const fs::path partial = path.string() + ".partial";
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    std::vector<uint8_t> chunk = encode_result_prefix(uint32_t(tree.nodes.size()));
    const size_t per_chunk = std::max<size_t>(1, kDefaultChunkBytes / result_record_bytes());
    for (size_t first = 0; first <= tree.nodes.size(); first += per_chunk) {
        append_result_records(tree, first, std::min(per_chunk, tree.nodes.size() - first), chunk);
        out.write(reinterpret_cast<const char*>(chunk.data()), std::streamsize(chunk.size()));
        chunk.clear();
        if (first == tree.nodes.size()) break;
    }
    out.close();
    if (!out) return make_error("cannot write " + partial.string());
    std::error_code ec;
    fs::rename(partial, path, ec);
    if (ec) return make_error("cannot rename " + partial.string() + ": " + ec.message());
    return Ok{};
}

Status write_text(const fs::path& path, const std::string& text) {
    return write_file_atomically(path, std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

Status read_into(const fs::path& path, std::vector<uint8_t>& out) {
    Result<std::vector<uint8_t>> bytes = read_file_bytes(path);
    if (!bytes) return bytes.failure();
    out = std::move(bytes.value());
    return Ok{};
}

BakeRequestMsg request_of(const BakeInputs& inputs, uint32_t ranks) {
    BakeRequestMsg request;
    request.builder = inputs.build.builder;
    request.seed = inputs.build.seed;
    request.representative_rule = inputs.build.representative_rule;
    request.pairing = inputs.build.pairing;
    request.exact_pairing_limit = inputs.build.exact_pairing_limit;
    request.environment_lights = inputs.environment_lights;
    request.area_lights = inputs.area_lights;
    request.indirect.method = inputs.indirect.method;
    request.indirect.bounces = inputs.indirect.vpl.bounces;
    request.indirect.vpl_count = inputs.indirect.vpl.particle_count;
    request.indirect.patch_size = inputs.indirect.radiosity.patch_size;
    request.indirect.tolerance = float(inputs.indirect.radiosity.tolerance);
    request.ranks = ranks;
    return request;
}

}  // namespace

RankJobBytes encode_rank_job(const BakeInputs& inputs, uint32_t ranks) {
    RankJobBytes job;
    job.request = encode_message(Message{request_of(inputs, ranks)});
    job.lights = encode_scene_channel(*inputs.lights);
    if (inputs.geometry) job.geometry = encode_geometry_channel(*inputs.geometry);
    if (inputs.environment) job.environment = encode_environment_channel(*inputs.environment);
    return job;
}

Status write_rank_job(const fs::path& dir, const RankJobBytes& job) {
    LC_RETURN_IF_ERROR(write_file_atomically(dir / "request.msg", job.request));
    LC_RETURN_IF_ERROR(write_file_atomically(dir / "lights.scene", job.lights));
    if (!job.geometry.empty()) LC_RETURN_IF_ERROR(write_file_atomically(dir / "geometry.geom", job.geometry));
    if (!job.environment.empty())
        LC_RETURN_IF_ERROR(write_file_atomically(dir / "environment.env", job.environment));
    return Ok{};
}

Result<RankJobBytes> read_rank_job(const fs::path& dir) {
    RankJobBytes job;
    LC_RETURN_IF_ERROR(read_into(dir / "request.msg", job.request));
    LC_RETURN_IF_ERROR(read_into(dir / "lights.scene", job.lights));
    if (fs::exists(dir / "geometry.geom")) LC_RETURN_IF_ERROR(read_into(dir / "geometry.geom", job.geometry));
    if (fs::exists(dir / "environment.env"))
        LC_RETURN_IF_ERROR(read_into(dir / "environment.env", job.environment));
    return job;
}

Result<RankJob> decode_rank_job(const RankJobBytes& bytes) {
    RankJob job;
    Result<Message> message = decode_message(bytes.request);
    if (!message) return make_error("job request: " + message.error());
    const auto* request = std::get_if<BakeRequestMsg>(&message.value());
    if (!request) return make_error("job request: not a BakeRequest");
    job.request = *request;
    Result<std::vector<SceneLight>> lights = decode_scene_channel(bytes.lights);
    if (!lights) return make_error("job lights: " + lights.error());
    job.lights = std::move(lights.value());
    if (!bytes.geometry.empty()) {
        Result<SceneGeometry> geometry = decode_geometry_channel(bytes.geometry);
        if (!geometry) return make_error("job geometry: " + geometry.error());
        job.geometry = std::move(geometry.value());
    }
    if (!bytes.environment.empty()) {
        Result<Environment> environment = decode_environment_channel(bytes.environment);
        if (!environment) return make_error("job environment: " + environment.error());
        job.environment = std::move(environment.value());
    }
    return job;
}

BuildOptions job_build_options(const BakeRequestMsg& request) {
    BuildOptions build;
    build.builder = request.builder;
    build.representative_rule = request.representative_rule;
    build.pairing = request.pairing;
    build.seed = request.seed;
    if (request.exact_pairing_limit != 0) build.exact_pairing_limit = request.exact_pairing_limit;
    return build;
}

Status write_rank_result(const fs::path& dir, const BuildResult& result,
                         const std::vector<std::string>& rank_lines) {
    LC_RETURN_IF_ERROR(write_result_channel(dir / "result.lcut", result.tree));
    return write_rank_report(dir, result.report, rank_lines);
}

Status write_rank_report(const fs::path& dir, const BuildReport& r,
                         const std::vector<std::string>& rank_lines) {
    std::ostringstream text;
    text.precision(17);
    for (const std::string& effect : r.effects) text << "effect " << effect << "\n";
    for (const std::string& warning : r.warnings) text << "warning " << warning << "\n";
    text << "build_ms " << r.build_ms << "\npairing_cost " << r.pairing_cost << "\npairing_lower_bound "
         << r.pairing_lower_bound << "\nexact " << (r.exact ? 1 : 0) << "\nlevels " << r.levels << "\ndepth "
         << r.depth << "\n";
    text << "tree_lights " << r.lights.punctual << " " << r.lights.area_samples << " " << r.lights.environment
         << " " << r.lights.vpls << " " << r.lights.patches << "\n";
    for (const std::string& line : rank_lines) text << line << "\n";
    return write_text(dir / "report.txt", text.str());
}

Result<BuildResult> read_rank_result(const fs::path& dir, const fs::path& tree_file) {
    BuildResult result;
    Result<std::shared_ptr<const ResultChannelFile>> file = ResultChannelFile::adopt(tree_file);
    if (!file) return make_error("rank 0's tree: " + file.error());
    result.channel_file = std::move(file.value());
    std::ifstream in(dir / "report.txt");
    if (!in) return make_error("rank 0 wrote no report.txt");
    BuildReport& r = result.report;
    for (std::string line; std::getline(in, line);) {
        const size_t space = line.find(' ');
        const std::string key = line.substr(0, space);
        const std::string value = space == std::string::npos ? "" : line.substr(space + 1);
        if (key == "effect")
            r.effects.push_back(value);
        else if (key == "warning")
            r.warnings.push_back(value);
        else if (key == "rank")
            r.effects.push_back("rank " + value);
        else if (key == "build_ms")
            r.build_ms = std::stod(value);
        else if (key == "pairing_cost")
            r.pairing_cost = std::stod(value);
        else if (key == "pairing_lower_bound")
            r.pairing_lower_bound = std::stod(value);
        else if (key == "exact")
            r.exact = value == "1";
        else if (key == "levels")
            r.levels = uint32_t(std::stoul(value));
        else if (key == "depth")
            r.depth = uint32_t(std::stoul(value));
        else if (key == "tree_lights")
            std::istringstream(value) >> r.lights.punctual >> r.lights.area_samples >> r.lights.environment >>
                r.lights.vpls >> r.lights.patches;
    }
    return result;
}

Status write_rank_error(const fs::path& dir, const std::string& text) {
    return write_text(dir / "error.txt", text);
}

Status write_rank_progress(const fs::path& dir, std::string_view stage, double percent) {
    char head[32];
    std::snprintf(head, sizeof head, "%.3f ", percent);
    return write_text(dir / "progress", head + std::string(stage));
}

}  // namespace lc::bake
