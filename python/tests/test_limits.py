"""The edges of the Python API: the memory limit (memory_limit=, refused before anything is
allocated with the library's message), sweep's progress and Ctrl-C, and keywords that used to
be ignored or to fail with Python's own errors (scan_step, chunk_lines, client)."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import flaplag


def _refused(excinfo, field, *words):
    e = excinfo.value
    assert isinstance(e, ValueError)
    assert e.field == field, str(e)
    for w in words:
        assert w in str(e), str(e)


def test_a_huge_map_is_refused_before_it_allocates():
    start = time.monotonic()
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.map(x=("mu", np.linspace(0, 1, 10000)), y=("theta", np.linspace(0.1, 0.3, 10000)))
    _refused(ei, "y", "a map of 10000 x 10000 cells", "would need about", "memory_limit")
    assert time.monotonic() - start < 10


def test_a_long_simulation_is_refused_before_it_runs():
    an = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.simulate(0.3, revolutions=100000, samples_per_rev=10000)
    _refused(ei, "revolutions", "1000000001 samples", "memory_limit")


def test_memory_limit_raises_the_limit():
    an = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.simulate(0.3, revolutions=2000, memory_limit="4M")
    _refused(ei, "revolutions", "72001 samples", "4 MiB")
    s = an.simulate(0.3, revolutions=2000, memory_limit="512M")
    assert len(s.psi) == 72001
    assert len(an.simulate(0.3, revolutions=2, memory_limit=2**30).psi) == 73


@pytest.mark.parametrize("bad", ["abc", 0, True, "2X", -1.0, float("nan"), [1]])
def test_bad_memory_limits_are_named(bad):
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.Analysis().response(0.3, memory_limit=bad)
    assert ei.value.field == "memory_limit"


def test_every_sized_call_is_checked():
    an = flaplag.Analysis()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.response(0.3, samples=100000, memory_limit="1M")
    _refused(ei, "samples", "100000 samples")
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.sweep(0.0, 10.0, 0.0001, memory_limit="16M")
    _refused(ei, "step", "a sweep of 100001 points")
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.study("omega_lag", np.linspace(0.5, 2, 20000), memory_limit="16M")
    _refused(ei, "values", "a study of 20000 values")
    # With a client the whole result comes back here: checked before anything is sent.
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.study("omega_lag", np.linspace(0.5, 2, 20000), memory_limit="16M",
                      client=_Executor())
    _refused(ei, "values", "a study of 20000 values")


def test_modes_of_a_huge_station_count_is_refused_at_once():
    an = flaplag.Analysis()
    start = time.monotonic()
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.modes(10**8)
    _refused(ei, "x", "100000000 stations", "memory_limit")
    assert time.monotonic() - start < 2
    shapes = an.modes(10**6)
    assert shapes.flap.shape == (1, 10**6) and shapes.x[-1] == 1.0
    assert np.array_equal(an.modes(11).x, np.linspace(0, 1, 11))


def test_modes_releases_the_gil():
    # Another Python thread runs while a large modes() call samples the shapes.
    an = flaplag.Analysis(modes="exact", flap_modes=2, lag_modes=2)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    time.sleep(0.01)
    start = time.monotonic()
    an.modes(4 * 10**6, memory_limit="4G")
    end = time.monotonic()
    stop.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    assert end - start < 0.05 or len(during) > 2, (end - start, len(during))


def test_too_many_advance_ratios_are_blamed_on_the_array():
    an = flaplag.Analysis()
    mus = np.linspace(0.0, 1.0, 2_000_000)
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.sweep(mus)
    assert ei.value.field == "mu", str(ei.value)
    assert "2000000" in str(ei.value)
    assert "0.01" not in ei.value.value


def test_sweep_reports_progress():
    an = flaplag.Analysis()
    calls = []
    r = an.sweep(0.0, 0.2, 0.05, progress=lambda d, n: calls.append((d, n)), threads=1)
    assert len(r.mu) == 5
    assert np.array_equal(r.max_zeta, an.sweep(0.0, 0.2, 0.05, threads=1).max_zeta)
    assert calls and calls[-1][0] == calls[-1][1]
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)
    calls.clear()
    an.sweep([0.1, 0.3], progress=lambda d, n: calls.append((d, n)))
    assert calls[-1] == (30, 30)  # 10 steps to 0.1, 20 more to 0.3
    with pytest.raises(flaplag.InvalidInput):
        an.sweep(0.0, 0.2, 0.05, progress=3)


def test_a_progress_callback_that_raises_stops_the_sweep():
    an = flaplag.Analysis()

    def stop(done, total):
        raise RuntimeError("enough")

    start = time.monotonic()
    with pytest.raises(RuntimeError, match="enough"):
        an.sweep(0.0, 1.5, 0.00005, progress=stop, threads=1)
    assert time.monotonic() - start < 3


def test_ctrl_c_interrupts_a_sweep():
    # 3001 points of a 3 x 3 model on one thread: about ten seconds, far longer than the wait
    # before Ctrl-C (a sweep that ignored it would raise KeyboardInterrupt only at its end).
    an = flaplag.Analysis(modes="exact", flap_modes=3, lag_modes=3)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            an.sweep(0.0, 1.5, 0.0005, threads=1)
    finally:
        timer.cancel()
    assert time.monotonic() - start < 2.5


def test_scan_step_is_checked_in_both_forms():
    an = flaplag.Analysis()
    for bad in (-1.0, 0.0, float("nan"), float("inf")):
        with pytest.raises(flaplag.InvalidInput) as ei:
            an.sweep(0.0, 0.2, 0.1, scan_step=bad)
        assert ei.value.field == "scan_step"
        with pytest.raises(flaplag.InvalidInput) as ei:
            an.sweep([0.1, 0.2], scan_step=bad)
        assert ei.value.field == "scan_step"
    # A grid continues in steps of `step`: a scan_step there would be ignored.
    with pytest.raises(flaplag.InvalidInput) as ei:
        an.sweep(0.0, 0.2, 0.1, scan_step=0.05)
    assert ei.value.field == "scan_step"


class _Executor:
    """A minimal executor: submit() runs at once."""

    def submit(self, fn, *args):
        class _Done:
            def __init__(self, value):
                self._value = value

            def result(self):
                return self._value

        return _Done(fn(*args))


def test_chunk_lines_is_checked_without_a_client():
    for bad in (0, -3, 1.5, "2"):
        with pytest.raises(flaplag.InvalidInput) as ei:
            flaplag.map(x=("mu", [0.1]), y=("theta", [0.1]), chunk_lines=bad)
        assert ei.value.field == "chunk_lines"
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.study("omega_lag", [1.0], chunk_lines=2)
    assert ei.value.field == "chunk_lines"
    assert "client" in ei.value.reason


@pytest.mark.parametrize("client", [object(), "localhost:8786", 42])
def test_a_client_without_submit_is_named(client):
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.study("omega_lag", [1.0], client=client)
    assert ei.value.field == "client"
    assert isinstance(ei.value, ValueError)
    with pytest.raises(flaplag.InvalidInput) as ei:
        flaplag.map(x=("mu", [0.1]), y=("theta", [0.1]), client=client)
    assert ei.value.field == "client"


def test_a_trimmed_sweep_reports_progress_too():
    an = flaplag.Analysis()
    calls = []
    r = an.sweep(0.0, 0.2, 0.1, trim="thrust", progress=lambda d, n: calls.append((d, n)))
    assert len(r.mu) == 3
    assert calls[-1] == (3, 3)
    # The same numbers as without progress.
    plain = an.sweep(0.0, 0.2, 0.1, trim="thrust")
    assert np.array_equal(r.max_zeta, plain.max_zeta)
