#include "raw_client.h"

#include <sys/socket.h>
#include <sys/time.h>

#include "protocol/codec.h"

namespace lc::test {

RawClient::RawClient(uint16_t port, std::chrono::milliseconds timeout) : socket_(io_) {
    socket_.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
    timeval tv{};
    tv.tv_sec = static_cast<time_t>(timeout.count() / 1000);
    tv.tv_usec = static_cast<suseconds_t>((timeout.count() % 1000) * 1000);
    ::setsockopt(socket_.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
}

bool RawClient::send_bytes(std::span<const uint8_t> bytes) {
    boost::system::error_code ec;
    asio::write(socket_, asio::buffer(bytes.data(), bytes.size()), ec);
    return !ec;
}

bool RawClient::send(const Message& message) { return send_bytes(encode_frame(message)); }

std::optional<Message> RawClient::receive() {
    std::vector<uint8_t> buffer(64 * 1024);
    while (frames_.empty()) {
        boost::system::error_code ec;
        size_t n = socket_.read_some(asio::buffer(buffer), ec);
        if (ec || n == 0) return std::nullopt;
        if (!decoder_.consume({buffer.data(), n}, frames_)) return std::nullopt;
    }
    std::vector<uint8_t> frame = std::move(frames_.front());
    frames_.erase(frames_.begin());
    auto message = decode_message(frame);
    if (!message) return std::nullopt;
    return std::move(message.value());
}

bool RawClient::wait_closed() {
    std::vector<uint8_t> buffer(4096);
    for (;;) {
        boost::system::error_code ec;
        socket_.read_some(asio::buffer(buffer), ec);
        if (ec == asio::error::eof || ec == asio::error::connection_reset) return true;
        if (ec) return false;  // timed out: still open
    }
}

uint16_t port_of(const std::string& address) {
    return static_cast<uint16_t>(std::stoi(address.substr(address.rfind(':') + 1)));
}

}  // namespace lc::test
