#include "editor_client/editor/undo_stack.h"

#include <utility>

namespace lc::client {

void UndoStack::push(EditSnapshot before) {
    undo_.push_back(std::move(before));
    redo_.clear();
    trim();
}

std::optional<EditSnapshot> UndoStack::undo(EditSnapshot current) {
    if (undo_.empty()) return std::nullopt;
    EditSnapshot target = std::move(undo_.back());
    undo_.pop_back();
    current.label = target.label;  // redoing it repeats the same edit
    redo_.push_back(std::move(current));
    return target;
}

std::optional<EditSnapshot> UndoStack::redo(EditSnapshot current) {
    if (redo_.empty()) return std::nullopt;
    EditSnapshot target = std::move(redo_.back());
    redo_.pop_back();
    current.label = target.label;
    undo_.push_back(std::move(current));
    trim();
    return target;
}

void UndoStack::clear() {
    undo_.clear();
    redo_.clear();
}

void UndoStack::trim() {
    size_t total = 0;
    for (const EditSnapshot& s : undo_) total += s.lights.size();
    for (const EditSnapshot& s : redo_) total += s.lights.size();
    // Always keep the newest undo entry: "undo the last edit" must work.
    while (undo_.size() > 1 && (undo_.size() > max_entries_ || total > max_total_lights_)) {
        total -= undo_.front().lights.size();
        undo_.pop_front();
    }
}

}  // namespace lc::client
