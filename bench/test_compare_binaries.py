"""bench/compare_binaries.py: its table from a real benchmark program, and its one-line errors.

BENCH_PROGRAM names a Google Benchmark program of this build (transition_bench).
"""
import os
import subprocess
import sys

import pytest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "compare_binaries.py")
PROGRAM = os.environ.get("BENCH_PROGRAM", "")


def compare(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)


@pytest.mark.skipif(not os.path.exists(PROGRAM), reason="BENCH_PROGRAM not set")
def test_one_row_per_benchmark_with_both_statistics():
    run = compare(PROGRAM, PROGRAM, "--rounds", "1", "--repetitions", "2", "--filter",
                  "^BM_Phi_Hsu_K50_J4_FixedKernel$")
    assert run.returncode == 0, run.stderr
    rows = run.stdout.strip().split("\n")
    assert rows[0].startswith("| benchmark | old: median / min |")
    assert len(rows) == 3, run.stdout
    cells = [c.strip() for c in rows[2].strip("|").split("|")]
    assert cells[0] == "`BM_Phi_Hsu_K50_J4_FixedKernel`"
    for cell in cells[1:3]:
        median, minimum = (float(x) for x in cell.split()[0:3:2])
        assert 0 < minimum <= median
    assert cells[3].endswith("%")


@pytest.mark.parametrize("args, says", [
    (["/nonexistent/bench", "/nonexistent/bench"], "/nonexistent/bench: No such file"),
    (["/bin/true", "/bin/true"], "/bin/true did not print Google Benchmark's JSON"),
    (["/bin/false", "/bin/false"], "/bin/false failed (exit 1)"),
    (["/bin/true", "/bin/true", "--rounds", "0"], "--rounds and --repetitions must be >= 1"),
])
def test_bad_input_is_one_line_and_exit_2(args, says):
    run = compare(*args)
    assert run.returncode == 2
    assert run.stdout == ""
    lines = run.stderr.strip().split("\n")
    assert len(lines) == 1 and says in lines[0], run.stderr
