// A scanner over the JSON grammar's structure only: strings (with their
// escapes), nesting and the separators at the levels it walks. Everything it
// skips lands in a parser's input (a run of elements, or the remainder), so
// a malformed value is still refused, by that parser.
#include "editor_client/scene/gltf/gltf_json_sections.h"

#include <array>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace lc::client {
namespace {

bool is_space(char c) {
    return c == ' ' || c == '\n' || c == '\r' || c == '\t';
}

bool is_bracket_or_quote(char c) {
    return c == '"' || c == '{' || c == '}' || c == '[' || c == ']';
}

// The offset of the first of " { } [ ] at or after `from` (text.size() if
// none): what nesting depends on. Elements are mostly indentation, numbers
// and keys, so sixteen bytes are looked at a time where SSE2 is there.
size_t next_bracket_or_quote(std::string_view text, size_t from) {
#if defined(__SSE2__)
    const __m128i quote = _mm_set1_epi8('"');
    // '[' and ']' are '{' and '}' without bit 0x20.
    const __m128i case_bit = _mm_set1_epi8(0x20);
    const __m128i open = _mm_set1_epi8('{');
    const __m128i close = _mm_set1_epi8('}');
    for (; from + 16 <= text.size(); from += 16) {
        const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(text.data() + from));
        const __m128i folded = _mm_or_si128(bytes, case_bit);
        const __m128i hits =
            _mm_or_si128(_mm_cmpeq_epi8(bytes, quote),
                         _mm_or_si128(_mm_cmpeq_epi8(folded, open), _mm_cmpeq_epi8(folded, close)));
        if (const int mask = _mm_movemask_epi8(hits); mask != 0) {
            return from + size_t(__builtin_ctz(unsigned(mask)));
        }
    }
#endif
    while (from < text.size() && !is_bracket_or_quote(text[from])) ++from;
    return from;
}

class SectionScanner {
public:
    SectionScanner(std::string_view json, size_t run_bytes, const GltfSectionHandlers& handlers)
        : text_(json), run_bytes_(run_bytes), handlers_(handlers) {}

    std::optional<std::string> run() {
        if (!object([&](std::string_view key) { return top_level_value(key); })) return std::nullopt;
        skip_space();
        if (at_ != text_.size()) return std::nullopt;
        remainder_.append(text_.substr(cut_end_));
        return std::move(remainder_);
    }

private:
    void skip_space() {
        while (at_ < text_.size() && is_space(text_[at_])) ++at_;
    }

    bool next_is(char c) {
        skip_space();
        return at_ < text_.size() && text_[at_] == c;
    }

    bool expect(char c) {
        if (!next_is(c)) return false;
        ++at_;
        return true;
    }

    // At an opening quote: moves past the closing one.
    bool skip_string() {
        size_t from = at_ + 1;
        for (;;) {
            const void* quote = std::memchr(text_.data() + from, '"', text_.size() - from);
            if (!quote) return false;
            const size_t q = size_t(static_cast<const char*>(quote) - text_.data());
            size_t backslashes = 0;
            while (q - backslashes > at_ + 1 && text_[q - backslashes - 1] == '\\') ++backslashes;
            from = q + 1;
            if (backslashes % 2 == 0) break;
        }
        at_ = from;
        return true;
    }

    // A key as written; keys with escapes are refused (the node reader compares them as written).
    bool plain_key(std::string_view& key) {
        if (!next_is('"')) return false;
        const size_t begin = at_ + 1;
        if (!skip_string()) return false;
        key = text_.substr(begin, at_ - 1 - begin);
        return key.find('\\') == std::string_view::npos;
    }

    // Any value: a string, an object or array (by nesting depth; the brackets'
    // kinds are the parser's to check), or a literal or number up to the next separator.
    bool skip_value() {
        skip_space();
        if (at_ >= text_.size()) return false;
        const char c = text_[at_];
        if (c == '"') return skip_string();
        if (c == '{' || c == '[') {
            size_t depth = 0;
            while ((at_ = next_bracket_or_quote(text_, at_)) < text_.size()) {
                const char d = text_[at_];
                if (d == '"') {
                    if (!skip_string()) return false;
                    continue;
                }
                ++at_;
                if (d == '{' || d == '[')
                    ++depth;
                else if (--depth == 0)
                    return true;
            }
            return false;
        }
        const size_t begin = at_;
        while (at_ < text_.size()) {
            const char d = text_[at_];
            if (is_space(d) || d == ',' || d == '}' || d == ']') break;
            ++at_;
        }
        return at_ > begin;
    }

    // An object whose values `value(key)` reads.
    template <typename Value>
    bool object(Value&& value) {
        if (!expect('{')) return false;
        if (expect('}')) return true;
        do {
            std::string_view key;
            if (!plain_key(key) || !expect(':') || !value(key)) return false;
        } while (expect(','));
        return expect('}');
    }

    bool top_level_value(std::string_view key) {
        if (key == "nodes") return section(GltfSection::kNodes);
        if (key == "scenes") return section(GltfSection::kScenes);
        if (key == "extensions") {
            if (seen_extensions_) return false;
            seen_extensions_ = true;
            return object([&](std::string_view name) {
                if (name != "KHR_lights_punctual") return skip_value();
                if (seen_lights_punctual_) return false;
                seen_lights_punctual_ = true;
                return object([&](std::string_view field) {
                    return field == "lights" ? section(GltfSection::kLights) : skip_value();
                });
            });
        }
        return skip_value();
    }

    // An array of one section: its elements go to the handler in runs, its
    // text leaves the remainder.
    bool section(GltfSection which) {
        bool& seen = seen_sections_[size_t(which)];
        if (seen || !next_is('[')) return false;
        seen = true;
        remainder_.append(text_.substr(cut_end_, at_ - cut_end_));
        remainder_ += "[]";
        ++at_;
        if (!expect(']')) {
            skip_space();
            size_t run_begin = at_;
            for (;;) {
                if (!skip_value()) return false;
                const size_t element_end = at_;
                const bool more = expect(',');
                if (!more && !next_is(']')) return false;
                if (!more || element_end - run_begin >= run_bytes_) {
                    if (!handlers_.on_elements(which, text_.substr(run_begin, element_end - run_begin))) {
                        return false;
                    }
                    if (handlers_.on_consumed) handlers_.on_consumed(element_end);
                    skip_space();
                    run_begin = at_;
                }
                if (!more) break;
            }
            ++at_;
        }
        cut_end_ = at_;
        return true;
    }

    std::string_view text_;
    size_t run_bytes_;
    const GltfSectionHandlers& handlers_;
    size_t at_ = 0;
    size_t cut_end_ = 0;  // the remainder holds the text before this offset
    std::string remainder_;
    std::array<bool, 3> seen_sections_{};
    bool seen_extensions_ = false;
    bool seen_lights_punctual_ = false;
};

}  // namespace

std::optional<std::string> split_gltf_sections(std::string_view json, size_t run_bytes,
                                               const GltfSectionHandlers& handlers) {
    return SectionScanner(json, run_bytes, handlers).run();
}

}  // namespace lc::client
