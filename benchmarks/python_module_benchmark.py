"""Figures of the Python module (docs/performance.md, "Python module"); not a test.

  PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_module_benchmark.py forces [THREADS]
  PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_module_benchmark.py study

forces: terrastudio.forces on the 10⁶ samples of gsa_benchmark.cpp's BatchMillion (θ_f = 25°,
φ, c, K and n varied per sample), wall time of the whole call: argument conversion, the batch,
the eleven output arrays and their angles in degrees. Compare with
  build/benchmarks/terra_benchmarks --benchmark_filter=BatchMillion
study: the 4 × 3 × 4096 Sobol' study of docs/sensitivity.md locally on 2 threads and on a 2-worker
LocalCluster (1 thread each), and the cluster's start-up.
"""

import os
import statistics
import sys
import time

import numpy as np
import terrastudio as ts


def samples(count):
    # gsa_benchmark.cpp's Samples, the same doubles.
    i = np.arange(count, dtype=np.int64)
    t = (i + 0.5) / count
    return dict(
        slip=0.05 + 0.85 * t,
        phi_deg=20.0 + 15.0 * ((i * 7) % count) / count,
        c_kPa=5.0 * ((i * 13) % count) / count,
        K_m=0.005 + 0.035 * ((i * 17) % count) / count,
        n=0.5 + 0.6 * ((i * 23) % count) / count,
    )


def forces(threads):
    s = samples(1_000_000)
    soil, wheel = ts.soil("sandy-loam"), ts.wheel("A")
    times, cpu = [], []
    for _ in range(3):
        start, start_cpu = time.perf_counter(), time.process_time()
        out = ts.forces(soil, wheel, entry_angle_deg=25.0, threads=threads, **s)
        times.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
        assert out["ok"].all()
    print(f"forces, 10^6 samples, {threads} thread(s): wall median {statistics.median(times):.3f} s"
          f" (runs: {', '.join(f'{t:.3f}' for t in times)}), CPU of all threads median "
          f"{statistics.median(cpu):.3f} s; load {os.getloadavg()[0]:.1f}")


PARAMETERS = {"phi_deg": (20.0, 35.0), "c_kPa": (0.0, 5.0), "K_m": (0.005, 0.04),
              "n": (0.5, 1.1)}
STUDY = dict(slip=[0.1, 0.3, 0.6], load_N=58.86, outputs=["Fx_N", "sinkage_m"], samples=4096,
             seed=1)


def study():
    from dask.distributed import Client, LocalCluster

    soil, wheel = ts.soil("sandy-loam"), ts.wheel("A")
    start = time.perf_counter()
    local = ts.sobol(soil, wheel, PARAMETERS, threads=2, **STUDY)
    local_s = time.perf_counter() - start
    start = time.perf_counter()
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=40)
    client = Client(cluster)
    startup_s = time.perf_counter() - start
    runs = []
    for _ in range(2):
        start = time.perf_counter()
        remote = ts.sobol(soil, wheel, PARAMETERS, client=client, threads=2, **STUDY)
        runs.append(time.perf_counter() - start)
    same = all(np.array_equal(local[k][o], remote[k][o])
               for k in ("S1", "ST", "S1_conf", "ST_conf") for o in local[k])
    # The fixed cost of distributing a study: one so small that its evaluations take ~1 ms.
    tiny = dict(STUDY, samples=16, resamples=0)
    tiny.pop("load_N")
    start = time.perf_counter()
    ts.sobol(soil, wheel, PARAMETERS, entry_angle_deg=25.0, **tiny)
    tiny_local = time.perf_counter() - start
    overhead = []
    for _ in range(3):
        start = time.perf_counter()
        ts.sobol(soil, wheel, PARAMETERS, entry_angle_deg=25.0, client=client, **tiny)
        overhead.append(time.perf_counter() - start)
    client.close()
    cluster.close()
    print(f"sobol 4x3x4096 ({local['evaluations']} solves): local 2 threads {local_s:.2f} s; "
          f"LocalCluster 2 workers: start-up {startup_s:.2f} s, first run {runs[0]:.2f} s, "
          f"second {runs[1]:.2f} s; identical: {same}; a 16-sample study (8 chunks): local "
          f"{tiny_local * 1e3:.1f} ms, cluster {statistics.median(overhead) * 1e3:.0f} ms "
          f"(median of 3); load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "forces"
    if what == "forces":
        forces(int(sys.argv[2]) if len(sys.argv) > 2 else 2)
    else:
        study()
