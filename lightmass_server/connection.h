#pragma once
// One client connection: a reader, a writer and a watchdog coroutine sharing
// one transport (plain TCP or TLS) on the server's I/O thread. Bakes run on the
// worker pool and post their progress and results back here. A failed TLS
// handshake or a malformed frame closes this connection only; a bad scene is
// refused with an error and the connection stays.
#include <atomic>
#include <chrono>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "protocol/asio.h"
#include "lightmass_server/result_stream.h"
#include "lightmass_server/server_options.h"
#include "lightmass_server/tree_builder.h"
#include "protocol/channel_recorder.h"
#include "protocol/channel_records.h"
#include "protocol/frame_decoder.h"
#include "protocol/messages.h"
#include "protocol/transport.h"

namespace lc::bake {

class Connection : public std::enable_shared_from_this<Connection> {
public:
    Connection(Transport transport, const ServerOptions& options, asio::thread_pool& workers,
               const ChannelRecorder& recorder, uint64_t id);

    void start();
    void close(const std::string& reason);
    // Sends what is queued (an error explaining why), then closes.
    void close_after_flush(const std::string& reason);
    bool closed() const { return closed_; }
    uint64_t id() const { return id_; }

private:
    struct IncomingScene {
        std::string name;
        uint64_t total_bytes = 0;
        uint64_t received = 0;
        SceneChannelReader reader;
        std::vector<uint8_t> recorded;  // kept only when recording
    };
    struct ActiveBake {
        uint32_t bake_id = 0;
        std::shared_ptr<std::atomic<bool>> cancel;
    };

    // The TLS handshake (nothing for plain TCP), then the reader and the writer.
    awaitable<void> handshake_then_serve();
    awaitable<void> read_loop();
    awaitable<void> write_loop();
    awaitable<void> watchdog();

    // Returns false when the connection must close (protocol violation).
    bool handle(Message message);
    bool on_hello(const HelloMsg& hello);
    bool on_open_channel(const OpenChannelMsg& open);
    bool on_write_channel(WriteChannelMsg& write);
    bool on_close_channel(const CloseChannelMsg& close);
    bool on_bake_request(const BakeRequestMsg& request);
    void on_bake_finished(uint32_t bake_id, Result<BuildResult> result);

    void send(const Message& message);
    void send_error(uint32_t bake_id, ErrorCode code, const std::string& text);
    void wake_writer();

    Transport transport_;
    const ServerOptions& options_;
    asio::thread_pool& workers_;
    const ChannelRecorder& recorder_;
    uint64_t id_;
    std::string peer_;

    FrameDecoder decoder_;
    asio::steady_timer wake_;
    std::deque<std::vector<uint8_t>> outbox_;
    std::optional<ResultStream> stream_;
    bool closed_ = false;
    bool handshaken_ = false;  // TLS handshake done (plain TCP: at once)
    bool greeted_ = false;
    bool closing_ = false;
    std::string closing_reason_;
    std::chrono::steady_clock::time_point closing_since_;
    std::chrono::steady_clock::time_point last_read_;

    std::map<uint32_t, IncomingScene> incoming_;
    std::set<uint32_t> refused_;  // channels already refused with an error: their writes are dropped
    std::map<std::string, std::vector<SceneLight>> scenes_;
    std::optional<ActiveBake> bake_;
    uint32_t next_channel_id_ = 1u << 31;  // server-opened channels use the upper half
};

}  // namespace lc::bake
