"""Peers that stall a lightmass_server connection (scripts/fault_test.sh).

  slow:   announces a 64-byte frame, then sends one byte every --interval s
  silent: connects and sends nothing

Opens --peers connections to 127.0.0.1:--port and waits at most --seconds for
the server to close each one; prints one JSON line with how many it closed
and when. Standard library only.
"""
import argparse
import json
import selectors
import socket
import struct
import time


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--port", type=int, required=True)
    parser.add_argument("--mode", choices=["slow", "silent"], required=True)
    parser.add_argument("--peers", type=int, default=8)
    parser.add_argument("--interval", type=float, default=0.5)
    parser.add_argument("--seconds", type=float, default=30.0)
    args = parser.parse_args()

    start = time.monotonic()
    peers = []
    selector = selectors.DefaultSelector()
    for index in range(args.peers):
        sock = socket.create_connection(("127.0.0.1", args.port), timeout=5)
        sock.setblocking(False)
        if args.mode == "slow":
            sock.send(struct.pack("<I", 64))
        peers.append({"sock": sock, "closed_at": None, "sent": 0})
        selector.register(sock, selectors.EVENT_READ, index)

    next_byte = start + args.interval
    while time.monotonic() - start < args.seconds:
        if all(p["closed_at"] is not None for p in peers):
            break
        for key, _ in selector.select(timeout=0.05):
            peer = peers[key.data]
            try:
                data = peer["sock"].recv(4096)
            except (ConnectionResetError, BlockingIOError):
                data = b""
            if not data:
                peer["closed_at"] = time.monotonic() - start
                selector.unregister(peer["sock"])
        if args.mode == "slow" and time.monotonic() >= next_byte:
            next_byte += args.interval
            for peer in peers:
                if peer["closed_at"] is not None or peer["sent"] >= 64:
                    continue
                try:
                    peer["sock"].send(b"\x00")
                    peer["sent"] += 1
                except (BrokenPipeError, ConnectionResetError):
                    peer["closed_at"] = time.monotonic() - start
                    selector.unregister(peer["sock"])

    closed = sorted(p["closed_at"] for p in peers if p["closed_at"] is not None)
    for peer in peers:
        peer["sock"].close()
    print(json.dumps({
        "mode": args.mode,
        "peers": args.peers,
        "closed_by_server": len(closed),
        "first_close_s": round(closed[0], 2) if closed else None,
        "last_close_s": round(closed[-1], 2) if closed else None,
        "watched_s": round(time.monotonic() - start, 2),
        "bytes_sent_per_slow_peer": max((p["sent"] for p in peers), default=0),
    }))


if __name__ == "__main__":
    main()
