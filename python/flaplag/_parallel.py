"""flaplag.study and flaplag.map: parametric studies and stability maps, on the threads of this
machine or, with ``client=``, on the workers of a Dask cluster.

Every line of a map (one continuation in mu per value of the other parameter; without a mu axis,
one row) and every value of a study is independent and its result depends only on its own
inputs.  So a run split into chunks of lines, each chunk a C++ run_map / run_study of its own on
some worker, gives exactly the arrays of one local run, bit for bit, for any chunking and any
number of threads or workers.
"""

import math

import numpy as np

from . import _flaplag
from ._analysis import (
    CRITICAL_DEFAULTS,
    InvalidInput,
    _flag,
    _int,
    _invalid,
    _memory_limit,
    _progress,
    _real,
    _real_array,
    _text,
    _inflow_request,
    split_parameters,
)
from ._results import MapResult, StudyResult

# The scalar options of a study and a map: their tables' defaults (StudyOptions, MapOptions).
STUDY_DEFAULTS = dict(_flaplag.option_defaults("study"))
MAP_DEFAULTS = dict(_flaplag.option_defaults("map"))


def _metadata(kwargs, rotor, transition, **extra):
    return {
        "flaplag_version": _flaplag.version,
        "git_commit": _flaplag.git_commit,
        "parameters": dict(kwargs),
        "rotor": rotor,
        "transition": transition,
        **extra,
    }


def _base(kwargs, axes):
    for name in axes:
        if name in kwargs:
            raise _invalid(
                InvalidInput, name, kwargs[name], "is an axis of the study or map as well"
            )
    rotor, transition, flap_modes, lag_modes = split_parameters(kwargs)
    # What every worker will check, checked here once so that bad input raises before any
    # work is sent anywhere.
    _flaplag.check(rotor, transition, flap_modes, lag_modes)
    return rotor, transition, flap_modes, lag_modes


def _trim_metadata(t):
    """The trim of a study or map for its metadata: None, or its kind, C_T and alpha_R."""
    if t is None:
        return None
    return {"kind": t[0], "thrust_coefficient": t[1], "shaft_angle": t[2]}


def _condition(trim, thrust_coefficient, shaft_angle, inflow):
    """What the native study and map take as their condition: the trim request (None: fixed
    controls) or, with inflow='momentum', the InflowModel dict; and the metadata that says it."""
    t, model = _inflow_request(inflow, trim, thrust_coefficient, shaft_angle)
    metadata = {"trim": _trim_metadata(t)}
    if model is not None:
        metadata["inflow"] = dict(model)
    return (t if model is None else model), metadata


def _distribution(client, chunk_lines):
    """Checks client= and chunk_lines= before any work: a client must have submit(), and
    chunk_lines (an integer >= 1) applies only with a client."""
    if client is not None and not callable(getattr(client, "submit", None)):
        raise _invalid(
            InvalidInput,
            "client",
            client,
            "must be a dask.distributed.Client or an executor with submit() "
            "(concurrent.futures), or None for this machine's threads",
        )
    if chunk_lines is not None:
        lines = _int("chunk_lines", chunk_lines)
        if lines < 1:
            raise _invalid(InvalidInput, "chunk_lines", chunk_lines, "must be >= 1")
        if client is None:
            raise _invalid(
                InvalidInput,
                "chunk_lines",
                chunk_lines,
                "applies only with client= (without a client the run is not split into chunks)",
            )


def _chunks(n, client, chunk_lines):
    """Slices of range(n): chunk_lines long, or about four per worker of the client."""
    if chunk_lines is None:
        workers = 0
        info = getattr(client, "scheduler_info", None)
        if callable(info):
            try:
                workers = len(info().get("workers", {}))
            except Exception:  # not a Dask client after all
                workers = 0
        chunk_lines = max(1, math.ceil(n / (4 * max(workers, 2))))
    chunk_lines = _int("chunk_lines", chunk_lines)
    if chunk_lines < 1:
        raise _invalid(InvalidInput, "chunk_lines", chunk_lines, "must be >= 1")
    return [slice(i, min(i + chunk_lines, n)) for i in range(0, n, chunk_lines)]


def _gather(client, fn, jobs, progress, total):
    """Runs fn(*job) for every job on the client (Dask Client or any executor with submit())
    and returns the results in job order."""
    futures = [client.submit(fn, *job) for job in jobs]
    out, done = [], 0
    for fut, job in zip(futures, jobs):
        out.append(fut.result())
        done += job[-1]
        if progress is not None:
            progress(done, total)
    return out


# -- study ---------------------------------------------------------------------------------------


def _study_chunk(
    rotor, transition, flap_modes, lag_modes, parameter, values, critical, trim, threads,
    memory_limit, n
):
    """One slice of a study (runs on a worker; n = len(values), for progress)."""
    return _flaplag.study(
        rotor, transition, flap_modes, lag_modes, parameter, values, critical, threads, None, trim,
        memory_limit
    )


def study(
    parameter,
    values,
    *,
    mu_max=CRITICAL_DEFAULTS["mu_max"],
    scan_step=CRITICAL_DEFAULTS["scan_step"],
    tolerance=CRITICAL_DEFAULTS["tolerance"],
    zeta_threshold=CRITICAL_DEFAULTS["zeta_threshold"],
    periodic_omega_tolerance=CRITICAL_DEFAULTS["periodic_omega_tolerance"],
    scan_zeta_tolerance=CRITICAL_DEFAULTS["scan_zeta_tolerance"],
    trim=None,
    thrust_coefficient=None,
    shaft_angle=None,
    inflow=None,
    threads=STUDY_DEFAULTS["threads"],
    progress=None,
    client=None,
    chunk_lines=None,
    memory_limit=None,
    damping_criterion=STUDY_DEFAULTS["damping_criterion"],
    **parameters,
) -> StudyResult:
    """mu_c and every instability interval versus one rotor parameter.

    parameter: a real field of the parameter table ('omega_lag', 'theta', 'damping_lag', ...;
    flaplag.study_parameters() lists them); values: its values (1-D, any order).  The other
    keyword arguments of Analysis (**parameters) set the rest of the blade.  At each value the
    critical search of Analysis.critical runs with all_intervals=True up to mu_max (the
    search options have the same meaning and defaults).

    trim='thrust' or 'moment' (the command line's study --trim; any model),
    thrust_coefficient (C_T, not C_T / sigma), shaft_angle (alpha_R
    [rad]): mu_c at fixed C_T, each row's rotor trimmed at every mu its search evaluates (as
    Analysis.critical(trim=...)).  Each row's ``trim`` is then the TrimResult at its mu_c, and
    the result's theta0, theta1c, theta1s, inflow are those controls as arrays (nan without
    mu_c).
    inflow='momentum': fixed controls at the inflow of eq 2.25 for C_T = thrust_coefficient
    at every mu (as Analysis.critical(inflow=...); the command line's study --inflow).

    threads: worker threads (0: all cores; the result does not depend on it).
    progress: called as progress(values_done, values_total) from the calling thread.
    client: a dask.distributed.Client (or any executor with submit()): the values are split
    into chunks of chunk_lines (default: about four chunks per worker) and run on its workers
    (each chunk with ``threads`` threads; 0 means 1 with a client), giving exactly the local
    result.  Ctrl-C cancels a local run (KeyboardInterrupt).
    memory_limit: the memory the result may take (bytes, or a size such as '8G'; default
    2 GiB): a study estimated to need more is refused before it starts.
    damping_criterion: a damping ratio asked of every mode, a fraction of critical (0.01 is
    1 %), 0 <= C < 1 (the command line's study --damping-criterion): each row also sweeps mu =
    0, scan_step, ..., mu_max (about twice the cost) and ``damping_crossings`` gives, per row,
    the first mu where each mode's damping ratio falls below it (Analysis.sweep's
    DampingCrossing).
    """
    _distribution(client, chunk_lines)
    progress = _progress(progress)
    limit = _memory_limit(memory_limit)
    # The type first: the name is looked up among the keywords next.
    parameter = _text("parameter", parameter)
    rotor, transition, flap_modes, lag_modes = _base(parameters, [parameter])
    vals = _real_array("values", values)
    critical = {
        "mu_max": _real("mu_max", mu_max),
        "scan_step": _real("scan_step", scan_step),
        "tolerance": _real("tolerance", tolerance),
        "zeta_threshold": _real("zeta_threshold", zeta_threshold),
        "periodic_omega_tolerance": _real("periodic_omega_tolerance", periodic_omega_tolerance),
        "scan_zeta_tolerance": _real("scan_zeta_tolerance", scan_zeta_tolerance),
        "all_intervals": True,
    }
    if damping_criterion is not None:
        critical["damping_criterion"] = _real("damping_criterion", damping_criterion)
    threads = _int("threads", threads)
    t, condition = _condition(trim, thrust_coefficient, shaft_angle, inflow)
    metadata = _metadata(parameters, rotor, transition, critical=critical, **condition)
    if client is None:
        raw = _flaplag.study(
            rotor, transition, flap_modes, lag_modes, parameter, vals, critical, threads,
            progress, t, limit
        )
        return StudyResult._from(raw, parameter=parameter, metadata=metadata)
    # Check the whole study here (a worker sees only its slice).
    _flaplag.check_study(
        rotor, transition, flap_modes, lag_modes, parameter, vals, critical, threads, t, limit
    )
    threads = threads or 1
    jobs = [
        (rotor, transition, flap_modes, lag_modes, parameter, vals[s], critical, t, threads,
         limit, len(vals[s]))
        for s in _chunks(len(vals), client, chunk_lines)
    ]
    parts = _gather(client, _study_chunk, jobs, progress, len(vals))
    return StudyResult._concatenate(parameter, parts, metadata)


# -- map -----------------------------------------------------------------------------------------


def _axis(name, axis):
    try:
        parameter, values = axis
    except (TypeError, ValueError):
        raise _invalid(
            InvalidInput, name, axis, "must be a pair (parameter name, values)"
        ) from None
    return _text(name, parameter), _real_array(name, values)


def _map_chunk(
    rotor, transition, flap_modes, lag_modes, x, xv, y, yv, mu, scan_step, trim, threads,
    memory_limit, n
):
    """One slice of a map (runs on a worker; n = the number of lines, for progress)."""
    return _flaplag.map(
        rotor, transition, flap_modes, lag_modes, x, xv, y, yv, mu, scan_step, threads, None, trim,
        memory_limit
    )


def map(
    x,
    y,
    *,
    mu=MAP_DEFAULTS["mu"],
    scan_step=MAP_DEFAULTS["scan_step"],
    trim=None,
    thrust_coefficient=None,
    shaft_angle=None,
    inflow=None,
    threads=MAP_DEFAULTS["threads"],
    progress=None,
    client=None,
    chunk_lines=None,
    memory_limit=None,
    **parameters,
) -> MapResult:
    """A stability map: the largest damping exponent zeta [per rev] over a grid.

    x, y: (name, values) pairs, name 'mu' or a real rotor parameter (flaplag.study_parameters();
    at most one axis 'mu', whose values must increase).  Cell [i, j] of the result is
    y = y_values[i], x = x_values[j].  With a mu axis each line along mu is one continuation
    from hover in steps of at most scan_step; without one, every cell is Analysis.point(mu) at
    the given mu.  The other keyword arguments of Analysis (**parameters) set the rest of the
    blade.

    trim, thrust_coefficient, shaft_angle: every cell trimmed at its mu to C_T (the command
    line's map --trim), as study().  inflow='momentum': every cell at fixed controls with the
    inflow of eq 2.25 for C_T = thrust_coefficient at its mu, as study().

    threads: worker threads (0: all cores; the result does not depend on it).
    progress: called as progress(lines_done, lines_total) from the calling thread.
    client: a dask.distributed.Client (or any executor with submit()): the grid is split into
    chunks of chunk_lines lines (rows; columns when y is 'mu', so that no continuation is cut;
    default: about four chunks per worker), run on its workers with ``threads`` threads each
    (0 means 1 with a client), and assembled into exactly the array a local run returns.
    Ctrl-C cancels a local run (KeyboardInterrupt).
    memory_limit: the memory the result may take (bytes, or a size such as '8G'; default
    2 GiB; about two million cells fit in it): a larger map is refused before it starts.
    """
    _distribution(client, chunk_lines)
    progress = _progress(progress)
    limit = _memory_limit(memory_limit)
    xname, xv = _axis("x", x)
    yname, yv = _axis("y", y)
    rotor, transition, flap_modes, lag_modes = _base(parameters, [xname, yname])
    mu = _real("mu", mu)
    scan_step = _real("scan_step", scan_step)
    threads = _int("threads", threads)
    t, condition = _condition(trim, thrust_coefficient, shaft_angle, inflow)
    metadata = _metadata(parameters, rotor, transition, mu=mu, scan_step=scan_step, **condition)
    common = (rotor, transition, flap_modes, lag_modes)
    if client is None:
        raw = _flaplag.map(
            *common, xname, xv, yname, yv, mu, scan_step, threads, progress, t, limit
        )
        return MapResult._assemble(xname, yname, [raw], 0, metadata)
    # The lines: along mu, one per value of the other axis; without mu, the rows.
    axis = 1 if yname == "mu" else 0
    lines = xv if axis == 1 else yv
    # Check the whole map here (a worker sees only its slice).
    _flaplag.check_map(*common, xname, xv, yname, yv, mu, scan_step, threads, t, limit)
    threads = threads or 1
    jobs = []
    for s in _chunks(len(lines), client, chunk_lines):
        cx, cy = (xv[s], yv) if axis == 1 else (xv, yv[s])
        jobs.append(
            (*common, xname, cx, yname, cy, mu, scan_step, t, threads, limit, len(lines[s]))
        )
    parts = _gather(client, _map_chunk, jobs, progress, len(lines))
    return MapResult._assemble(xname, yname, parts, axis, metadata)


def study_parameters():
    """The rotor parameters a study or a map can vary (besides 'mu' for a map axis)."""
    return list(_flaplag.study_parameters())
