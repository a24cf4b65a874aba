#!/usr/bin/env python3
"""Two builds of one Google Benchmark program, side by side in one session.

    bench/compare_binaries.py OLD NEW [--rounds 6] [--repetitions 3] [--filter REGEX]

Runs OLD and NEW alternately, --rounds times, each with --repetitions repetitions of every
benchmark that --filter selects, so that the VM's drift during the session falls on both alike.
Prints one Markdown row per benchmark: the median and the minimum of all samples of each binary
(real time for the benchmarks that ask for it, CPU time otherwise) and NEW's change against OLD.
Needs only Python's standard library.
"""
import argparse
import json
import statistics
import subprocess
import sys


def fail(message):
    """One line on stderr and exit 2, as for any bad input."""
    print("compare_binaries.py: " + message, file=sys.stderr)
    sys.exit(2)


def samples(binary, regex, repetitions):
    """{benchmark: [(time, unit)]} of one run of `binary`."""
    try:
        run = subprocess.run(
            [binary, "--benchmark_filter=" + regex, "--benchmark_repetitions=%d" % repetitions,
             "--benchmark_format=json"], capture_output=True, text=True)
    except OSError as e:
        fail("%s: %s" % (binary, e.strerror))
    if run.returncode != 0:
        fail("%s failed (exit %d): %s" % (binary, run.returncode, run.stderr.strip()))
    try:
        benchmarks = json.loads(run.stdout)["benchmarks"]
    except (ValueError, KeyError, TypeError):
        fail("%s did not print Google Benchmark's JSON" % binary)
    out = {}
    for b in benchmarks:
        if b.get("run_type") != "iteration":
            continue
        time = b["real_time"] if b["run_name"].endswith("/real_time") else b["cpu_time"]
        out.setdefault(b["run_name"], []).append((time, b["time_unit"]))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=6)
    parser.add_argument("--repetitions", type=int, default=3)
    parser.add_argument("--filter", default=".")
    args = parser.parse_args()
    if args.rounds < 1 or args.repetitions < 1:
        fail("--rounds and --repetitions must be >= 1")
    data = {}
    for _ in range(args.rounds):
        for which, binary in (("old", args.old), ("new", args.new)):
            for name, values in samples(binary, args.filter, args.repetitions).items():
                data.setdefault(name, {}).setdefault(which, []).extend(values)
    print("| benchmark | old: median / min | new: median / min | change: median / min |")
    print("|---|---|---|---|")
    for name, by in data.items():
        if "old" not in by or "new" not in by:
            continue
        unit = by["old"][0][1]
        stats = {w: (statistics.median(t for t, _ in v), min(t for t, _ in v))
                 for w, v in by.items()}
        (om, on), (nm, nn) = stats["old"], stats["new"]
        print("| `%s` | %.4g / %.4g %s | %.4g / %.4g %s | %+.1f / %+.1f %% |" %
              (name.replace("/real_time", ""), om, on, unit, nm, nn, unit,
               100 * (nm / om - 1), 100 * (nn / on - 1)))


if __name__ == "__main__":
    main()
