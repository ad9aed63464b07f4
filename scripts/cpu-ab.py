#!/usr/bin/env python3
"""CPU time of one gearshock command on two or more builds, interleaved.

The machine is a shared virtual machine whose speed drifts, so the
builds take turns: run 1 of each, then run 2 of each, and so on. Each
run is the whole process (user + system CPU of the child); the medians
and minimums are printed with each build's ratio to the first. Outputs
go to a scratch file, not /dev/null (the command line refuses a stdout
opened read-write, which is how Python's DEVNULL opens it).

  scripts/cpu-ab.py OLD_BINARY,NEW_BINARY [RUNS] [COMMAND ...]

The command defaults to the benchmark sweep, `frf --omega-from 0.1
--omega-to 0.5 --harmonics 7 --mesh s2b1`; docs/performance.md quotes
its figures. Instruction counts, which do not drift, come from
`valgrind --tool=callgrind BINARY COMMAND`.
"""
import resource
import statistics
import subprocess
import sys
import tempfile

SWEEP = "frf --omega-from 0.1 --omega-to 0.5 --harmonics 7 --mesh s2b1".split()


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    builds = sys.argv[1].split(",")
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 10
    command = sys.argv[3:] or SWEEP
    times = {b: [] for b in builds}
    with tempfile.TemporaryFile() as out:
        for _ in range(runs):
            for b in builds:
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                out.seek(0)
                subprocess.run([b] + command, stdout=out, check=True)
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                times[b].append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    first = statistics.median(times[builds[0]])
    for b in builds:
        median = statistics.median(times[b])
        print(f"{b}: median {median:.4f} s, min {min(times[b]):.4f} s, "
              f"ratio to the first {median / first:.3f} ({runs} runs)")


if __name__ == "__main__":
    main()
