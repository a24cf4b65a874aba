"""The options structs' field tables drive the Python keywords and their defaults, the generic
converter's errors, and the command line's options and help (one row, every front end)."""

import inspect
import os
import re
import subprocess

import pytest

import flaplag
from flaplag import _flaplag
from conftest import CLI

# The Analysis method of each options struct, and the keywords it takes from the table.
METHODS = {
    "critical": "critical",
    "response": "response",
    "simulation": "simulate",
    "equilibrium": "periodic_equilibrium",
    "campbell": "campbell",
    "trim": "trim",
}


@pytest.mark.parametrize("struct", sorted(METHODS))
def test_keyword_defaults_are_the_tables(struct):
    rows = {r[0]: r for r in _flaplag.option_table(struct)}
    defaults = _flaplag.option_defaults(struct)
    assert set(rows) == set(defaults)
    params = inspect.signature(getattr(flaplag.Analysis, METHODS[struct])).parameters
    shared = [k for k in params if k in defaults and k != "kind"]
    assert shared, struct
    for key in shared:
        assert rows[key][4] == defaults[key]
        assert params[key].default == defaults[key], (struct, key)


def test_rows_are_documented_and_ranges_worded():
    for struct in list(METHODS) + ["transition"]:
        for name, units, doc, words, default in _flaplag.option_table(struct):
            assert re.fullmatch(r"[a-z][a-z0-9_]*", name), name
            assert len(doc) > 5, name
            assert words is None or isinstance(words, str)
    rows = {r[0]: r for r in _flaplag.option_table("critical")}
    assert rows["mu_max"][3] == "> 0 and <= 1000"
    assert rows["all_intervals"][3] is None


def test_a_row_checks_its_range_under_its_key():
    a = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput, match=r"^mu_max = 0: must be > 0 and <= 1000$"):
        a.critical(mu_max=0)
    with pytest.raises(flaplag.InvalidInput, match=r"^samples_per_rev = 0: must be 1\.\.10000$"):
        a.simulate(0.3, samples_per_rev=0)


def test_unknown_key_and_wrong_type_name_the_key():
    a = flaplag.Analysis()._native
    with pytest.raises(flaplag.InvalidInput, match=r"^bogus = 1: unknown option of the critical"):
        a.critical({"bogus": 1})
    with pytest.raises(flaplag.InvalidInput, match=r"^mu_max = 'x': must be a real number$"):
        a.critical({"mu_max": "x"})
    with pytest.raises(flaplag.InvalidInput, match=r"^all_intervals = 1: must be True or False$"):
        a.critical({"all_intervals": 1})
    with pytest.raises(flaplag.InvalidInput, match=r"^points = 2\.5: must be a whole number$"):
        a.campbell({"points": 2.5})
    with pytest.raises(flaplag.InvalidInput, match=r"^method = 'x': must be one of rk4, hsu"):
        flaplag.Analysis(method="x")


def _help(command):
    return subprocess.run([CLI, command, "--help"], capture_output=True, text=True,
                          check=True).stdout


@pytest.mark.skipif(not CLI, reason="FLAPLAG_CLI not set")
@pytest.mark.parametrize(
    "command, option, struct, key",
    [
        ("critical", "--mu-max", "critical", "mu_max"),
        ("critical", "--scan-step", "critical", "scan_step"),
        ("campbell", "--speed-max", "campbell", "speed_max"),
        ("campbell", "--speeds", "campbell", "points"),
        ("campbell", "--harmonics", "campbell", "harmonics"),
        ("trim", "--thrust-coefficient", "trim", "thrust_coefficient"),
        ("simulate", "--revs", "simulation", "revolutions"),
        ("simulate", "--samples", "simulation", "samples_per_rev"),
        ("point", "--terms", "transition", "terms"),
        ("point", "--zeta-tolerance", "transition", "zeta_tolerance"),
        ("point", "--method", "transition", "method"),
    ],
)
def test_cli_option_of_a_row_shows_its_range_and_default(command, option, struct, key):
    """The help line of the row's option holds its range words and the struct's default, the
    value Python's keyword has."""
    text = _help(command)
    start = re.search(r"^  " + re.escape(option) + " ", text, re.M).start()
    entry = text[start:text.index("\n  -", start + 1)]
    entry = " ".join(entry.split())
    name, units, doc, words, default = next(
        r for r in _flaplag.option_table(struct) if r[0] == key)
    m = re.search(r"\(default ([^)]*)\)$", entry)
    assert m, entry
    if isinstance(default, str):
        assert m.group(1) == default, entry
    else:
        assert float(m.group(1)) == default, entry
    if words is not None:
        assert words in entry, entry
    assert " ".join(doc.split()) in entry, entry


# The scalar options of flaplag.study and flaplag.map (StudyOptions, MapOptions rows).
@pytest.mark.parametrize("struct,function", [("study", flaplag.study), ("map", flaplag.map)])
def test_study_and_map_keyword_defaults_are_the_tables(struct, function):
    rows = {r[0]: r for r in _flaplag.option_table(struct)}
    params = inspect.signature(function).parameters
    assert set(rows) <= set(params), struct
    for key, (name, units, doc, words, default) in rows.items():
        assert params[key].default == default, (struct, key)
        assert words is not None, key  # every scalar option has its range
        assert len(doc) > 5 and units is not None, key
    assert rows["threads"][3] == "0 (all cores) or 1..256"


def test_study_and_map_rows_check_their_ranges_under_their_keys():
    with pytest.raises(flaplag.InvalidInput, match=r"^threads = 257: must be 0 \(all cores\)"):
        flaplag.study("omega_lag", [1.0], threads=257)
    with pytest.raises(flaplag.InvalidInput, match=r"^damping_criterion = 1: must be >= 0 and < 1"):
        flaplag.study("omega_lag", [1.0], damping_criterion=1.0)
    with pytest.raises(flaplag.InvalidInput, match=r"^mu = 1001: must be in \[0, 1000\]$"):
        flaplag.map(("theta", [0.1]), ("omega_lag", [1.0]), mu=1001)
    with pytest.raises(flaplag.InvalidInput, match=r"^scan_step = -1: must be > 0$"):
        flaplag.map(("mu", [0.0, 0.1]), ("omega_lag", [1.0]), scan_step=-1)
