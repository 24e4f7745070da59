#pragma once
// Runs editor commands (from `--script FILE`, or typed) against a session,
// one frame at a time, so the window keeps drawing while a scripted bake runs.
// Edits and view changes go through EditorSession, exactly as the panels do;
// what needs the window (screenshots, closing) goes through an EditorHost.
#include <filesystem>
#include <string>
#include <vector>

#include "editor_client/editor/editor_command.h"
#include "editor_client/editor/editor_session.h"
#include "lightcuts/result.h"

namespace lc::client {

// What the window side of the editor provides to commands.
class EditorHost {
public:
    virtual ~EditorHost() = default;
    // Renders the session's current state at full resolution and saves a PNG
    // (a PFM of the linear radiance when the path ends in .pfm).
    virtual Status screenshot(const std::filesystem::path& path) = 0;
    virtual void request_quit() = 0;
    // A host that refines the view over frames saves it as refined so far and
    // says when it is complete; without refinement the view is always
    // complete and saving it is a screenshot.
    virtual Status save_view(const std::filesystem::path& path) { return screenshot(path); }
    virtual bool view_refined() const { return true; }
};

// Executes one command now. A `bake` only starts the bake; the caller waits
// (ScriptRunner does). Lights added by add-lights go into the scene bounds.
Status execute_editor_command(const EditorCommand& command, EditorSession& session,
                              EditorHost& host);

enum class ScriptState {
    kRunning,   // more commands to run
    kWaiting,   // a scripted bake, frames or the refinement to wait for; step again next frame
    kFinished,  // every command ran
    kQuit,      // a `quit` command ran
    kFailed,    // a command failed: see error()
};

class ScriptRunner {
public:
    ScriptRunner(std::vector<ScriptLine> lines, std::string name);

    // Runs commands until the script ends, quits, fails, or waits for a bake.
    // Call once per frame after the session's poll_bake().
    ScriptState step(EditorSession& session, EditorHost& host);
    ScriptState state() const { return state_; }
    // "script.txt:4: bake failed: ..." when state() is kFailed.
    const std::string& error() const { return error_; }
    size_t commands_run() const { return next_; }

private:
    ScriptState fail(const ScriptLine& line, const std::string& message);

    std::vector<ScriptLine> lines_;
    std::string name_;
    size_t next_ = 0;
    bool waiting_for_bake_ = false;
    uint32_t frames_to_wait_ = 0;
    bool waiting_for_refinement_ = false;
    ScriptState state_ = ScriptState::kRunning;
    std::string error_;
};

// Without a window loop: steps the runner, waiting for bakes in between.
ScriptState run_script_to_end(ScriptRunner& runner, EditorSession& session, EditorHost& host);

}  // namespace lc::client
