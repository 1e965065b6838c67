#!/usr/bin/env python3
"""Interleaved timing of `twoball bench kernel` for two or more twoball binaries.

A VM's speed drifts by 5-15 % within minutes, so a before/after comparison of two builds is
only sound when their runs alternate: this runs each binary in turn, ROUNDS times, one
thread, and prints the minimum, median and maximum of the ns-per-element-cycle figures.

    python3 scripts/kernel_ab.py OLD_BINARY NEW_BINARY [--rounds 8] [--element b-bar]
        [--size-per-d 0.07] [-- extra bench-kernel arguments]
"""

import argparse
import statistics
import subprocess
import sys


def one_run(binary, element, size, extra):
    """ns per element-cycle of one `bench kernel --threads 1 --repeats 5` run."""
    cmd = [binary, "bench", "kernel", "--threads", "1", "--repeats", "5",
           "--element", element, "--size-per-d", str(size)] + extra
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        if line.startswith(("OnePoint,1,", "BBar,1,")):
            return float(line.split(",")[2])
    raise RuntimeError(f"no timing line in the output of {' '.join(cmd)}")


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binaries", nargs="+", help="twoball binaries to compare")
    ap.add_argument("--rounds", type=int, default=8, help="runs of each binary (default 8)")
    ap.add_argument("--element", choices=["one-point", "b-bar"], default="one-point")
    ap.add_argument("--size-per-d", type=float, default=0.07,
                    help="element size / D of the benchmark ball (default 0.07)")
    a = ap.parse_args(argv)
    if a.rounds < 1:
        ap.error("--rounds must be at least 1")
    times = {b: [] for b in a.binaries}
    for _ in range(a.rounds):
        for b in a.binaries:
            times[b].append(one_run(b, a.element, a.size_per_d, extra))
    print(f"# {a.element}, size {a.size_per_d} D, {a.rounds} interleaved rounds, "
          "ns per element-cycle (one thread)")
    print("binary,min,median,max")
    for b in a.binaries:
        t = times[b]
        print(f"{b},{min(t):.1f},{statistics.median(t):.1f},{max(t):.1f}")


if __name__ == "__main__":
    main()
