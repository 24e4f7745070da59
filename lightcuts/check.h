#pragma once
// Invariants stated in code (after pbrt-v4's CHECK and DCHECK): LC_CHECK holds
// in every build and stops the program with the condition, file and line when
// it fails; LC_DCHECK only in builds without NDEBUG (the asan preset), for
// checks on hot paths such as a walk's node accesses. Neither is error
// handling: bad input gets a Result with a message; these catch our own bugs.
namespace lc::detail {

[[noreturn]] void check_failed(const char* condition, const char* file, int line);

}  // namespace lc::detail

#define LC_CHECK(condition) \
    ((condition) ? static_cast<void>(0) : ::lc::detail::check_failed(#condition, __FILE__, __LINE__))

#ifdef NDEBUG
// Compiled (so the condition stays valid code) but never evaluated.
#define LC_DCHECK(condition) static_cast<void>(sizeof((condition) ? 1 : 0))
#else
#define LC_DCHECK(condition) LC_CHECK(condition)
#endif

// Both bounds of an index range in one check.
#define LC_CHECK_INDEX(index, size) LC_CHECK(static_cast<size_t>(index) < static_cast<size_t>(size))
#define LC_DCHECK_INDEX(index, size) LC_DCHECK(static_cast<size_t>(index) < static_cast<size_t>(size))
