#include "lightmass_server/server_options.h"

#include "protocol/asio.h"

namespace lc::bake {

bool is_loopback_host(const std::string& host) {
    if (host == "localhost") return true;
    boost::system::error_code ec;
    auto address = asio::ip::make_address(host, ec);
    return !ec && address.is_loopback();
}

}  // namespace lc::bake
