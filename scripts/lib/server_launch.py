"""Starts a lightmass_server on a free loopback port for the fault scripts
(footprint_peak.py, sigterm_timer.py): the port is read back from
--port-file, so runs never collide on a fixed port."""
import os
import subprocess
import sys
import time


def start_server(server_bin, folder, extra_args, stderr):
    """The server process and its port; exits the script if it does not start in 20 s."""
    port_file = os.path.join(folder, "port")
    server = subprocess.Popen(
        [server_bin, "--listen", "127.0.0.1:0", "--port-file", port_file] + list(extra_args),
        stdout=subprocess.DEVNULL, stderr=stderr)
    end = time.monotonic() + 20
    while time.monotonic() < end:
        if os.path.exists(port_file) and os.path.getsize(port_file) > 0:
            with open(port_file) as f:
                return server, int(f.read().strip())
        if server.poll() is not None:
            break
        time.sleep(0.05)
    server.kill()
    server.wait()
    sys.exit("lightmass_server did not start")
