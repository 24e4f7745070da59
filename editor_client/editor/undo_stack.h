#pragma once
// Undo and redo of light edits. Every edit stores the lights and selection as
// they were before it (a whole copy: simple, and an edit of N lights is O(N)
// anyway). The stack forgets its oldest entries beyond a count and a total
// light budget, so 10^6-light scenes cannot exhaust memory through undo.
#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "lightcuts/scene_light.h"

namespace lc::client {

struct EditSnapshot {
    std::string label;  // the edit this snapshot undoes, e.g. "add light 3"
    std::vector<SceneLight> lights;
    std::optional<size_t> selection;
};

class UndoStack {
public:
    explicit UndoStack(size_t max_entries = 64, size_t max_total_lights = 4u << 20)
        : max_entries_(max_entries), max_total_lights_(max_total_lights) {}

    // Records the state before a new edit; clears the redo side.
    void push(EditSnapshot before);
    // Takes the state to go back to; `current` goes onto the redo side.
    std::optional<EditSnapshot> undo(EditSnapshot current);
    // Takes the state to go forward to; `current` goes back onto the undo side.
    std::optional<EditSnapshot> redo(EditSnapshot current);
    void clear();

    bool can_undo() const { return !undo_.empty(); }
    bool can_redo() const { return !redo_.empty(); }
    size_t undo_depth() const { return undo_.size(); }
    size_t redo_depth() const { return redo_.size(); }
    // Label of the edit undo() would revert ("" when none).
    std::string next_undo_label() const { return undo_.empty() ? "" : undo_.back().label; }
    std::string next_redo_label() const { return redo_.empty() ? "" : redo_.back().label; }

private:
    void trim();

    size_t max_entries_;
    size_t max_total_lights_;
    std::deque<EditSnapshot> undo_;  // newest at the back
    std::deque<EditSnapshot> redo_;
};

}  // namespace lc::client
