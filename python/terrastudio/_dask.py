"""Global sensitivity studies and mission studies on a Dask cluster (docs/python.md, "Studies on
a cluster"; docs/field.md, "Mission studies").

The design's rows are cut into chunks of whole base samples (trajectories for Morris); each
worker rebuilds the study from its arguments (soils and wheels travel as their exact doubles),
evaluates its rows through the same module with the GIL released, and the caller gathers the
chunks in row order and estimates the indices. Every row is a pure function of the design, so
the result is bit for bit the local one with the same seed.
"""

import threading

from . import _core

# Per worker process: the last plans built, by the token of their arguments (a study's chunks
# reuse one plan instead of rebuilding the design for each).
_plans = {}
_plans_lock = threading.Lock()


def _worker_plan(token, kind, arguments):
    with _plans_lock:
        plan = _plans.get(token)
        if plan is None:
            if len(_plans) >= 4:
                _plans.clear()
            plan = (_core._SobolPlan if kind == "sobol" else _core._MorrisPlan)(**arguments)
            _plans[token] = plan
    return plan


def evaluate_chunk(token, kind, arguments, begin, end):
    """Rows [begin, end) of the study: (values, status) arrays. Runs on a worker, one thread
    per task (the worker runs as many tasks at once as it has threads)."""
    return _worker_plan(token, kind, arguments).evaluate(begin, end, 1)


def chunk_bounds(rows, per_group, chunks):
    """[begin, end) of `chunks` pieces of whole groups (base samples or trajectories)."""
    groups = rows // per_group
    chunks = max(1, min(int(chunks), groups))
    bounds = []
    for c in range(chunks):
        begin = groups * c // chunks * per_group
        end = groups * (c + 1) // chunks * per_group
        bounds.append((begin, end))
    return bounds


def run_on(client, kind, arguments, plan, chunks, threads):
    """The study's rows evaluated on the client's workers, the result gathered here."""
    from dask.base import tokenize

    if chunks is None:
        nthreads = sum(client.nthreads().values()) or 1
        chunks = 4 * nthreads
    token = tokenize(kind, {k: v for k, v in arguments.items() if k not in ("soil", "wheel")},
                     arguments["soil"].__getstate__(), arguments["wheel"].__getstate__())
    [scattered] = client.scatter([arguments], broadcast=True)
    bounds = chunk_bounds(plan.rows, plan.rows_per_group, chunks)
    futures = [
        client.submit(evaluate_chunk, token, kind, scattered, begin, end, pure=False)
        for begin, end in bounds
    ]
    parts = client.gather(futures)
    return plan.gather(parts, threads)


def run_mission(settings):
    """One case of a mission study on a worker (terrastudio.mission_study)."""
    from . import _mission

    return _mission(settings)


def run_missions(client, runs):
    """Each case as one task on the client's workers, the summaries gathered in case order."""
    futures = [client.submit(run_mission, one, pure=False) for one in runs]
    return client.gather(futures)
