"""flaplag: coupled flap-lag aeroelastic stability of hingeless helicopter blades in forward
flight (Friedmann & Silverthorn, NASA CR-132431, 1974), by Floquet analysis.

    >>> import flaplag
    >>> an = flaplag.Analysis()                  # the paper's typical case
    >>> an.critical()                            # mu_c, mode, omega, kind
    >>> an.sweep(numpy.linspace(0, 1.2, 61)).zeta["lag"]
    >>> flaplag.study("omega_lag", numpy.linspace(0.5, 2, 16))
    >>> flaplag.map(x=("mu", numpy.linspace(0, 1, 51)), y=("theta", [0.1, 0.15, 0.2]))

Analysis takes the C++ field names as keyword arguments (help(flaplag.Analysis) lists them with
units and ranges).  Results are small classes with numpy arrays, a status ('ok', 'warning',
'failed') and a message; invalid input raises flaplag.InvalidInput (a ValueError) with the
library's message '<field> = <value>: <reason>'.  flaplag.map and flaplag.study run on all
cores, or with client=<dask.distributed.Client> on a Dask cluster.  flaplag.report and
flaplag.merge make the HTML report of a result file and merge the --shard parts of a map or
study, as the command line's report and merge do.
"""

from . import _flaplag
from ._analysis import PARAMETERS, TRANSITION, Analysis, InvalidInput, UnknownParameter
from ._documents import merge, report
from ._parallel import map, study, study_parameters
from ._results import (
    CampbellCrossing,
    CampbellFrequency,
    CampbellPoint,
    CampbellResult,
    CriticalResult,
    Exponent,
    FloquetSample,
    HoverResult,
    Interval,
    MapResult,
    ModelInfo,
    ModeShapes,
    PeriodicEquilibriumResult,
    PointResult,
    ResponseResult,
    SimulationResult,
    StudyResult,
    SweepResult,
    DampingCrossing,
    SystemResult,
    ThrustResult,
    TipMotion,
    TrimResult,
)

__version__ = _flaplag.version
git_commit = _flaplag.git_commit  # the commit the library was configured from ("" if unknown)
max_advance_ratio = _flaplag.max_advance_ratio


def momentum_inflow(thrust_coefficient, mu, shaft_angle=0.0):
    """The inflow ratio lambda of eq 2.25 for the thrust coefficient C_T (not C_T/sigma) at
    advance ratio mu and shaft angle alpha_R [rad]: sqrt(C_T/2) in hover; the inflow of
    Analysis.point(..., inflow='momentum') at that mu (C++ flaplag::momentum_inflow)."""
    from ._analysis import _real

    return _flaplag.momentum_inflow(
        _real("thrust_coefficient", thrust_coefficient), _real("mu", mu),
        _real("shaft_angle", shaft_angle)
    )


def models():
    """The compiled ordering models, one per spec at the spec's mode counts (the command
    line's ``flaplag models``); each also exists as '<name>-<M>x<N>' for any 1 <= M, N <= 12
    exact modes (Analysis(model=..., modes='exact', flap_modes=M, lag_modes=N))."""
    return [ModelInfo._from(m) for m in _flaplag.models()]


def parameter_table():
    """The rotor parameters: one dict per field with symbol, units, type, default, the
    admissible values (requirement, range) and a description (the library's table)."""
    return [dict(r) for r in PARAMETERS]


__all__ = [
    "Analysis",
    "InvalidInput",
    "UnknownParameter",
    "study",
    "map",
    "study_parameters",
    "report",
    "merge",
    "models",
    "parameter_table",
    "CampbellCrossing",
    "CampbellFrequency",
    "CampbellPoint",
    "CampbellResult",
    "CriticalResult",
    "Exponent",
    "FloquetSample",
    "HoverResult",
    "Interval",
    "MapResult",
    "ModelInfo",
    "ModeShapes",
    "PointResult",
    "ResponseResult",
    "SimulationResult",
    "StudyResult",
    "SweepResult",
    "DampingCrossing",
    "SystemResult",
    "PeriodicEquilibriumResult",
    "TrimResult",
    "ThrustResult",
    "TipMotion",
    "__version__",
    "git_commit",
]
