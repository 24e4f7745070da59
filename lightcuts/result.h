#pragma once
// A value or an error message naming the problem. C++20 has no std::expected;
// this is the small subset we need on network and file paths.
#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace lc {

// Why an operation ended without a value, for callers to test: outcomes are
// codes, never matched from the message (which is for people).
enum class ErrorKind : uint8_t { kFailed = 0, kCancelled = 1, kBusy = 2, kRefused = 3 };

struct Error {
    std::string message;
    ErrorKind kind = ErrorKind::kFailed;
};

template <typename T>
class [[nodiscard]] Result {
public:
    // Default: an error, so a Result is never mistaken for a value by accident
    // (asio's co_spawn needs the type to be default-constructible).
    Result() : state_(Error{"no result"}) {}
    Result(T value) : state_(std::move(value)) {}
    Result(Error error) : state_(std::move(error)) {}

    bool ok() const { return std::holds_alternative<T>(state_); }
    explicit operator bool() const { return ok(); }

    T& value() & { return std::get<T>(state_); }
    const T& value() const& { return std::get<T>(state_); }
    T&& value() && { return std::get<T>(std::move(state_)); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

    const std::string& error() const { return std::get<Error>(state_).message; }
    ErrorKind error_kind() const { return std::get<Error>(state_).kind; }
    // The whole error, to pass on with its kind.
    const Error& failure() const { return std::get<Error>(state_); }

private:
    std::variant<T, Error> state_;
};

// Result<void> equivalent.
struct Ok {};
using Status = Result<Ok>;

inline Error make_error(std::string message, ErrorKind kind = ErrorKind::kFailed) {
    return Error{std::move(message), kind};
}

}  // namespace lc
