#pragma once
// A value or an error message naming the problem. C++20 has no std::expected;
// this is the small subset we need on network and file paths.
#include <string>
#include <utility>
#include <variant>

namespace lc {

struct Error {
    std::string message;
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

private:
    std::variant<T, Error> state_;
};

// Result<void> equivalent.
struct Ok {};
using Status = Result<Ok>;

inline Error make_error(std::string message) { return Error{std::move(message)}; }

}  // namespace lc
