#pragma once
// Both programs include Boost.Asio through this header, the way Boost 1.74
// needs it: <utility> first (its coroutines use std::exchange without it).
#include <utility>

#include <boost/asio.hpp>
#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/use_awaitable.hpp>

namespace lc {
namespace asio = boost::asio;
using asio::awaitable;
using asio::ip::tcp;
}  // namespace lc
