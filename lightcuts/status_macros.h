#pragma once
// The project's one error-propagation helper for lc::Result / lc::Status
// (result.h): returns the error of an expression from the enclosing function,
// which must itself return a Result or a Status.
#include "lightcuts/result.h"

// Evaluates `expr` once; on error returns its lc::Error, kind included, to the caller.
#define LC_RETURN_IF_ERROR(expr)                                      \
    do {                                                              \
        auto&& lc_status_ = (expr);                                   \
        if (!lc_status_) return lc_status_.failure();                 \
    } while (0)
