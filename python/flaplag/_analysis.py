"""flaplag.Analysis: the stability analysis of one blade, with the vocabulary of the C++ library.

The keyword arguments are the field names of the C++ RotorParameters (rotor/parameter_table.h)
and TransitionOptions, read from the library's own tables when this module is imported, so that
the names, units, ranges, defaults and descriptions have one source.  The command line spells
the same names as options (``omega_lag`` is ``--omega-lag``).
"""

import contextlib
import difflib
import inspect
import math
import numbers
import operator
import os
import re
import textwrap

import numpy as np

from . import _flaplag
from ._results import (
    CampbellResult,
    CriticalResult,
    FloquetSample,
    HoverResult,
    ModelInfo,
    ModeShapes,
    PeriodicEquilibriumResult,
    PointResult,
    ResponseResult,
    SimulationResult,
    SweepResult,
    SystemResult,
    ThrustResult,
    TrimResult,
)

InvalidInput = _flaplag.InvalidInput


class UnknownParameter(InvalidInput, TypeError):
    """A keyword that names no parameter: both a ValueError (as every bad input of flaplag)
    and the TypeError Python raises for an unexpected keyword argument."""


UnknownParameter.__module__ = "flaplag"


PARAMETERS = tuple(_flaplag.parameter_table())  # rows of the RotorParameters table
TRANSITION = tuple(_flaplag.transition_table())  # method, steps, terms, zeta_tolerance
_MODE_COUNTS = (
    {
        "field": "flap_modes",
        "symbol": "M",
        "type": "int",
        "default": 1,
        "units": "-",
        "requirement": "in 1..12",
        "description": "flap modes M: selects the model '<model>-<M>x<N>' "
        "(<model> itself for 1 x 1; more than one mode needs modes='exact' and at most "
        "basis modes per direction)",
    },
    {
        "field": "lag_modes",
        "symbol": "N",
        "type": "int",
        "default": 1,
        "units": "-",
        "requirement": "in 1..12",
        "description": "lag modes N (see flap_modes)",
    },
)
# What the rotor is linearized about: part of the operating condition (C++
# OperatingCondition::linearization), not of the rotor; passed to the native layer with the
# rotor's dict as "linearization" ("hover" or "periodic").
_CONDITION = (
    {
        "field": "periodic_linearization",
        "type": "flag",
        "default": False,
        "description": "linearize about the periodic equilibrium q°(psi) of the nonlinear "
        "equations instead of the hover equilibrium (the paper); the command line's "
        "--periodic-linearization",
    },
)
_ROTOR_FIELDS = {r["field"]: r for r in PARAMETERS}
_TRANSITION_FIELDS = {r["field"]: r for r in TRANSITION}
_COUNT_FIELDS = {r["field"]: r for r in _MODE_COUNTS}
_CONDITION_FIELDS = {r["field"]: r for r in _CONDITION}
_ALL_FIELDS = {**_ROTOR_FIELDS, **_CONDITION_FIELDS, **_TRANSITION_FIELDS, **_COUNT_FIELDS}
# The defaults of the C++ options structs: a default-constructed struct by its field table.
CRITICAL_DEFAULTS = dict(_flaplag.option_defaults("critical"))  # CriticalOptions
RESPONSE_DEFAULTS = dict(_flaplag.option_defaults("response"))  # ResponseOptions
SIMULATION_DEFAULTS = dict(_flaplag.option_defaults("simulation"))  # SimulationOptions
EQUILIBRIUM_DEFAULTS = dict(_flaplag.option_defaults("equilibrium"))  # PeriodicEquilibriumOptions
TRIM_DEFAULTS = dict(_flaplag.option_defaults("trim"))  # TrimOptions (kind "none": untrimmed)
CAMPBELL_DEFAULTS = dict(_flaplag.option_defaults("campbell"))  # CampbellOptions
# The inflow models at fixed controls: InflowModel's kinds but 'given' (a given lambda is a
# trim's), as the command line's --inflow.
_INFLOW_KINDS = tuple(
    k
    for row in _flaplag.inflow_table()
    if row["field"] == "kind"
    for k in row["choices"]
    if k != "given"
)

_INT_MAX = 2**31 - 1


def _invalid(cls, field, value, reason, text=None):
    """cls('<field> = <value>: <reason>') with .field, .value (as text) and .reason; text: the
    value as shown, when not its repr."""
    text = _shown(value) if text is None else text
    e = cls(f"{field} = {text}: {reason}")
    e.field, e.value, e.reason = field, text, reason
    return e


_SHOWN_MAX = 60  # characters of a value shown in a message


def _shown(value):
    """A value as a message shows it: one line of at most _SHOWN_MAX characters, whatever the
    value (an array by its shape, a long list by its length, a long text cut), computed without
    the repr of a large object."""
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, np.ndarray) and (value.ndim > 1 or value.size > 8):
        return f"array of shape {value.shape}"
    if isinstance(value, (list, tuple)) and len(value) > 8:
        return f"{type(value).__name__} of {len(value)} items"
    if isinstance(value, (str, bytes)) and len(value) > _SHOWN_MAX:
        value = value[:_SHOWN_MAX]  # the repr of the start: the rest would be cut anyway
    try:
        r = repr(value)
    except Exception:  # a user's object whose repr fails
        r = f"<{type(value).__name__}>"
    r = " ".join(r.split())  # one line
    return r if len(r) <= _SHOWN_MAX else r[: _SHOWN_MAX - 3] + "..."


@contextlib.contextmanager
def _keywords(**names):
    """Names the library's checks after the keywords the user typed: an InvalidInput from the
    library whose field is a key of `names` (the C++ argument, e.g. mu0) is raised again naming
    the keyword (names[field], e.g. mu), and the other C++ names in its reason are replaced as
    well ("must be >= mu0" becomes "must be >= mu")."""
    try:
        yield
    except InvalidInput as e:
        field = getattr(e, "field", None)
        if field not in names:
            raise
        reason = getattr(e, "reason", str(e))
        for cxx, python in names.items():
            reason = re.sub(r"(?<![A-Za-z0-9_`])" + re.escape(cxx) + r"(?![A-Za-z0-9_`])",
                            python, reason)
        raise _invalid(type(e), names[field], None, reason, getattr(e, "value", "?")) from None


def _real(field, value):
    """A float from any real number (not a bool, not a string)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise _invalid(InvalidInput, field, value, "must be a real number")
    return float(value)


def _int(field, value):
    if isinstance(value, (bool, np.bool_)):
        raise _invalid(InvalidInput, field, value, "must be an integer")
    try:
        v = operator.index(value)
    except TypeError:
        raise _invalid(InvalidInput, field, value, "must be an integer") from None
    if not -_INT_MAX <= v <= _INT_MAX:
        raise _invalid(InvalidInput, field, value, "out of range")
    return int(v)


def _flag(field, value):
    if not isinstance(value, (bool, np.bool_)):
        raise _invalid(InvalidInput, field, value, "must be True or False")
    return bool(value)


def _text(field, value):
    if not isinstance(value, str):
        raise _invalid(InvalidInput, field, value, "must be a string")
    return value


def _options(defaults, **values):
    """The options {keyword: value} of a C++ options struct, each checked as the type of its
    default (the struct's table): a flag, a whole number, a real number or a name."""
    def check(default):  # bool before int: a bool is an int
        if isinstance(default, bool):
            return _flag
        if isinstance(default, int):
            return _int
        return _real if isinstance(default, float) else _text

    return {key: check(defaults[key])(key, value) for key, value in values.items()}


def _real_array_np(field, values):
    """A 1-D float64 numpy array from a scalar or an array-like of real numbers."""
    if isinstance(values, (str, bytes)):
        raise _invalid(InvalidInput, field, values, "must be real numbers")
    try:
        a = np.asarray(values)
    except Exception:  # ragged input
        raise _invalid(InvalidInput, field, values, "must be real numbers") from None
    if a.dtype == bool or not (
        np.issubdtype(a.dtype, np.floating) or np.issubdtype(a.dtype, np.integer)
    ):
        raise _invalid(InvalidInput, field, values, "must be real numbers")
    if a.ndim > 1:
        raise _invalid(InvalidInput, field, a, "must be one-dimensional", f"<{a.ndim}-D array>")
    return np.ascontiguousarray(np.atleast_1d(a), dtype=float)


def _real_array(field, values):
    """As _real_array_np, as a list of Python floats."""
    return _real_array_np(field, values).tolist()


def _coerce(field, value):
    row = _ALL_FIELDS[field]
    t = row["type"]
    if t == "real":
        return _real(field, value)
    if t == "int":
        if field == "steps" and isinstance(value, str) and value == "auto":
            return 0
        if isinstance(value, str) and value in row.get("names", ()):
            return value  # basis="paper": the library turns the name into its value
        return _int(field, value)
    if t == "flag":
        return _flag(field, value)
    return _text(field, value)  # text and choice: the library checks the name


_MAX_BLADE_BYTES = 4 << 20


def split_parameters(kwargs):
    """(rotor dict, transition dict, flap_modes, lag_modes) from Analysis keyword arguments,
    names checked and values converted to the field types; the values themselves are checked
    by the library."""
    rotor, transition, counts = {}, {}, {"flap_modes": 1, "lag_modes": 1}
    if "spec" in kwargs:
        # spec="my.toml": the model derived from that ordering spec file now (spec:<name>).
        kwargs = dict(kwargs)
        spec = kwargs.pop("spec")
        if "model" in kwargs:
            raise _invalid(InvalidInput, "model", kwargs["model"], "not with spec (the spec is the model)")
        if not isinstance(spec, (str, os.PathLike)):
            raise _invalid(InvalidInput, "spec", spec, "must be the path of a spec file (str)")
        kwargs["model"] = _flaplag.load_spec(os.fspath(spec))
    tables = {}
    # blade="table.csv": a blade property table; mode_shapes="modes.csv": imported mode shapes
    # (docs/your-blade.md).  Read here, parsed and applied by the library.
    for key, what in (("blade", "blade table"), ("mode_shapes", "mode file")):
        if key not in kwargs:
            continue
        kwargs = dict(kwargs)
        path = kwargs.pop(key)
        if not isinstance(path, (str, os.PathLike)):
            raise _invalid(InvalidInput, key, path, f"must be the path of a {what} (str)")
        try:
            with open(os.fspath(path), "rb") as f:
                data = f.read(_MAX_BLADE_BYTES + 1)
        except OSError as e:
            raise _invalid(InvalidInput, key, os.fspath(path), f"cannot be read ({e.strerror})") from None
        if len(data) > _MAX_BLADE_BYTES:
            raise _invalid(InvalidInput, key, os.fspath(path), f"larger than 4 MiB (the limit on a {what})")
        tables[key + "_csv"] = data.decode("utf-8", errors="replace")
        tables[key + "_source"] = os.fspath(path)
    for field, value in kwargs.items():
        if field not in _ALL_FIELDS:
            close = difflib.get_close_matches(field, list(_ALL_FIELDS), n=1)
            hint = f" (did you mean {close[0]}?)" if close else ""
            raise _invalid(UnknownParameter, field, value, "unknown parameter" + hint)
        v = _coerce(field, value)
        if field in _ROTOR_FIELDS:
            rotor[field] = v
        elif field == "periodic_linearization":
            rotor["linearization"] = "periodic" if v else "hover"
        elif field in _TRANSITION_FIELDS:
            transition[field] = v
        else:
            counts[field] = v
    rotor.update(tables)
    return rotor, transition, counts["flap_modes"], counts["lag_modes"]


def _describe(row):
    """A numpydoc parameter entry from a table row."""
    t = row["type"]
    kind = {
        "real": "float",
        "int": "int or {" + ", ".join(repr(c) for c in row.get("names", ())) + "}"
        if row.get("names") else "int",
        "flag": "bool",
        "text": "str",
        "choice": "{" + ", ".join(repr(c) for c in row.get("choices", ())) + "}",
    }[t]
    head = f"{row['field']} : {kind}, default {row['default']!r}"
    details = []
    if row.get("symbol"):
        details.append(row["symbol"])
    if row.get("units") and row["units"] != "-":
        details.append(f"[{row['units']}]")
    if row.get("requirement") and t not in ("choice", "text", "flag"):
        details.append(row["requirement"])
    desc = row["description"]
    if details:
        desc = f"{desc}; {' '.join(details)}"
    return head + "\n" + textwrap.indent(textwrap.fill(desc, 88), "    ")


def _signature(rows, self_param=True):
    params = [inspect.Parameter("self", inspect.Parameter.POSITIONAL_ONLY)] if self_param else []
    params += [
        inspect.Parameter(r["field"], inspect.Parameter.KEYWORD_ONLY, default=r["default"])
        for r in rows
    ]
    return inspect.Signature(params)


def parameters_doc():
    """The parameter part of the Analysis docstring, from the library's tables."""
    out = ["Rotor and blade (C++ RotorParameters; the paper's typical case by default)"]
    out += [_describe(r) for r in PARAMETERS]
    out += ["", "Operating condition (C++ OperatingCondition)"]
    out += [_describe(r) for r in _CONDITION]
    out += ["", "Transition matrix Phi(2 pi) (C++ TransitionOptions)"]
    out += [_describe(r) for r in TRANSITION]
    out += ["", "Number of modes (the command line's --flap-modes, --lag-modes)"]
    out += [_describe(r) for r in _MODE_COUNTS]
    return "\n".join(out)


def _trim_request(trim, thrust_coefficient, shaft_angle):
    """None (no trim), or (kind, C_T, alpha_R) for the trimmed analyses; the command line's
    --trim, --thrust-coefficient, --shaft-angle (which, without a trim, are refused)."""
    if trim is None or (isinstance(trim, str) and trim == "none"):
        for field, value in (("thrust_coefficient", thrust_coefficient),
                             ("shaft_angle", shaft_angle)):
            if value is not None:
                raise _invalid(InvalidInput, field, value,
                               "needs trim='thrust' or trim='moment', or inflow='momentum' "
                               "(without either it would be ignored)")
        return None
    if not isinstance(trim, str) or trim not in ("thrust", "moment"):
        raise _invalid(InvalidInput, "trim", trim, "must be None, 'none', 'thrust' or 'moment'")
    ct = TRIM_DEFAULTS["thrust_coefficient"] if thrust_coefficient is None else thrust_coefficient
    alpha = TRIM_DEFAULTS["shaft_angle"] if shaft_angle is None else shaft_angle
    return (trim, _real("thrust_coefficient", ct), _real("shaft_angle", alpha))


def _inflow_request(inflow, trim, thrust_coefficient, shaft_angle):
    """(trim request, inflow model): the trim of _trim_request, and None (eq 2.24, the paper)
    or the InflowModel dict of inflow='momentum': eq 2.25 at every mu for C_T =
    thrust_coefficient (required) and alpha_R = shaft_angle (default 0), at fixed controls; the
    command line's --inflow.  Not with a trim, which solves eq 2.25 itself."""
    if inflow is None or (isinstance(inflow, str) and inflow == "uniform"):
        return _trim_request(trim, thrust_coefficient, shaft_angle), None
    if not isinstance(inflow, str) or inflow not in _INFLOW_KINDS:
        raise _invalid(InvalidInput, "inflow", inflow,
                       "must be None, " + ", ".join(repr(k) for k in _INFLOW_KINDS))
    if trim is not None and not (isinstance(trim, str) and trim == "none"):
        t = _trim_request(trim, thrust_coefficient, shaft_angle)  # a bad trim is named first
        raise _invalid(InvalidInput, "inflow", inflow,
                       f"not with trim={t[0]!r} (the trim solves eq 2.25 itself, with its own "
                       "inflow at every mu)")
    if thrust_coefficient is None:
        raise _invalid(InvalidInput, "inflow", inflow,
                       "needs thrust_coefficient (the C_T of eq 2.25, not C_T/sigma)")
    alpha = 0.0 if shaft_angle is None else shaft_angle
    return None, {
        "kind": inflow,
        "thrust_coefficient": _real("thrust_coefficient", thrust_coefficient),
        "shaft_angle": _real("shaft_angle", alpha),
    }


def _memory_limit(value):
    """The memory limit in bytes: None (the default, 2 GiB), a number of bytes or a size text
    such as '8G' or '512M' (units K, M, G, T, P: powers of 1024)."""
    if value is None:
        return _flaplag.default_memory_limit
    if isinstance(value, np.generic):
        value = value.item()
    return _flaplag.memory_limit(value)


def _progress(progress):
    if progress is not None and not callable(progress):
        raise _invalid(InvalidInput, "progress", progress,
                       "must be None or a function progress(done, total)")
    return progress


def _rebuild(kwargs):
    return Analysis(**kwargs)


class Analysis:
    def __init__(self, **kwargs):
        rotor, transition, flap_modes, lag_modes = split_parameters(kwargs)
        self._kwargs = dict(kwargs)
        self._native = _flaplag.Analysis(rotor, transition, flap_modes, lag_modes)
        self._hover = None

    # -- what was built ------------------------------------------------------------------------

    @property
    def parameters(self) -> dict:
        """Every RotorParameters field as used (model: the model selected for the mode counts)."""
        return dict(self._native.parameters())

    @property
    def options(self) -> dict:
        """The TransitionOptions: method, steps (0: automatic), terms, zeta_tolerance."""
        return dict(self._native.transition())

    @property
    def model(self) -> ModelInfo:
        """The ordering model of this analysis (its family and mode counts)."""
        return ModelInfo._from(self._native.model())

    @property
    def hover(self) -> HoverResult:
        """The hover equilibrium and exponents (computed with the analysis)."""
        if self._hover is None:
            self._hover = HoverResult._from(self._native.hover())
        return self._hover

    def _labels(self):
        labels = []
        for l in self.hover.labels:
            if l not in labels:
                labels.append(l)
        return labels

    # -- analyses ------------------------------------------------------------------------------

    def _at(self, trim_request, inflow_model):
        """The native analysis at an operating condition: trimmed by a _trim_request, or at fixed
        controls with an inflow model (both None: this one)."""
        if trim_request is not None:
            return self._native.trimmed(*trim_request)
        return self._native if inflow_model is None else self._native.at_inflow(inflow_model)

    def point(
        self,
        mu,
        *,
        scan_step=0.01,
        trim=None,
        thrust_coefficient=None,
        shaft_angle=None,
        inflow=None,
    ) -> PointResult:
        """The labelled exponents at advance ratio mu (0 <= mu <= 1000), continued from hover
        in steps of at most scan_step so that each exponent keeps its flap / lag label and its
        omega its integer part.  zeta, omega per rev.

        trim='thrust' or 'moment' (the command line's --trim; every model has the thrust and
        the cyclic pitch): the rotor is trimmed to C_T = thrust_coefficient (shaft angle
        alpha_R [rad]) at every mu the continuation evaluates (C++ OperatingCondition::Trimmed); see trim().

        inflow='momentum' (the command line's --inflow; not with a trim): the controls stay
        fixed and the inflow is that of eq 2.25 for C_T = thrust_coefficient (required) and
        alpha_R = shaft_angle (default 0) at every mu, sqrt(C_T/2) in hover; None or 'uniform'
        is eq 2.24, the paper's (C++ OperatingCondition::inflow, InflowModel::Momentum)."""
        t, model = _inflow_request(inflow, trim, thrust_coefficient, shaft_angle)
        mu, scan_step = _real("mu", mu), _real("scan_step", scan_step)
        return PointResult._from(self._at(t, model).point(mu, scan_step))

    def sweep(
        self,
        mu,
        stop=None,
        step=None,
        *,
        scan_step=0.01,
        trim=None,
        thrust_coefficient=None,
        shaft_angle=None,
        inflow=None,
        threads=0,
        progress=None,
        memory_limit=None,
        damping_criterion=None,
    ) -> SweepResult:
        """Exponents along advance ratios, continued from hover.

        sweep(mus): at the given advance ratios (nondecreasing, any spacing), continued in steps
        of at most scan_step (C++ Analysis::track).
        sweep(start, stop, step): at start, start + step, ..., stop inclusive, reported at the
        decimal grid values (C++ Analysis::sweep, the command line's --mu START:STOP:STEP).
        trim, thrust_coefficient, shaft_angle: at fixed C_T, as point().
        inflow: the inflow model at fixed controls, as point().
        threads: worker threads (0: all cores; the result does not depend on it; a trimmed
        sweep runs on one).
        progress: called as progress(evaluations_done, evaluations_total) from the calling
        thread (the steps from hover included); Ctrl-C stops the sweep (KeyboardInterrupt).
        memory_limit: the memory the result may take (bytes, or a size such as '8G'; default
        2 GiB): a sweep estimated to need more is refused before it starts.
        damping_criterion: a damping ratio asked of every mode, a fraction of critical (0.01 is
        1 %), 0 <= C < 1 (the command line's --damping-criterion): the result's
        ``damping_crossings`` give, per mode, the first mu where its damping ratio falls below
        it (interpolated between the sweep points) and a status.
        """
        t, model = _inflow_request(inflow, trim, thrust_coefficient, shaft_angle)
        dc = None if damping_criterion is None else _real("damping_criterion", damping_criterion)
        threads = _int("threads", threads)
        progress = _progress(progress)
        limit = _memory_limit(memory_limit)
        # The continuation step: the step between the points of a grid, scan_step between
        # given advance ratios; checked in both forms.
        ss = _real("scan_step", scan_step)
        if not (math.isfinite(ss) and ss > 0.0):
            raise _invalid(InvalidInput, "scan_step", ss, "must be finite and > 0")
        if t is not None:
            threads = 1  # a trimmed sweep runs on one
        if stop is None and step is None:
            mus = _real_array("mu", mu)
            raw = self._at(t, model).track(mus, ss, threads, progress, limit, dc)
        elif stop is None or step is None:
            raise TypeError("sweep(start, stop, step) needs all three, or sweep(mus) an array")
        else:
            if ss != 0.01:
                raise _invalid(InvalidInput, "scan_step", scan_step,
                               "applies to sweep(mus) only: sweep(start, stop, step) continues "
                               "in steps of `step`")
            grid = (_real("mu", mu), _real("stop", stop), _real("step", step))
            # The library names the grid mu0, mu1 (its arguments, the command line's
            # START:STOP): the user typed mu and stop.
            with _keywords(mu0="mu", mu1="stop"):
                raw = self._at(t, model).sweep(*grid, threads, progress, limit, dc)
        return SweepResult._from(raw, self._labels())

    def critical(
        self,
        *,
        mu_max=CRITICAL_DEFAULTS["mu_max"],
        scan_step=CRITICAL_DEFAULTS["scan_step"],
        tolerance=CRITICAL_DEFAULTS["tolerance"],
        all_intervals=CRITICAL_DEFAULTS["all_intervals"],
        zeta_threshold=CRITICAL_DEFAULTS["zeta_threshold"],
        periodic_omega_tolerance=CRITICAL_DEFAULTS["periodic_omega_tolerance"],
        scan_zeta_tolerance=CRITICAL_DEFAULTS["scan_zeta_tolerance"],
        trim=None,
        thrust_coefficient=None,
        shaft_angle=None,
        inflow=None,
    ) -> CriticalResult:
        """The critical advance ratio mu_c: scans mu = scan_step, 2 scan_step, ... up to mu_max,
        continuing the exponents from hover, and refines the first crossing of
        max zeta = zeta_threshold [per rev] by Brent's method to ``tolerance`` in mu.
        all_intervals=True scans on to mu_max and reports every instability interval.
        periodic_omega_tolerance: |omega - k/2| [per rev] below which a crossing is 'periodic';
        scan_zeta_tolerance: the exponent accuracy asked of the scan [per rev].
        trim, thrust_coefficient, shaft_angle: mu_c at fixed C_T, as point(); the
        result's trim is the TrimResult at mu_c.
        inflow: the inflow model at fixed controls, as point()."""
        t, model = _inflow_request(inflow, trim, thrust_coefficient, shaft_angle)
        opts = _options(CRITICAL_DEFAULTS, mu_max=mu_max, scan_step=scan_step, tolerance=tolerance,
                        all_intervals=all_intervals, zeta_threshold=zeta_threshold,
                        periodic_omega_tolerance=periodic_omega_tolerance,
                        scan_zeta_tolerance=scan_zeta_tolerance)
        return CriticalResult._from(self._at(t, model).critical(opts))

    def system(self, mu, psi=0.0) -> SystemResult:
        """The periodic system y' = A(psi) y + f(psi) at advance ratio mu and azimuth psi [rad]
        (any finite angle, reduced to [0, 2 pi)): A, f as numpy arrays, the flow region and
        every spanwise integral and generalized mass by name."""
        return SystemResult._from(self._native.snapshot(_real("mu", mu), _real("psi", psi)))

    def modes(self, x=101, *, derivative=0, memory_limit=None) -> ModeShapes:
        """The blade's mode shapes (flap eta_k, lag gamma_m) at stations x in [0, 1] (x0 = r/l):
        an array of stations, or a number of equally spaced ones (default 101).  derivative:
        0..3, the d/dx0 derivative to sample.  memory_limit: as sweep() (default 2 GiB)."""
        limit = _memory_limit(memory_limit)
        if isinstance(x, numbers.Integral) and not isinstance(x, (bool, np.bool_)):
            if x < 2:
                raise _invalid(InvalidInput, "x", x, "need at least 2 stations")
            if x > 2**62:
                raise _invalid(InvalidInput, "x", x, "too many stations")
            stations = int(x)
        else:
            stations = _real_array_np("x", x)
        return ModeShapes._from(
            self._native.modes(stations, _int("derivative", derivative), limit)
        )

    def export_mode_shapes(self, path=None, *, stations=1001) -> str:
        """The mode file of this analysis' mode shapes, as the command line's ``flaplag modes
        --export-shapes FILE.csv`` writes it (the same text for the same blade and mode counts):
        columns x0, flap1..flapM, lag1..lagN at ``stations`` equally spaced stations (8..100000;
        1001 as the command line) and the row ``omega`` of their rotating frequencies, every
        number in round-trip form; ``mode_shapes=`` reads it back (docs/your-blade.md).  Needs
        modes='exact' (or imported shapes); with a blade table the shapes are the table's.
        Written to ``path`` (a file name) when given; the text is returned either way."""
        text = self._native.mode_table(_int("stations", stations))
        if path is not None:
            with open(os.fspath(path), "w", encoding="utf-8", newline="") as f:
                f.write(text)
        return text

    def response(
        self,
        mu,
        *,
        samples=RESPONSE_DEFAULTS["samples"],
        steps=RESPONSE_DEFAULTS["steps"],
        tolerance=RESPONSE_DEFAULTS["tolerance"],
        memory_limit=None,
    ) -> ResponseResult:
        """The periodic forced response at mu (C++ Analysis::response, the command line's
        ``flaplag response``): the tip deflections at ``samples`` azimuths psi_k = 2 pi k / n
        over one revolution and their harmonics.  steps: RK4 steps per period (0: automatic,
        doubled until y(0) agrees to ``tolerance``, relative).  memory_limit: as sweep()."""
        return ResponseResult._from(
            self._native.response(
                _real("mu", mu),
                _options(RESPONSE_DEFAULTS, samples=samples, steps=steps, tolerance=tolerance),
                _memory_limit(memory_limit),
            )
        )

    def simulate(
        self,
        mu,
        *,
        revolutions=SIMULATION_DEFAULTS["revolutions"],
        y0=0.01,
        forced=False,
        samples_per_rev=SIMULATION_DEFAULTS["samples_per_rev"],
        steps_per_rev=SIMULATION_DEFAULTS["steps_per_rev"],
        nonlinear=False,
        memory_limit=None,
    ) -> SimulationResult:
        """Integrates the linear system at mu from y(0) = y0 (C++ Analysis::simulate, the
        command line's ``flaplag simulate``): y0 a number (every state, the command line's
        --perturbation) or one value per state (the order of ``Analysis.system(mu).states``);
        forced: include f(psi) (default: the free response).  ``revolutions`` (> 0), reported
        ``samples_per_rev`` times per revolution; steps_per_rev: RK4 steps (0: automatic).

        nonlinear=True (``--nonlinear``): the nonlinear equations (every model has the
        nonlinear loads), the full state from the periodic equilibrium
        q°(psi) plus y0; each direction's tips[d].deflection is then the deviation from
        q°(psi) (its growth_rate compares with the largest zeta about it), tips[d].total the
        total tip deflection.  forced must stay False (the loads are part of the equations).
        memory_limit: as sweep() (default 2 GiB): about five million samples fit in it."""
        n = self._native.state_size()
        if isinstance(y0, numbers.Real) and not isinstance(y0, (bool, np.bool_)):
            start = [float(y0)] * n
        else:
            start = _real_array("y0", y0)
        options = _options(SIMULATION_DEFAULTS, revolutions=revolutions,
                           samples_per_rev=samples_per_rev, steps_per_rev=steps_per_rev,
                           nonlinear=nonlinear)
        raw = self._native.simulate(
            _real("mu", mu), start, _flag("forced", forced), options, _memory_limit(memory_limit)
        )
        return SimulationResult._from(raw)

    def periodic_equilibrium(
        self,
        mu,
        *,
        harmonics=EQUILIBRIUM_DEFAULTS["harmonics"],
        harmonics_tolerance=EQUILIBRIUM_DEFAULTS["harmonics_tolerance"],
        max_iterations=EQUILIBRIUM_DEFAULTS["max_iterations"],
        tolerance=EQUILIBRIUM_DEFAULTS["tolerance"],
        check_stability=EQUILIBRIUM_DEFAULTS["check_stability"],
        samples=72,
    ) -> PeriodicEquilibriumResult:
        """The periodic equilibrium q°(psi) of the nonlinear equations at mu (C++
        Analysis::periodic_equilibrium; every model has the nonlinear loads): harmonic balance with ``harmonics`` K (-1, the default:
        doubled from 8 up to 64 until two K's coefficients agree to ``harmonics_tolerance``,
        relative) and Newton to ``tolerance``, continued from hover; its Fourier coefficients, the state and the tip
        deflections at ``samples`` azimuths psi_k = 2 pi k / samples, and (check_stability)
        the Floquet multipliers of the linearization about it.  The analysis' point, sweep and
        critical use this linearization with periodic_linearization=True."""
        return PeriodicEquilibriumResult._from(
            self._native.periodic_equilibrium(
                _real("mu", mu),
                _options(EQUILIBRIUM_DEFAULTS, harmonics=harmonics,
                         harmonics_tolerance=harmonics_tolerance, max_iterations=max_iterations,
                         tolerance=tolerance, check_stability=check_stability),
                _int("samples", samples),
            )
        )

    def campbell(
        self,
        *,
        speed_max=CAMPBELL_DEFAULTS["speed_max"],
        points=CAMPBELL_DEFAULTS["points"],
        mu=CAMPBELL_DEFAULTS["mu"],
        scan_step=CAMPBELL_DEFAULTS["scan_step"],
        harmonics=CAMPBELL_DEFAULTS["harmonics"],
        threads=CAMPBELL_DEFAULTS["threads"],
    ) -> CampbellResult:
        """The Campbell diagram of this blade (C++ flaplag::campbell_diagram, the command line's
        ``flaplag campbell``): every mode's frequency by the nominal speed Omega_0 against the
        rotor speed Omega/Omega_0 = 0 .. speed_max (``points`` speeds, evenly spaced), at the
        advance ratio mu, the bending stiffness fixed at its value for Omega_0 (centrifugal
        stiffening at each speed; a blade table keeps its EI columns); with the crossings of the
        per-rev lines n Omega, n = 1 .. harmonics.  threads: 0 = all cores (the result does not
        depend on it).  Imported mode_shapes are refused (they hold at one rotor speed)."""
        return CampbellResult._from(
            self._native.campbell(
                _options(CAMPBELL_DEFAULTS, speed_max=speed_max, points=points, mu=mu,
                         scan_step=scan_step, harmonics=harmonics, threads=threads)
            )
        )

    def trim(
        self,
        mu,
        *,
        kind="thrust",
        thrust_coefficient=TRIM_DEFAULTS["thrust_coefficient"],
        shaft_angle=TRIM_DEFAULTS["shaft_angle"],
        max_iterations=TRIM_DEFAULTS["max_iterations"],
        tolerance=TRIM_DEFAULTS["tolerance"],
    ) -> TrimResult:
        """Trims this rotor at mu (C++ flaplag::trim, the command line's ``flaplag trim``; any
        model: each has the thrust and the cyclic pitch): kind 'thrust' (theta0 and the
        inflow of eq 2.25) or 'moment' (also theta1c, theta1s with no first flap harmonic) such
        that the model's C_T (not C_T / sigma) equals thrust_coefficient, with the shaft angle
        alpha_R [rad] in eq 2.25.  Newton to ``tolerance`` in max_iterations."""
        return TrimResult._from(
            self._native.trim(
                _real("mu", mu),
                _options(TRIM_DEFAULTS, kind=kind, thrust_coefficient=thrust_coefficient,
                         shaft_angle=shaft_angle, max_iterations=max_iterations,
                         tolerance=tolerance),
            )
        )

    def thrust(self, mu, *, inflow="momentum", shaft_angle=0.0) -> ThrustResult:
        """The model's own thrust coefficient at mu with this rotor's pitch (C++
        rotor_thrust).  inflow: 'momentum' (eq 2.25
        solved together with C_T, shaft angle alpha_R [rad]: the thrust the rotor produces at
        this pitch), 'paper' (eq 2.24, the untrimmed default) or a number (lambda itself)."""
        if isinstance(inflow, str):
            if inflow not in ("momentum", "paper"):
                raise _invalid(
                    InvalidInput, "inflow", inflow, "must be 'momentum', 'paper' or a real number"
                )
            source, value = inflow, 0.0
        else:
            source, value = "given", _real("inflow", inflow)
        return ThrustResult._from(
            self._native.thrust(_real("mu", mu), source, value, _real("shaft_angle", shaft_angle))
        )

    def floquet(self, mu, *, zeta_tolerance=None) -> FloquetSample:
        """One Floquet analysis at mu without continuation (omega only as principal value),
        resolved to zeta_tolerance [per rev] (default: the analysis' zeta_tolerance)."""
        tol = self.options["zeta_tolerance"] if zeta_tolerance is None else zeta_tolerance
        return FloquetSample._from(
            self._native.floquet(_real("mu", mu), _real("zeta_tolerance", tol))
        )

    # -- Python protocol -----------------------------------------------------------------------

    def __reduce__(self):
        return (_rebuild, (self._kwargs,))

    def __repr__(self):
        given = ", ".join(f"{k}={v!r}" for k, v in self._kwargs.items())
        return f"flaplag.Analysis({given})"


Analysis.__doc__ = (
    """The coupled flap-lag stability analysis of one hingeless blade (NASA CR-132431).

Analysis(**parameters) builds the blade, its periodic system and the hover equilibrium; the
methods then analyse it at any advance ratio mu.  Keyword arguments only; every one has the
paper's typical-case default (gamma = 10, theta = 0.15, omega_flap = 1.175, omega_lag =
1.28303, assumed modes, model 'paper', Hsu's method with automatic steps).  The names are the
C++ field names (the command line's options without -- and with _ for -).  Quantities are
nondimensional as in the paper: angles in rad, frequencies per rev (by Omega).

Invalid values raise flaplag.InvalidInput, a ValueError with the library's one-line message
'<field> = <value>: <reason>'; unknown names raise flaplag.UnknownParameter (ValueError and
TypeError).  Numerical outcomes are results with a status and a message.

    >>> import flaplag
    >>> flaplag.Analysis().critical()
    >>> flaplag.Analysis(modes="exact", omega_lag=1.4).sweep(numpy.linspace(0, 1, 51))

Parameters
----------
"""
    + parameters_doc()
)
Analysis.__module__ = "flaplag"
Analysis.__init__.__signature__ = _signature(PARAMETERS + TRANSITION + _MODE_COUNTS)
Analysis.__init__.__doc__ = "Builds the analysis; see help(flaplag.Analysis) for the parameters."
