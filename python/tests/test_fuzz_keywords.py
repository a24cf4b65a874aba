"""Fuzzing the keywords of the public Python API with generated values.

Every keyword of Analysis(...), its methods and flaplag.study / flaplag.map gets values of the
wrong type, NaN, inf, huge and negative integers, huge lists and arrays, strings.  Each call
must either return or raise what the API documents: ValueError (flaplag.InvalidInput) or
TypeError (UnknownParameter, a missing positional), with a one-line message naming the keyword
as the user typed it; never another exception (AttributeError, MemoryError, OverflowError,
RuntimeError, ...), never a crash, never a hang, and a NaN or infinite value is never accepted
into a result that says 'ok'.

The calls run in a worker process (this file run as a script), one at a time, under an
address-space cap (RLIMIT_AS, 2 GiB) and a time limit per call: a crash or a hang is reported
with its call and the worker is restarted after it.  Deterministic: case i is generated from
FLAPLAG_FUZZ_SEED and i alone.  Budget: FLAPLAG_PY_FUZZ_VECTORS calls (default 600), each
killed after FLAPLAG_PY_FUZZ_TIMEOUT seconds (default 20).
"""

import json
import os
import random
import re
import select
import subprocess
import sys
import time

try:
    import resource
except ImportError:  # not POSIX
    resource = None

MEMORY_CAP = 2 << 30  # bytes of address space for the worker


def _env_int(name, default):
    try:
        v = int(os.environ.get(name, ""))
        return v if v > 0 else default
    except ValueError:
        return default


VECTORS = _env_int("FLAPLAG_PY_FUZZ_VECTORS", 600)
SEED = _env_int("FLAPLAG_FUZZ_SEED", 19740601)
TIMEOUT = _env_int("FLAPLAG_PY_FUZZ_TIMEOUT", 20)

# ---- the values ---------------------------------------------------------------------------------
# Values are described by a token (JSON-able, for the report) and built in the worker.

# token: the Python expression of the value (np: numpy, Fraction: fractions.Fraction).
HOSTILE = {
    "none": "None",
    "true": "True",
    "false": "False",
    "nan": "float('nan')",
    "inf": "float('inf')",
    "-inf": "float('-inf')",
    "neg1": "-1",
    "zero": "0",
    "neg_huge_float": "-1e308",
    "huge_float": "1e308",
    "tiny": "5e-324",
    "huge_int": "10**30",
    "int64": "2**63",
    "int_max": "2**31 - 1",
    "neg_int": "-(2**31)",
    "str_num": "'0.3'",
    "str_nan": "'nan'",
    "str_word": "'paper`touch pwned`'",
    "empty_str": "''",
    "bytes": "b'0.3'",
    "complex": "complex(0.3, 1.0)",
    "list1": "[0.3]",
    "list_nan": "[0.1, float('nan'), 0.3]",
    "list_str": "['0.1', 'a']",
    "nested": "[[0.1, 0.2], [0.3]]",
    "dict": "{'a': 1}",
    "object": "object()",
    "np_nan": "np.float64('nan')",
    "np_int64_huge": "np.int64(2**62)",
    "np_bool": "np.bool_(True)",
    "array_2d": "np.zeros((3, 3))",
    "array_nan": "np.array([0.1, np.nan])",
    "huge_list": "[0.1] * 2_000_000",
    "huge_array": "np.linspace(0.0, 0.5, 2_000_000)",
    "empty_list": "[]",
    "long_str": "'x' * 1_000_000",
    "np_float32_inf": "np.float32('inf')",
    "fraction": "Fraction(3, 10)",
}


def build(token):
    """The value of a token (numpy imported here: the parent does not need it)."""
    from fractions import Fraction

    import numpy as np

    return eval(HOSTILE[token], {"np": np, "Fraction": Fraction})  # noqa: S307 - our own table


NON_FINITE = {"nan", "inf", "-inf", "list_nan", "np_nan", "array_nan", "np_float32_inf"}


def non_finite(token):
    return token in NON_FINITE


# ---- the calls ----------------------------------------------------------------------------------
# A call: target, the keyword fuzzed, and the other (cheap) arguments.  Each target is a
# function of the keyword arguments that returns a result.

CHEAP = {"mu_max": 0.3, "scan_step": 0.1}

TARGETS = {
    # target: (keywords to fuzz, fixed cheap keywords)
    "Analysis": (None, {}),  # every parameter of the table (filled in the worker)
    "point": (["mu", "scan_step", "trim", "thrust_coefficient", "shaft_angle", "inflow"],
              {"mu": 0.3, "scan_step": 0.1}),
    "sweep": (["mu", "scan_step", "threads", "trim", "thrust_coefficient", "shaft_angle",
               "inflow"], {"mu": [0.0, 0.1, 0.2], "scan_step": 0.1}),
    "sweep3": (["mu", "stop", "step", "scan_step", "threads"],
               {"mu": 0.0, "stop": 0.2, "step": 0.1}),
    "critical": (["mu_max", "scan_step", "tolerance", "all_intervals", "zeta_threshold",
                  "periodic_omega_tolerance", "scan_zeta_tolerance", "trim", "inflow"],
                 dict(CHEAP)),
    "system": (["mu", "psi"], {"mu": 0.3}),
    "modes": (["x", "derivative"], {}),
    "response": (["mu", "samples", "steps", "tolerance"], {"mu": 0.3}),
    "simulate": (["mu", "revolutions", "y0", "forced", "samples_per_rev", "steps_per_rev",
                  "nonlinear"], {"mu": 0.3, "revolutions": 1}),
    "trim": (["mu", "kind", "thrust_coefficient", "shaft_angle", "max_iterations", "tolerance"],
             {"mu": 0.2}),
    "thrust": (["mu", "inflow", "shaft_angle"], {"mu": 0.2}),
    "floquet": (["mu", "zeta_tolerance"], {"mu": 0.3}),
    "periodic_equilibrium": (["mu", "harmonics", "harmonics_tolerance", "max_iterations",
                              "tolerance", "check_stability", "samples"], {"mu": 0.3}),
    "study": (["parameter", "values", "mu_max", "scan_step", "threads", "chunk_lines",
               "progress", "client", "trim"],
              {"parameter": "omega_lag", "values": [0.6, 1.4], **CHEAP}),
    "map": (["x", "y", "mu", "scan_step", "threads", "chunk_lines", "progress", "client"],
            {"x": ("mu", [0.0, 0.1]), "y": ("omega_lag", [0.6, 1.4]), "scan_step": 0.1}),
}

def make_case(i, fields):
    """Case i: (target, keyword, token). `fields`: the Analysis keywords."""
    rnd = random.Random(SEED * 1000003 + i)
    target = rnd.choice(sorted(TARGETS))
    keywords = TARGETS[target][0] or fields
    keyword = rnd.choice(keywords)
    token = rnd.choice(sorted(HOSTILE))
    return target, keyword, token


# The arguments given positionally, in order (the rest are keywords).
POSITIONAL = {"point": ["mu"], "sweep": ["mu"], "sweep3": ["mu", "stop", "step"],
              "system": ["mu"], "modes": ["x"], "response": ["mu"], "simulate": ["mu"],
              "trim": ["mu"], "thrust": ["mu"], "floquet": ["mu"],
              "periodic_equilibrium": ["mu"], "study": ["parameter", "values"], "map": ["x", "y"]}


def invocation(target, keyword, value):
    """(receiver, positional arguments, keyword arguments) of a case; receiver: the text of the
    callable ('flaplag.Analysis', 'an.sweep', 'flaplag.study')."""
    kw = dict(TARGETS[target][1])
    kw[keyword] = value
    args = [kw.pop(n) for n in POSITIONAL.get(target, []) if n in kw]
    if target == "Analysis":
        receiver = "flaplag.Analysis"
    elif target in ("study", "map"):
        receiver = "flaplag." + target
    else:
        receiver = "an." + ("sweep" if target == "sweep3" else target)
    return receiver, args, kw


def call(target, keyword, token):
    """Runs one case in this process: the result, or raises."""
    import flaplag

    receiver, args, kw = invocation(target, keyword, build(token))
    an = flaplag.Analysis()
    owner, name = receiver.split(".")
    return getattr(flaplag if owner == "flaplag" else an, name)(*args, **kw)


def statuses(result):
    """Every status a result (or its points/rows) reports."""
    out = []
    if hasattr(result, "status"):
        out.append(result.status)
    for name in ("points", "rows"):
        for p in getattr(result, name, None) or []:
            if hasattr(p, "status"):
                out.append(p.status)
    return out


def judge(target, keyword, token, outcome):
    """The contract violations of one case's outcome (a dict from the worker)."""
    problems = []
    kind = outcome["kind"]
    if kind == "exception":
        name, message = outcome["type"], outcome["message"]
        if not outcome["documented"]:
            problems.append(f"raised {name} (not ValueError/TypeError): {message[:200]}")
        elif "\n" in message.strip():
            problems.append(f"{name} message is not one line: {message[:200]!r}")
        elif not re.search(r"(^|[^A-Za-z0-9_])" + re.escape(keyword) + r"([^A-Za-z0-9_]|$)",
                           message):
            problems.append(f"{name} message does not name the keyword {keyword!r}: "
                            f"{message[:200]}")
    elif kind == "returned":
        if non_finite(token) and outcome["ok"]:
            problems.append(f"{token} accepted, the result says 'ok': {outcome['repr'][:200]}")
    return problems


def describe(target, keyword, token):
    """The case as Python a user can paste."""

    class Value:
        def __repr__(self):
            return "value"

    receiver, args, kw = invocation(target, keyword, Value())
    setup = "an = flaplag.Analysis(); "
    given = [repr(a) for a in args] + [f"{k}={v!r}" for k, v in kw.items()]
    return (f"value = {HOSTILE[token]}; {setup if receiver.startswith('an.') else ''}"
            f"{receiver}({', '.join(given)})")


# ---- the worker ---------------------------------------------------------------------------------

def worker(start, stop):
    """Runs cases start..stop-1, writing 'S i' before and 'E i <json>' after each."""
    import numpy  # noqa: F401 - loaded before the first case (not a finding of any case)

    import flaplag

    fields = analysis_keywords(flaplag)
    for i in range(start, stop):
        target, keyword, token = make_case(i, fields)
        print(f"S {i}", flush=True)
        try:
            result = call(target, keyword, token)
            # A result without a status has no way to say it is not clean: 'ok'.
            outcome = {"kind": "returned", "ok": all(s == "ok" for s in statuses(result)),
                       "repr": repr(result)[:300]}
        except KeyboardInterrupt:
            raise
        except BaseException as e:  # noqa: B902 - everything else is judged
            documented = isinstance(e, (ValueError, TypeError)) and not isinstance(e, UnicodeError)
            outcome = {"kind": "exception", "type": type(e).__name__, "message": str(e)[:2000],
                       "documented": documented}
        print(f"E {i} {json.dumps(outcome)}", flush=True)


def analysis_keywords(flaplag):
    """The keywords of Analysis: the parameter table, the transition options, the mode counts."""
    import inspect

    return list(inspect.signature(flaplag.Analysis).parameters)


def _limit_memory():
    if resource is not None:
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP, MEMORY_CAP))


def run_cases(n):
    """[(i, problems)] for cases 0..n-1, restarting the worker after a crash or a hang."""
    import flaplag

    fields = analysis_keywords(flaplag)
    findings, totals = [], {"returned": 0, "exception": 0, "crash": 0, "hang": 0}
    i = 0
    while i < n:
        proc = subprocess.Popen([sys.executable, __file__, "--worker", str(i), str(n)],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                preexec_fn=_limit_memory)
        current, started, pending, err = None, time.monotonic(), b"", b""
        fds = [proc.stdout.fileno(), proc.stderr.fileno()]
        open_fds = list(fds)
        hang = False
        while open_fds:
            ready, _, _ = select.select(open_fds, [], [], 0.5)
            for fd in ready:
                chunk = os.read(fd, 65536)
                if not chunk:
                    open_fds.remove(fd)
                elif fd == fds[1]:
                    err = (err + chunk)[-4000:]
                else:
                    pending += chunk
            while b"\n" in pending:
                line, pending = pending.split(b"\n", 1)
                line = line.decode()
                if line.startswith("S "):
                    current, started = int(line.split()[1]), time.monotonic()
                elif line.startswith("E "):
                    _, idx, payload = line.split(" ", 2)
                    idx = int(idx)
                    outcome = json.loads(payload)
                    totals[outcome["kind"]] += 1
                    case = make_case(idx, fields)
                    problems = judge(*case, outcome)
                    if problems:
                        findings.append((idx, case, problems))
                    current, i = None, idx + 1
            if current is not None and time.monotonic() - started > TIMEOUT:
                hang = True
                proc.kill()
                break
        proc.wait()
        proc.stdout.close()
        proc.stderr.close()
        if current is None and i >= n:
            break
        if current is None:
            # The worker ended between cases: it could not start (import failure).
            raise AssertionError(f"the fuzz worker ended before case {i}: {err.decode()[-2000:]}")
        case = make_case(current, fields)
        totals["hang" if hang else "crash"] += 1
        what = (f"hang: no answer after {TIMEOUT} s" if hang
                else f"crash: exit {proc.returncode}: {err.decode(errors='replace').strip()[-300:]}")
        findings.append((current, case, [what]))
        i = current + 1
    return findings, totals


def test_keywords_raise_only_documented_errors():
    findings, totals = run_cases(VECTORS)
    print(f"python keyword fuzz: seed {SEED}, {VECTORS} calls: {totals}; "
          f"{len(findings)} violations")
    report = []
    for idx, case, problems in findings:
        report.append(f"case {idx}: {describe(*case)}\n    " + "\n    ".join(problems))
    for line in report:
        print(line)
    assert not findings, f"{len(findings)} of {VECTORS} calls broke the contract:\n" + "\n".join(
        report[:40])


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "--worker":
        worker(int(sys.argv[2]), int(sys.argv[3]))
