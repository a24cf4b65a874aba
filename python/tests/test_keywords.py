"""Error messages of the Python API name the keyword the user typed, on one bounded line.

Each test is a class the keyword fuzzer (test_fuzz_keywords.py) found: a value shown in a
message (an array, a long list or text) must not spread it over lines or pages; the library's
own argument names (mu0, mu1, samples, steps) are the Python keywords' (mu, stop,
samples_per_rev, steps_per_rev); a derived quantity (the Brent bracket "b" of the trim's
momentum inflow) is not what the user gave; a study parameter of the wrong type is refused
naming `parameter`.
"""

import re

import numpy as np
import pytest

import flaplag

MAX_MESSAGE = 300  # characters: the value part is at most about 60 of them


def _one_line(excinfo, keyword, *words):
    """The error is a ValueError/TypeError with a one-line, bounded message naming `keyword`."""
    e = excinfo.value
    assert isinstance(e, (ValueError, TypeError)), repr(e)
    message = str(e)
    assert "\n" not in message, message
    assert len(message) <= MAX_MESSAGE, message[:400]
    assert re.match(re.escape(keyword) + r" = ", message), message
    for w in words:
        assert w in message, message
    return message


BIG_VALUES = [
    (np.zeros((3, 3)), "array of shape (3, 3)"),
    (np.linspace(0.0, 0.5, 2_000_000), "array of shape (2000000,)"),
    ([0.1] * 2_000_000, "list of 2000000 items"),
    ("x" * 1_000_000, "'xxx"),
]


@pytest.mark.parametrize("value, shown", BIG_VALUES)
def test_a_big_value_is_shown_short_on_one_line(value, shown):
    an = flaplag.Analysis()
    calls = [
        ("gamma", lambda: flaplag.Analysis(gamma=value)),
        ("theta1s", lambda: flaplag.Analysis(theta1s=value)),
        ("scan_step", lambda: an.critical(mu_max=0.3, scan_step=value)),
        ("derivative", lambda: an.modes(derivative=value)),
        ("steps", lambda: an.response(0.3, steps=value)),
        ("steps_per_rev", lambda: an.simulate(0.3, revolutions=1, steps_per_rev=value)),
        ("mu", lambda: an.floquet(value)),
        ("chunk_lines", lambda: flaplag.map(("mu", [0.0, 0.1]), ("omega_lag", [0.6, 1.4]),
                                            chunk_lines=value)),
        ("client", lambda: flaplag.map(("mu", [0.0, 0.1]), ("omega_lag", [0.6, 1.4]),
                                       client=value)),
    ]
    if not isinstance(value, str):
        calls.append(("check_stability",
                      lambda: flaplag.Analysis().periodic_equilibrium(
                          0.3, check_stability=value)))
    for keyword, call in calls:
        with pytest.raises((ValueError, TypeError)) as ei:
            call()
        _one_line(ei, keyword, shown)


def test_a_long_text_from_the_library_is_cut():
    # The library's own messages show the text the user gave (a model name, a trim kind).
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.Analysis(model="m" * 1_000_000)
    _one_line(ei, "model", "mmm", "...")
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.Analysis(model="paper\nsecond line")
    _one_line(ei, "model", "paper second line")
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.Analysis().trim(0.2, kind="k" * 100_000)
    _one_line(ei, "kind", "'kkk", "...")
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.Analysis().modes(memory_limit=np.zeros((3, 3)))
    _one_line(ei, "memory_limit", "array of shape (3, 3)")


@pytest.mark.parametrize(
    "args, keyword, words",
    [
        (("x", 0.2, 0.1), "mu", ["must be a real number"]),
        ((None, 0.2, 0.1), "mu", ["must be a real number"]),
        ((float("inf"), 0.2, 0.1), "mu", ["must be >= 0"]),
        ((-1, 0.2, 0.1), "mu", ["must be >= 0"]),
        ((0.0, complex(0.3, 1.0), 0.1), "stop", ["must be a real number"]),
        ((0.0, 2**31 - 1, 0.1), "stop", ["must be >= mu and"]),
        ((0.0, float("nan"), 0.1), "stop", []),
        ((0.0, 0, 0.1), "stop", ["must exceed mu = 0"]),
        ((0.0, 0.2, 0.0), "step", []),
    ],
)
def test_sweep_start_stop_step_names_mu_and_stop(args, keyword, words):
    an = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.sweep(*args)
    message = _one_line(ei, keyword, *words)
    assert "mu0" not in message and "mu1" not in message, message
    assert ei.value.field == keyword


def test_trimmed_sweep_start_stop_step_names_mu_and_stop():
    an = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.sweep(0.3, 0.1, 0.1, trim="thrust")
    message = _one_line(ei, "stop", "must be >= mu")
    assert "mu0" not in message and "mu1" not in message, message


def test_simulate_names_samples_per_rev_and_steps_per_rev():
    an = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.simulate(0.3, revolutions=1, samples_per_rev=-1)
    _one_line(ei, "samples_per_rev", "1..10000")
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.simulate(0.3, revolutions=1, steps_per_rev=-1)
    _one_line(ei, "steps_per_rev")


@pytest.mark.parametrize("value", [{"a": 1}, ["0.1", "a"], np.zeros(2), 3])
def test_study_parameter_of_the_wrong_type_names_parameter(value):
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.study(value, [0.6, 1.4], mu_max=0.3, scan_step=0.1)
    _one_line(ei, "parameter", "must be a string")


TINY_MUS = [5e-324, 1e-310, 1e-200, 1e-150]  # mu^2 underflows, or C_T / (2 mu) is huge


@pytest.mark.parametrize("mu", TINY_MUS)
def test_a_trim_at_a_vanishing_advance_ratio_is_the_hover_trim(mu):
    # The momentum inflow of eq 2.25 divided by |(mu, lambda)| and bracketed its root up to
    # C_T / (2 mu): below mu ~ 1e-154 the library reported its Brent bracket ("b = inf"), and at
    # mu = 1e-150 it returned a wrong trim (theta0 = 0.095 instead of 0.170, inflow 0) as "ok".
    an = flaplag.Analysis()
    hover = an.trim(0.0)
    t = an.trim(mu)
    assert t.status == "ok", t.message
    assert t.theta0 == pytest.approx(hover.theta0, rel=1e-12, abs=0)
    assert t.inflow == pytest.approx(hover.inflow, rel=1e-12, abs=0)
    assert an.thrust(mu).status == "ok"
    assert an.point(mu, scan_step=0.1, trim="thrust").status != "failed"


@pytest.mark.parametrize("inflow", [1e308, -1e308, 1e6])
def test_a_huge_given_inflow_names_inflow(inflow):
    an = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.thrust(0.2, inflow=inflow)
    _one_line(ei, "inflow", "must be in [-1000, 1000]")


def test_a_small_array_is_shown_as_its_repr():
    an = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.floquet(np.array([0.1, np.nan]))
    _one_line(ei, "mu", "array([0.1, nan])")
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.floquet(np.array("a"))
    _one_line(ei, "mu", "array('a'")


@pytest.mark.parametrize("lift_slope", [5e-324, 1e-310])
def test_a_vanishing_lift_slope_names_lift_slope(lift_slope):
    # C_Do / a overflowed the hover matrix: the library named "A0", a matrix nobody typed.
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.Analysis(lift_slope=lift_slope)
    _one_line(ei, "lift_slope", "too small for `cdo` = 0.01")
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.study("omega_lag", [0.6], lift_slope=lift_slope, client=_Executor())
    _one_line(ei, "lift_slope")


def test_a_small_lift_slope_without_profile_drag_still_builds():
    assert flaplag.Analysis(lift_slope=5e-324, cdo=0.0).hover.status != "failed"
    assert flaplag.Analysis(lift_slope=1e-300).hover is not None


class _Executor:
    """An executor with submit() that must never be reached (the checks come first)."""

    def submit(self, *args, **kwargs):
        raise AssertionError("work was submitted before the parameters were checked")
