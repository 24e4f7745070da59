// Human-readable names for the protocol's enums, used in logs, JSON and errors.
#include <type_traits>

#include "messages.h"

namespace lc {

const char* builder_name(BuilderKind kind) {
    switch (kind) {
        case BuilderKind::kOptimalPair: return "optimal-pair";
        case BuilderKind::kAgglomerative: return "agglomerative";
        case BuilderKind::kLbvh: return "lbvh";
    }
    return "unknown";
}

const char* representative_rule_name(RepresentativeRule rule) {
    switch (rule) {
        case RepresentativeRule::kIntensity: return "intensity";
        case RepresentativeRule::kThesisFirst: return "thesis-first";
    }
    return "unknown";
}

const char* pairing_mode_name(PairingMode mode) {
    switch (mode) {
        case PairingMode::kExact: return "exact";
        case PairingMode::kApproximate: return "approximate";
        case PairingMode::kAuto: return "auto";
    }
    return "unknown";
}

const char* indirect_method_name(IndirectMethod method) {
    switch (method) {
        case IndirectMethod::kOff: return "off";
        case IndirectMethod::kVpl: return "vpl";
        case IndirectMethod::kRadiosity: return "radiosity";
    }
    return "unknown";
}

const char* message_name(const Message& message) {
    return std::visit(
        [](const auto& m) -> const char* {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, HelloMsg>) return "Hello";
            else if constexpr (std::is_same_v<T, HelloAckMsg>) return "HelloAck";
            else if constexpr (std::is_same_v<T, OpenChannelMsg>) return "OpenChannel";
            else if constexpr (std::is_same_v<T, WriteChannelMsg>) return "WriteChannel";
            else if constexpr (std::is_same_v<T, CloseChannelMsg>) return "CloseChannel";
            else if constexpr (std::is_same_v<T, BakeRequestMsg>) return "BakeRequest";
            else if constexpr (std::is_same_v<T, ProgressMsg>) return "Progress";
            else if constexpr (std::is_same_v<T, WarningMsg>) return "Warning";
            else if constexpr (std::is_same_v<T, ErrorMsg>) return "Error";
            else if constexpr (std::is_same_v<T, CancelMsg>) return "Cancel";
            else if constexpr (std::is_same_v<T, BakeDoneMsg>) return "BakeDone";
            else if constexpr (std::is_same_v<T, StatusRequestMsg>) return "StatusRequest";
            else return "StatusReply";
        },
        message);
}

}  // namespace lc
