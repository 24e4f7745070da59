#!/usr/bin/env bash
# Test hosts on one machine: each "host" is a Linux network namespace with its
# own loopback, its own address on a shared bridge and, when entered through
# this script, its own host name, so Open MPI sees N machines that reach each
# other only over TCP. Root only (ip netns). Everything it makes is named by
# the prefix and removed by `down`.
#   netns_hosts.sh up N            hosts PREFIX1..PREFIXN at SUBNET.1..N/24 on the bridge
#                                  in namespace PREFIXnet (the root namespace is untouched)
#   netns_hosts.sh down N          kill what still runs in them, remove them (idempotent)
#   netns_hosts.sh exec HOST CMD.. run CMD in HOST (its hostname is HOST)
#   netns_hosts.sh link HOST up|down   plug or pull HOST's cable (its bridge port)
#   netns_hosts.sh link HOST silent    pull it so that HOST's packets vanish instead of failing
#                                  at once (its neighbours pinned): a host behind a dropping firewall
#   netns_hosts.sh cable HOST      prints the state of HOST's cable: up, down or silent
#   netns_hosts.sh mpi-args        mpirun's arguments for these hosts, one a line
# The rsh agent that lets mpirun start its daemons "remotely" is netns_rsh.sh.
# env: LC_NETNS_PREFIX (default lchost), LC_NETNS_SUBNET (first three octets, default 10.213.7)
set -euo pipefail
prefix="${LC_NETNS_PREFIX:-lchost}"
subnet="${LC_NETNS_SUBNET:-10.213.7}"
net="${prefix}net"

usage() { sed -n '2,17p' "$0" >&2; exit 2; }

# The bridge port that carries HOST's cable: "p-" + the host's name fits IFNAMSIZ (15).
port_of() { echo "p-$1"; }
[[ "$prefix" =~ ^[a-z][a-z0-9]{0,9}$ ]] || { echo "netns_hosts: LC_NETNS_PREFIX must be 1-10 of a-z0-9" >&2; exit 2; }

host_up() {
    local i="$1" host="$prefix$1" port
    port="$(port_of "$host")"
    ip netns add "$host"
    ip -n "$net" link add "$port" type veth peer name eth0 netns "$host"
    ip -n "$net" link set "$port" master br0 up
    ip -n "$host" link set lo up
    ip -n "$host" addr add "$subnet.$i/24" dev eth0
    ip -n "$host" link set eth0 up
    # Keepalives only probe an idle connection: a cable pulled while mpirun and a daemon have data
    # in flight is noticed when TCP gives up retransmitting, after about 15 minutes by default
    # (tcp_retries2 = 15). Three retries give up after about 3 s (README, "Several machines").
    ip netns exec "$host" sysctl -qw net.ipv4.tcp_retries2=3
    # `ip netns exec` bind-mounts /etc/netns/HOST/* over /etc: every host resolves the others' names.
    mkdir -p "/etc/netns/$host"
    { echo "127.0.0.1 localhost"; for j in $(seq "$2"); do echo "$subnet.$j $prefix$j"; done; } \
        > "/etc/netns/$host/hosts"
}

up() {
    local count="$1"
    [[ "$count" =~ ^[1-9][0-9]?$ && "$count" -le 250 ]] || { echo "netns_hosts: N must be 1..250, not '$count'" >&2; exit 2; }
    ip netns add "$net"
    ip -n "$net" link add br0 type bridge
    ip -n "$net" link set br0 up
    for i in $(seq "$count"); do host_up "$i" "$count"; done
}

# Ends what is left in a namespace (a test's server, mpirun, orted, ranks), then removes it.
remove_namespace() {
    local ns="$1" pids
    ip netns list | grep -q "^$ns\b" || return 0
    for signal in TERM KILL; do
        pids="$(ip netns pids "$ns" || true)"
        [[ -z "$pids" ]] && break
        kill "-$signal" $pids 2>/dev/null || true
        for _ in $(seq 20); do [[ -z "$(ip netns pids "$ns" || true)" ]] && break; sleep 0.1; done
    done
    ip netns delete "$ns"
}

down() {
    local count="$1"
    for i in $(seq "$count"); do
        remove_namespace "$prefix$i"
        rm -rf "/etc/netns/$prefix$i"
    done
    remove_namespace "$net"
    rmdir /etc/netns 2>/dev/null || true
}

# The host's own hostname (a UTS namespace) inside its network namespace:
# Open MPI names nodes by gethostname().
run_in() {
    local host="$1"; shift
    exec ip netns exec "$host" unshare --uts sh -c 'hostname "$0" && exec "$@"' "$host" "$@"
}

# Without an answer to ARP, a pulled cable fails new connections within
# seconds; pinned neighbour entries make them wait for TCP's own timeouts.
pin_neighbours() {
    local host="$1" other mac
    for other in $(ip netns list | awk '{print $1}' | grep -x "$prefix[0-9]*"); do
        [[ "$other" == "$host" ]] && continue
        mac="$(ip -n "$other" -br link show eth0 | awk '{print $3}')"
        ip -n "$host" neigh replace "$(ip -n "$other" -4 -br addr show eth0 | awk '{print $3}' | cut -d/ -f1)" \
            lladdr "$mac" dev eth0 nud permanent
    done
}

link() {
    local host="$1" state="$2"
    case "$state" in
        up) ip -n "$host" neigh flush dev eth0 nud permanent ;;
        down) ;;
        silent) pin_neighbours "$host"; state=down ;;
        *) usage ;;
    esac
    ip -n "$net" link set "$(port_of "$host")" "$state"
}

cable() {
    if ip -n "$net" -br link show "$(port_of "$1")" | grep -qw UP; then
        echo up
    elif ip -n "$1" neigh show nud permanent | grep -q .; then
        echo silent
    else
        echo down
    fi
}

# What mpirun needs to run over these hosts: daemons started through the rsh
# agent (directly, not from daemon to daemon), MPI's and Open MPI's own
# traffic on the bridge's subnet only, and more ranks than slots where a host
# is lost. (lightmass_server itself shortens Open MPI's TCP keepalives and
# keeps the daemons attached: rank_bake_launcher.cpp.)
mpi_args() {
    printf '%s\n' --mca plm_rsh_agent "$(cd "$(dirname "$0")" && pwd)/netns_rsh.sh" \
        --mca plm_rsh_no_tree_spawn 1 \
        --mca btl self,tcp --mca btl_tcp_if_include "$subnet.0/24" --mca oob_tcp_if_include "$subnet.0/24" \
        --oversubscribe --bind-to none
}

case "${1:-}" in
    up) [[ $# -eq 2 ]] || usage; up "$2" ;;
    down) [[ $# -eq 2 ]] || usage; down "$2" ;;
    exec) [[ $# -ge 3 ]] || usage; shift; run_in "$@" ;;
    link) [[ $# -eq 3 ]] || usage; link "$2" "$3" ;;
    cable) [[ $# -eq 2 ]] || usage; cable "$2" ;;
    mpi-args) [[ $# -eq 1 ]] || usage; mpi_args ;;
    *) usage ;;
esac
