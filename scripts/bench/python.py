#!/usr/bin/env python3
"""Files per second checking one folder three ways, in one run: the CLI, the Python API in a
thread pool, and gltfmat.dask on a LocalCluster; then the Python overhead per small file.

    python scripts/bench/python.py [FOLDER] [--runs N]

Needs the package installed with its dask extra (`pip install './python[dask]'`) and a
release build of the CLI (`cargo build --release`). Best of N runs each, the ways taken in
turn within every round, because this machine's timings vary from run to run.
"""

import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import gltfmat

REPO = Path(__file__).resolve().parents[2]
CLI = REPO / "target" / "release" / "gltfmat"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("folder", nargs="?", default=str(REPO.parent / "shared" / "real-world" / "gltf2"))
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    if not CLI.exists():
        sys.exit(f"{CLI} is missing: cargo build --release")
    listed = subprocess.run([str(CLI), "check", args.folder, "--format", "jsonl"], capture_output=True, text=True)
    files = [json.loads(line)["uri"] for line in listed.stdout.splitlines()]
    workers = os.cpu_count() or 1

    def cli():
        subprocess.run([str(CLI), "check", args.folder, "--format", "jsonl"], capture_output=True, check=False)

    def pool():
        with ThreadPoolExecutor(max_workers=workers) as threads:
            list(threads.map(gltfmat.check, files))

    from dask.distributed import Client, LocalCluster

    import gltfmat.dask

    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=None)
    client = Client(cluster)

    def dask_run():
        gltfmat.dask.check_table(files, files_per_partition=max(1, len(files) // (4 * workers))).compute()

    ways = {"CLI (one process, all cores)": cli, f"Python API, {workers} threads": pool,
            f"gltfmat.dask, LocalCluster of {workers}": dask_run}
    best = {name: float("inf") for name in ways}
    for _ in range(args.runs):
        for name, run in ways.items():
            start = time.perf_counter()
            run()
            best[name] = min(best[name], time.perf_counter() - start)
    print(f"{len(files)} files under {args.folder}, best of {args.runs}")
    print(f"{'way':<40} {'seconds':>8} {'files/s':>9}")
    for name, seconds in best.items():
        print(f"{name:<40} {seconds:>8.3f} {len(files) / seconds:>9.0f}")
    client.close()
    cluster.close()
    overhead(files, args.runs)


def overhead(files, runs) -> None:
    """Per small file (the smallest half) on one thread, the CLI's start-up taken out: the
    time of the list given ten times less the time of it given once, over nine lists."""
    small = sorted(files, key=lambda f: os.path.getsize(f))[: max(1, len(files) // 2)]

    def cli(times):
        env = {**os.environ, "RAYON_NUM_THREADS": "1"}
        subprocess.run([str(CLI), "check", *(small * times), "--format", "jsonl"], capture_output=True, env=env)

    def python(times):
        for f in small * times:
            gltfmat.check(f).findings

    def per_file(run):
        best = {1: float("inf"), 10: float("inf")}
        for _ in range(runs):
            for times in best:
                start = time.perf_counter()
                run(times)
                best[times] = min(best[times], time.perf_counter() - start)
        return (best[10] - best[1]) / (9 * len(small))

    per_cli, per_python = per_file(cli), per_file(python)
    print(f"\nsmallest {len(small)} files, one thread, start-up taken out: CLI {per_cli * 1e6:.0f} µs/file,"
          f" Python API {per_python * 1e6:.0f} µs/file: Python's overhead {100 * (per_python / per_cli - 1):+.0f} %")


if __name__ == "__main__":
    main()
