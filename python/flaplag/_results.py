"""Result classes of flaplag: plain, picklable values with numpy arrays and readable reprs.

Every result carries ``status`` ('ok', 'warning' or 'failed') and ``message``, as in C++:
numerical outcomes (an unstable hover, no mu_c below the scan limit, an under-resolved
transition matrix) are results, never exceptions.  Units: zeta and omega per rev (by the rotor
speed Omega), advance ratios mu and angles psi nondimensional / in radians.
"""

import collections.abc
import dataclasses
import functools
import math
import re
import typing
from dataclasses import dataclass, field
from typing import Dict, Mapping, Optional, Tuple

import numpy as np

from . import _flaplag

__all__ = [
    "Exponent",
    "HoverResult",
    "PointResult",
    "SweepResult",
    "DampingCrossing",
    "Interval",
    "CriticalResult",
    "SystemResult",
    "ModeShapes",
    "FloquetSample",
    "TipMotion",
    "ResponseResult",
    "SimulationResult",
    "PeriodicEquilibriumResult",
    "TrimResult",
    "ThrustResult",
    "ModelInfo",
    "StudyResult",
    "MapResult",
]


def _g(v, digits=6):
    """A number for a repr: about six significant digits, None as None."""
    if v is None:
        return "None"
    if isinstance(v, float) and not math.isfinite(v):
        return repr(v)
    return f"{v:.{digits}g}"


def _same_mode(a, b):
    """Whether two labels name one mode: one scheme for every model ("flap", "flap2", "lag"),
    and "lag1", the first lag mode's label in M x N results of older versions, is "lag"."""

    def canonical(label):  # a direction's name followed by 1 is its first mode
        match = re.fullmatch(r"([a-z]+)1", label)
        return match.group(1) if match else label

    return canonical(a) == canonical(b)


def _status(status, message):
    if status == "ok":
        return "status='ok'"
    return f"status={status!r}, message={message!r}"


def _array(dtype):
    """The annotation of a numpy array attribute with elements of dtype (complex, float)."""
    return typing.Annotated[np.ndarray, dtype]


def _convert(hint, value):
    """A value of the module's dict as the annotated type of a result's attribute."""
    if value is None:
        return None
    origin = typing.get_origin(hint)
    if origin is typing.Union:  # Optional[X]
        args = [a for a in typing.get_args(hint) if a is not type(None)]
        return _convert(args[0], value) if len(args) == 1 else value
    if origin is tuple:
        return tuple(_convert(typing.get_args(hint)[0], v) for v in value)
    if origin is collections.abc.Mapping:  # Mapping[str, X]: the module's dict, in its order
        item = typing.get_args(hint)[1]
        return {key: _convert(item, v) for key, v in value.items()}
    if origin is typing.Annotated:  # _Array[dtype]: a numpy array of that element type
        return np.asarray(value, dtype=typing.get_args(hint)[1])
    if hint is np.ndarray:
        return np.asarray(value)
    if isinstance(hint, type) and hasattr(hint, "_from"):
        return hint._from(value)
    if hint is complex:
        return complex(value)
    return value


class _Described:
    """A result built from the dict of a C++ struct with a field table (core/fields.h): the
    table's keys (``_flaplag.result_fields(name)``) are the attributes, under the names of the
    command line's JSON.  A key the class declares (or _table declares for it) is converted to
    its annotated type; a key the class computes itself is a property of the same name; any
    other key (a row of a struct whose class is not built by _table, or a key the module adds)
    is an attribute as the module gives it."""

    @classmethod
    def _from(cls, d, **given):
        fields = _init_fields(cls)
        values = {
            name: _convert(hint, d[name]) for name, hint in fields if name in d and name not in given
        }
        values.update(given)
        result = cls(**values)
        declared = {name for name, _ in fields}
        extra = {k: v for k, v in d.items() if k not in declared and not hasattr(cls, k)}
        if extra:
            object.__setattr__(result, "_extra", extra)
        return result

    def __getattr__(self, name):  # only when the attribute is not found otherwise
        extra = self.__dict__.get("_extra", {})
        if name in extra:
            return extra[name]
        tip = _tip_alias(self.__dict__.get("tips"), name)
        if tip is not None:
            return getattr(*tip)
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(_tip_aliases(self.__dict__.get("tips"))))


def _tip_aliases(tips):
    """The former names of a result's per-direction values: '<direction>_<field>' for each
    direction of ``tips`` and each field of TipMotion but the direction ('flap_tip' for
    tips['flap'].deflection, the old name of a deflection being '<direction>_tip')."""
    if not tips:
        return {}
    fields = [f.name for f in dataclasses.fields(TipMotion) if f.name != "direction"]
    return {
        f"{direction}_{_TIP_ALIAS.get(f, f)}": (motion, f)
        for direction, motion in tips.items()
        for f in fields
    }


def _tip_alias(tips, name):
    """(tips[direction], field) when ``name`` is one of _tip_aliases(tips), else None."""
    return _tip_aliases(tips).get(name)


@functools.lru_cache(maxsize=None)
def _init_fields(cls):
    """(name, type hint) of the attributes a result class is constructed with."""
    hints = typing.get_type_hints(cls, globalns=globals(), include_extras=True)
    return tuple((f.name, hints[f.name]) for f in dataclasses.fields(cls) if f.init)


def _annotation(words):
    """The annotation of a row's value from its C++ type (_flaplag.result_types): numbers in a
    list are a numpy array of their type, other lists tuples, a struct its class (by name) or a
    dict."""
    kind, _, rest = words.partition(" ")
    if kind == "optional":
        return Optional[_annotation(rest)]
    if kind == "list":
        item = _annotation(rest)
        return _array(item) if item in (float, complex) else Tuple[item, ...]
    if kind == "struct":
        return rest or dict
    simple = {"float": float, "int": int, "bool": bool, "str": str, "complex": complex}
    arrays = {"dict": Dict[str, float], "matrix": np.ndarray, "vector": _array(float)}
    return simple.get(kind) or arrays[kind]


def _table(name):
    """A result class's attributes from the C++ table of ``name`` (under @dataclass): one per
    row, in the table's order, annotated by the row's type, but for a row the class computes (a
    property); the class declares only a row whose type or default differs and attributes of
    its own (after the rows, with defaults).  Rows that documents leave out when empty default
    to empty when only rows with defaults follow."""

    def build(cls):
        own = dict(cls.__dict__.get("__annotations__", {}))
        rows = [r for r in _flaplag.result_types(name)
                if r[0] in own or not isinstance(getattr(cls, r[0], None), property)]
        annotations = {}
        for k, (key, words, optional) in enumerate(rows):
            annotations[key] = own.pop(key, None) or _annotation(words)
            trailing = all(r[2] or r[0] in cls.__dict__ for r in rows[k:])
            if optional and trailing and key not in cls.__dict__:
                setattr(cls, key, () if words.startswith("list") else None)
        cls.__annotations__ = {**annotations, **own}
        return cls

    return build


@dataclass(frozen=True, repr=False)
@_table("Exponent")
class Exponent(_Described):
    """One characteristic exponent lambda = zeta + i omega [per rev] with its mode label.

    ``multiplier`` is the characteristic multiplier exp(2 pi lambda) of Phi(2 pi) (None for the
    hover eigenvalues, which come from A at mu = 0 directly).  omega has its integer part fixed
    by continuation from hover; zeta = -inf marks a multiplier that underflowed to zero.
    """

    multiplier: Optional[complex] = None  # None for the hover eigenvalues

    @property
    def damping_ratio(self) -> Optional[float]:
        """-zeta / |lambda|, a fraction of critical (the command line's damping ratio; its text
        and pictures show it in %), with omega as here: continued from hover, not reduced
        modulo 1/rev.  For omega = 0 +1 when the mode decays, -1 when it grows; None for
        lambda = 0 (undefined)."""
        return _flaplag.damping_ratio(self.zeta, self.omega)

    def __repr__(self):
        return f"Exponent({self.label!r}, zeta={_g(self.zeta)}, omega={_g(self.omega)})"


def _exponent_list(exponents):
    return "[" + ", ".join(f"{e.label} {_g(e.zeta, 4)}{e.omega:+.5g}i" for e in exponents) + "]"


@dataclass(frozen=True, repr=False)
@_table("HoverResult")
class HoverResult(_Described):
    """The hover equilibrium (eqs 2.24, 2.29-2.32) and the hover exponents.

    inflow: lambda (eq 2.24); equilibrium: {'g0_1': ..., 'h0_1': ...} (modal amplitudes);
    A0: the constant A at mu = 0; eigenvalues: eig(A0) [per rev] with ``labels``; stable: all
    zeta <= 0 (None when unknown: the largest real part is within the rounding level of zero,
    status 'warning').
    """

    @property
    def exponents(self) -> Tuple[Exponent, ...]:
        return tuple(
            Exponent(l, float(z.real), float(z.imag)) for l, z in zip(self.labels, self.eigenvalues)
        )

    def __repr__(self):
        eq = ", ".join(f"{k}={_g(v)}" for k, v in self.equilibrium.items())
        return (
            f"HoverResult(inflow={_g(self.inflow)}, {eq}, stable={self.stable}, "
            f"exponents={_exponent_list(self.exponents)}, {_status(self.status, self.message)})"
        )


@dataclass(frozen=True, repr=False)
@_table("PointResult")
class PointResult(_Described):
    """The labelled exponents at one advance ratio mu.

    exponents: sorted by label, then by omega (descending); liouville_residual: the relative
    |det Phi - exp int tr A| (None when not representable); error_estimate: the estimated
    largest zeta error [per rev] (None when not estimated); steps: the steps per period used;
    stable: all zeta <= 0 (None when unknown: status 'failed', or status 'warning' when the
    largest zeta is within its own error estimate of zero); notes: remarks that do not lower
    the status.  trim: at fixed C_T (trim='thrust' or 'moment'), the TrimResult at mu the
    point rests on; otherwise None.  equilibrium: with periodic_linearization=True at fixed
    controls, the PeriodicEquilibriumResult at mu the exponents were computed about (its state
    and tips at 72 azimuths; trimmed, the trim's ``equilibrium`` says it); otherwise None.
    """

    trim: Optional["TrimResult"] = None
    equilibrium: Optional["PeriodicEquilibriumResult"] = field(default=None, compare=False)

    @property
    def zeta(self) -> np.ndarray:
        """zeta of every exponent [per rev], in the order of ``exponents``."""
        return np.array([e.zeta for e in self.exponents])

    @property
    def omega(self) -> np.ndarray:
        """omega of every exponent [per rev]."""
        return np.array([e.omega for e in self.exponents])

    @property
    def multipliers(self) -> np.ndarray:
        return np.array([e.multiplier for e in self.exponents], dtype=complex)

    @property
    def labels(self) -> Tuple[str, ...]:
        return tuple(e.label for e in self.exponents)

    @property
    def max_zeta(self) -> float:
        """The largest zeta [per rev] (nan without exponents)."""
        return max((e.zeta for e in self.exponents), default=math.nan)

    def dominant(self, label) -> Optional[Exponent]:
        """The exponent that decides mode ``label``'s stability: the largest zeta, of a
        conjugate pair the one with omega >= 0 (the command line's rule for its tables)."""
        best = None
        for e in self.exponents:
            if not _same_mode(e.label, label):
                continue
            if (
                best is None
                or e.zeta > best.zeta
                or (e.zeta == best.zeta and e.omega >= 0.0 and best.omega < 0.0)
            ):
                best = e
        return best

    def __repr__(self):
        return (
            f"PointResult(mu={_g(self.mu)}, stable={self.stable}, "
            f"exponents={_exponent_list(self.exponents)}, {_status(self.status, self.message)})"
        )


@dataclass(frozen=True, repr=False)
@_table("DampingCrossing")
class DampingCrossing(_Described):
    """Where mode ``mode``'s damping ratio -zeta/|lambda| (a fraction of critical) first falls
    below the sweep's damping criterion C.

    mu: interpolated linearly between the sweep points mu_above (the last at or above C) and
    mu_below (the first below C); status: 'crossed'; 'unresolved' (a bracketing point failed,
    has no error estimate or lies within its error of C, or a point between has no ratio; mu
    may be None); 'below_at_start' (mu: the first point); 'not_crossed' (mu None).
    """

    def __repr__(self):
        return f"DampingCrossing({self.mode!r}, mu={_g(self.mu)}, status={self.status!r})"


@dataclass(frozen=True, repr=False)
class SweepResult(_Described):
    """Exponents along advance ratios mu, continued from hover.

    mu: the advance ratios (1-D array); points: one PointResult each; labels: the mode labels
    in hover order.  ``zeta[label]``, ``omega[label]`` and ``damping_ratio[label]`` are 1-D
    arrays of the mode's dominant exponent (PointResult.dominant; nan where a point has none or
    the ratio is undefined); the damping ratio -zeta/|lambda| is a fraction of critical, with
    omega continued from hover.  damping_criterion: C when asked for (else None), and
    damping_crossings: one DampingCrossing per label.  A failed step ends the sweep: then there
    are fewer points than advance ratios asked for, the failed one last.  trims: at fixed C_T
    (trim='thrust' or 'moment'), the TrimResult each point rests on, in order; otherwise ().
    equilibria: with periodic_linearization=True at fixed controls, the
    PeriodicEquilibriumResult each point rests on, in order (each point's ``equilibrium``);
    otherwise ().
    """

    mu: np.ndarray
    points: Tuple[PointResult, ...]
    labels: Tuple[str, ...]
    status: str
    message: str
    notes: Tuple[str, ...] = ()
    damping_criterion: Optional[float] = None
    damping_crossings: Tuple[DampingCrossing, ...] = ()
    trims: Tuple["TrimResult", ...] = ()
    equilibria: Tuple["PeriodicEquilibriumResult", ...] = field(default=(), compare=False)
    zeta: Dict[str, np.ndarray] = field(init=False)
    omega: Dict[str, np.ndarray] = field(init=False)

    def __post_init__(self):
        zeta, omega = {}, {}
        for label in self.labels:
            dom = [p.dominant(label) for p in self.points]
            zeta[label] = np.array([math.nan if e is None else e.zeta for e in dom])
            omega[label] = np.array([math.nan if e is None else e.omega for e in dom])
        object.__setattr__(self, "zeta", zeta)
        object.__setattr__(self, "omega", omega)

    @property
    def damping_ratio(self) -> Dict[str, np.ndarray]:
        """Per label, the damping ratio -zeta/|lambda| of the dominant exponent at each point,
        a fraction of critical (nan where a point has no exponent of the mode or lambda = 0)."""
        ratio = {}
        for label in self.labels:
            dom = [p.dominant(label) for p in self.points]
            ratio[label] = np.array(
                [math.nan if e is None or e.damping_ratio is None else e.damping_ratio for e in dom]
            )
        return ratio

    def crossing(self, label) -> Optional[DampingCrossing]:
        """The DampingCrossing of mode ``label`` (None without a damping criterion)."""
        return next((c for c in self.damping_crossings if _same_mode(c.mode, label)), None)

    @property
    def max_zeta(self) -> np.ndarray:
        """The largest zeta at each point [per rev]."""
        return np.array([p.max_zeta for p in self.points])

    @property
    def stable(self) -> Tuple[Optional[bool], ...]:
        return tuple(p.stable for p in self.points)

    def __len__(self):
        return len(self.points)

    def __repr__(self):
        if len(self.mu) == 0:
            return f"SweepResult(no points, {_status(self.status, self.message)})"
        unstable = [p.mu for p in self.points if p.stable is False]
        where = f", unstable from mu = {_g(unstable[0])}" if unstable else ", stable throughout"
        return (
            f"SweepResult({len(self.points)} points, mu = {_g(self.mu[0])}..{_g(self.mu[-1])}, "
            f"modes {list(self.labels)}{where}, {_status(self.status, self.message)})"
        )

    @classmethod
    def _from(cls, d, labels):
        equilibria = tuple(PeriodicEquilibriumResult._from(e) for e in d.get("equilibria", ()))
        points = tuple(
            PointResult._from(p, equilibrium=equilibria[k] if k < len(equilibria) else None)
            for k, p in enumerate(d["points"])
        )
        return super()._from(
            d,
            points=points,
            mu=np.array([p.mu for p in points]),
            labels=tuple(labels),
            equilibria=equilibria,
        )


@dataclass(frozen=True, repr=False)
@_table("CampbellFrequency")
class CampbellFrequency(_Described):
    """One mode at one rotor speed: ``frequency`` by the nominal speed Omega_0 (omega Omega /
    Omega_0), ``omega`` per rev at this speed, the damping ratio -zeta/|lambda| (None at
    Omega = 0, where nothing rotates)."""

    def __repr__(self):
        return f"CampbellFrequency({self.label!r}, frequency={_g(self.frequency)})"


@dataclass(frozen=True, repr=False)
@_table("CampbellPoint")
class CampbellPoint(_Described):
    """The modes at one rotor speed Omega/Omega_0, with the blade's first rotating frequencies
    by Omega there (omega_flap, omega_lag)."""

    def __repr__(self):
        return f"CampbellPoint(speed={_g(self.speed)}, {_status(self.status, self.message)})"


@dataclass(frozen=True, repr=False)
@_table("CampbellCrossing")
class CampbellCrossing(_Described):
    """Where mode ``label``'s frequency meets the per-rev line n Omega (n = ``harmonic``), at
    the rotor speed ``speed`` = Omega/Omega_0 (linear between the speeds around it)."""

    def __repr__(self):
        return f"CampbellCrossing({self.label!r}, {self.harmonic}/rev at speed {_g(self.speed)})"


@dataclass(frozen=True, repr=False)
@_table("CampbellResult")
class CampbellResult(_Described):
    """The Campbell diagram (Analysis.campbell): every mode's frequency by the nominal speed
    against the rotor speed Omega/Omega_0, at the advance ratio mu.

    ``speed`` is the 1-D array of the speeds, ``frequency[label]`` the mode's frequencies there
    (nan where a point failed); points: one CampbellPoint each; crossings: every crossing of a
    mode with a per-rev line n Omega, n = 1 .. harmonics.
    """

    @property
    def speed(self) -> np.ndarray:
        return np.array([p.speed for p in self.points])

    @property
    def frequency(self) -> Dict[str, np.ndarray]:
        out = {}
        for m, label in enumerate(self.labels):
            out[label] = np.array(
                [p.modes[m].frequency if m < len(p.modes) else math.nan for p in self.points]
            )
        return out

    def __repr__(self):
        return (
            f"CampbellResult({len(self.points)} speeds, modes {list(self.labels)}, "
            f"{len(self.crossings)} crossings, {_status(self.status, self.message)})"
        )


@dataclass(frozen=True, repr=False)
@_table("Interval")
class Interval(_Described):
    """One interval of instability in mu: max zeta > zeta_threshold for onset < mu < end
    (end None: still unstable at mu_max), with the mode that crosses at the onset, its omega
    [per rev] and kind ('flutter' or 'periodic'); *_error: estimated |error| of onset / end."""

    def __repr__(self):
        return (
            f"Interval({_g(self.onset)}..{_g(self.end)}, mode={self.mode!r}, "
            f"kind={self.kind!r}, omega={_g(self.omega)})"
        )


@dataclass(frozen=True, repr=False)
@_table("CriticalResult")
class CriticalResult(_Described):
    """The critical advance ratio mu_c: the first mu in (0, mu_max] where an exponent has
    zeta > zeta_threshold.

    mu_c is None when the blade is stable up to mu_max, unstable already in hover
    (hover_unstable) or the search failed (status 'failed').  With mu_c: mode ('flap', 'lag',
    'flap2', ...), omega [per rev, >= 0] and kind ('flutter': omega not locked; 'periodic':
    omega locked to 0, 1/2 or 1 per rev); otherwise these are None.  mu_c_error is the
    estimated |mu_c error|; intervals lists the instability intervals (every one up to mu_max
    with all_intervals=True); exponents are those at mu_c, at hover or at the last mu scanned;
    evaluations counts the Floquet analyses.  trim: for a search at fixed C_T (trim='thrust' or
    'moment') that found mu_c, the TrimResult at mu_c (its theta0, theta1c, theta1s, inflow; as
    ``flaplag critical --trim`` reports it); otherwise None.  equilibrium: with
    periodic_linearization=True at fixed controls, the PeriodicEquilibriumResult at mu_c (at a
    fold of the branch, beyond which there is none, the last one found below it); otherwise None.
    """

    trim: Optional["TrimResult"] = None
    equilibrium: Optional["PeriodicEquilibriumResult"] = field(default=None, compare=False)

    def __repr__(self):
        if self.mu_c is not None:
            what = (
                f"mu_c={_g(self.mu_c)}, mode={self.mode!r}, kind={self.kind!r}, "
                f"omega={_g(self.omega)}"
            )
            if len(self.intervals) > 1:
                what += f", intervals={list(self.intervals)}"
        elif self.hover_unstable:
            what = "mu_c=None (unstable in hover)"
        elif self.status == "failed":
            what = "mu_c=None (the search failed)"
        else:
            what = f"mu_c=None (stable up to mu = {_g(self.mu_max)})"
        return f"CriticalResult({what}, {_status(self.status, self.message)})"


@dataclass(frozen=True, repr=False)
class SystemResult:
    """The linear periodic system y' = A(psi) y + f(psi) at one (mu, psi), for auditing.

    states: the state names (dg1', dg1, dh1', dh1 for one flap and one lag mode); region:
    'normal' or 'reversed' (the reversed-flow sector of Appendix D, or with exact_reversed_flow
    the exact circle x < -mu sin psi); aero_integrals: the
    spanwise aerodynamic integrals of the normal-flow region by name, aero_integrals_at_psi the
    values used at psi; structural_integrals: the generalized masses and structural integrals
    (by I_b); paper_names: the Appendix B name of each integral ('' where there is none).
    """

    mu: float
    psi: float
    region: str
    A: np.ndarray
    f: np.ndarray
    states: Tuple[str, ...]
    aero_integrals: Dict[str, float]
    aero_integrals_at_psi: Dict[str, float]
    structural_integrals: Dict[str, float]
    paper_names: Dict[str, str]

    def __repr__(self):
        n = self.A.shape[0]
        return (
            f"SystemResult(mu={_g(self.mu)}, psi={_g(self.psi)}, region={self.region!r}, "
            f"A: {n}x{n}, states {list(self.states)}, {len(self.aero_integrals)} aerodynamic "
            f"and {len(self.structural_integrals)} structural integrals)"
        )

    @classmethod
    def _from(cls, d):  # the dict of the C++ SystemSnapshot's table
        aero, structural = d["aero_integrals"], d["structural_integrals"]
        paper = {a["name"]: a["paper_name"] for a in aero}
        paper.update({s["name"]: s["paper_name"] for s in structural})
        return cls(
            d["mu"],
            d["psi"],
            d["region"],
            np.asarray(d["A"]),
            np.asarray(d["f"]),
            tuple(d["state"]),
            {a["name"]: a["normal"] for a in aero},
            {a["name"]: math.nan if a["at_psi"] is None else a["at_psi"] for a in aero},
            {s["name"]: s["value"] for s in structural},
            paper,
        )


@dataclass(frozen=True, repr=False)
class ModeShapes(_Described):
    """The blade's mode shapes sampled at stations x (x0 = r / l in [0, 1], the elastic span).

    flap[k] (eta_k) and lag[m] (gamma_m) are the shapes or their ``derivative``-th derivative
    d/dx0 at x; omega_flap / omega_lag: the rotating frequencies [per rev];
    stiffness_flap / stiffness_lag: EI / (Omega^2 l I_b) (0 for the assumed mode of eq 4.1; with a
    blade table the scale s of its EI columns, EI / (Omega^2 l I_b) = s times the column).
    Analysis.export_mode_shapes writes the shapes as a mode file.
    """

    kind: str
    x: np.ndarray
    derivative: int
    flap: np.ndarray
    lag: np.ndarray
    omega_flap: np.ndarray
    omega_lag: np.ndarray
    stiffness_flap: float
    stiffness_lag: float

    def __repr__(self):
        return (
            f"ModeShapes({self.kind!r}, {self.flap.shape[0]} flap x {self.lag.shape[0]} lag, "
            f"omega_flap={[float(_g(w)) for w in self.omega_flap]}, "
            f"omega_lag={[float(_g(w)) for w in self.omega_lag]}, {len(self.x)} stations, "
            f"derivative {self.derivative})"
        )


@dataclass(frozen=True, repr=False)
@_table("FloquetSample")
class FloquetSample(_Described):
    """One Floquet analysis at mu, without continuation: multipliers of Phi(2 pi), zeta and
    omega (principal value in (-1/2, 1/2]) [per rev], zeta_errors (estimated, per exponent),
    error_estimate (the largest), steps per period, the Liouville residual."""

    @property
    def error(self) -> Optional[float]:
        """The former name of error_estimate."""
        return self.error_estimate

    def __repr__(self):
        return (
            f"FloquetSample(zeta={[float(_g(z)) for z in self.zeta]}, steps={self.steps}, "
            f"error_estimate={_g(self.error_estimate)}, {_status(self.status, self.message)})"
        )


@dataclass(frozen=True, repr=False, eq=False)
@_table("TipMotion")
class TipMotion(_Described):
    """The tip motion of one blade direction (C++ flaplag::TipMotion), an entry of a result's
    ``tips`` (keyed by the direction, in the model's state order): direction ('flap', 'lag');
    deflection: the tip deflection by l at the result's psi (flap w/l up, lag v/l positive
    lag); harmonics (ResponseResult; else empty): value = c[0] + sum_n (c[2n-1] cos n psi +
    c[2n] sin n psi), n = 1..5; total (nonlinear SimulationResult; else empty): the total
    deflection, reference included; growth_rate (SimulationResult; else None): the envelope
    growth rate of deflection per rev over the last 3/4 of the run (None with fewer than 3
    revolutions there).  A result's ``<direction>_tip`` is tips[direction].deflection, and
    ``<direction>_<field>`` tips[direction].<field> (``flap_harmonics``, ``lag_growth_rate``)."""

    def __repr__(self):
        return (
            f"TipMotion({self.direction!r}, {len(self.deflection)} samples, "
            f"growth_rate={_g(self.growth_rate)})"
        )


_TIP_ALIAS = {"deflection": "tip"}  # a field whose former name is not the field's


@dataclass(frozen=True, repr=False, eq=False)
@_table("ResponseResult")
class ResponseResult(_Described):
    """The periodic forced response at one mu (the command line's ``flaplag response``): the
    2 pi-periodic solution of y' = A(psi) y + f(psi), the Floquet particular solution
    (I - Phi) y(0) = int Phi(2 pi, s) f(s) ds.

    psi: the sample azimuths [rad] in [0, 2 pi); y: the perturbation state about the hover
    equilibrium at psi (samples x states, the state order of ``Analysis.system``); y0 = y(0);
    tips: per blade direction of the model ('flap', 'lag', in state order), a TipMotion with
    the tip deflection by l at psi, hover equilibrium included (flap w/l up, lag v/l positive
    lag), and its harmonics, value = c[0] + sum_n (c[2n-1] cos n psi + c[2n] sin n psi),
    n = 1..5, named by ``harmonic_names`` ('const', 'cos psi', 'sin psi', 'cos 2psi', ...);
    ``flap_tip``, ``lag_harmonics``, ... are tips['flap'].deflection, tips['lag'].harmonics,
    ... under their former names; closure: |y(2 pi) - y(0)| / max(1, |y0|);
    error_estimate: the estimated error of y0 (relative; ``error`` is its former name);
    min_distance_to_one: min |multiplier - 1| (near 0: no unique periodic solution); steps:
    RK4 steps per period.  status 'failed'
    (arrays empty) when a multiplier is at 1, 'warning' when the blade is unstable (the
    solution exists but is not what the blade settles to).
    """

    # The module's arrays beside the table's rows (always given).
    y: np.ndarray = None
    tips: Mapping[str, TipMotion] = None
    harmonic_names: Tuple[str, ...] = ()

    @property
    def error(self) -> Optional[float]:
        """The former name of error_estimate."""
        return self.error_estimate

    def harmonics(self, which="flap") -> Dict[str, float]:
        """{'const': ..., 'cos psi': ..., ...} of the tip deflection of direction ``which``
        (a key of ``tips``: 'flap', 'lag')."""
        c = self.tips[which].harmonics
        return {n: float(v) for n, v in zip(self.harmonic_names, c)}

    def __repr__(self):
        first = ""
        direction, motion = next(iter(self.tips.items()), ("", None))
        if motion is not None and len(motion.harmonics) >= 3:
            c = motion.harmonics
            first = f"{direction} const={_g(c[0])}, cos={_g(c[1])}, sin={_g(c[2])}, "
        return (
            f"ResponseResult(mu={_g(self.mu)}, {len(self.psi)} samples, {first}"
            f"closure={_g(self.closure)}, {_status(self.status, self.message)})"
        )


@dataclass(frozen=True, repr=False, eq=False)
@_table("SimulationResult")
class SimulationResult(_Described):
    """A time-domain simulation at one mu (the command line's ``flaplag simulate``).

    Linear (nonlinear False): y' = A(psi) y (+ f(psi) when forced) from y(0) = y0, y the
    perturbation about the hover equilibrium.  Nonlinear: the full state of the nonlinear
    equations (with the model's nonlinear loads) from the reference
    equilibrium plus y0; ``reference`` says which: 'periodic equilibrium' (q°(psi); at mu = 0
    the hover equilibrium) or, where the branch from hover has no periodic equilibrium,
    'hover equilibrium' (status 'warning').

    psi: [rad] from 0; revolutions: psi / 2 pi; y: the state (samples x states): the
    perturbation (linear) or the full state (nonlinear); tips: per blade direction of the model
    ('flap', 'lag', in state order), a TipMotion with the tip deflection by l of the state
    minus the reference (the perturbation), the total tip deflection (nonlinear only, else
    empty) and the envelope growth rate of the deflection per rev over the last 3/4 of the run
    (None with fewer than 3 revolutions there), to compare with the largest Floquet zeta about
    the reference; ``flap_tip``, ``lag_total``, ``lag_growth_rate``, ... are
    tips['flap'].deflection, tips['lag'].total, tips['lag'].growth_rate, ... under their
    former names; steps_per_rev: RK4 steps per revolution.  status 'failed' on overflow (the state
    is kept up to there).
    """

    nonlinear: bool = False
    reference: str = "hover equilibrium"
    # The module's arrays beside the table's rows (always given).
    y: np.ndarray = None
    tips: Mapping[str, TipMotion] = None

    @property
    def revolutions(self) -> np.ndarray:
        return self.psi / (2.0 * math.pi)

    def __repr__(self):
        kind = "nonlinear, " if self.nonlinear else ""
        rates = "".join(f"{d}_growth_rate={_g(t.growth_rate)}, " for d, t in self.tips.items())
        return (
            f"SimulationResult(mu={_g(self.mu)}, {kind}{len(self.psi)} samples, {rates}"
            f"{_status(self.status, self.message)})"
        )


@dataclass(frozen=True, repr=False, eq=False)
@_table("PeriodicEquilibriumResult")
class PeriodicEquilibriumResult(_Described):
    """The periodic equilibrium q°(psi) of the nonlinear equations at one mu (C++
    Analysis::periodic_equilibrium, harmonic balance + Newton, continued from hover).

    coefficients: the Fourier coefficients of the coordinates q° = [g°_1..g°_M, h°_1..h°_N]
    (modes x 2K+1; column 0 the constant, 2k-1 cos k psi, 2k sin k psi); harmonics: K;
    psi: sample azimuths [rad] in [0, 2 pi); y: the full state y°(psi) = [g°', g°, h°', h°]
    there (samples x states); tips: per blade direction of the model ('flap', 'lag', in state
    order), a TipMotion with the tip deflection (w/l, v/l) there (``flap_tip``, ``lag_tip``:
    tips['flap'].deflection, tips['lag'].deflection under their former names);
    multiplier_moduli: |Floquet multipliers| of the linearization about it, descending (with
    check_stability; empty otherwise), min_distance_to_one: min |multiplier - 1| (None without
    check_stability); truncation: the size of harmonic K relative to the largest coefficient;
    harmonics_error: with the automatic K, the largest coefficient difference between K/2 and
    K relative to the largest coefficient (nan for a fixed K);
    continued_to: the largest mu the continuation from hover reached; iterations, step,
    residual: of the last Newton solve; mean_thrust: the azimuth mean of one blade's thrust
    along q° (C_T = sigma a / 2 mean_thrust; nan for a model without nonlinear thrust).
    status 'failed' (no samples) beyond the fold of the hover branch or without convergence;
    'warning' when unstable or the truncation is not small.
    """

    # The module's arrays beside the table's rows (always given).
    coefficients: np.ndarray = None
    psi: np.ndarray = None
    y: np.ndarray = None
    tips: Mapping[str, TipMotion] = None

    @property
    def max_zeta(self) -> Optional[float]:
        """ln(largest |multiplier|) / 2 pi [per rev]: the largest damping exponent about the
        equilibrium (None without check_stability)."""
        if len(self.multiplier_moduli) == 0:
            return None
        return float(np.log(self.multiplier_moduli[0]) / (2.0 * math.pi))

    def __repr__(self):
        return (
            f"PeriodicEquilibriumResult(mu={_g(self.mu)}, K={self.harmonics}, "
            f"max_zeta={_g(self.max_zeta)}, truncation={_g(self.truncation)}, "
            f"{_status(self.status, self.message)})"
        )


@dataclass(frozen=True, repr=False)
@_table("TrimResult")
class TrimResult(_Described):
    """A trim at one mu (C++ flaplag::trim, the command line's ``flaplag trim``): the controls
    theta0, theta1c, theta1s [rad] and the inflow lambda (eq 2.25) at which the model's own
    thrust coefficient C_T (not C_T / sigma) equals ``target``, and (kind 'moment') the first
    flap tip harmonic flap_1c, flap_1s vanishes.  parameters: the rotor parameters with the
    trimmed pitch (Analysis(**parameters) analyses the trimmed rotor at the eq 2.24 inflow; the
    command line's trimmed studies use ``inflow``).  equilibrium: with the periodic
    linearization, the periodic equilibrium trimmed about ({'harmonics': K, 'truncation': ...});
    None otherwise.  status 'warning' when not converged in max_iterations or the trimmed rotor
    is unstable; 'failed' without a periodic response or when the residual cannot be reduced.
    """

    parameters: Dict[str, object] = field(default_factory=dict)

    def __repr__(self):
        return (
            f"TrimResult(mu={_g(self.mu)}, {self.kind}, theta0={_g(self.theta0)}, "
            f"theta1c={_g(self.theta1c)}, theta1s={_g(self.theta1s)}, "
            f"inflow={_g(self.inflow)}, C_T={_g(self.thrust_coefficient)}, "
            f"{_status(self.status, self.message)})"
        )


@dataclass(frozen=True, repr=False)
@_table("ThrustResult")
class ThrustResult(_Described):
    """The model's own thrust at one mu (C++ rotor_thrust): thrust_coefficient C_T (not
    C_T / sigma) with the inflow lambda used, and the first flap tip harmonic flap_1c,
    flap_1s (by l).  status 'failed' without a periodic response."""

    def __repr__(self):
        return (
            f"ThrustResult(mu={_g(self.mu)}, inflow={_g(self.inflow)}, "
            f"C_T={_g(self.thrust_coefficient)}, {_status(self.status, self.message)})"
        )


@dataclass(frozen=True)
class ModelInfo(_Described):
    """An ordering model: name (e.g. 'paper-2x2'), base (its family: one per ordering spec,
    'paper'), flap_modes M, lag_modes N (any 1..12 per family), harmonics, spec_file and a
    one-line summary."""

    name: str
    base: str
    flap_modes: int
    lag_modes: int
    harmonics: int
    spec_file: str
    summary: str


def _worst(statuses):
    order = {"ok": 0, "warning": 1, "failed": 2}
    return max(statuses, key=lambda s: order.get(s, 0), default="ok")


@dataclass(frozen=True, repr=False, eq=False)
class StudyResult(_Described):
    """mu_c (and every instability interval) versus one rotor parameter.

    parameter: the field varied; values: its values (1-D array); rows: a CriticalResult per
    value (searched with all_intervals=True).  Columns as arrays, one entry per value: mu_c
    (nan where there is none), mu_c_error, basis_error (exact modes: the basis's part of
    mu_c_error), omega [per rev] (nan without mu_c), mode and kind
    ('' without mu_c), hover_unstable, row_status; for a trimmed study (trim='thrust' or
    'moment') also the controls at mu_c: theta0, theta1c, theta1s [rad] and inflow (lambda,
    eq 2.25), nan without mu_c (rows[i].trim: the whole TrimResult).  A value the analysis
    refuses (e.g. an exact-mode frequency the basis cannot reach) is a row with status
    'failed' and the reason as message.  status / message: the worst row and the first problem
    met.  metadata: the flaplag version and commit, the base parameters, the transition
    options and the trim (None, or its kind, thrust_coefficient and shaft_angle).
    """

    parameter: str
    values: np.ndarray
    rows: Tuple[CriticalResult, ...]
    status: str
    message: str
    metadata: dict

    def _column(self, name, missing=math.nan):
        return np.array([missing if getattr(r, name) is None else getattr(r, name) for r in self.rows])

    @property
    def mu_c(self) -> np.ndarray:
        return self._column("mu_c")

    @property
    def mu_c_error(self) -> np.ndarray:
        return self._column("mu_c_error")

    @property
    def basis_error(self) -> np.ndarray:
        """Exact modes: the part of mu_c_error that is the Galerkin basis's (nan where not
        estimated, and for the assumed mode)."""
        return self._column("basis_error")

    @property
    def omega(self) -> np.ndarray:
        return self._column("omega")

    @property
    def mode(self) -> np.ndarray:
        return np.array([r.mode or "" for r in self.rows], dtype=object)

    def _trim_column(self, name):
        return np.array([math.nan if r.trim is None else getattr(r.trim, name) for r in self.rows])

    @property
    def theta0(self) -> np.ndarray:
        """The trimmed collective pitch at mu_c [rad] (nan: no mu_c, or not trimmed)."""
        return self._trim_column("theta0")

    @property
    def theta1c(self) -> np.ndarray:
        """The trimmed cyclic pitch (cos psi part) at mu_c [rad]."""
        return self._trim_column("theta1c")

    @property
    def theta1s(self) -> np.ndarray:
        """The trimmed cyclic pitch (sin psi part) at mu_c [rad]."""
        return self._trim_column("theta1s")

    @property
    def inflow(self) -> np.ndarray:
        """The inflow lambda of eq 2.25 at mu_c of the trimmed rotor."""
        return self._trim_column("inflow")

    @property
    def kind(self) -> np.ndarray:
        return np.array([r.kind or "" for r in self.rows], dtype=object)

    @property
    def hover_unstable(self) -> np.ndarray:
        return np.array([r.hover_unstable for r in self.rows], dtype=bool)

    @property
    def row_status(self) -> np.ndarray:
        return np.array([r.status for r in self.rows], dtype=object)

    @property
    def damping_crossings(self) -> Tuple[Tuple[DampingCrossing, ...], ...]:
        """Per row, one DampingCrossing per mode (study(damping_criterion=...); () without)."""
        return tuple(
            tuple(DampingCrossing._from(x) for x in r.__dict__.get("_extra", {}).get(
                "damping_crossings", ()))
            for r in self.rows
        )

    def first_below(self, label) -> np.ndarray:
        """Per row, the first mu where mode ``label``'s damping ratio falls below the damping
        criterion (nan where there is none: not crossed, unresolved without a point above, or
        no criterion)."""
        out = []
        for row in self.damping_crossings:
            c = next((c for c in row if _same_mode(c.mode, label)), None)
            out.append(math.nan if c is None or c.mu is None else c.mu)
        return np.array(out)

    def __len__(self):
        return len(self.rows)

    def __repr__(self):
        found = int(np.sum(~np.isnan(self.mu_c)))
        return (
            f"StudyResult({self.parameter} = {_g(self.values[0])}..{_g(self.values[-1])}, "
            f"{len(self.rows)} values, mu_c found for {found}, "
            f"{_status(self.status, self.message)})"
        )

    @classmethod
    def _concatenate(cls, parameter, parts, metadata):
        """The result of one study from studies of consecutive slices of its values."""
        rows = tuple(CriticalResult._from(r) for d in parts for r in d["rows"])
        values = np.concatenate([np.asarray(d["values"]) for d in parts])
        status = _worst([d["status"] for d in parts])
        message = next((d["message"] for d in parts if d["status"] != "ok"), "")
        return cls(parameter, values, rows, status, message, metadata)


@dataclass(frozen=True, repr=False, eq=False)
class MapResult(_Described):
    """A stability map: the largest damping exponent over a grid of two parameters.

    x, y: the axis names ('mu' or a rotor parameter; at most one of them 'mu'); x_values,
    y_values: 1-D arrays.  Cell [i, j] is y = y_values[i], x = x_values[j] (rows along y, so
    ``plt.pcolormesh(x_values, y_values, max_zeta)`` draws it): max_zeta [per rev] (nan where
    unknown, i.e. status 'failed'), omega of that exponent [per rev], mode (its label) and kind
    ('flutter' / 'periodic'; '' where unknown), cell_status and cell_message.  status /
    message: the worst cell and the first problem met (row by row).  metadata: the flaplag
    version and commit, the base parameters, the transition options, mu, scan_step and
    the trim (None, or its kind, thrust_coefficient and shaft_angle).
    """

    x: str
    x_values: np.ndarray
    y: str
    y_values: np.ndarray
    max_zeta: np.ndarray
    omega: np.ndarray
    mode: np.ndarray
    kind: np.ndarray
    cell_status: np.ndarray
    cell_message: np.ndarray
    status: str
    message: str
    metadata: dict

    @property
    def stable(self) -> np.ndarray:
        """max_zeta <= 0 (False where unknown)."""
        with np.errstate(invalid="ignore"):
            return self.max_zeta <= 0.0

    @property
    def shape(self):
        return self.max_zeta.shape

    def __eq__(self, other):
        """Equal, bit for bit, in every array (nan equal to nan) and in status and message."""
        if not isinstance(other, MapResult):
            return NotImplemented
        same = lambda a, b: a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()
        return (
            (self.x, self.y, self.status, self.message) == (other.x, other.y, other.status, other.message)
            and all(
                same(getattr(self, n), getattr(other, n))
                for n in ("x_values", "y_values", "max_zeta", "omega")
            )
            and all(
                np.array_equal(getattr(self, n), getattr(other, n))
                for n in ("mode", "kind", "cell_status", "cell_message")
            )
        )

    __hash__ = None

    def __repr__(self):
        ny, nx = self.max_zeta.shape
        known = ~np.isnan(self.max_zeta)
        unstable = int(np.sum(self.max_zeta[known] > 0.0))
        return (
            f"MapResult({self.y} ({ny}) x {self.x} ({nx}), {unstable} of {ny * nx} cells unstable"
            + (f", {int(np.sum(~known))} unknown" if not known.all() else "")
            + f", {_status(self.status, self.message)})"
        )

    @classmethod
    def _assemble(cls, x, y, parts, axis, metadata):
        """One map from maps of consecutive slices of its lines (axis 0: slices of y, 1: of x).

        Cell values come straight from the parts; status and message are recomputed over the
        cells row by row, the rule of the C++ run_map, so that any split gives the same result.
        """
        cat = lambda key, dtype=None: np.concatenate(
            [np.asarray(d[key], dtype=dtype) for d in parts], axis=axis
        )
        if axis == 0:
            x_values = np.asarray(parts[0]["x_values"])
            y_values = np.concatenate([np.asarray(d["y_values"]) for d in parts])
        else:
            x_values = np.concatenate([np.asarray(d["x_values"]) for d in parts])
            y_values = np.asarray(parts[0]["y_values"])
        computed = cat("computed", bool)
        if not computed.all():
            raise RuntimeError("flaplag.map: a part of the map was not computed (cancelled)")
        cell_status = cat("status", object)
        cell_message = cat("message", object)
        status, message = "ok", ""
        for s, m in zip(cell_status.ravel(), cell_message.ravel()):
            status = _worst([status, s])
            if not message and s != "ok":
                message = m
        return cls(
            x,
            x_values,
            y,
            y_values,
            cat("max_zeta"),
            cat("omega"),
            cat("mode", object),
            cat("kind", object),
            cell_status,
            cell_message,
            status,
            message,
            metadata,
        )


for _cls in (Exponent, HoverResult, PointResult, SweepResult, Interval, CriticalResult,
             SystemResult, ModeShapes, FloquetSample, ModelInfo, StudyResult, MapResult):
    _cls.__module__ = "flaplag"  # shown (and pickled) as flaplag.<class>
del _cls
