#include "editor_client/editor/editor_command.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "editor_client/editor/editor_session.h"

namespace lc::client {
namespace {

std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

// Reads the words of one command, each error naming the command and argument.
class Args {
public:
    Args(std::string_view name, std::vector<std::string_view> words)
        : name_(name), words_(std::move(words)) {}

    size_t count() const { return words_.size(); }
    Status expect(size_t min, size_t max, std::string_view usage) const {
        if (words_.size() >= min && words_.size() <= max) return Ok{};
        return make_error(
            std::string(name_) + " takes " +
            (min == max ? std::to_string(min)
                        : std::to_string(min) + " to " + std::to_string(max)) +
            " arguments, got " + std::to_string(words_.size()) +
            (usage.empty() ? std::string()
                           : " (usage: " + std::string(name_) + " " + std::string(usage) + ")"));
    }
    std::string_view word(size_t i) const { return words_[i]; }

    Result<float> number(size_t i, std::string_view what) const {
        const std::string_view w = words_[i];
        float value = 0.0f;
        auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
        if (ec != std::errc() || ptr != w.data() + w.size() || !std::isfinite(value))
            return make_error(std::string(name_) + ": " + std::string(what) + " '" +
                              std::string(w) + "' is not a finite number");
        return value;
    }
    Result<uint64_t> integer(size_t i, std::string_view what) const {
        const std::string_view w = words_[i];
        uint64_t value = 0;
        auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
        if (ec != std::errc() || ptr != w.data() + w.size())
            return make_error(std::string(name_) + ": " + std::string(what) + " '" +
                              std::string(w) + "' is not a non-negative integer");
        return value;
    }
    Result<glm::vec3> vec3(size_t first, std::string_view what) const {
        glm::vec3 v(0.0f);
        for (int a = 0; a < 3; ++a) {
            Result<float> c = number(first + a, std::string(what) + " " + "xyz"[a]);
            if (!c) return make_error(c.error());
            v[a] = c.value();
        }
        return v;
    }

private:
    std::string_view name_;
    std::vector<std::string_view> words_;
};

#define LC_TRY(var, expr)                                       \
    auto var##_result = (expr);                                 \
    if (!var##_result) return make_error(var##_result.error()); \
    auto var = std::move(var##_result).value()

Result<std::optional<EditorCommand>> parse_add_light(const Args& args) {
    const char* usage = "TYPE X Y Z R G B INTENSITY [RANGE] [classic]";
    if (Status ok = args.expect(8, 10, usage); !ok) return make_error(ok.error());
    SceneLight light;
    LC_TRY(type, parse_light_type(args.word(0)));
    light.type = type;
    LC_TRY(position, args.vec3(1, "position"));
    LC_TRY(color, args.vec3(4, "colour"));
    LC_TRY(intensity, args.number(7, "intensity"));
    light.position = position;
    light.color = color;
    light.intensity = intensity;
    size_t next = 8;
    if (next < args.count() && args.word(next) != "classic") {
        LC_TRY(range, args.number(next, "range"));
        light.range = range;
        ++next;
    }
    if (next < args.count()) {
        if (args.word(next) != "classic")
            return make_error("add-light: unexpected '" + std::string(args.word(next)) +
                              "' (usage: add-light " + usage + ")");
        light.classic = true;
        ++next;
    }
    if (next != args.count())
        return make_error("add-light: too many arguments (usage: add-light " + std::string(usage) +
                          ")");
    // Oriented lights shine straight down, spots with the generated cone.
    if (light.type != LightType::kPoint) light.direction = {0.0f, -1.0f, 0.0f};
    if (light.type == LightType::kSpot) {
        light.inner_cone_angle = kGeneratedSpotInner;
        light.outer_cone_angle = kGeneratedSpotOuter;
    }
    return std::optional<EditorCommand>(cmd::AddLight{light});
}

Result<std::optional<EditorCommand>> parse_add_lights(const Args& args) {
    if (Status ok = args.expect(3, 6, "COUNT LAYOUT SEED [TYPE [INTENSITY [RANGE]]]"); !ok)
        return make_error(ok.error());
    cmd::AddLights c;
    LC_TRY(count, args.integer(0, "count"));
    if (count == 0 || count > (1u << 24))
        return make_error("add-lights: count " + std::to_string(count) +
                          " is outside [1, 16777216]");
    c.count = static_cast<uint32_t>(count);
    LC_TRY(layout, parse_light_layout(args.word(1)));
    c.layout = layout;
    LC_TRY(seed, args.integer(2, "seed"));
    c.seed = seed;
    if (args.count() > 3) {
        LC_TRY(type, parse_light_type_choice(args.word(3)));
        c.type = type;
    }
    if (args.count() > 4) {
        LC_TRY(intensity, args.number(4, "intensity"));
        c.intensity = intensity;
    }
    if (args.count() > 5) {
        LC_TRY(range, args.number(5, "range"));
        c.range = range;
    }
    return std::optional<EditorCommand>(c);
}

Result<size_t> parse_index(const Args& args, std::string_view usage) {
    if (Status ok = args.expect(1, 1, usage); !ok) return make_error(ok.error());
    LC_TRY(index, args.integer(0, "index"));
    return static_cast<size_t>(index);
}

Result<std::optional<EditorCommand>> no_args(const Args& args, EditorCommand command) {
    if (Status ok = args.expect(0, 0, ""); !ok) return make_error(ok.error());
    return std::optional<EditorCommand>(std::move(command));
}

// The rest of the line after the command word, so paths may hold spaces.
Result<std::filesystem::path> parse_path(std::string_view name, std::string_view line) {
    std::string_view rest = line.substr(line.find(name) + name.size());
    while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
    while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t' || rest.back() == '\r'))
        rest.remove_suffix(1);
    if (rest.empty()) return make_error(std::string(name) + " needs a PATH");
    return std::filesystem::path(std::string(rest));
}

// error-ratio, max-cut, realtime-cut, realtime-rays and exposure: one number each.
Result<std::optional<EditorCommand>> parse_view_setting(std::string_view name, const Args& args) {
    using R = std::optional<EditorCommand>;
    if (name == "error-ratio") {
        if (Status ok = args.expect(1, 1, "RATIO"); !ok) return make_error(ok.error());
        LC_TRY(ratio, args.number(0, "ratio"));
        return R(cmd::ErrorRatio{ratio});
    }
    if (name == "max-cut") {
        if (Status ok = args.expect(1, 1, "N"); !ok) return make_error(ok.error());
        LC_TRY(max_cut, args.integer(0, "N"));
        if (max_cut > UINT32_MAX) return make_error("max-cut: N is too large");
        return R(cmd::MaxCut{static_cast<uint32_t>(max_cut)});
    }
    if (name == "realtime-cut") {
        if (Status ok = args.expect(1, 1, "K"); !ok) return make_error(ok.error());
        LC_TRY(nodes, args.integer(0, "K"));
        if (nodes > UINT32_MAX) return make_error("realtime-cut: K is too large");
        return R(cmd::RealtimeCut{static_cast<uint32_t>(nodes)});
    }
    if (name == "realtime-rays") {
        if (Status ok = args.expect(1, 1, "S"); !ok) return make_error(ok.error());
        LC_TRY(rays, args.integer(0, "S"));
        if (rays > UINT32_MAX) return make_error("realtime-rays: S is too large");
        return R(cmd::RealtimeRays{static_cast<uint32_t>(rays)});
    }
    // exposure
    if (Status ok = args.expect(1, 1, "E"); !ok) return make_error(ok.error());
    LC_TRY(exposure, args.number(0, "exposure"));
    return R(cmd::Exposure{exposure});
}

// camera EX EY EZ TX TY TZ FOVY (degrees).
Result<std::optional<EditorCommand>> parse_camera(const Args& args) {
    using R = std::optional<EditorCommand>;
    if (Status ok = args.expect(7, 7, "EX EY EZ TX TY TZ FOVY"); !ok)
        return make_error(ok.error());
    cmd::Camera c;
    LC_TRY(eye, args.vec3(0, "eye"));
    LC_TRY(target, args.vec3(3, "target"));
    LC_TRY(fovy, args.number(6, "fovy"));
    if (fovy <= 0.0f || fovy >= 178.0f)
        return make_error("camera: fovy " + std::to_string(fovy) +
                          " degrees is outside (0, 178)");
    c.camera.eye = eye;
    c.camera.target = target;
    c.camera.yfov = fovy * std::numbers::pi_v<float> / 180.0f;
    return R(c);
}

// screenshot, save and save-view: a PATH, which may hold spaces.
Result<std::optional<EditorCommand>> parse_file_command(std::string_view name, std::string_view line) {
    using R = std::optional<EditorCommand>;
    LC_TRY(path, parse_path(name, line));
    if (name == "screenshot") return R(cmd::Screenshot{path});
    if (name == "save") return R(cmd::Save{path});
    return R(cmd::SaveView{path});
}

}  // namespace

Result<std::optional<EditorCommand>> parse_editor_command(std::string_view line) {
    if (const size_t hash = line.find('#'); hash != std::string_view::npos)
        line = line.substr(0, hash);
    std::vector<std::string_view> words = split_words(line);
    if (words.empty()) return std::optional<EditorCommand>();
    const std::string_view name = words.front();
    const Args args(name, std::vector<std::string_view>(words.begin() + 1, words.end()));
    using R = std::optional<EditorCommand>;

    if (name == "add-light") return parse_add_light(args);
    if (name == "add-lights") return parse_add_lights(args);
    if (name == "remove-light") {
        LC_TRY(index, parse_index(args, "INDEX"));
        return R(cmd::RemoveLight{index});
    }
    if (name == "move-light") {
        if (Status ok = args.expect(4, 4, "INDEX X Y Z"); !ok) return make_error(ok.error());
        LC_TRY(index, args.integer(0, "index"));
        LC_TRY(position, args.vec3(1, "position"));
        return R(cmd::MoveLight{static_cast<size_t>(index), position});
    }
    if (name == "select") {
        LC_TRY(index, parse_index(args, "INDEX"));
        return R(cmd::Select{index});
    }
    if (name == "undo") return no_args(args, cmd::Undo{});
    if (name == "redo") return no_args(args, cmd::Redo{});
    if (name == "bake") return no_args(args, cmd::Bake{});
    if (name == "cancel-bake") return no_args(args, cmd::CancelBake{});
    if (name == "quit") return no_args(args, cmd::Quit{});
    if (name == "mode" || name == "criterion" || name == "representatives") {
        if (Status ok = args.expect(1, 1, "NAME"); !ok) return make_error(ok.error());
        if (name == "mode") return R(cmd::Mode{std::string(args.word(0))});
        if (name == "representatives") return R(cmd::RepresentativesChoice{std::string(args.word(0))});
        return R(cmd::Criterion{std::string(args.word(0))});
    }
    if (name == "error-ratio" || name == "max-cut" || name == "realtime-cut" || name == "realtime-rays" ||
        name == "exposure")
        return parse_view_setting(name, args);
    if (name == "camera") return parse_camera(args);
    if (name == "screenshot" || name == "save" || name == "save-view") return parse_file_command(name, line);
    if (name == "wait-refined") return no_args(args, cmd::WaitRefined{});
    if (name == "wait-frames") {
        if (Status ok = args.expect(1, 1, "N"); !ok) return make_error(ok.error());
        LC_TRY(frames, args.integer(0, "N"));
        if (frames > UINT32_MAX) return make_error("wait-frames: N is too large");
        return R(cmd::WaitFrames{static_cast<uint32_t>(frames)});
    }
    return make_error("unknown command '" + std::string(name) +
                      "' (add-light, add-lights, remove-light, move-light, select, undo, redo, "
                      "bake, cancel-bake, mode, criterion, error-ratio, max-cut, realtime-cut, realtime-rays, representatives, exposure, "
                      "camera, screenshot, save, save-view, wait-frames, wait-refined, quit)");
}

Result<std::vector<ScriptLine>> parse_editor_script(std::string_view text,
                                                    const std::string& name) {
    std::vector<ScriptLine> lines;
    size_t number = 0;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find('\n', start), text.size());
        std::string_view line = text.substr(start, end - start);
        ++number;
        Result<std::optional<EditorCommand>> command = parse_editor_command(line);
        if (!command)
            return make_error(name + ":" + std::to_string(number) + ": " + command.error());
        if (command.value())
            lines.push_back(ScriptLine{number, std::string(line), std::move(*command.value())});
        if (end == text.size()) break;
        start = end + 1;
    }
    return lines;
}

Result<std::vector<ScriptLine>> load_editor_script(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error("cannot open script " + path.string());
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return make_error("cannot read script " + path.string());
    return parse_editor_script(text.str(), path.string());
}

#undef LC_TRY

}  // namespace lc::client
