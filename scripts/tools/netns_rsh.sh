#!/usr/bin/env bash
# Open MPI's "remote shell" for the namespaced test hosts of netns_hosts.sh:
# `netns_rsh.sh [options] HOST COMMAND...` runs COMMAND (joined, through sh, as
# ssh would) inside HOST's namespace. Given to mpirun as
# `--mca plm_rsh_agent /path/to/netns_rsh.sh`; options ssh would take are ignored.
set -euo pipefail
while [[ "${1:-}" == -* ]]; do shift; done
[[ $# -ge 2 ]] || { echo "usage: netns_rsh.sh HOST COMMAND..." >&2; exit 255; }
host="$1"; shift
exec "$(dirname "$0")/netns_hosts.sh" exec "$host" sh -c "$*"
