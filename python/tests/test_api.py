"""The Python API: vocabulary, errors, results, the GIL, studies and maps."""

import inspect
import math
import os
import signal
import time
import pickle
import pydoc
import threading

import numpy as np
import pytest

import flaplag
from conftest import cli_error, cli_args


# ---- vocabulary --------------------------------------------------------------------------------

def test_keywords_are_the_library_fields():
    sig = inspect.signature(flaplag.Analysis)
    names = list(sig.parameters)
    table = [r["field"] for r in flaplag.parameter_table()]
    assert names[: len(table)] == table
    assert names[len(table):] == ["method", "steps", "terms", "zeta_tolerance", "flap_modes",
                                  "lag_modes"]
    for name in ("gamma", "sigma", "lift_slope", "cdo", "theta", "precone", "droop",
                 "omega_flap", "omega_lag", "damping_flap", "damping_lag", "length_ratio",
                 "tip_loss_a", "tip_loss_b", "root_offset", "reversed_flow",
                 "exact_reversed_flow", "modes",
                 "elastic_coupling", "paper_1974_shapes", "model"):
        assert name in names
    assert all(p.kind is inspect.Parameter.KEYWORD_ONLY for p in sig.parameters.values())
    # defaults: the paper's typical case (Fig 3)
    assert sig.parameters["omega_lag"].default == 1.28303
    assert sig.parameters["gamma"].default == 10.0
    assert sig.parameters["method"].default == "auto"
    assert sig.parameters["steps"].default == 0


def test_help_reads_well():
    text = pydoc.render_doc(flaplag.Analysis, renderer=pydoc.plaintext)
    for row in flaplag.parameter_table():
        assert row["field"] in text
        assert row["description"].split()[0] in text
    assert "omega_lag : float, default 1.28303" in text
    assert "[per rev]" in text and "[rad]" in text
    for method in ("critical", "sweep", "point", "system", "modes"):
        assert method in text


def test_parameters_round_trip():
    an = flaplag.Analysis(theta=0.2, omega_lag=1.5, reversed_flow=False, modes="exact")
    p = an.parameters
    assert p["theta"] == 0.2 and p["omega_lag"] == 1.5
    assert p["reversed_flow"] is False and p["modes"] == "exact"
    assert an.options == {"method": "hsu", "steps": 0, "terms": 4, "zeta_tolerance": 1e-5}
    assert "theta=0.2" in repr(an)
    assert flaplag.Analysis(modes="exact", flap_modes=2, lag_modes=2).model.name == "paper-2x2"


def test_any_mode_counts_up_to_twelve():
    """One model per spec, instantiated for any M x N (1..12) with exact modes."""
    m = flaplag.Analysis(modes="exact", flap_modes=4, lag_modes=1).model
    assert (m.name, m.base, m.flap_modes, m.lag_modes) == ("paper-4x1", "paper", 4, 1)
    m = flaplag.Analysis(model="lag-order-2", modes="exact", flap_modes=3, lag_modes=2).model
    assert (m.name, m.base, m.flap_modes, m.lag_modes) == ("lag-order-2-3x2", "lag-order-2", 3, 2)
    m = flaplag.Analysis(modes="exact", flap_modes=6, lag_modes=6).model  # 12 functions hold 6
    assert m.name == "paper-6x6"
    assert flaplag.Analysis(model="paper-3x2", modes="exact").model.name == "paper-3x2"
    # the models are one per spec, at the spec's mode counts
    assert sorted(m.name for m in flaplag.models()) == ["lag-order-2", "no-radial-flow", "paper"]
    # the names of before one model per spec still run, as the model that replaced them
    for old, now in (("paper-cyclic", "paper"), ("paper-nonlinear", "paper"),
                     ("paper-cyclic-nonlinear", "paper")):
        assert flaplag.Analysis(model=old).model.name == now
    assert flaplag.Analysis(model="paper-cyclic-2x2", modes="exact").model.name == "paper-2x2"


def test_one_label_scheme_for_every_model():
    """The first mode of a direction is the direction's name in every model, so "lag" of the
    1 x 1 and of a 2 x 2 model are one mode; "lag1" (older M x N results) names it too."""
    one = flaplag.Analysis().point(0.3)
    two = flaplag.Analysis(modes="exact", flap_modes=2, lag_modes=2).point(0.3)
    assert sorted(set(one.labels)) == ["flap", "lag"]
    assert sorted(set(two.labels)) == ["flap", "flap2", "lag", "lag2"]
    lag = two.dominant("lag")
    assert lag is not None and abs(lag.omega - one.dominant("lag").omega) < 0.05
    assert two.dominant("lag1") == lag
    assert two.dominant("lag3") is None


def test_numpy_scalars_are_numbers():
    a = flaplag.Analysis(theta=np.float64(0.15), steps=np.int64(50), reversed_flow=np.bool_(True))
    b = flaplag.Analysis(theta=0.15, steps=50)
    assert a.critical().mu_c == b.critical().mu_c


# ---- errors ------------------------------------------------------------------------------------

@pytest.mark.parametrize("field,value", [
    ("gamma", -1.0), ("gamma", 0.0), ("sigma", 2.0), ("theta", 2.0), ("omega_lag", 0.0),
    ("omega_flap", 1e6), ("damping_lag", -0.1), ("tip_loss_b", 0.0), ("root_offset", 1.0),
    ("cdo", -0.01), ("lift_slope", 101.0), ("basis", 0), ("basis", 13),
])
def test_invalid_value_has_the_cli_reason(field, value):
    with pytest.raises(ValueError) as err:
        flaplag.Analysis(**{field: value})
    e = err.value
    assert isinstance(e, flaplag.InvalidInput)
    assert e.field == field
    assert str(e) == f"{e.field} = {e.value}: {e.reason}"
    # the command line says the same about the same value
    option, cli_value, reason = cli_error(*cli_args(**{field: value}), "critical")
    assert option == "--" + field.replace("_", "-")
    assert reason == e.reason
    assert float(cli_value) == float(e.value)


@pytest.mark.parametrize("kwargs,field", [
    ({"model": "nope"}, "model"),
    ({"modes": "foo"}, "modes"),
    ({"method": "euler"}, "method"),
    ({"steps": -1}, "steps"),
    ({"terms": 0}, "terms"),
    ({"zeta_tolerance": 0.0}, "zeta_tolerance"),
    ({"theta": "0.1"}, "theta"),
    ({"theta": None}, "theta"),
    ({"theta": math.nan}, "theta"),
    ({"lift_slope": math.inf}, "lift_slope"),
    ({"reversed_flow": 1}, "reversed_flow"),
    ({"steps": 50.5}, "steps"),
    ({"steps": True}, "steps"),
    ({"flap_modes": 2}, "flap_modes"),  # more than one mode needs exact modes
    ({"modes": "exact", "lag_modes": 13, "basis": 12}, "lag_modes"),  # more than 12
    ({"modes": "exact", "flap_modes": 6, "basis": 5}, "basis"),  # the basis given: it is named
    ({"model": "paper-13x1", "modes": "exact"}, "model"),
    ({"flap_modes": 0}, "flap_modes"),
    ({"basis": 2.5}, "basis"),
    ({"basis": "5"}, "basis"),
    ({"modes": "exact", "flap_modes": 3, "lag_modes": 3, "basis": 2}, "basis"),
    ({"modes": "exact", "omega_lag": 0.2, "basis": "paper"}, "omega_lag"),  # below 5's 0.2074
    ({"basis": "fine"}, "basis"),  # not one of the names
])
def test_bad_arguments_raise_value_error(kwargs, field):
    with pytest.raises(ValueError) as err:
        flaplag.Analysis(**kwargs)
    assert err.value.field == field
    assert str(err.value).startswith(field + " = ")


def test_unknown_keyword():
    with pytest.raises(ValueError) as err:
        flaplag.Analysis(omega_lagg=1.2)
    assert isinstance(err.value, TypeError)
    assert "did you mean omega_lag" in str(err.value)


def test_bad_method_arguments():
    an = flaplag.Analysis()
    cases = [
        lambda: an.point(-1.0),
        lambda: an.point(math.nan),
        lambda: an.point("0.5"),
        lambda: an.point(0.5, scan_step=0.0),
        lambda: an.sweep([0.5, 0.4]),
        lambda: an.sweep(1.0, 0.5, 0.1),
        lambda: an.sweep(0.0, 1.0, 0.0),
        lambda: an.sweep([[0.1, 0.2]]),
        lambda: an.sweep(0.0, 1.0, 0.1, threads=-1),
        lambda: an.sweep([0.1], threads=257),
        lambda: an.critical(mu_max=0.0),
        lambda: an.critical(scan_step=-0.01),
        lambda: an.critical(tolerance=0.0),
        lambda: an.system(0.5, math.inf),
        lambda: an.modes([0.0, 1.5]),
        lambda: an.modes(derivative=4),
        lambda: an.floquet(0.5, zeta_tolerance=0.0),
        lambda: flaplag.study("mu", [0.1]),
        lambda: flaplag.study("nope", [0.1]),
        lambda: flaplag.study("omega_lag", []),
        lambda: flaplag.study("omega_lag", [1.0], threads=-1),
        lambda: flaplag.study("omega_lag", [1.0], omega_lag=1.2),
        lambda: flaplag.map(x=("mu", [0.2, 0.1]), y=("theta", [0.1])),
        lambda: flaplag.map(x=("theta", [0.1]), y=("theta", [0.2])),
        lambda: flaplag.map(x=("mu", [0.1]), y=("mu", [0.2])),
        lambda: flaplag.map(x=("theta", [0.1]), y=("gamma", [5.0]), mu=-1.0),
        lambda: flaplag.map(x=("theta", [0.1]), y=("gamma", [5.0]), theta=0.2),
        lambda: flaplag.map(x="theta", y=("gamma", [5.0])),
        lambda: flaplag.map(x=("theta", [0.1]), y=("gamma", [5.0]), gamma=-1.0),
    ]
    for i, case in enumerate(cases):
        with pytest.raises(ValueError):
            case()
            pytest.fail(f"case {i} did not raise")
    with pytest.raises(TypeError):
        an.sweep(0.0, 1.0)


# ---- results -----------------------------------------------------------------------------------

def test_critical_result_reads_well():
    crit = flaplag.Analysis().critical()
    text = repr(crit)
    assert text.startswith("CriticalResult(mu_c=0.754")
    assert "mode='lag'" in text and "kind='flutter'" in text and "status='ok'" in text
    assert str(crit) == text
    stable = flaplag.Analysis(omega_lag=1.7).critical(mu_max=1.0)
    assert stable.mu_c is None and stable.mode is None and stable.kind is None
    assert "stable up to mu = 1" in repr(stable)


def test_all_intervals():
    crit = flaplag.Analysis().critical(all_intervals=True)
    assert crit.intervals and crit.intervals[0].onset == crit.mu_c
    for a, b in zip(crit.intervals, crit.intervals[1:]):
        assert a.end is not None and a.end < b.onset


def test_hover_is_eq_2_24():
    """lambda = sigma a / 16 [sqrt(1 + 24 theta / (sigma a)) - 1] (eq 2.24)."""
    sigma, a, theta = 0.07, 5.9, 0.12
    hover = flaplag.Analysis(sigma=sigma, lift_slope=a, theta=theta).hover
    expected = sigma * a / 16 * (math.sqrt(1 + 24 * theta / (sigma * a)) - 1)
    assert hover.inflow == pytest.approx(expected, rel=1e-14)
    assert hover.A0.shape == (4, 4) and len(hover.eigenvalues) == 4
    assert set(hover.labels) == {"flap", "lag"} and hover.stable
    assert set(hover.equilibrium) == {"g0_1", "h0_1"}


def test_assumed_mode_shape_is_eq_4_1():
    """eta = gamma = -(1/3) [1 - 4 x0 - (1 - x0)^4] (eq 4.1), with eta(1) = 1."""
    x = np.linspace(0.0, 1.0, 11)
    shapes = flaplag.Analysis().modes(x)
    expected = -(1 - 4 * x - (1 - x) ** 4) / 3
    assert shapes.flap.shape == (1, 11) and shapes.lag.shape == (1, 11)
    np.testing.assert_allclose(shapes.flap[0], expected, rtol=0, atol=1e-15)
    np.testing.assert_allclose(shapes.lag[0], expected, rtol=0, atol=1e-15)
    slope = flaplag.Analysis().modes(x, derivative=1).flap[0]
    np.testing.assert_allclose(slope, -(-4 + 4 * (1 - x) ** 3) / 3, rtol=0, atol=1e-14)
    exact = flaplag.Analysis(modes="exact", flap_modes=2, lag_modes=2).modes(51)
    assert exact.kind == "exact" and exact.flap.shape == (2, 51)
    assert list(exact.omega_lag)[0] == 1.28303


def test_sweep_of_an_array():
    an = flaplag.Analysis()
    mus = np.array([0.0, 0.3, 0.35, 0.8, 1.0])
    s = an.sweep(mus)
    assert s.mu.tolist() == mus.tolist() and len(s) == 5
    assert s.stable[-1] is False and s.stable[0] is True
    assert "lag" in s.zeta and s.zeta["lag"].shape == (5,)


def test_sweep_is_the_same_for_one_and_two_threads():
    an = flaplag.Analysis()
    one, two = an.sweep(0.0, 1.5, 0.01, threads=1), an.sweep(0.0, 1.5, 0.01, threads=2)
    assert len(one) == 151
    for label in one.zeta:
        assert one.zeta[label].tolist() == two.zeta[label].tolist()
        assert one.omega[label].tolist() == two.omega[label].tolist()


def test_results_pickle():
    an = flaplag.Analysis(theta=0.2)
    again = pickle.loads(pickle.dumps(an))
    assert again.critical().mu_c == an.critical().mu_c
    for r in (an.critical(), an.point(0.3), an.sweep([0.1, 0.2]), an.hover, an.system(0.3, 1.0)):
        assert repr(pickle.loads(pickle.dumps(r))) == repr(r)


def test_version():
    assert flaplag.__version__.count(".") == 2
    assert isinstance(flaplag.git_commit, str)


# ---- the GIL -----------------------------------------------------------------------------------

def test_the_gil_is_released_during_a_computation():
    """A Python thread keeps running while the analysis computes: with the GIL held for the
    whole call it could not take a single step."""
    an = flaplag.Analysis()
    counter = [0]
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            counter[0] += 1

    t = threading.Thread(target=spin)
    t.start()
    try:
        before = counter[0]
        an.sweep(0.0, 2.0, 0.002)
        during = counter[0] - before
    finally:
        stop.set()
        t.join()
    assert during > 1000


# ---- studies and maps --------------------------------------------------------------------------

def test_study_rows_are_the_single_analyses():
    values = [0.5, 1.0, 1.28303]
    st = flaplag.study("omega_lag", values, threads=2)
    assert st.values.tolist() == values and len(st) == 3
    for v, row in zip(values, st.rows):
        crit = flaplag.Analysis(omega_lag=v).critical(all_intervals=True)
        assert row.mu_c == crit.mu_c and row.mode == crit.mode and row.kind == crit.kind
    assert st.kind.tolist() == ["periodic", "flutter", "flutter"]
    assert st.metadata["flaplag_version"] == flaplag.__version__
    one = flaplag.study("omega_lag", values, threads=1)
    assert one.mu_c.tobytes() == st.mu_c.tobytes()


def test_study_rows_carry_the_basis_error():
    """Exact modes: each row's basis_error is the change of its mu_c with the neighbouring
    basis, part of mu_c_error; nan for the assumed mode."""
    st = flaplag.study("theta", [0.15], modes="exact", basis="paper")
    six = flaplag.Analysis(modes="exact", basis=6, theta=0.15).critical()
    assert st.rows[0].basis == 5
    assert abs(st.basis_error[0] - abs(six.mu_c - st.mu_c[0])) < 1e-12
    assert st.mu_c_error[0] >= st.basis_error[0] > 0
    assert math.isnan(flaplag.study("theta", [0.15]).basis_error[0])


def _map(threads, **kw):
    return flaplag.map(x=("mu", np.linspace(0.0, 1.2, 13)), y=("omega_lag", [0.6, 1.0, 1.4, 1.8]),
                       threads=threads, **kw)


def test_map_two_threads_equal_one():
    one, two = _map(1), _map(2)
    assert one.max_zeta.shape == (4, 13)
    assert one.max_zeta.tobytes() == two.max_zeta.tobytes()
    assert one.omega.tobytes() == two.omega.tobytes()
    assert one.mode.tolist() == two.mode.tolist() and one.kind.tolist() == two.kind.tolist()
    assert one == two
    assert "4) x mu (13)" in repr(one)


def test_map_cells_are_the_analyses():
    m = _map(2, theta=0.2)
    mus = m.x_values
    for i, w in enumerate(m.y_values):
        sweep = flaplag.Analysis(theta=0.2, omega_lag=w).sweep(mus)
        assert m.max_zeta[i].tobytes() == sweep.max_zeta.tobytes()
    # without a mu axis every cell is a point; rows along y
    grid = flaplag.map(x=("theta", [0.1, 0.2]), y=("gamma", [5.0, 10.0, 15.0]), mu=0.6)
    assert grid.max_zeta.shape == (3, 2)
    assert grid.max_zeta[2, 0] == flaplag.Analysis(gamma=15.0, theta=0.1).point(0.6).max_zeta
    # mu on y: columns along mu
    t = flaplag.map(x=("omega_lag", [0.6, 1.0, 1.4, 1.8]), y=("mu", np.linspace(0.0, 1.2, 13)),
                    theta=0.2)
    assert t.max_zeta.tobytes() == np.ascontiguousarray(m.max_zeta.T).tobytes()


def test_progress_and_cancel():
    seen = []
    _map(1, progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1] == (4, 4)

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop()

    with pytest.raises(Stop):
        flaplag.map(x=("mu", np.linspace(0, 1, 101)), y=("omega_lag", np.linspace(0.5, 2, 40)),
                    threads=1, progress=stop)


def test_ctrl_c_cancels_a_map():
    """SIGINT during a long map raises KeyboardInterrupt soon after (the lines already started
    finish; the rest is not computed)."""
    timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        timer.start()
        # about a minute of work on one thread
        flaplag.map(x=("mu", np.linspace(0, 1.5, 301)), y=("omega_lag", np.linspace(0.2, 2.5, 400)),
                    threads=1)
    timer.join()
    assert time.monotonic() - start < 10.0


# ---- the exact-mode basis, the forced response and the simulation ----------------------------

def test_basis_keyword_reaches_the_exact_modes():
    """basis (the command line's --basis): the Galerkin basis of the exact modes, by default
    the converged one (12 functions, its error estimated against 11); "paper" is the paper's
    five functions, whose lag limit 0.2074 refuses the left end of Fig 15 (omega_lag = 0.2)."""
    assert flaplag.Analysis().parameters["basis"] == "converged"
    assert flaplag.Analysis(basis="paper").parameters["basis"] == 5
    an = flaplag.Analysis(modes="exact", omega_lag=0.2, basis=12)
    assert an.parameters["basis"] == 12
    crit = an.critical(mu_max=1.5)
    assert crit.mu_c is not None and crit.basis == 12
    # resolved in the Floquet analysis; the basis error is in mu_c_error (and, above 10
    # tolerances, in the status)
    assert "not resolved to" not in crit.message
    assert crit.basis_error is not None and crit.mu_c_error >= crit.basis_error
    assert crit.status == ("warning" if crit.basis_error > 10 * 1e-5 else "ok"), crit.message
    x = np.linspace(0, 1, 11)
    five = flaplag.Analysis(modes="exact", basis="paper").modes(x).lag
    twelve = flaplag.Analysis(modes="exact", basis=12).modes(x).lag
    assert not np.array_equal(five, twelve)
    assert abs(five[0, -1] - 1.0) < 1e-12 and abs(twelve[0, -1] - 1.0) < 1e-12  # tip-normalised


def test_response_is_periodic_and_its_harmonics_rebuild_it():
    r = flaplag.Analysis().response(0.3, samples=72)
    assert r.status == "ok", r.message
    assert list(r.tips) == ["flap", "lag"]
    assert r.psi.shape == r.tips["flap"].deflection.shape == r.tips["lag"].deflection.shape == (72,)
    assert r.y.shape == (72, 4) and np.array_equal(r.y[0], r.y0)
    assert r.closure < 1e-10
    assert r.harmonic_names[:3] == ("const", "cos psi", "sin psi")
    assert set(r.harmonics("lag")) == set(r.harmonic_names)
    # five harmonics rebuild the tip deflection to within the higher harmonics left out
    flap = r.tips["flap"]
    rebuilt = np.full_like(r.psi, flap.harmonics[0])
    for n in range(1, 6):
        rebuilt += flap.harmonics[2 * n - 1] * np.cos(n * r.psi)
        rebuilt += flap.harmonics[2 * n] * np.sin(n * r.psi)
    assert np.max(np.abs(rebuilt - flap.deflection)) < 1e-4 * np.max(np.abs(flap.deflection))


def test_simulation_growth_rate_is_the_largest_zeta():
    """Issue 12: the envelope of the free response grows like exp(max zeta psi)."""
    an = flaplag.Analysis()
    s = an.simulate(0.9, revolutions=40)
    zeta = max(e.zeta for e in an.point(0.9).exponents if e.label == "lag")
    assert s.status == "ok", s.message
    assert s.y.shape == (len(s.psi), 4)
    assert abs(s.tips["lag"].growth_rate - zeta) < 0.01 * abs(zeta)
    assert np.array_equal(s.revolutions, s.psi / (2 * math.pi))
    # y0 per state: only the lag displacement perturbed
    t = an.simulate(0.9, revolutions=2, y0=[0.0, 0.0, 0.0, 0.02])
    assert t.tips["lag"].deflection[0] == 0.02 and t.tips["flap"].deflection[0] == 0.0
    with pytest.raises(ValueError):
        an.simulate(0.9, y0=[0.0, 1.0])
    with pytest.raises(ValueError):
        an.simulate(0.9, revolutions=0.0)
    with pytest.raises(ValueError):
        an.response(-0.1)


# ---- forward flight: periodic equilibrium, nonlinear simulation, trim (issue 12) --------------


def test_periodic_linearization_keyword_reaches_the_analysis():
    """The parameter table's switch: about the periodic equilibrium the exponents at mu > 0
    differ from the hover linearization's, with the default model (every model has the
    nonlinear loads) and with the old name of the model that had them."""
    hover = flaplag.Analysis().point(0.3)
    periodic = flaplag.Analysis(periodic_linearization=True).point(0.3)
    assert periodic.status != "failed", periodic.message
    assert abs(periodic.max_zeta - hover.max_zeta) > 1e-4
    old = flaplag.Analysis(model="paper-nonlinear", periodic_linearization=True).point(0.3)
    assert old.max_zeta == periodic.max_zeta


def test_periodic_linearization_is_the_conditions_keyword_not_a_parameter():
    """The linearization moved from the rotor parameters into the operating condition: the
    keyword stays, named as typed in errors, and it is no longer among the parameters."""
    assert "periodic_linearization" not in flaplag.Analysis().parameters
    an = flaplag.Analysis(periodic_linearization=True)
    assert "periodic_linearization" not in an.parameters
    with pytest.raises(flaplag.InvalidInput) as e:
        an.response(0.3)
    assert e.value.field == "periodic_linearization"
    assert str(e.value).startswith("periodic_linearization = True: ")
    with pytest.raises(flaplag.InvalidInput) as e:
        flaplag.Analysis(periodic_linearization=True, exact_reversed_flow=True)
    assert e.value.field == "exact_reversed_flow"
    assert "`periodic_linearization`" in str(e.value)
    # off is the hover linearization, as without the keyword
    assert flaplag.Analysis(periodic_linearization=False).point(0.3).max_zeta == (
        flaplag.Analysis().point(0.3).max_zeta
    )


def _same_equilibrium(carried, alone):
    """carried (a result's q°) is alone (found on its own, continued from hover) to the Newton
    tolerance: the same K, coefficients within 1e-9, sampled at the same 72 azimuths."""
    assert isinstance(carried, flaplag.PeriodicEquilibriumResult)
    assert carried.status != "failed", carried.message
    assert carried.mu == alone.mu and carried.harmonics == alone.harmonics
    assert carried.coefficients.shape == alone.coefficients.shape
    assert np.max(np.abs(carried.coefficients - alone.coefficients)) < 1e-9
    assert np.array_equal(carried.psi, alone.psi) and carried.y.shape == alone.y.shape == (72, 4)
    assert np.max(np.abs(carried.tips["flap"].deflection - alone.tips["flap"].deflection)) < 1e-9
    # a q° of its own mu, not the hover one or another point's
    assert np.max(np.abs(carried.coefficients[:, 1:])) > 1e-3


def test_results_about_the_periodic_equilibrium_carry_it():
    """point, each point of a sweep and critical about q° hold the PeriodicEquilibriumResult
    their exponents were computed about; about hover and with a trim (the trim holds it) None."""
    an = flaplag.Analysis(periodic_linearization=True)
    alone = an.periodic_equilibrium(0.3)
    _same_equilibrium(an.point(0.3).equilibrium, alone)
    s = an.sweep(0.1, 0.3, 0.1)
    assert len(s.equilibria) == len(s.points) == 3
    for p, e in zip(s.points, s.equilibria):
        assert p.equilibrium is e and e.mu == p.mu
        _same_equilibrium(e, an.periodic_equilibrium(p.mu))
    assert an.sweep([0.3]).points[0].equilibrium.mu == 0.3
    # critical: a lag flutter near mu = 0.3 with a soft lag mode and a higher pitch
    soft = flaplag.Analysis(periodic_linearization=True, omega_lag=0.8, theta=0.25)
    c = soft.critical(mu_max=0.5)
    assert c.mu_c is not None and c.equilibrium is not None, c
    assert abs(c.equilibrium.mu - c.mu_c) <= c.mu_c_error
    _same_equilibrium(c.equilibrium, soft.periodic_equilibrium(c.equilibrium.mu))
    hover = flaplag.Analysis()
    assert hover.point(0.3).equilibrium is None and hover.critical(mu_max=0.3).equilibrium is None
    assert hover.sweep(0.1, 0.3, 0.1).equilibria == ()
    assert all(p.equilibrium is None for p in hover.sweep(0.1, 0.3, 0.1).points)
    trimmed = an.point(0.3, trim="thrust", thrust_coefficient=0.005)
    assert trimmed.equilibrium is None and trimmed.trim.equilibrium["harmonics"] == 16


def test_periodic_equilibrium_arrays_and_its_hover_limit():
    an = flaplag.Analysis()
    e = an.periodic_equilibrium(0.3, harmonics=8, samples=36)
    assert e.status == "ok", e.message
    assert e.coefficients.shape == (2, 17) and e.harmonics == 8
    flap_tip = e.tips["flap"].deflection
    assert e.psi.shape == flap_tip.shape == (36,) and e.y.shape == (36, 4)
    # the samples are the Fourier series of the coefficients (assumed modes: tip value 1)
    g = e.coefficients[0, 0] + sum(
        e.coefficients[0, 2 * k - 1] * np.cos(k * e.psi) + e.coefficients[0, 2 * k] * np.sin(k * e.psi)
        for k in range(1, 9)
    )
    assert np.max(np.abs(g - flap_tip)) < 1e-14
    assert np.max(np.abs(e.y[:, 1] - flap_tip)) == 0.0
    assert len(e.multiplier_moduli) == 4 and e.max_zeta < 0.0
    assert e.min_distance_to_one > 0.0
    # at mu = 0 it is the hover equilibrium of eqs 2.29-2.32
    h = an.periodic_equilibrium(0.0, check_stability=False)
    assert abs(h.coefficients[0, 0] - an.hover.equilibrium["g0_1"]) < 1e-13
    assert np.all(h.coefficients[:, 1:] == 0.0)
    assert h.min_distance_to_one is None and h.max_zeta is None
    assert math.isnan(e.harmonics_error)  # a fixed K has no estimate


def test_periodic_equilibrium_automatic_harmonics_meet_their_tolerance():
    an = flaplag.Analysis()
    auto = an.periodic_equilibrium(0.3, samples=12, check_stability=False)
    assert auto.status == "ok", auto.message
    assert auto.harmonics >= 16 and auto.harmonics_error <= 1e-4
    # the estimate compares K with K/2: the K/2 solution differs from this one by about that
    half = an.periodic_equilibrium(0.3, harmonics=auto.harmonics // 2, samples=12,
                                   check_stability=False)
    k = half.coefficients.shape[1]
    diff = np.max(np.abs(auto.coefficients[:, :k] - half.coefficients))
    assert diff <= 1.1 * auto.harmonics_error * np.max(np.abs(auto.coefficients))
    tight = an.periodic_equilibrium(0.3, harmonics_tolerance=1e-12, samples=12,
                                    check_stability=False)
    assert tight.status == "warning" and "harmonics_tolerance" in tight.message
    assert tight.harmonics == 64


@pytest.mark.parametrize("call,field", [
    (lambda an: an.periodic_equilibrium(0.3, harmonics=0), "harmonics"),
    (lambda an: an.periodic_equilibrium(0.3, harmonics_tolerance=0.0), "harmonics_tolerance"),
    (lambda an: an.periodic_equilibrium(0.3, tolerance=1.0), "tolerance"),
    (lambda an: an.periodic_equilibrium(0.3, samples=1), "samples"),
    (lambda an: an.periodic_equilibrium(-0.3), "mu"),
    (lambda an: an.periodic_equilibrium(0.3, check_stability=1), "check_stability"),
    (lambda an: an.simulate(0.3, nonlinear=True, forced=True), "forced"),
    (lambda an: an.simulate(0.3, nonlinear="yes"), "nonlinear"),
])
def test_forward_flight_bad_inputs_name_the_keyword(call, field):
    with pytest.raises(ValueError) as err:
        call(flaplag.Analysis())
    assert err.value.field == field
    assert str(err.value).startswith(field + " = ")


def test_nonlinear_simulation_settles_on_the_periodic_equilibrium():
    """The nonlinear equations from q°(0) + y0 come back to q°(psi) (damped lag mode), and the
    tip deviation is measured from it."""
    an = flaplag.Analysis(damping_lag=0.05)
    e = an.periodic_equilibrium(0.5, samples=12, check_stability=False)
    s = an.simulate(0.5, nonlinear=True, revolutions=60, samples_per_rev=12)
    assert s.status == "ok", s.message
    assert s.nonlinear and s.reference == "periodic equilibrium"
    flap = s.tips["flap"]
    assert flap.total.shape == flap.deflection.shape == s.psi.shape
    scale = np.max(np.abs(e.y))
    last = slice(-13, -1)  # the last whole revolution, psi = 2 pi k / 12 as e.psi
    assert np.allclose(s.psi[last] - 59 * 2 * math.pi, e.psi, atol=1e-12)
    assert np.max(np.abs(s.y[last] - e.y)) < 1e-4 * scale  # (measured 7e-5: q°'s truncation)
    assert np.max(np.abs(flap.total[last] - e.tips["flap"].deflection)) < 1e-4 * scale
    assert abs(flap.deflection[0] - 0.01) < 1e-15
    # the linear simulation has no totals
    lin = flaplag.Analysis().simulate(0.5, revolutions=1)
    assert not lin.nonlinear and lin.tips["flap"].total.shape == (0,)


def test_trim_round_trip_in_hover():
    """Issue 12: the model's own C_T at theta = 0.15 in hover (eq 2.25 inflow), trimmed back,
    gives theta = 0.15."""
    c = flaplag.Analysis(theta=0.15).thrust(0.0)
    assert c.status == "ok", c.message
    assert 0.001 < c.thrust_coefficient < 0.02
    assert abs(c.inflow - math.sqrt(c.thrust_coefficient / 2)) < 1e-12  # eq 2.25 at mu = 0
    t = flaplag.Analysis(theta=0.1).trim(
        0.0, thrust_coefficient=c.thrust_coefficient
    )
    assert t.status == "ok", t.message
    assert t.converged and t.kind == "thrust"
    assert abs(t.theta0 - 0.15) < 1e-12
    assert abs(t.thrust_coefficient - c.thrust_coefficient) < 1e-15
    assert t.parameters["theta"] == t.theta0
    # the paper's eq 2.24 inflow gives another lambda at the same pitch
    p = flaplag.Analysis(theta=0.15).thrust(0.0, inflow="paper")
    assert abs(p.inflow - c.inflow) > 1e-3
    g = flaplag.Analysis(theta=0.15).thrust(0.0, inflow=c.inflow)
    assert abs(g.thrust_coefficient - c.thrust_coefficient) < 1e-15


def test_moment_trim_removes_the_first_flap_harmonic():
    t = flaplag.Analysis().trim(0.3, kind="moment", thrust_coefficient=0.005)
    assert t.status == "ok", t.message
    assert abs(t.flap_1c) < 1e-10 and abs(t.flap_1s) < 1e-10
    assert abs(t.thrust_coefficient - 0.005) < 1e-10 * 0.005
    assert t.theta1c != 0.0 and t.theta1s != 0.0


@pytest.mark.parametrize("call,field", [
    (lambda an: an.trim(0.3, kind="sideways"), "kind"),
    (lambda an: an.trim(0.3, kind="none"), "kind"),
    (lambda an: an.trim(0.3, thrust_coefficient=-0.005), "thrust_coefficient"),
    (lambda an: an.trim(0.3, shaft_angle=2.0), "shaft_angle"),
    (lambda an: an.trim(0.3, max_iterations=0), "max_iterations"),
    (lambda an: an.trim(-1.0), "mu"),
    (lambda an: an.trim(0.3, thrust_coefficient="0.005"), "thrust_coefficient"),
    (lambda an: an.thrust(0.3, inflow="eq2.24"), "inflow"),
    (lambda an: an.thrust(0.3, inflow=math.nan), "inflow"),
])
def test_trim_bad_inputs_name_the_keyword(call, field):
    with pytest.raises(ValueError) as err:
        call(flaplag.Analysis())
    assert err.value.field == field
    assert str(err.value).startswith(field + " = ")


@pytest.mark.parametrize("call,field", [
    (lambda an: an.point(0.3, thrust_coefficient=0.005), "thrust_coefficient"),
    (lambda an: an.critical(shaft_angle=0.1), "shaft_angle"),
    (lambda an: an.sweep([0.1, 0.2], trim="none", thrust_coefficient=0.005), "thrust_coefficient"),
    (lambda an: an.point(0.3, trim="sideways"), "trim"),
    (lambda an: an.point(0.3, trim=True), "trim"),
    (lambda an: an.point(0.3, trim="thrust", thrust_coefficient=0.5), "thrust_coefficient"),
    (lambda an: an.sweep(0, 1, 0.5, trim="moment", shaft_angle="0"), "shaft_angle"),
])
def test_trimmed_analyses_bad_inputs_name_the_keyword(call, field):
    with pytest.raises(ValueError) as err:
        call(flaplag.Analysis())
    assert err.value.field == field
    assert str(err.value).startswith(field + " = ")


@pytest.mark.parametrize("call,field,reason", [
    (lambda an: an.point(0.3, inflow="momentum"), "inflow", "needs thrust_coefficient"),
    (lambda an: an.critical(inflow="momentum", trim="thrust", thrust_coefficient=0.005),
     "inflow", "not with trim='thrust'"),
    (lambda an: an.sweep([0.1], inflow="momentum", trim="moment", thrust_coefficient=0.005),
     "inflow", "not with trim='moment'"),
    (lambda an: an.point(0.3, inflow="momentum", trim="sideways"), "trim", "must be"),
    (lambda an: an.point(0.3, inflow="given"), "inflow", "must be None, 'uniform', 'momentum'"),
    (lambda an: an.point(0.3, inflow=True), "inflow", "must be None"),
    (lambda an: an.point(0.3, inflow="momentum", thrust_coefficient=0.0), "thrust_coefficient",
     "in (0, 0.1]"),
    (lambda an: an.point(0.3, inflow="momentum", thrust_coefficient=0.2), "thrust_coefficient",
     "in (0, 0.1]"),
    (lambda an: an.point(0.3, inflow="momentum", thrust_coefficient="0.005"),
     "thrust_coefficient", "must be a real number"),
    (lambda an: an.critical(inflow="momentum", thrust_coefficient=0.005, shaft_angle=2.0),
     "shaft_angle", "in (-pi/2, pi/2)"),
    (lambda an: an.point(0.3, inflow="uniform", thrust_coefficient=0.005), "thrust_coefficient",
     "or inflow='momentum'"),
    (lambda an: an.point(0.3, shaft_angle=0.1), "shaft_angle", "or inflow='momentum'"),
])
def test_inflow_bad_inputs_name_the_keyword(call, field, reason):
    """inflow= refuses what the command line's --inflow refuses, naming the keyword."""
    with pytest.raises(flaplag.InvalidInput) as err:
        call(flaplag.Analysis())
    assert err.value.field == field
    assert str(err.value).startswith(field + " = ")
    assert reason in err.value.reason, str(err.value)
    assert "\n" not in str(err.value)


_AXES = dict(x=("mu", [0.0, 0.2, 0.4, 0.6]), y=("omega_lag", [0.5, 1.0, 1.5]))


@pytest.mark.parametrize("call,field", [
    (lambda: flaplag.study("omega_lag", [0.5], inflow="momentum"), "inflow"),
    (lambda: flaplag.study("omega_lag", [0.5], inflow="momentum", trim="thrust",
                           thrust_coefficient=0.005), "inflow"),
    (lambda: flaplag.study("omega_lag", [0.5], inflow="momentum", thrust_coefficient=0.5),
     "thrust_coefficient"),
    (lambda: flaplag.map(**_AXES, inflow="Momentum"), "inflow"),
    (lambda: flaplag.map(**_AXES, inflow="momentum", thrust_coefficient=0.005, shaft_angle=2.0),
     "shaft_angle"),
])
def test_inflow_study_and_map_bad_inputs_name_the_keyword(call, field):
    with pytest.raises(flaplag.InvalidInput) as err:
        call()
    assert err.value.field == field
    assert str(err.value).startswith(field + " = ")


def test_momentum_inflow_function():
    """flaplag.momentum_inflow is eq 2.25: sqrt(C_T/2) in hover, its own root at mu > 0."""
    assert flaplag.momentum_inflow(0.005, 0.0) == pytest.approx(0.05, abs=1e-16)
    lam = flaplag.momentum_inflow(0.005, 0.3, 0.05)
    assert lam == pytest.approx(0.3 * math.tan(0.05) + 0.005 / (2 * math.hypot(0.3, lam)),
                                abs=1e-15)
    with pytest.raises(flaplag.InvalidInput) as err:
        flaplag.momentum_inflow(0.0, 0.3)
    assert err.value.field == "thrust_coefficient"


@pytest.mark.parametrize("call,field", [
    (lambda: flaplag.study("omega_lag", [0.5], thrust_coefficient=0.005), "thrust_coefficient"),
    (lambda: flaplag.study("omega_lag", [0.5], trim="none", shaft_angle=0.1), "shaft_angle"),
    (lambda: flaplag.study("omega_lag", [0.5], trim="sideways"), "trim"),
    (lambda: flaplag.study("omega_lag", [0.5], trim="thrust", thrust_coefficient=0.5),
     "thrust_coefficient"),
    (lambda: flaplag.map(**_AXES, shaft_angle=0.1), "shaft_angle"),
    (lambda: flaplag.map(**_AXES, trim="Moment"), "trim"),
    (lambda: flaplag.map(**_AXES, trim="moment", shaft_angle=2.0), "shaft_angle"),
    (lambda: flaplag.map(**_AXES, trim="thrust", thrust_coefficient="0.005"),
     "thrust_coefficient"),
])
def test_trimmed_study_and_map_bad_inputs_name_the_keyword(call, field):
    with pytest.raises(ValueError) as err:
        call()
    assert err.value.field == field
    assert str(err.value).startswith(field + " = ")


class _Executor:
    """A client with submit() (as flaplag.study/map accept) on a thread pool, counting jobs."""

    def __init__(self):
        import concurrent.futures

        self.pool = concurrent.futures.ThreadPoolExecutor(2)
        self.jobs = 0

    def submit(self, fn, *args):
        self.jobs += 1
        return self.pool.submit(fn, *args)


def test_trimmed_study_and_map_through_a_client_equal_the_local_ones():
    """The chunks sent to a client carry the trim: the assembled result is the local one."""
    ex = _Executor()
    kw = dict(trim="thrust", thrust_coefficient=0.0042384)
    local = flaplag.map(**_AXES, scan_step=0.2, **kw)
    remote = flaplag.map(**_AXES, scan_step=0.2, **kw, client=ex, chunk_lines=1)
    assert ex.jobs == 3 and remote == local
    assert remote.metadata["trim"]["kind"] == "thrust"
    # one value (test_dask.py splits a longer trimmed study on a cluster)
    local = flaplag.study("omega_lag", [0.5], mu_max=1.1, scan_step=0.1, **kw)
    remote = flaplag.study("omega_lag", [0.5], mu_max=1.1, scan_step=0.1, **kw, client=ex)
    assert ex.jobs == 4
    assert remote.mu_c.tobytes() == local.mu_c.tobytes() and not math.isnan(local.mu_c[0])
    for name in ("theta0", "theta1c", "theta1s", "inflow"):
        assert getattr(remote, name).tobytes() == getattr(local, name).tobytes(), name
    # with a client, bad input raises before anything is sent
    with pytest.raises(ValueError):
        flaplag.study("omega_lag", [0.5], thrust_coefficient=0.005, client=ex)
    with pytest.raises(ValueError):
        flaplag.map(**_AXES, **dict(kw, thrust_coefficient=0.2), client=ex)
    assert ex.jobs == 4
    ex.pool.shutdown()


def test_trim_in_every_model():
    """Every model has the cyclic pitch and the thrust: the trim of the default model, of the
    other specs' and of more modes (zero cyclic pitch is the paper's rotor)."""
    for kw in ({}, {"model": "no-radial-flow"}, {"model": "lag-order-2"},
               {"modes": "exact", "flap_modes": 2, "lag_modes": 2}):
        t = flaplag.Analysis(**kw).trim(0.3, kind="moment", thrust_coefficient=0.005)
        assert t.converged, (kw, t.message)
        assert abs(t.thrust_coefficient - 0.005) < 1e-10 * 0.005
        assert abs(t.flap_1c) < 1e-10 and abs(t.flap_1s) < 1e-10
