#!/usr/bin/env bash
# Open MPI's "remote shell" for the namespaced test hosts of netns_hosts.sh:
# `netns_rsh.sh [options] HOST COMMAND...` runs COMMAND (joined, through sh, as
# ssh would) inside HOST's namespace. Given to mpirun as
# `--mca plm_rsh_agent /path/to/netns_rsh.sh`; options ssh would take are ignored.
# It answers as ssh would over HOST's cable (netns_hosts.sh cable HOST):
#   down at the start: ssh's own error after ARP gives up (3 s), exit 255;
#   silent at the start (packets vanish): no answer at all;
#   pulled during the session: the command's end never reaches mpirun.
# A silent session ends when the cable is back, when mpirun ends it, or after 10 minutes.
set -euo pipefail
while [[ "${1:-}" == -* ]]; do shift; done
[[ $# -ge 2 ]] || { echo "usage: netns_rsh.sh HOST COMMAND..." >&2; exit 255; }
hosts_tool="$(dirname "$0")/netns_hosts.sh"
host="$1"; shift

stay_silent_while_unplugged() {
    for _ in $(seq 600); do
        [[ "$("$hosts_tool" cable "$host")" == up ]] && return 0
        sleep 1
    done
}

case "$("$hosts_tool" cable "$host")" in
    down) sleep 3; echo "ssh: connect to host $host port 22: No route to host" >&2; exit 255 ;;
    silent) stay_silent_while_unplugged; exit 255 ;;
esac
status=0
"$hosts_tool" exec "$host" sh -c "$*" || status=$?
stay_silent_while_unplugged
exit "$status"
