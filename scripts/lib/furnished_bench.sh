# Shared by scripts/bench/speedup.sh and scripts/bench/supersampling.sh (sourced, not run).

# build_bench_client BUILD_DIR: configures BUILD_DIR when it has no cache yet,
# builds the client and the server, and sets LC_CLIENT to the client.
build_bench_client() {
    local build_dir=$1
    if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
        cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
    fi
    cmake --build "$build_dir" --target editor_client lightmass_server -j "$(nproc)"
    LC_CLIENT="$build_dir/bin/editor_client"
}

# make_furnished_room DIR LIGHTS: DIR/scene.gltf, the furnished room with LIGHTS
# unbounded point lights at random through the volume (0.3 m from every
# surface, 819.2 cd in total), and DIR/tree.lcut, its agglomerative tree.
make_furnished_room() {
    local dir=$1 lights=$2 intensity
    intensity="$(python3 -c "print(819.2 / $lights)")"
    "$LC_CLIENT" make-scene furnished-room -o "$dir/empty.gltf" >/dev/null
    "$LC_CLIENT" add-lights "$dir/empty.gltf" --count "$lights" --layout random --type point \
        --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity "$intensity" --range 0 -o "$dir/scene.gltf" \
        >/dev/null
    "$LC_CLIENT" bake "$dir/scene.gltf" --spawn-server --builder agglomerative -o "$dir/tree.lcut" \
        >/dev/null 2>&1
}
