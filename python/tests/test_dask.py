"""flaplag.map and flaplag.study on a Dask cluster give exactly the local arrays.

A LocalCluster of two worker processes (one thread each) stands in for a real cluster: the
workers import flaplag themselves (PYTHONPATH is inherited), receive chunks of lines and send
back arrays, so everything a remote worker does happens here too.
"""

import numpy as np
import pytest

import flaplag

# tornado (under distributed) on Python 3.11
pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")

distributed = pytest.importorskip(
    "distributed", reason="dask.distributed is not importable (Debian: python3-distributed)")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                       dashboard_address=None)
    c = distributed.Client(cluster)
    try:
        yield c
    finally:
        c.close()
        cluster.close()


def test_map_on_the_cluster_equals_the_local_map(client):
    axes = dict(x=("mu", np.linspace(0.0, 1.4, 29)), y=("omega_lag", np.linspace(0.5, 2.0, 7)))
    local = flaplag.map(**axes, theta=0.2)
    done = []
    remote = flaplag.map(**axes, theta=0.2, client=client, chunk_lines=2,
                         progress=lambda d, n: done.append((d, n)))
    assert remote.max_zeta.tobytes() == local.max_zeta.tobytes()
    assert remote.omega.tobytes() == local.omega.tobytes()
    assert remote.mode.tolist() == local.mode.tolist()
    assert remote.kind.tolist() == local.kind.tolist()
    assert remote.cell_status.tolist() == local.cell_status.tolist()
    assert remote == local
    assert done[-1] == (7, 7) and len(done) == 4
    # both workers took part
    assert len(client.scheduler_info()["workers"]) == 2


def test_map_with_mu_on_y_is_split_by_columns(client):
    axes = dict(x=("theta", [0.05, 0.1, 0.15, 0.2, 0.25]), y=("mu", np.linspace(0.0, 1.0, 11)))
    local = flaplag.map(**axes)
    remote = flaplag.map(**axes, client=client)  # default chunking
    assert remote == local and remote.max_zeta.shape == (11, 5)


def test_study_on_the_cluster(client):
    values = np.linspace(0.4, 2.0, 9)
    local = flaplag.study("omega_lag", values, mu_max=1.5)
    remote = flaplag.study("omega_lag", values, mu_max=1.5, client=client, chunk_lines=3)
    assert remote.mu_c.tobytes() == local.mu_c.tobytes()
    assert remote.kind.tolist() == local.kind.tolist()
    assert [r.intervals for r in remote.rows] == [r.intervals for r in local.rows]


def test_trimmed_map_and_study_on_the_cluster(client):
    """At fixed C_T (trim=): the workers trim as a local run does."""
    kw = dict(trim="thrust", thrust_coefficient=0.0042384)
    axes = dict(x=("mu", [0.0, 0.2, 0.4, 0.6]), y=("omega_lag", [0.5, 1.0, 1.5]))
    local = flaplag.map(**axes, scan_step=0.2, **kw)
    remote = flaplag.map(**axes, scan_step=0.2, **kw, client=client, chunk_lines=1)
    assert remote == local
    values = [0.5, 0.55]
    local = flaplag.study("omega_lag", values, mu_max=1.1, scan_step=0.1, **kw)
    remote = flaplag.study("omega_lag", values, mu_max=1.1, scan_step=0.1, **kw, client=client,
                           chunk_lines=1)
    assert remote.mu_c.tobytes() == local.mu_c.tobytes()
    assert remote.theta0.tobytes() == local.theta0.tobytes()
    assert remote.inflow.tobytes() == local.inflow.tobytes()


def test_bad_input_raises_before_anything_is_sent(client):
    with pytest.raises(ValueError):
        flaplag.map(x=("mu", [0.2, 0.1]), y=("theta", [0.1]), client=client)
    with pytest.raises(ValueError):
        flaplag.map(x=("mu", [0.1, 0.2]), y=("theta", [0.1]), gamma=-1.0, client=client)
    with pytest.raises(ValueError):
        flaplag.study("omega_lag", [0.5], thrust_coefficient=0.005, client=client)
