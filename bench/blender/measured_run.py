# SPDX-License-Identifier: MIT
# What compare.py and scale.py share: a command run with its wall time, CPU time and peak memory,
# and the wall time between the frames `inkline render -v` reports.

import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

FRAME_LINE = re.compile(r"^frame (\d+): .*$", re.M)


def run(cmd, log_path, stamps=None, who="bench"):
    """Runs cmd, its output into log_path; returns (wall s, CPU s, peak RSS MB, output). Exits
    with the output's end, naming `who`, if it fails. With a list for stamps, the output is read
    as it comes and each line is appended with its arrival time (s since the start)."""
    start = time.perf_counter()
    with open(log_path, "w") as log:
        if stamps is None:
            proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)
        else:
            proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                    errors="replace", bufsize=1)
            for line in proc.stdout:
                stamps.append((time.perf_counter() - start, line))
                log.write(line)
            proc.stdout.close()
        _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    text = Path(log_path).read_text(errors="replace")
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        sys.exit("%s: command failed (%d): %s\n%s" % (who, code, " ".join(map(str, cmd)), text[-3000:]))
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0, text


def ms_between_frames(stamps):
    """Median wall ms from one frame's `render -v` line to the next (frames 2..): what a frame
    costs the run where its work overlaps the frame before's (the next frame's lines are found
    while a frame is drawn), so its stage times add up to more."""
    times = [t for t, line in stamps if FRAME_LINE.match(line)]
    return statistics.median([1000.0 * (b - a) for a, b in zip(times, times[1:])] or [0.0])
