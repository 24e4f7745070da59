// Result-channel streaming over loopback against a raw socket copy of the same
// bytes, in one run. Usage: stream_throughput_bench RECORDS [RECORDS...]
// Prints CSV: records,channel_bytes,protocol_ms,protocol_mb_s,raw_ms,raw_mb_s,ratio,peak_rss_mb,
// client_rss_bytes_per_record, and the CPU time of each side of the protocol
// run (server_cpu_ms, client_cpu_ms) and of the raw copy (raw_server_cpu_ms,
// raw_client_cpu_ms): on a shared machine the wall clock moves with the load,
// the CPU time much less. Both runs are plain TCP over loopback. The protocol
// run is `bake`'s client, which validates the tree and keeps none of it; the
// decoded_* columns are a second run that keeps the nodes (editor, render).
#include <sys/resource.h>
#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include <glm/common.hpp>

#include "lightmass_server/net/result_stream.h"
#include "protocol/asio.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "protocol/frame_decoder.h"

namespace {

using Clock = std::chrono::steady_clock;

// A complete binary tree in breadth-first order: children of i at 2i+1, 2i+2.
lc::LightTree make_tree(size_t node_count) {
    if (node_count % 2 == 0) ++node_count;
    lc::LightTree tree;
    tree.nodes.resize(node_count);
    for (size_t i = node_count; i-- > 0;) {
        lc::LightTreeNode& n = tree.nodes[i];
        n.guid = lc::Guid{static_cast<uint32_t>(i), 1, 2, 3};
        size_t l = 2 * i + 1, r = 2 * i + 2;
        float x = static_cast<float>(i % 1000), y = static_cast<float>(i / 1000);
        if (r < node_count) {
            n.left = static_cast<int32_t>(l);
            n.right = static_cast<int32_t>(r);
            n.representative = tree.nodes[l].representative;
            const auto& a = tree.nodes[l];
            const auto& b = tree.nodes[r];
            n.position = a.position;
            n.intensity = a.intensity + b.intensity;
            n.brightness = a.brightness + b.brightness;
            n.bbox_min = glm::min(a.bbox_min, b.bbox_min);
            n.bbox_max = glm::max(a.bbox_max, b.bbox_max);
        } else {
            n.representative = static_cast<int32_t>(i);
            n.position = {x, y, 1.0f};
            n.intensity = glm::vec3(1.0f);
            n.brightness = 1.0f;
            n.bbox_min = n.bbox_max = n.position;
            ++tree.leaf_count;
        }
        n.cone_cos = -1.0f;
    }
    return tree;
}

double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

struct Run {
    double wall_ms = 0.0;
    double server_cpu_ms = 0.0;
    double client_cpu_ms = 0.0;
};

double peak_rss_mb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// Streams `tree` through ResultStream to a client that reads as bake_client
// does (straight into the frame, records read in the frame) and validates
// every record and the structure, keeping the decoded nodes or not.
Run protocol_run(const std::shared_ptr<const lc::LightTree>& tree, lc::TreeImport import) {
    Run run;
    lc::asio::io_context io;
    lc::tcp::acceptor acceptor(io, lc::tcp::endpoint(lc::asio::ip::make_address("127.0.0.1"), 0));
    uint16_t port = acceptor.local_endpoint().port();
    std::thread server([&] {
        lc::tcp::socket socket = acceptor.accept();
        lc::BakeDoneMsg done;
        done.result_channel = lc::lightcuts_result_channel_name();
        done.node_count = static_cast<uint32_t>(tree->nodes.size());
        const double cpu_start = thread_cpu_ms();
        lc::bake::ResultStream stream(tree, 1u << 31, done, lc::kDefaultChunkBytes);
        while (auto frame = stream.next_frame()) {
            const std::span<const uint8_t> bytes = frame->bytes();
            lc::asio::write(socket, lc::asio::buffer(bytes.data(), bytes.size()));
        }
        run.server_cpu_ms = thread_cpu_ms() - cpu_start;
    });
    auto start = Clock::now();
    const double cpu_start = thread_cpu_ms();
    lc::tcp::socket socket(io);
    socket.connect(lc::tcp::endpoint(lc::asio::ip::make_address("127.0.0.1"), port));
    lc::FrameDecoder decoder;
    lc::ResultChannelReader reader(import);
    std::vector<std::vector<uint8_t>> frames;
    bool finished = false;
    while (!finished) {
        boost::system::error_code ec;
        const std::span<uint8_t> into = decoder.read_buffer(256 * 1024);
        size_t n = socket.read_some(lc::asio::buffer(into.data(), into.size()), ec);
        if (ec) break;
        frames.clear();
        if (!decoder.commit(n, frames)) std::abort();
        for (auto& f : frames) {
            auto message = lc::decode_message_in_frame(f);
            if (!message) std::abort();
            if (auto* w = std::get_if<lc::WriteChannelMsg>(&message.value())) {
                if (!reader.consume(w->bytes())) std::abort();
            } else if (std::holds_alternative<lc::BakeDoneMsg>(message.value())) {
                finished = true;
            }
            decoder.recycle(std::move(f));
        }
    }
    const size_t received = reader.nodes_received();
    const bool valid =
        import == lc::TreeImport::kNodes ? reader.finish().ok() : reader.finish_validation().ok();
    run.wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    run.client_cpu_ms = thread_cpu_ms() - cpu_start;
    server.join();
    if (!valid || received != tree->nodes.size()) {
        std::fprintf(stderr, "stream failed\n");
        std::exit(1);
    }
    return run;
}

// The same number of bytes, written in 1 MiB buffers and read as the protocol
// client reads, over the same plain TCP loopback (no TLS on either side).
Run raw_run(uint64_t bytes) {
    Run run;
    lc::asio::io_context io;
    lc::tcp::acceptor acceptor(io, lc::tcp::endpoint(lc::asio::ip::make_address("127.0.0.1"), 0));
    uint16_t port = acceptor.local_endpoint().port();
    std::thread server([&] {
        lc::tcp::socket socket = acceptor.accept();
        const double cpu_start = thread_cpu_ms();
        std::vector<uint8_t> chunk(1u << 20, 0x5A);
        for (uint64_t sent = 0; sent < bytes;) {
            size_t n = static_cast<size_t>(std::min<uint64_t>(chunk.size(), bytes - sent));
            lc::asio::write(socket, lc::asio::buffer(chunk.data(), n));
            sent += n;
        }
        run.server_cpu_ms = thread_cpu_ms() - cpu_start;
    });
    auto start = Clock::now();
    const double cpu_start = thread_cpu_ms();
    lc::tcp::socket socket(io);
    socket.connect(lc::tcp::endpoint(lc::asio::ip::make_address("127.0.0.1"), port));
    std::vector<uint8_t> buffer(256 * 1024);
    uint64_t got = 0;
    while (got < bytes) {
        boost::system::error_code ec;
        got += socket.read_some(lc::asio::buffer(buffer), ec);
        if (ec) break;
    }
    run.wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    run.client_cpu_ms = thread_cpu_ms() - cpu_start;
    server.join();
    return run;
}

}  // namespace

int main(int argc, char** argv) {
    std::printf(
        "records,channel_bytes,protocol_ms,protocol_mb_s,raw_ms,raw_mb_s,raw_over_protocol,peak_rss_mb,"
        "client_rss_bytes_per_record,server_cpu_ms,client_cpu_ms,raw_server_cpu_ms,raw_client_cpu_ms,"
        "decoded_ms,decoded_client_cpu_ms,decoded_rss_bytes_per_record\n");
    for (int i = 1; i < argc; ++i) {
        size_t records = std::strtoull(argv[i], nullptr, 10);
        auto tree = std::make_shared<const lc::LightTree>(make_tree(records));
        uint64_t bytes = 4 + tree->nodes.size() * lc::result_record_bytes();
        // The protocol columns are `bake`'s client: every record validated, none kept.
        double rss_before = peak_rss_mb();
        const Run run = protocol_run(tree, lc::TreeImport::kValidateOnly);
        const double p = run.wall_ms;
        double rss = peak_rss_mb();
        const Run raw = raw_run(bytes);
        const double r = raw.wall_ms;
        // The decoded columns are the editor's and render's: the tree kept as nodes.
        const double rss_before_decoded = peak_rss_mb();
        const Run decoded = protocol_run(tree, lc::TreeImport::kNodes);
        const double rss_decoded = peak_rss_mb();
        double mb = static_cast<double>(bytes) / (1024.0 * 1024.0);
        const auto per_record = [&](double grown_mb) {
            return grown_mb * 1024.0 * 1024.0 / static_cast<double>(tree->nodes.size());
        };
        std::printf("%zu,%llu,%.1f,%.1f,%.1f,%.1f,%.2f,%.1f,%.0f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.0f\n",
                    tree->nodes.size(), static_cast<unsigned long long>(bytes), p, mb / (p / 1000.0), r,
                    mb / (r / 1000.0), r / p, rss, per_record(rss - rss_before), run.server_cpu_ms,
                    run.client_cpu_ms, raw.server_cpu_ms, raw.client_cpu_ms, decoded.wall_ms,
                    decoded.client_cpu_ms, per_record(rss_decoded - rss_before_decoded));
        std::fflush(stdout);
    }
    return 0;
}
