"""Runs an example script headless and checks that it wrote its output files.

    python3 run_example.py SCRIPT OUTPUT [OUTPUT...] [-- ARGS...]
The outputs are removed first, the script is run with MPLBACKEND=Agg and the given arguments,
and every output must exist and be non-empty afterwards.
"""

import os
import subprocess
import sys

args = sys.argv[1:]
extra = []
if "--" in args:
    i = args.index("--")
    args, extra = args[:i], args[i + 1:]
script, outputs = args[0], args[1:]
for out in outputs:
    if os.path.exists(out):
        os.remove(out)
env = dict(os.environ, MPLBACKEND="Agg")
proc = subprocess.run([sys.executable, script, *extra], env=env)
if proc.returncode != 0:
    sys.exit(f"{script} exited with {proc.returncode}")
for out in outputs:
    if not os.path.isfile(out) or os.path.getsize(out) == 0:
        sys.exit(f"{script} did not write {out}")
    print(f"{out}: {os.path.getsize(out)} bytes")
