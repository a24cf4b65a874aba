"""The results' attributes are the keys of their C++ field tables (core/fields.h), the same keys
the command line's JSON uses: one name per field in every front end."""

import dataclasses
import math
import pickle

import numpy as np
import pytest

import flaplag
from flaplag import _flaplag
from flaplag._results import TipMotion
from conftest import run_cli

# Attributes a class adds of its own (not rows of the C++ struct's field table), by class: the
# trims and equilibria are the analysis' (RotorPoint::trim, RotorSweep::trims, ...).
PYTHON_ONLY = {
    "PointResult": {"trim", "equilibrium"},
    "SweepResult": {"mu", "labels", "zeta", "omega", "trims", "equilibria"},
    "CriticalResult": {"trim", "equilibrium"},
    "TrimResult": {"parameters"},
    "PeriodicEquilibriumResult": {"coefficients", "psi", "y", "tips"},
}

CLASSES = [
    "Exponent",
    "HoverResult",
    "PointResult",
    "SweepResult",
    "Interval",
    "CriticalResult",
    "TrimResult",
    "CampbellResult",
    "CampbellPoint",
    "CampbellFrequency",
    "CampbellCrossing",
    "ThrustResult",
    "FloquetSample",
    "PeriodicEquilibriumResult",
    "ModelInfo",
]


def keys(name):
    return [key for key, _, _ in _flaplag.result_fields(name)]


def results():
    """One result of each class, from the library."""
    an = flaplag.Analysis()
    point = an.point(0.3)
    crit = an.critical(mu_max=1.0)
    campbell = flaplag.Analysis(omega_lag=0.7).campbell(points=4)
    return {
        "Exponent": point.exponents[0],
        "HoverResult": an.hover,
        "PointResult": point,
        "SweepResult": an.sweep(0.0, 0.2, 0.1),
        "Interval": crit.intervals[0],
        "CriticalResult": crit,
        "TrimResult": an.trim(0.3, thrust_coefficient=0.005),
        "CampbellResult": campbell,
        "CampbellPoint": campbell.points[1],
        "CampbellFrequency": campbell.points[1].modes[0],
        "CampbellCrossing": campbell.crossings[0],
        "ThrustResult": an.thrust(0.3),
        "FloquetSample": an.floquet(0.3),
        "PeriodicEquilibriumResult": an.periodic_equilibrium(0.3),
        "ModelInfo": an.model,
    }


def test_every_key_is_an_attribute():
    for name, result in results().items():
        assert type(result).__name__ == name
        for key in keys(name):
            assert hasattr(result, key), (name, key)


def test_a_key_the_class_does_not_declare_is_an_attribute():
    """A row added to a C++ table reaches Python before the class declares it."""
    raw = {"onset": 0.5, "end": None, "onset_error": None, "end_error": None, "mode": "lag",
           "omega": 0.3, "kind": "flutter", "new_key": 2.5}
    interval = flaplag.Interval._from(raw)
    assert interval.new_key == 2.5
    with pytest.raises(AttributeError):
        interval.no_such_key


@pytest.mark.parametrize("name", CLASSES)
def test_every_field_is_a_key(name):
    cls = getattr(flaplag, name)
    own = PYTHON_ONLY.get(name, set())
    for f in dataclasses.fields(cls):
        assert f.name in keys(name) or f.name in own, f.name


def test_every_row_is_documented():
    for name in CLASSES:
        for key, units, doc in _flaplag.result_fields(name):
            assert key and doc, (name, key, units)


def test_point_json_has_the_keys_of_the_table():
    doc = run_cli("point", "--mu", "0.3")
    point = flaplag.Analysis().point(0.3)
    for key in keys("PointResult"):
        if key == "notes" and not point.notes:
            assert key not in doc  # absent when empty
        else:
            assert key in doc, key
    for key in keys("Exponent"):
        assert key in doc["exponents"][0], key
    assert doc["steps"] == point.steps
    assert doc["error_estimate"] == point.error_estimate


def test_critical_json_has_the_keys_of_the_table():
    doc = run_cli("critical", "--mu-max", "0.5")
    crit = flaplag.Analysis().critical(mu_max=0.5)
    for key in keys("CriticalResult"):
        if key != "notes":
            assert key in doc, key
    assert doc["evaluations"] == crit.evaluations
    assert len(doc["intervals"]) == len(crit.intervals)


def test_hover_json_and_python_are_the_rows_of_the_table():
    """The document's hover is HoverResult's rows that a document holds; Python has every row
    (exponents as the class's own property)."""
    for modes in ([], ["--modes", "exact", "--flap-modes", "3", "--lag-modes", "2"]):
        doc = run_cli("point", "--mu", "0.3", *modes)["hover"]
        assert list(doc) == ["inflow", "equilibrium", "exponents", "stable", "status", "message"]
        assert set(doc) <= set(keys("HoverResult"))
        kw = dict(modes="exact", flap_modes=3, lag_modes=2) if modes else {}
        hover = flaplag.Analysis(**kw).hover
        assert doc["equilibrium"] == hover.equilibrium
        assert [e["label"] for e in doc["exponents"]] == list(hover.labels)
        assert doc["stable"] == hover.stable


def test_unknown_struct_is_refused():
    with pytest.raises(ValueError):
        _flaplag.result_fields("NoSuchResult")


def test_campbell_is_the_command_lines():
    """Analysis.campbell and ``flaplag campbell --json`` give the same numbers (one library)."""
    doc = run_cli("campbell", "--omega-lag", "0.7", "--speeds", "5", "--harmonics", "2")
    c = flaplag.Analysis(omega_lag=0.7).campbell(points=5, harmonics=2)
    assert list(c.labels) == doc["labels"]
    assert list(c.speed) == [p["speed"] for p in doc["points"]]
    for m, label in enumerate(c.labels):
        assert list(c.frequency[label]) == [p["modes"][m]["frequency"] for p in doc["points"]]
    assert [(x.label, x.harmonic, x.speed) for x in c.crossings] == [
        (x["label"], x["harmonic"], x["speed"]) for x in doc["crossings"]
    ]
    assert c.points[0].modes[0].damping_ratio is None
    with pytest.raises(ValueError, match="speed_max"):
        flaplag.Analysis().campbell(speed_max=0.0)


def test_floquet_sample_columns_are_numpy_arrays():
    """The exponents' columns of a sample are arrays of their element type, as the dict's lists
    would not be: multipliers complex, the rest real, one entry per exponent."""
    s = flaplag.Analysis().floquet(0.3)
    assert s.multipliers.dtype == np.complex128
    for name in ("zeta", "omega", "zeta_errors"):
        assert getattr(s, name).dtype == np.float64, name
    assert len(s.multipliers) == len(s.zeta) == len(s.omega) == 4
    # zeta = ln|multiplier| / 2 pi, omega = arg(multiplier) / 2 pi: the columns are in one order
    assert np.allclose(s.zeta, np.log(np.abs(s.multipliers)) / (2 * np.pi), rtol=0, atol=1e-12)
    assert np.allclose(s.omega, np.angle(s.multipliers) / (2 * np.pi), rtol=0, atol=1e-12)


def test_an_empty_array_keeps_its_element_type():
    raw = {"multipliers": [], "zeta": [], "omega": [], "zeta_errors": [], "error_estimate": None,
           "steps": 0, "liouville_residual": 1.0, "status": "failed", "message": "x"}
    s = flaplag.FloquetSample._from(raw)
    assert s.multipliers.dtype == np.complex128 and s.zeta.dtype == np.float64


def test_error_estimate_is_one_name():
    """The estimated error is `error_estimate` in every result, as in the command line's JSON;
    `error` stays as its former name."""
    an = flaplag.Analysis()
    s = an.floquet(0.3)
    assert "error_estimate" in keys("FloquetSample") and "error" not in keys("FloquetSample")
    assert s.error == s.error_estimate
    r = an.response(0.3)
    assert r.error_estimate is not None and r.error == r.error_estimate
    doc = run_cli("response", "--mu", "0.3")
    assert doc["error_estimate"] == r.error_estimate


def test_equilibrium_without_stability_check():
    """Without the stability check there are no multipliers and no distance to one (None, not
    the struct's 0); the table's mean thrust is the model's, a number for the paper model."""
    an = flaplag.Analysis()
    e = an.periodic_equilibrium(0.3, check_stability=False)
    assert len(e.multiplier_moduli) == 0 and e.multiplier_moduli.dtype == np.float64
    assert e.min_distance_to_one is None and e.max_zeta is None
    checked = an.periodic_equilibrium(0.3)
    assert 0.0 < checked.min_distance_to_one < 1.0
    assert checked.max_zeta < 0.0
    assert math.isfinite(checked.mean_thrust) and checked.mean_thrust > 0.0


def test_model_object_is_the_model_info():
    """The header's `model` object and Analysis.model are one table: the same keys and values."""
    doc = run_cli("point", "--mu", "0.3", "--model", "paper-2x1", "--modes", "exact")
    info = flaplag.Analysis(model="paper-2x1", modes="exact").model
    assert set(doc["model"]) == {f.name for f in dataclasses.fields(info)}
    for key, value in doc["model"].items():
        assert getattr(info, key) == value, key
    assert doc["model"]["base"] == "paper" and doc["model"]["flap_modes"] == 2


def cli_directions(doc, suffix):
    """The directions of the command line's per-direction keys '<direction><suffix>', in the
    order of the document."""
    found = []

    def walk(node):
        if isinstance(node, dict):
            for key, value in node.items():
                if key.endswith(suffix) and key[: -len(suffix)] not in found:
                    found.append(key[: -len(suffix)])
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)

    walk(doc)
    return found


def test_tips_are_the_directions_of_the_model_in_state_order():
    """Each result with tip motions holds one TipMotion per blade direction, keyed by its name
    in the model's state order: the directions the command line's keys name, none missing, and
    each direction's tip deflection the displacement of its state (1 x 1, assumed modes: tip
    value 1; the state is [rate, displacement] per direction)."""
    an = flaplag.Analysis()
    r = an.response(0.3, samples=12)
    s = an.simulate(0.3, revolutions=1)
    e = an.periodic_equilibrium(0.3, samples=12, check_stability=False)
    assert cli_directions(run_cli("response", "--mu", "0.3", "--samples", "12"), "_tip") == [
        "flap",
        "lag",
    ]
    for result in (r, s, e):
        assert list(result.tips) == ["flap", "lag"], type(result).__name__
        for direction, tip in result.tips.items():
            assert isinstance(tip, TipMotion)
            assert tip.direction == direction
            assert tip.deflection.shape == result.psi.shape
    for i, tip in enumerate(e.tips.values()):
        assert np.array_equal(tip.deflection, e.y[:, 2 * i + 1]), tip.direction
    wide = flaplag.Analysis(modes="exact", flap_modes=2, lag_modes=2).response(0.3, samples=12)
    assert list(wide.tips) == ["flap", "lag"]
    assert all(len(t.harmonics) == len(wide.harmonic_names) for t in wide.tips.values())


def test_former_names_are_the_tips():
    """flap_tip, lag_harmonics, lag_growth_rate, ...: read-only names of the tips' fields."""
    an = flaplag.Analysis()
    r = an.response(0.3, samples=12)
    s = an.simulate(0.3, revolutions=4)
    assert r.flap_tip is r.tips["flap"].deflection
    assert r.lag_harmonics is r.tips["lag"].harmonics
    assert s.lag_growth_rate == s.tips["lag"].growth_rate is not None
    assert s.flap_total is s.tips["flap"].total
    assert r.harmonics("lag") == {
        n: float(v) for n, v in zip(r.harmonic_names, r.tips["lag"].harmonics)
    }
    assert r.harmonics() == r.harmonics("flap")
    for result in (r, s):
        for direction, tip in result.tips.items():
            assert getattr(result, direction + "_tip") is tip.deflection
            assert direction + "_tip" in dir(result)
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.flap_tip = np.zeros(12)
    for missing in ("torsion_tip", "flap_modes", "flap_direction", "tip"):
        with pytest.raises(AttributeError):
            getattr(r, missing)
    again = pickle.loads(pickle.dumps(r))
    assert list(again.tips) == list(r.tips) and np.array_equal(again.lag_tip, r.lag_tip)


def test_a_direction_the_module_does_not_give_has_no_names():
    """The names come from the module's directions, none from the class: a result without a
    'lag' direction has no lag_tip, and one with a third direction has its names too."""
    tip = {"deflection": np.ones(2), "harmonics": np.zeros(0), "total": np.zeros(0),
           "growth_rate": 0.5}
    raw = {"mu": 0.0, "psi": np.zeros(2), "y": np.zeros((2, 2)),
           "tips": {"flap": dict(tip, direction="flap"), "torsion": dict(tip, direction="torsion")},
           "steps_per_rev": 1, "status": "ok", "message": ""}
    s = flaplag.SimulationResult._from(raw)
    assert list(s.tips) == ["flap", "torsion"]
    assert s.torsion_growth_rate == 0.5 and s.flap_tip is s.tips["flap"].deflection
    with pytest.raises(AttributeError):
        s.lag_tip
    assert "torsion_growth_rate=0.5" in repr(s)


def test_study_json_rows_are_the_keys_of_the_tables():
    # A row: StudyRow's rows in its order; trim and damping_crossings when the study asks for
    # them, basis_error with exact modes only.
    doc = run_cli("study", "--vary", "omega-lag=1.0,1.3", "--trim", "thrust", "--mu-max", "0.3",
                  "--damping-criterion", "0.01", "--quiet")
    for row in doc["rows"]:
        assert list(row) == [k for k in keys("StudyRow") if k != "basis_error"], list(row)
    plain = run_cli("study", "--vary", "omega-lag=1.0,1.3", "--mu-max", "0.3", "--quiet")
    asked = {"basis_error", "trim", "damping_crossings"}
    for row in plain["rows"]:
        assert list(row) == [k for k in keys("StudyRow") if k not in asked], list(row)
    exact = run_cli("study", "--vary", "omega-lag=1.0", "--mu-max", "0.3", "--modes", "exact",
                    "--quiet")
    for row in exact["rows"]:
        assert list(row) == [k for k in keys("StudyRow") if k not in asked - {"basis_error"}]
    # The search's keys, each as CriticalResult has it (intervals: [onset, end] pairs).
    assert set(keys("StudyRow")) - set(keys("CriticalResult")) == {
        "value", "trim", "damping_crossings"}


def test_map_json_grids_and_python_arrays_are_the_keys_of_the_table():
    doc = run_cli("map", "--x", "mu=0:0.2:0.1", "--y", "omega-lag=1.0,1.4", "--quiet")
    grids = {k for k, v in doc.items()
             if isinstance(v, list) and len(v) == 2 and all(len(line) == 3 for line in v)}
    assert grids == {"max_zeta", "mode", "kind"}
    assert grids <= set(keys("MapCell"))
    raw = _flaplag.map({}, {}, 1, 1, "mu", [0.0, 0.1, 0.2], "omega_lag", [1.0, 1.4], 0.0, 0.01,
                       1, None, None, 1 << 30)
    for key in keys("MapCell"):
        if key != "notes":  # a list per cell: not an array
            assert np.shape(raw[key]) == (2, 3), key
