#include "editor_client/scene/gltf/writer/gltf_document_output.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <string_view>
#include <utility>

#include "editor_client/scene/gltf/writer/gltf_glb_container.h"

namespace lc::client {
namespace {

using json = nlohmann::json;

std::string base64_encode(std::span<const uint8_t> bytes) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v = (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    if (i + 1 == bytes.size()) {
        const uint32_t v = uint32_t(bytes[i]) << 16;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == bytes.size()) {
        const uint32_t v = (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8);
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

Status write_file_atomically(const std::filesystem::path& out,
                             const std::function<void(std::ostream&)>& write) {
    std::error_code ec;
    const std::filesystem::path dir = out.has_parent_path() ? out.parent_path() : ".";
    if (!std::filesystem::is_directory(dir, ec)) {
        return make_error("cannot write " + out.string() + ": folder " + dir.string() + " does not exist");
    }
    std::filesystem::path tmp = out;
    tmp += ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
        if (!file) return make_error("cannot write " + out.string() + ": cannot create the file");
        write(file);
        file.flush();
        if (!file) {
            file.close();
            std::filesystem::remove(tmp, ec);
            return make_error("cannot write " + out.string() + ": write failed (disk full?)");
        }
    }
    std::filesystem::rename(tmp, out, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        return make_error("cannot write " + out.string() + ": " + ec.message());
    }
    return Ok{};
}

// Each marker stands once in the text: no string of the scene's spells one.
bool markers_stand_alone(const std::string& text, const std::vector<StreamedArray>& arrays) {
    for (const StreamedArray& array : arrays) {
        const std::string quoted = json(array.marker).dump();
        const size_t first = text.find(quoted);
        if (first == std::string::npos || text.find(quoted, first + 1) != std::string::npos) return false;
    }
    return true;
}

// A scene string that spells a marker: the arrays are made whole in the document.
std::string dump_whole(json& doc, int indent, const std::vector<StreamedArray>& arrays) {
    for (const StreamedArray& array : arrays) {
        json& elements = doc[array.array];
        elements.erase(elements.size() - 1);
        for (size_t i = 0; i < array.count; ++i) elements.push_back(array.element(i));
    }
    return doc.dump(indent);
}

// One streamed array's elements, where its marker stood. An element dumped
// alone is indented from column 0: every line it breaks is moved right to
// where the marker stood, which is the text dump(indent) gives for the whole array.
void write_elements(const StreamedArray& array, int indent, const std::string& break_and_indent,
                    const std::function<void(std::string_view)>& out) {
    for (size_t i = 0; i < array.count; ++i) {
        if (i > 0) out(indent < 0 ? "," : "," + break_and_indent);
        std::string element = array.element(i).dump(indent);
        if (indent >= 0) {
            for (size_t nl = element.find('\n'); nl != std::string::npos; nl = element.find('\n', nl + 1)) {
                element.replace(nl, 1, break_and_indent);
                nl += break_and_indent.size() - 1;
            }
        }
        out(element);
    }
}

// `doc`'s text as dump(indent) gives it, each marker's array elements in its
// place, handed to `out` a piece at a time.
void write_json(json& doc, int indent, const std::vector<StreamedArray>& arrays,
                const std::function<void(std::string_view)>& out) {
    const std::string text = doc.dump(indent);
    if (!markers_stand_alone(text, arrays)) {
        out(dump_whole(doc, indent, arrays));
        return;
    }
    std::vector<std::pair<size_t, const StreamedArray*>> places;
    for (const StreamedArray& array : arrays)
        places.emplace_back(text.find(json(array.marker).dump()), &array);
    std::sort(places.begin(), places.end());
    size_t at = 0;
    for (const auto& [place, array] : places) {
        out(std::string_view(text).substr(at, place - at));
        const size_t line_start = text.rfind('\n', place) + 1;
        write_elements(*array, indent, "\n" + text.substr(line_start, place - line_start), out);
        at = place + json(array->marker).dump().size();
    }
    out(std::string_view(text).substr(at));
}

}  // namespace

bool is_glb_path(const std::filesystem::path& out) {
    std::string ext = out.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext == ".glb";
}

Status write_gltf_document(json doc, std::span<const uint8_t> bin, int bin_buffer,
                           const std::filesystem::path& out, const std::vector<StreamedArray>& arrays) {
    if (is_glb_path(out)) {
        std::string text;
        write_json(doc, -1, arrays, [&](std::string_view piece) { text += piece; });
        const std::vector<uint8_t> bytes = encode_glb(std::move(text), bin);
        return write_file_atomically(out, [&](std::ostream& file) {
            file.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        });
    }
    if (bin_buffer >= 0) {
        doc["buffers"][size_t(bin_buffer)]["uri"] =
            "data:application/octet-stream;base64," + base64_encode(bin);
    }
    return write_file_atomically(out, [&](std::ostream& file) {
        write_json(doc, 2, arrays,
                   [&](std::string_view piece) { file.write(piece.data(), std::streamsize(piece.size())); });
        file << "\n";
    });
}

}  // namespace lc::client
