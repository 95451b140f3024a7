"""Run a command and print its peak resident set size, for hosts without /usr/bin/time.

Usage: rss_launch.py OUTFILE CMD [ARGS...]. Runs CMD with inherited stdout and stderr,
writes the child's ru_maxrss (KiB, from os.wait4) to OUTFILE and exits with its status.

Why a launcher: on Linux a process's peak RSS carries over from the process it was
forked from, through exec. Forked from the (large) harness, a child would report the
harness's memory; forked from this small launcher, it reports its own plus at most this
launcher's ~10 MB.
"""
import os
import sys

out, argv = sys.argv[1], sys.argv[2:]
pid = os.fork()
if pid == 0:
    try:
        os.execvp(argv[0], argv)
    finally:
        os._exit(127)
_, status, ru = os.wait4(pid, 0)
with open(out, "w") as fh:
    fh.write(str(ru.ru_maxrss))
sys.exit(os.waitstatus_to_exitcode(status))
