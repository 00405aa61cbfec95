"""Benchmark: the same sweep on a Dask LocalCluster of 1 worker and of 2 (processes, one
thread each), wall time of each and the speed-up; the target is 1.7x or more on 2 cores.

The sweep: pendulum_period (closed form, a frame every step) on MuJoCo and Bullet at
dt = 1/3000 and 1/4000 s with iterations 10, 20 and 50: 12 runs of about a second or two
each. Timed: conformance.analyses.sweep.run_sweep, from connecting to the cluster to the last result
(the clusters are started before, and the backends' declarations probed once, outside).
Each size runs --repeat times, the two sizes taking turns; the speed-up is of the best
times (other work on the machine only ever slows a run), and each run's time is printed
with the load average before it.

    python benchmarks/sweep_scaling.py [--backends mujoco,bullet] [--repeat 3]
"""

from __future__ import annotations

import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from distributed import LocalCluster  # noqa: E402

from conformance.analyses import sweep as S  # noqa: E402

SCENE = "pendulum_period"
DTS = (1 / 3000, 1 / 4000)
ITERATIONS = (10, 20, 50)


def timed_sweep(workers: int, chosen: list[S.Target], plans: dict[str, S.BackendPlan]) -> tuple[float, list]:
    with LocalCluster(n_workers=workers, processes=True, threads_per_worker=1, dashboard_address=None,
                      silence_logs=50) as cluster:
        started = time.perf_counter()
        sweep = S.run_sweep(chosen, plans, DTS, ITERATIONS, (False,), scheduler=cluster.scheduler_address)
        return time.perf_counter() - started, [p.error for p in sweep.points]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--backends", default="mujoco,bullet", help="comma-separated (default mujoco,bullet)")
    parser.add_argument("--repeat", type=int, default=3, help="runs of each size (default 3)")
    args = parser.parse_args()
    chosen = S.targets([SCENE], DTS)
    plans, skipped = S.backend_plans(args.backends.split(","))
    if skipped:
        print(f"not available: {skipped}", file=sys.stderr)
        return 1
    runs = len(plans) * len(DTS) * len(ITERATIONS)
    walls: dict[int, list[float]] = {1: [], 2: []}
    for _ in range(args.repeat):
        for workers in (1, 2):
            load = os.getloadavg()[0]
            wall, errors = timed_sweep(workers, chosen, plans)
            walls[workers].append(wall)
            print(f"{workers} worker{'s' if workers > 1 else ''}: {wall:.1f} s for {runs} runs "
                  f"(load average {load:.2f} before)", flush=True)
            if any(e is None for e in errors):
                print("some runs gave no error: see x3drbp sweep on the same scene", file=sys.stderr)
                return 1
    best = {n: min(w) for n, w in walls.items()}
    print(f"best: 1 worker {best[1]:.1f} s, 2 workers {best[2]:.1f} s; "
          f"speed-up {best[1] / best[2]:.2f}x on {os.cpu_count()} CPUs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
