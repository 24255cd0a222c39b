"""The cluster path (issue 17 §7): stability maps through joblib's dask backend on a LocalCluster.

A map computed on a ``dask.distributed.LocalCluster`` must be byte for byte
the map computed in this process with ``n_jobs=1``; so must the map of the
README's dask snippet, run as written except for the scheduler address and a
smaller grid.
"""

import os
import re

import numpy as np
import pytest

import dfa

distributed = pytest.importorskip("dask.distributed")
joblib = pytest.importorskip("joblib")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

pytestmark = pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="the dask path is taken with n_jobs >= 2")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None, silence_logs=40
    )
    cl = distributed.Client(cluster)
    try:
        yield cl
    finally:
        cl.close()
        cluster.close()


def _same(a: dfa.StabilityMap, b: dfa.StabilityMap) -> None:
    for name in ("beta", "sigma", "outcome", "amplitude", "frequency"):
        x, y = getattr(a, name), getattr(b, name)
        assert x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes(), name
    assert a.to_dict() == b.to_dict()


def test_fig4_map_on_dask_cluster_equals_one_job(client):
    kw = dict(grid=5, samples=4000, beta_range=(0.0, 1.0), sigma_range=(0.0, 1.5), progress=False)
    ref = dfa.stability_map(100.0, [1.0, 3.0], n_jobs=1, **kw)
    with distributed.get_task_stream(client=client) as stream, joblib.parallel_config(backend="dask"):
        got = dfa.stability_map(100.0, [1.0, 3.0], n_jobs=2, backend="joblib", **kw)
    assert len(stream.data) > 0  # the chunks ran as tasks on the cluster
    _same(ref, got)
    # the grid is not degenerate: more than one outcome occurs, so the comparison can fail
    assert len(np.unique(ref.outcome)) > 1


def _readme_snippet() -> str:
    with open(os.path.join(ROOT, "docs", "python.md"), encoding="utf-8") as fh:  # linked from the README
        text = fh.read()
    blocks = [b for b in re.findall(r"```python\n(.*?)```", text, flags=re.S) if 'backend="dask"' in b]
    assert len(blocks) == 1, "the dask snippet of docs/python.md"
    return blocks[0]


def test_readme_dask_snippet_on_local_cluster(client):
    code = _readme_snippet()
    assert 'Client("tcp://scheduler:8786")' in code and "grid=400" in code
    code = code.replace('Client("tcp://scheduler:8786")', "Client(ADDRESS)").replace("grid=400", "grid=4")
    ns = {"dfa": dfa, "ADDRESS": client.scheduler.address}
    try:
        exec(compile(code, "docs/python.md (dask snippet)", "exec"), ns)
    finally:
        if "client" in ns:
            ns["client"].close()
    m = ns["m"]
    ref = dfa.stability_map(100.0, [1, 2, 5, 10], grid=4, n_jobs=1, progress=False)
    _same(ref, m)
