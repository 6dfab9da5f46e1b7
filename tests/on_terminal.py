#!/usr/bin/env python3
"""Runs a command with its standard output and error on a pseudo-terminal, as on a user's
terminal, and keeps what it printed (progress lines included).

    tests/on_terminal.py OUT COMMAND [ARG...]

Writes the bytes the command printed to OUT and exits with the command's status.
"""
import os
import pty
import subprocess
import sys

out, argv = sys.argv[1], sys.argv[2:]
leader, follower = pty.openpty()
p = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=follower, stderr=follower)
os.close(follower)
seen = b""
while True:
    try:
        chunk = os.read(leader, 4096)
    except OSError:  # EIO once the command and its children closed the terminal
        break
    if not chunk:
        break
    seen += chunk
with open(out, "wb") as f:
    f.write(seen)
sys.exit(p.wait())
