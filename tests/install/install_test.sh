#!/usr/bin/env bash
# The installed programs work from their installed paths alone: installs the
# build into a scratch root (DESTDIR), checks the file list, then runs the
# installed lightmass_server --version, serves from it and bakes with the
# installed editor_client, in one process and over 2 MPI ranks (the server
# must find lightmass_rank under libexec/lightcuts/, not beside itself).
# Usage: bash tests/install/install_test.sh BUILD_DIR
set -euo pipefail
build_dir="$(cd "${1:?usage: install_test.sh BUILD_DIR}" && pwd)"
root="$(mktemp -d -t lightcuts-install-XXXXXX)"
server_pid=""
trap '[ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null; rm -rf "$root"' EXIT
fail() { echo "install test: $*" >&2; exit 1; }

DESTDIR="$root" cmake --install "$build_dir" --prefix /usr > "$root.install.log" 2>&1 ||
  { cat "$root.install.log"; rm -f "$root.install.log"; fail "cmake --install failed"; }
rm -f "$root.install.log"

# Ours and nothing else: the programs, the rank program, the service, the docs.
expected=(
  usr/bin/lightmass_server usr/bin/editor_client
  usr/lib/systemd/system/lightmass_server.service etc/lightcuts/lightmass_server.conf
  usr/share/doc/lightcuts/README.md usr/share/doc/lightcuts/OPERATING.md
)
[ -x "$build_dir/bin/lightmass_rank" ] && expected+=(usr/libexec/lightcuts/lightmass_rank)
for f in "${expected[@]}"; do [ -e "$root/$f" ] || fail "not installed: /$f"; done
ours='usr/bin/(lightmass_server|editor_client)|usr/libexec/lightcuts/lightmass_rank'
ours+='|usr/lib/systemd/system/lightmass_server\.service|etc/lightcuts/lightmass_server\.conf'
ours+='|usr/share/doc/lightcuts/.*\.(md|png)'
unexpected=$(cd "$root" && find . -type f | sed 's|^\./||' | grep -v -E "^($ours)\$" || true)
[ -z "$unexpected" ] || fail "installed files outside the list: $unexpected"

bin="$root/usr/bin"
version=$("$bin/lightmass_server" --version)
[[ "$version" =~ ^lightmass_server\ [0-9]+\.[0-9]+\.[0-9]+$ ]] || fail "lightmass_server --version said '$version'"
[ "$("$bin/editor_client" --version)" = "editor_client ${version#lightmass_server }" ] ||
  fail "editor_client --version is not '${version#lightmass_server }'"

work="$root/work"
mkdir -p "$work"
"$bin/editor_client" make-scene thesis-fig91 -o "$work/fig91.gltf" > /dev/null
mpi_args=()
[ "$(id -u)" -eq 0 ] && mpi_args+=(--mpi-arg=--allow-run-as-root)  # Open MPI refuses root without it
"$bin/lightmass_server" --listen 127.0.0.1:0 --port-file "$work/port" --quiet "${mpi_args[@]}" &
server_pid=$!
for _ in $(seq 1 100); do [ -s "$work/port" ] && break; sleep 0.1; done
[ -s "$work/port" ] || fail "the installed server did not start"
server="127.0.0.1:$(cat "$work/port")"

"$bin/editor_client" bake "$work/fig91.gltf" --server "$server" -o "$work/one.lcut" > "$work/bake.txt" ||
  { cat "$work/bake.txt"; fail "a bake on the installed server failed"; }
grep -q '^baked ' "$work/bake.txt" || fail "no summary: $(cat "$work/bake.txt")"
if [ -e "$root/usr/libexec/lightcuts/lightmass_rank" ] && command -v mpirun > /dev/null; then
  "$bin/editor_client" bake "$work/fig91.gltf" --server "$server" --ranks 2 -o "$work/two.lcut" \
    > "$work/ranks.txt" 2>&1 || { cat "$work/ranks.txt"; fail "a bake over 2 ranks on the installed server failed"; }
  cmp -s "$work/one.lcut" "$work/two.lcut" || fail "2 ranks baked other bytes than one process"
else
  echo "install test: no mpirun or lightmass_rank: the bake over ranks is not checked"
fi
echo "install test: $version installed under a scratch root, served and baked"
