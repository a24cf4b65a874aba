"""Helpers of the flaplag Python tests: the built command line as the reference.

The tests run from ctest (python/tests/register.cmake) with PYTHONPATH at the build's module
directory and FLAPLAG_CLI naming the built `flaplag` binary.  The CLI's JSON keys are read
defensively (a key may move into a sub-object), but a value that is found must agree bit for
bit with the Python result.
"""

import json
import math
import os
import subprocess

import pytest

import flaplag

CLI = os.environ.get("FLAPLAG_CLI", "")


def _default(field):
    for row in flaplag.parameter_table():
        if row["field"] == field:
            return row["default"]
    return None


def cli_args(**kw):
    """The command-line options of Analysis keyword arguments: '--' + the field with '-' for
    '_'; a bool field by the option that changes its default (--no-reversed-flow,
    --paper-1974-shapes); floats in shortest round-trip form (repr), read back exactly."""
    args = []
    for field, value in kw.items():
        option = "--" + field.replace("_", "-")
        if isinstance(value, bool):
            default = _default(field)
            if value == default:
                continue
            args.append("--no-" + field.replace("_", "-") if default else option)
        else:
            args += [option, repr(value) if isinstance(value, float) else str(value)]
    return args


def run_cli(*args):
    """The JSON document of `flaplag <args> --json`."""
    if not CLI:
        pytest.fail("FLAPLAG_CLI is not set (run the tests through ctest)")
    proc = subprocess.run([CLI, *args, "--json"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, f"flaplag {' '.join(args)}: {proc.stderr}"
    return json.loads(proc.stdout)


def cli_error(*args):
    """(option, value, reason) of the error line of a command line that must fail."""
    proc = subprocess.run([CLI, *args], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2, f"flaplag {' '.join(args)} exited with {proc.returncode}"
    line = proc.stderr.strip().splitlines()[-1]
    prefix = "flaplag: error: "
    assert line.startswith(prefix), line
    head, _, reason = line[len(prefix):].partition(": ")
    option, _, value = head.partition(" = ")
    return option, value, reason


def find(doc, *paths, default=KeyError):
    """The value at the first of the key paths ('a.b.c') that the document has."""
    for path in paths:
        node = doc
        ok = True
        for key in path.split("."):
            if isinstance(node, dict) and key in node:
                node = node[key]
            else:
                ok = False
                break
        if ok:
            return node
    if default is KeyError:
        raise KeyError(f"none of {paths} in the CLI's JSON (keys: {sorted(doc)})")
    return default


def zeta_value(v):
    """A zeta from the CLI's JSON: a number, or the string '-inf' for a zero multiplier."""
    return float(v) if isinstance(v, str) else v


def same(a, b):
    """Bit-for-bit equality of two floats (None equal to None, nan to nan, 0.0 not -0.0)."""
    if a is None or b is None:
        return a is None and b is None
    a, b = float(a), float(b)
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)
