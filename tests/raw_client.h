#pragma once
// A deliberately simple blocking client for tests that must misbehave on the
// wire (wrong versions, garbage frames, stalls) where bake_client would refuse.
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/asio.h"
#include "protocol/frame_decoder.h"
#include "protocol/messages.h"

namespace lc::test {

class RawClient {
public:
    // Connects to 127.0.0.1:port; receive calls time out after `timeout`.
    RawClient(uint16_t port, std::chrono::milliseconds timeout = std::chrono::seconds(10));
    bool send_bytes(std::span<const uint8_t> bytes);
    bool send(const Message& message);
    // The next message, or nothing when the connection closed or timed out.
    std::optional<Message> receive();
    // True when the server has closed the connection (reads EOF or error).
    bool wait_closed();

private:
    asio::io_context io_;
    tcp::socket socket_;
    FrameDecoder decoder_;
    std::vector<std::vector<uint8_t>> frames_;
};

uint16_t port_of(const std::string& address);  // "127.0.0.1:PORT" -> PORT

}  // namespace lc::test
