#pragma once
// The client's imported tree. An import either replaces the tree whole or
// leaves it untouched: a failed or cancelled bake never loses the previous one.
#include <cstdint>
#include <filesystem>
#include <memory>

#include "editor_client/bake/bake_client.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/result.h"

namespace lc::client {

class TreeStore {
public:
    TreeStore() : tree_(std::make_shared<const LightTree>()) {}

    std::shared_ptr<const LightTree> current() const { return tree_; }
    // Increments on every successful import.
    uint64_t generation() const { return generation_; }

    // Takes the bake's tree when the bake succeeded; otherwise returns its error.
    Status import(Result<BakeOutcome> outcome);
    // Reads a result channel dump (bake -o), validates it, then swaps it in.
    Status import_dump(const std::filesystem::path& path);

private:
    std::shared_ptr<const LightTree> tree_;
    uint64_t generation_ = 0;
};

}  // namespace lc::client
