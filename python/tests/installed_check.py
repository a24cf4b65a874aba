"""Run with PYTHONPATH at an install tree's site-packages: flaplag is imported from there and
works (the typical case's mu_c is the paper's 0.754)."""

import os
import sys

prefix = os.path.realpath(sys.argv[1])
import flaplag  # noqa: E402

where = os.path.realpath(flaplag.__file__)
assert where.startswith(prefix + os.sep), f"flaplag imported from {where}, not from {prefix}"
crit = flaplag.Analysis().critical()
print(f"flaplag {flaplag.__version__} from {os.path.dirname(where)}: {crit}")
assert crit.mu_c is not None and abs(crit.mu_c - 0.754) < 1e-3, crit
