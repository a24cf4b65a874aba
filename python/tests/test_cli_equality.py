"""The Python module gives the command line's numbers, bit for bit: both are front ends of the
same library, so any difference is a front end passing a different parameter or option, or
converting a number."""

import math

import numpy as np
import pytest

import flaplag
from conftest import cli_args, find, run_cli, same, zeta_value


def check_parameters(doc, an):
    """The parameters the CLI reports are the ones the Python analysis used."""
    params = find(doc, "parameters", default=None)
    if params is None:
        return
    for field, value in an.parameters.items():
        for key in (field.replace("_", "-"), field):
            if key in params:
                if isinstance(value, float):
                    assert same(params[key], value), field
                else:
                    assert params[key] == value, field
                break


def check_exponents(cli_exponents, exponents):
    assert len(cli_exponents) == len(exponents)
    for c, e in zip(cli_exponents, exponents):
        assert c["label"] == e.label
        assert same(zeta_value(c["zeta"]), e.zeta), (c, e)
        assert same(c["omega"], e.omega), (c, e)
        if "damping_ratio" in c:
            assert same(c["damping_ratio"], e.damping_ratio), (c, e)
        m = c.get("multiplier")
        if m is not None:
            assert same(m["re"], e.multiplier.real) and same(m["im"], e.multiplier.imag)


def check_critical(doc, crit):
    mu_c = find(doc, "mu_c", "critical.mu_c")
    assert same(mu_c, crit.mu_c)
    assert same(find(doc, "mu_c_error", "critical.mu_c_error", default=crit.mu_c_error),
                crit.mu_c_error)
    if crit.mu_c is not None:
        assert same(find(doc, "omega", "critical.omega"), crit.omega)
        assert find(doc, "mode", "critical.mode") == crit.mode
        assert find(doc, "kind", "critical.kind") == crit.kind
    assert find(doc, "hover_unstable", "critical.hover_unstable") == crit.hover_unstable
    assert same(find(doc, "mu_max", "critical.mu_max"), crit.mu_max)
    assert find(doc, "status", "critical.status") == crit.status
    message = find(doc, "message", "critical.message", default=None)
    if message is not None and "`" not in crit.message:
        assert message == crit.message


def test_typical_case_critical():
    """Fig 3: the typical case loses stability in lag flutter at mu_c = 0.754 (the paper)."""
    crit = flaplag.Analysis().critical()
    assert crit.mu_c is not None and abs(crit.mu_c - 0.754) < 1e-3
    assert crit.mode == "lag" and crit.kind == "flutter"
    doc = run_cli("critical")
    check_critical(doc, crit)
    check_parameters(doc, flaplag.Analysis())


CRITICAL_CASES = [
    ({}, {"mu_max": 1.5, "scan_step": 0.02}),
    ({"theta": 0.2, "omega_lag": 1.0, "gamma": 8.0}, {}),
    ({"omega_lag": 0.5}, {}),  # Fig 15: a periodic (omega = 1/2) lag instability
    ({"method": "rk4", "steps": 50}, {}),
    ({"method": "magnus"}, {"mu_max": 1.2}),
    ({"method": "hsu", "steps": 50, "terms": 4}, {}),  # the paper's K = 50, J = 4
    ({"model": "no-radial-flow"}, {"mu_max": 1.5}),
    ({"reversed_flow": False, "cdo": 0.02}, {}),
    ({"exact_reversed_flow": True}, {}),  # the exact circular reversed-flow region
    ({"omega_lag": 1.7}, {"mu_max": 1.0}),  # stable up to mu_max: mu_c is null
]


@pytest.mark.parametrize("params,options", CRITICAL_CASES)
def test_critical_search(params, options):
    an = flaplag.Analysis(**params)
    crit = an.critical(**options)
    doc = run_cli(*cli_args(**params), "critical", *cli_args(**options))
    check_critical(doc, crit)
    check_parameters(doc, an)


EXACT_CASES = [
    {"modes": "exact"},
    {"modes": "exact", "elastic_coupling": False},
    {"modes": "exact", "paper_1974_shapes": True},
    {"modes": "exact", "exact_reversed_flow": True},
    {"modes": "exact", "theta": 0.3, "damping_lag": 0.01},
    {"modes": "exact", "flap_modes": 2, "lag_modes": 1},
]


@pytest.mark.parametrize("params", EXACT_CASES)
def test_exact_modes_critical(params):
    an = flaplag.Analysis(**params)
    crit = an.critical()
    doc = run_cli(*cli_args(**params), "critical")
    check_critical(doc, crit)
    check_parameters(doc, an)
    if params.get("flap_modes") == 2:
        assert an.model.flap_modes == 2 and an.model.lag_modes == 1


@pytest.mark.parametrize("params", [{}, {"modes": "exact", "omega_lag": 1.4}])
def test_sweep(params):
    an = flaplag.Analysis(**params)
    sweep = an.sweep(0.0, 1.2, 0.1)
    doc = run_cli(*cli_args(**params), "sweep", "--mu", "0:1.2:0.1")
    rows = find(doc, "rows", "sweep.rows")
    assert len(rows) == len(sweep.points) == 13
    for row, point, mu in zip(rows, sweep.points, sweep.mu):
        assert same(row["mu"], point.mu) and same(mu, point.mu)
        if "exponents" in row:
            check_exponents(row["exponents"], point.exponents)
        for label in sweep.labels:
            if isinstance(row.get(label), dict):
                e = point.dominant(label)
                assert same(zeta_value(row[label]["zeta"]), e.zeta)
                assert same(row[label]["omega"], e.omega)
        for key, value in (("liouville_residual", point.liouville_residual),
                           ("error_estimate", point.error_estimate)):
            if key in row:
                assert same(row[key], value), key
        if "stable" in row:
            assert row["stable"] == point.stable
        if "status" in row:
            assert row["status"] == point.status
    # the per-label arrays are the dominant exponents of the points
    for label in sweep.labels:
        assert np.array_equal(sweep.zeta[label], [p.dominant(label).zeta for p in sweep.points])


def test_point():
    an = flaplag.Analysis(omega_lag=1.1)
    point = an.point(0.55)
    doc = run_cli("--omega-lag", "1.1", "point", "--mu", "0.55")
    check_exponents(find(doc, "exponents", "point.exponents"), point.exponents)
    assert same(find(doc, "liouville_residual", "point.liouville_residual"),
                point.liouville_residual)
    assert find(doc, "stable", "point.stable") == point.stable


def test_trimmed_point_and_sweep():
    """`point --trim` and `sweep --trim` (stability at fixed C_T) and Analysis.point/sweep with
    trim=: the same exponents."""
    an = flaplag.Analysis()
    point = an.point(0.3, scan_step=0.1, trim="moment", thrust_coefficient=0.005)
    assert point.status == "ok", point.message
    doc = run_cli("point", "--mu", "0.3", "--scan-step", "0.1",
                  "--trim", "moment", "--thrust-coefficient", "0.005")
    check_exponents(find(doc, "exponents", "point.exponents"), point.exponents)
    # the trim the point rests on, that of the CLI's point, bit for bit
    check_trim(doc["trim"], point.trim)
    assert point.trim.mu == 0.3
    # not the untrimmed rotor's exponents
    untrimmed = an.point(0.3, scan_step=0.1)
    assert abs(point.max_zeta - untrimmed.max_zeta) > 1e-4
    assert untrimmed.trim is None
    sweep = an.sweep(0.0, 0.2, 0.1, trim="thrust", thrust_coefficient=0.004, shaft_angle=0.05)
    doc = run_cli("sweep", "--mu", "0:0.2:0.1", "--trim", "thrust",
                  "--thrust-coefficient", "0.004", "--shaft-angle", "0.05")
    rows = find(doc, "rows", "sweep.rows")
    assert len(rows) == len(sweep.points) == 3
    for row, p in zip(rows, sweep.points):
        assert same(row["mu"], p.mu)
        check_exponents(row["exponents"], p.exponents)
        for label in sweep.labels:
            if isinstance(row.get(label), dict):
                assert same(zeta_value(row[label]["zeta"]), p.dominant(label).zeta)
                assert same(row[label]["omega"], p.dominant(label).omega)
        if "status" in row:
            assert row["status"] == p.status
    # one trim per point, those of the CLI's sweep
    assert len(sweep.trims) == len(doc["trim"]) == 3
    for t_doc, t in zip(doc["trim"], sweep.trims):
        check_trim(t_doc, t)


TRIM_CT = "0.0042384"  # the typical case's C_T in hover (theta = 0.15, eq 2.25 inflow)


# The fields of a trim in the CLI's JSON: those of TrimResult (one vocabulary), less its
# ``parameters`` (the CLI's header holds them); its ``message`` names options as the CLI does.
TRIM_FIELDS = ("mu", "kind", "theta0", "theta1c", "theta1s", "inflow", "thrust_coefficient",
               "target", "flap_1c", "flap_1s", "iterations", "converged", "status")


def check_trim(doc, t):
    """A trim of the CLI's JSON (`flaplag trim`, `critical --trim`, a `study --trim` row) and a
    TrimResult: the same fields, bit for bit."""
    for key in TRIM_FIELDS:
        value = getattr(t, key)
        if isinstance(value, float):
            assert same(doc[key], value), key
        else:
            assert doc[key] == value, key
    assert doc.get("message", "") == t.message or "`" in t.message


def test_trimmed_study():
    """`study --trim` and flaplag.study(trim=...): mu_c at fixed C_T, the same rows bit for bit;
    each row with mu_c carries the trim at mu_c, that of `flaplag trim --mu <mu_c>`."""
    values = [0.45, 0.5, 0.55]
    st = flaplag.study("omega_lag", values, mu_max=1.1, scan_step=0.1,
                       trim="thrust", thrust_coefficient=float(TRIM_CT), threads=2)
    doc = run_cli("study", "--vary", "omega-lag=0.45,0.5,0.55",
                  "--mu-max", "1.1", "--scan-step", "0.1", "--trim", "thrust",
                  "--thrust-coefficient", TRIM_CT)
    rows = find(doc, "rows", "study.rows")
    assert len(rows) == len(st.rows) == 3
    for row, value, crit in zip(rows, st.values, st.rows):
        assert same(row["value"], value)
        assert row["hover_unstable"] == crit.hover_unstable
        assert same(row["mu_c"], crit.mu_c) and same(row["mu_c_error"], crit.mu_c_error)
        assert row["mode"] == crit.mode and row["kind"] == crit.kind
        assert same(row["omega"], crit.omega)
        assert len(row["intervals"]) == len(crit.intervals)
        for (onset, end), iv in zip(row["intervals"], crit.intervals):
            assert same(onset, iv.onset) and same(end, iv.end)
        assert row["status"] == crit.status
        if "`" not in crit.message:
            assert row["message"] == crit.message
        # the trim at mu_c, under the names of StudyResult's rows (null without mu_c)
        if crit.trim is None:
            assert row["trim"] is None
        else:
            assert set(row["trim"]) - {"message"} == set(TRIM_FIELDS)
            check_trim(row["trim"], crit.trim)
    assert find(doc, "status") == st.status
    # rows with and without mu_c (the typical C_T: a periodic lag instability near mu = 1.02
    # at omega_lag = 0.5 only, stable up to 1.1 beside it)
    found = ~np.isnan(st.mu_c)
    assert found.tolist() == [False, True, False]
    assert np.isnan(st.theta0[~found]).all() and all(r.trim is None for r in st.rows[::2])
    t = st.rows[1].trim
    # converged; at mu_c the trimmed rotor is neutrally stable, which the trim flags (warning)
    assert t.mu == st.mu_c[1] and t.kind == "thrust" and t.converged
    assert abs(t.thrust_coefficient - t.target) <= 1e-10 * t.target
    assert (st.theta0[1], st.theta1c[1], st.theta1s[1], st.inflow[1]) == (
        t.theta0, t.theta1c, t.theta1s, t.inflow)
    trim_doc = run_cli("--omega-lag", "0.5", "trim", "--mu",
                       repr(st.mu_c[1]), "--thrust-coefficient", TRIM_CT)
    check_trim(trim_doc, t)
    assert st.metadata["trim"] == {"kind": "thrust", "thrust_coefficient": float(TRIM_CT),
                                   "shaft_angle": 0.0}


def test_momentum_inflow_point_sweep_critical():
    """`--inflow momentum` and inflow='momentum': fixed controls at the inflow of eq 2.25, the
    same exponents and mu_c bit for bit; the header says which inflow."""
    an = flaplag.Analysis()
    kw = dict(inflow="momentum", thrust_coefficient=0.005)
    hover = an.point(0.0, **kw)
    # eq 2.25 in hover: lambda = sqrt(C_T / 2), not the paper's eq 2.24
    assert flaplag.momentum_inflow(0.005, 0.0) == math.sqrt(0.0025)
    doc = run_cli("point", "--mu", "0", "--inflow", "momentum", "--thrust-coefficient", "0.005")
    check_exponents(find(doc, "exponents", "point.exponents"), hover.exponents)
    assert same(doc["hover"]["inflow"], math.sqrt(0.0025))
    assert abs(an.hover.inflow - math.sqrt(0.0025)) > 1e-4
    point = an.point(0.3, scan_step=0.1, **kw)
    doc = run_cli("point", "--mu", "0.3", "--scan-step", "0.1", "--inflow", "momentum",
                  "--thrust-coefficient", "0.005")
    check_exponents(find(doc, "exponents", "point.exponents"), point.exponents)
    assert doc["inflow"] == {"kind": "momentum", "thrust_coefficient": 0.005,
                             "shaft_angle": 0.0,
                             "lambda": flaplag.momentum_inflow(0.005, 0.3)}
    uniform = an.point(0.3, scan_step=0.1)
    assert abs(point.max_zeta - uniform.max_zeta) > 1e-4
    assert an.point(0.3, scan_step=0.1, inflow="uniform").max_zeta == uniform.max_zeta
    sweep = an.sweep(0.0, 0.2, 0.1, shaft_angle=0.05, **kw)
    doc = run_cli("sweep", "--mu", "0:0.2:0.1", "--inflow", "momentum",
                  "--thrust-coefficient", "0.005", "--shaft-angle", "0.05")
    rows = find(doc, "rows", "sweep.rows")
    assert len(rows) == len(sweep.points) == 3
    for row, p in zip(rows, sweep.points):
        check_exponents(row["exponents"], p.exponents)
    crit = an.critical(**kw)
    doc = run_cli("critical", "--inflow", "momentum", "--thrust-coefficient", "0.005")
    assert crit.status == "ok", crit.message
    assert same(find(doc, "mu_c"), crit.mu_c) and crit.mu_c is not None
    assert abs(crit.mu_c - an.critical().mu_c) > 1e-3
    assert same(doc["inflow"]["lambda_at_mu_c"], flaplag.momentum_inflow(0.005, crit.mu_c))


def test_momentum_inflow_study_and_map():
    """`study`/`map --inflow momentum` and flaplag.study/map(inflow='momentum'): the same rows
    and cells bit for bit."""
    kw = dict(inflow="momentum", thrust_coefficient=0.005)
    st = flaplag.study("omega_lag", [1.2, 1.4], mu_max=1.0, scan_step=0.1, threads=2, **kw)
    doc = run_cli("study", "--vary", "omega-lag=1.2,1.4", "--mu-max", "1", "--scan-step", "0.1",
                  "--inflow", "momentum", "--thrust-coefficient", "0.005")
    rows = find(doc, "rows", "study.rows")
    for row, crit in zip(rows, st.rows):
        assert same(row["mu_c"], crit.mu_c) and row["status"] == crit.status
    assert st.metadata["inflow"] == {"kind": "momentum", "thrust_coefficient": 0.005,
                                     "shaft_angle": 0.0}
    assert st.metadata["trim"] is None
    # not the rows at the paper's inflow
    plain = flaplag.study("omega_lag", [1.2, 1.4], mu_max=1.0, scan_step=0.1, threads=2)
    assert "inflow" not in plain.metadata
    assert not np.array_equal(st.mu_c, plain.mu_c)
    m = flaplag.map(x=("mu", [0.0, 0.2, 0.4]), y=("theta", [0.1, 0.15]), scan_step=0.1, **kw)
    doc = run_cli("map", "--x", "mu=0:0.4:0.2", "--y", "theta=0.1,0.15", "--scan-step", "0.1",
                  "--inflow", "momentum", "--thrust-coefficient", "0.005")
    for i, row in enumerate(find(doc, "max_zeta")):
        for j, z in enumerate(row):
            assert same(zeta_value(z), m.max_zeta[i, j])


def test_trimmed_critical_reports_the_trim_at_mu_c():
    """`critical --trim` and Analysis.critical(trim=...): the same mu_c and the same trim there."""
    an = flaplag.Analysis(omega_lag=0.5)
    crit = an.critical(mu_max=1.1, scan_step=0.1, trim="thrust", thrust_coefficient=float(TRIM_CT))
    doc = run_cli("--omega-lag", "0.5", "critical", "--mu-max", "1.1",
                  "--scan-step", "0.1", "--trim", "thrust", "--thrust-coefficient", TRIM_CT)
    check_critical(doc, crit)
    assert crit.trim is not None and crit.trim.mu == crit.mu_c
    check_trim(find(doc, "trim"), crit.trim)
    assert an.critical(mu_max=1.1, scan_step=0.1).trim is None


def check_map(doc, m):
    assert np.array(find(doc, "x.values"), dtype=float).tobytes() == m.x_values.tobytes()
    assert np.array(find(doc, "y.values"), dtype=float).tobytes() == m.y_values.tobytes()
    zeta = np.array([[math.nan if z is None else zeta_value(z) for z in row]
                     for row in find(doc, "max_zeta")])
    assert zeta.tobytes() == m.max_zeta.tobytes()
    assert [[x or "" for x in row] for row in find(doc, "mode")] == m.mode.tolist()
    assert [[x or "" for x in row] for row in find(doc, "kind")] == m.kind.tolist()
    assert find(doc, "status") == m.status
    if "`" not in m.message:
        assert find(doc, "message") == m.message


def test_trimmed_maps():
    """`map --trim` and flaplag.map(trim=...): the same cells bit for bit, along mu (a trimmed
    continuation per line) and at one mu (a trimmed point per cell)."""
    m = flaplag.map(x=("mu", [0.0, 0.2, 0.4, 0.6]), y=("omega_lag", [0.5, 1.0, 1.5]),
                    scan_step=0.2, trim="thrust",
                    thrust_coefficient=float(TRIM_CT), threads=2)
    assert m.shape == (3, 4) and m.status == "ok"
    doc = run_cli("map", "--x", "mu=0:0.6:0.2", "--y",
                  "omega-lag=0.5,1.0,1.5", "--scan-step", "0.2", "--trim", "thrust",
                  "--thrust-coefficient", TRIM_CT)
    check_map(doc, m)
    # not the map at fixed theta
    plain = flaplag.map(x=("mu", [0.0, 0.2, 0.4, 0.6]), y=("omega_lag", [0.5, 1.0, 1.5]),
                        scan_step=0.2)
    assert np.abs(plain.max_zeta[:, 1:] - m.max_zeta[:, 1:]).min() > 1e-6
    g = flaplag.map(x=("omega_lag", [0.5, 1.5]), y=("gamma", [8.0, 10.0]), mu=0.3,
                    scan_step=0.3, trim="moment",
                    thrust_coefficient=float(TRIM_CT), shaft_angle=0.02)
    doc = run_cli("map", "--x", "omega-lag=0.5,1.5", "--y",
                  "gamma=8,10", "--mu", "0.3", "--scan-step", "0.3", "--trim", "moment",
                  "--thrust-coefficient", TRIM_CT, "--shaft-angle", "0.02")
    assert same(find(doc, "mu"), 0.3)
    check_map(doc, g)


def test_system():
    an = flaplag.Analysis(modes="exact")
    sys_ = an.system(0.8, 4.7)
    doc = run_cli("--modes", "exact", "system", "--mu", "0.8", "--psi", "4.7")
    A = np.array(find(doc, "A", "system.A"), dtype=float)
    assert A.shape == sys_.A.shape == (4, 4)
    assert A.tobytes() == sys_.A.tobytes()
    assert np.array(find(doc, "f", "system.f"), dtype=float).tobytes() == sys_.f.tobytes()
    assert find(doc, "region", "system.region") == sys_.region == "reversed"
    for item in find(doc, "aero_integrals", "system.aero_integrals", default=[]):
        assert same(item["normal"], sys_.aero_integrals[item["name"]])
        if item.get("at_psi") is not None:
            assert same(item["at_psi"], sys_.aero_integrals_at_psi[item["name"]])
    for item in find(doc, "structural_integrals", "system.structural_integrals", default=[]):
        assert same(item["value"], sys_.structural_integrals[item["name"]])
    hover = find(doc, "hover", default=None)
    if hover is not None:
        assert same(hover["inflow"], an.hover.inflow)


RESPONSE_CASES = [
    ({}, "0.3", {}),
    ({"modes": "exact", "theta": 0.2}, "0.6", {"samples": 36}),
    ({"modes": "exact", "flap_modes": 2, "lag_modes": 1, "basis": 8}, "0.4", {}),
]


@pytest.mark.parametrize("params,mu,options", RESPONSE_CASES)
def test_response(params, mu, options):
    """`flaplag response` and Analysis.response: the same tip deflections and harmonics."""
    an = flaplag.Analysis(**params)
    r = an.response(float(mu), **options)
    doc = run_cli(*cli_args(**params), "response", "--mu", mu, *cli_args(**options))
    check_parameters(doc, an)
    assert find(doc, "status") == r.status
    assert np.array(find(doc, "psi"), dtype=float).tobytes() == r.psi.tobytes()
    assert list(r.tips) == ["flap", "lag"]
    for direction, tip in r.tips.items():
        cli_tip = np.array(find(doc, direction + "_tip"), dtype=float)
        assert cli_tip.tobytes() == tip.deflection.tobytes(), direction
        h = find(doc, direction + "_harmonics")
        assert list(h) == list(r.harmonic_names)
        assert np.array(list(h.values()), dtype=float).tobytes() == tip.harmonics.tobytes()
    assert same(find(doc, "closure"), r.closure)
    assert same(find(doc, "error_estimate", default=r.error_estimate), r.error_estimate)
    assert find(doc, "steps") == r.steps


@pytest.mark.parametrize("params,mu,options", [
    ({}, "0.9", {"revolutions": 12.0}),
    ({"modes": "exact"}, "0.5", {"revolutions": 6.5, "samples_per_rev": 20, "forced": True}),
    ({"model": "no-radial-flow"}, "0.3", {"revolutions": 5.0, "nonlinear": True}),
])
def test_simulate(params, mu, options):
    """`flaplag simulate` and Analysis.simulate: the same tip response and growth rates."""
    an = flaplag.Analysis(**params)
    s = an.simulate(float(mu), y0=0.01, **options)
    args = ["--revs", repr(options["revolutions"]), "--perturbation", "0.01"]
    if "samples_per_rev" in options:
        args += ["--samples", str(options["samples_per_rev"])]
    if options.get("forced"):
        args.append("--forced")
    if options.get("nonlinear"):
        args.append("--nonlinear")
    doc = run_cli(*cli_args(**params), "simulate", "--mu", mu, *args)
    check_parameters(doc, an)
    assert find(doc, "status") == s.status
    assert find(doc, "steps_per_rev") == s.steps_per_rev
    assert np.array(find(doc, "psi"), dtype=float).tobytes() == s.psi.tobytes()
    assert list(s.tips) == ["flap", "lag"]
    for direction, tip in s.tips.items():
        key = direction + "_tip"
        assert np.array(find(doc, key), dtype=float).tobytes() == tip.deflection.tobytes(), key
        assert same(find(doc, direction + "_growth_rate"), tip.growth_rate)
    assert find(doc, "nonlinear", default=False) == s.nonlinear
    if s.nonlinear:
        assert find(doc, "reference") == s.reference
        for direction, tip in s.tips.items():
            key = direction + "_total"
            assert np.array(find(doc, key), dtype=float).tobytes() == tip.total.tobytes(), key


def test_damping_criterion_sweep_and_study():
    """damping_criterion: the per-mode damping ratios and the first mu below the criterion, as
    the command line's --damping-criterion gives them, bit for bit; the crossing is the linear
    interpolation of the damping ratio between the two points around it."""
    c = 0.0005  # 0.05 % of critical: the typical lag mode has 0.086 % in hover
    an = flaplag.Analysis()
    sweep = an.sweep(0.0, 1.2, 0.05, damping_criterion=c)
    doc = run_cli("sweep", "--mu", "0:1.2:0.05", "--damping-criterion", repr(c))
    assert sweep.damping_criterion == doc["damping_criterion"] == c
    assert [x.mode for x in sweep.damping_crossings] == list(sweep.labels) == doc["labels"]
    for x, d in zip(sweep.damping_crossings, doc["damping_crossings"]):
        assert x.mode == d["mode"] and x.status == d["status"], (x, d)
        for key in ("mu", "mu_above", "mu_below"):
            assert same(getattr(x, key), d[key]), (key, x, d)
    for label in sweep.labels:
        ratio = sweep.damping_ratio[label]
        for i, row in enumerate(doc["rows"]):
            assert same(ratio[i], row[label]["damping_ratio"])
            z, w = zeta_value(row[label]["zeta"]), row[label]["omega"]
            assert abs(ratio[i] - (-z / math.hypot(z, w))) <= 1e-15
        below = [i for i, r in enumerate(ratio) if r < c]
        x = sweep.crossing(label)
        if not below:
            assert x.status == "not_crossed" and x.mu is None
            continue
        k = below[0]
        assert k > 0 and x.status == "crossed", x
        mu = sweep.mu
        expected = mu[k - 1] + (c - ratio[k - 1]) / (ratio[k] - ratio[k - 1]) * (mu[k] - mu[k - 1])
        assert abs(x.mu - expected) <= 1e-12, (x, expected)
    assert sweep.crossing("lag").status == "crossed"
    # Without it: no criterion, no crossings.
    plain = an.sweep(0.0, 0.2, 0.1)
    assert plain.damping_criterion is None and plain.damping_crossings == ()
    # The study's rows: the crossings of each row's sweep over 0..mu_max, as the command line.
    study = flaplag.study("theta", [0.1, 0.15], mu_max=1.0, scan_step=0.05, damping_criterion=c)
    sdoc = run_cli("study", "--vary", "theta=0.1,0.15", "--mu-max", "1", "--scan-step", "0.05",
                   "--damping-criterion", repr(c))
    assert sdoc["damping_criterion"] == c
    for row, drow in zip(study.damping_crossings, sdoc["rows"]):
        assert [(x.mode, x.status) for x in row] == [
            (d["mode"], d["status"]) for d in drow["damping_crossings"]]
        for x, d in zip(row, drow["damping_crossings"]):
            assert same(x.mu, d["mu"])
    assert np.array_equal(
        study.first_below("lag"),
        [d["mu"] if d["mu"] is not None else math.nan
         for drow in sdoc["rows"] for d in drow["damping_crossings"] if d["mode"] == "lag"],
        equal_nan=True)
    # Bad criteria: InvalidInput naming the keyword, as the command line's exit 2.
    for bad in (-1.0, math.nan, 2.0, 1.0):
        with pytest.raises(flaplag.InvalidInput, match="damping_criterion"):
            an.sweep(0.0, 0.2, 0.1, damping_criterion=bad)
        with pytest.raises(flaplag.InvalidInput, match="damping_criterion"):
            flaplag.study("theta", [0.1], damping_criterion=bad)


TAPER_CSV = """# a tapered blade with a tip mass (nondimensional: the columns are shapes)
x, m, EI_flap, EI_lag, chord
0.05, 1.5, 2.0, 2.5, 1.0
0.4, 1.2, 1.4, 1.6, 1.0
1, 0.7, 0.5, 0.8, 1.0
tip_mass, 0.05
"""


@pytest.mark.parametrize("table", [False, True])
def test_exported_mode_shapes_are_the_command_lines(tmp_path, table):
    """Analysis.export_mode_shapes is `flaplag modes --export-shapes`, byte for byte (the
    uniform blade and a blade table), and the file reads back as the same modes."""
    params = {"omega_lag": 0.8}
    args = ["--omega-lag", "0.8"]
    if table:  # a table sets the exact modes
        blade = tmp_path / "taper.csv"
        blade.write_text(TAPER_CSV)
        params["blade"] = str(blade)
        args += ["--blade-table", str(blade)]
    else:
        params["modes"] = "exact"
        args += ["--modes", "exact"]
    an = flaplag.Analysis(flap_modes=2, **params)
    written = tmp_path / "python.csv"
    text = an.export_mode_shapes(written)
    assert written.read_text() == text
    exported = tmp_path / "cli.csv"
    run_cli(*args, "modes", "--flap-modes", "2", "--export-shapes", str(exported))
    assert exported.read_text() == text
    assert ("stiffness scale" in text) == table
    # Read back: the same frequencies, and shapes within the spline's error at 1001 stations.
    back = flaplag.Analysis(flap_modes=2, mode_shapes=str(written), **params)
    mine, theirs = an.modes(51), back.modes(51)
    assert theirs.kind == "imported"
    assert np.array_equal(mine.omega_flap, theirs.omega_flap)
    assert np.array_equal(mine.omega_lag, theirs.omega_lag)
    assert np.max(np.abs(mine.flap - theirs.flap)) < 1e-10
    assert np.max(np.abs(mine.lag - theirs.lag)) < 1e-10
    # The text alone, at another station count; refused for the assumed shape and bad counts.
    assert an.export_mode_shapes(stations=8).count("\n") < text.count("\n")
    with pytest.raises(flaplag.InvalidInput, match="stations"):
        an.export_mode_shapes(stations=7)
    with pytest.raises(flaplag.InvalidInput, match="modes"):
        flaplag.Analysis().export_mode_shapes()
