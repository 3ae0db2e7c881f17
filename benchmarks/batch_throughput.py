"""Batch throughput (docs/batch.md, docs/performance.md): trials per minute of sinew_batch on the shipped whole-body
kick, run by a direct call of each trial in this process (the peer), by Dask on a LocalCluster of 1 and 2 worker
processes, and by a local process pool of 2, in alternation; and Dask's per-trial overhead over the direct call.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/batch_throughput.py [--trials 8] [--window 0.5]
        [--repetitions 3] [-o build/benchmarks/batch_throughput.json]

Each trial is `sinew tensions models/whole_body/whole_body_subject11.yaml models/whole_body/kick_11_01.mot
--method lp --max-tension 1e6 --lowpass 6` over its own window of the kick (the demo's formulation), long
enough (a second and more) that the figures are of the trials, not of start-up. Every configuration runs the
same trials with force on (all work done again) into its own folder. The direct call runs in an interpreter
of its own (this one hosts the clusters' schedulers); it and Dask's workers have the model loaded beforehand,
and it has the allocator settings sinew_batch gives a Dask worker (sinew_batch/allocator.py), so the overhead
measured is the per-trial cost of scheduling, serialising the
trial and its record, and the worker round trip. The process pool starts cold (spawned interpreters, each
loading the model), as `--workers N` does."""
import argparse
import dataclasses
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import tempfile
import time

import sinew
import sinew_batch
from sinew_batch.allocator import keep_freed_memory
from sinew_batch.manifest import load_manifest
from sinew_batch.trial import run_trial

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[1]
MODEL = SOURCE_DIR / "models" / "whole_body" / "whole_body_subject11.yaml"
MOTION = SOURCE_DIR / "models" / "whole_body" / "kick_11_01.mot"


def write_manifest(folder, trials, window):
    """`trials` windows of `window` s of the kick, back to back from 0.1 s."""
    lines = ["defaults:", f"  model: {MODEL}", f"  motion: {MOTION}", "  pipeline: tensions", "  method: lp",
             "  max_tension: 1000000", "  lowpass: 6", "trials:"]
    for index in range(trials):
        start = 0.1 + index * window
        lines.append(f"  - {{start: {start:.4f}, end: {start + window:.4f}, output: out/window_{index}}}")
    path = folder / "manifest.yaml"
    path.write_text("\n".join(lines) + "\n")
    return path


def warm_model():
    from sinew_batch.input_digest import file_sha256
    from sinew_batch.trial import _load_model
    _load_model(str(MODEL), file_sha256(MODEL))


def run_direct_child(manifest, output):
    """The peer, in a plain interpreter of its own (not beside the clusters' schedulers, whose event loops
    share this process): the model loaded, then each trial called in turn. Prints wall s and each trial's s."""
    trials = relocate(load_manifest(manifest), pathlib.Path(output))
    warm_model()
    keep_freed_memory()
    started = time.perf_counter()
    seconds = []
    for trial in trials:
        record = run_trial(trial, force=True)
        assert record["status"] == "ok", record
        seconds.append(record["seconds"])
    print(json.dumps({"wall": time.perf_counter() - started, "seconds": seconds}))


def run_direct(manifest, output):
    child = subprocess.run([sys.executable, __file__, "--direct-child", str(manifest), str(output)],
                           capture_output=True, text=True, check=True)
    measured = json.loads(child.stdout.splitlines()[-1])
    return measured["wall"], measured["seconds"]


def run_batch(trials, **where):
    started = time.perf_counter()
    records = sinew_batch.run_batch(trials, force=True, progress=False, echo=None, **where)
    assert all(record["status"] == "ok" for record in records), records
    return time.perf_counter() - started


def relocate(trials, folder):
    """The same trials writing under `folder`, so that configurations do not share output files."""
    return [dataclasses.replace(trial, output=str(folder / pathlib.Path(trial.output).name)) for trial in trials]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=8)
    parser.add_argument("--window", type=float, default=0.5, help="each trial's span of the kick, s")
    parser.add_argument("--repetitions", type=int, default=3)
    parser.add_argument("-o", "--output", default=str(SOURCE_DIR / "build" / "benchmarks" / "batch_throughput.json"))
    arguments = parser.parse_args()
    if 0.1 + arguments.trials * arguments.window > 4.97:
        parser.error(f"{arguments.trials} windows of {arguments.window} s do not fit in the kick (0.1 to 4.97 s)")

    from dask.distributed import Client, LocalCluster

    model = sinew.load_model(str(MODEL))
    census = model.census()
    print(f"model {MODEL.name}: {census.links} links, {census.dof} DOF, {census.wires} wires; "
          f"{arguments.trials} trials of {arguments.window} s of the kick each; {os.cpu_count()} CPUs", flush=True)
    folder = pathlib.Path(tempfile.mkdtemp(prefix="sinew_batch_throughput_"))
    manifest = write_manifest(folder, arguments.trials, arguments.window)
    trials = load_manifest(manifest)
    warm_model()
    clusters = {workers: LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                      dashboard_address=":0") for workers in (1, 2)}
    clients = {workers: Client(cluster) for workers, cluster in clusters.items()}
    for client in clients.values():
        client.run(warm_model)
    walls = {name: [] for name in ("direct", "dask_1_worker", "dask_2_workers", "process_pool_2")}
    trial_seconds = []
    try:
        for repetition in range(arguments.repetitions):
            wall, seconds = run_direct(manifest, folder / "direct")
            walls["direct"].append(wall)
            trial_seconds.append(seconds)
            walls["dask_1_worker"].append(run_batch(relocate(trials, folder / "dask1"), dask=clients[1]))
            walls["dask_2_workers"].append(run_batch(relocate(trials, folder / "dask2"), dask=clients[2]))
            walls["process_pool_2"].append(run_batch(relocate(trials, folder / "pool2"), workers=2))
            print(f"repetition {repetition + 1}/{arguments.repetitions}: " +
                  ", ".join(f"{name} {values[-1]:.2f} s" for name, values in walls.items()), flush=True)
    finally:
        for client in clients.values():
            client.close()
        for cluster in clusters.values():
            cluster.close()

    median = {name: statistics.median(values) for name, values in walls.items()}
    mean_trial = statistics.median(statistics.mean(seconds) for seconds in trial_seconds)
    overhead = (median["dask_1_worker"] - median["direct"]) / arguments.trials
    results = {
        "context": {"date": time.strftime("%Y-%m-%dT%H:%M:%S"), "host": platform.node(), "cpus": os.cpu_count(),
                    "python": sys.version.split()[0], "model": MODEL.name, "links": census.links,
                    "dof": census.dof, "wires": census.wires, "trials": arguments.trials,
                    "window_s": arguments.window, "repetitions": arguments.repetitions},
        "wall_s": walls,
        "median_wall_s": median,
        "trials_per_minute": {name: 60 * arguments.trials / wall for name, wall in median.items()},
        "mean_trial_s": mean_trial,
        "dask_overhead_per_trial_s": overhead,
        "dask_overhead_fraction": overhead / mean_trial,
        "speedup_2_workers_over_1": median["dask_1_worker"] / median["dask_2_workers"],
    }
    output = pathlib.Path(arguments.output)
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text(json.dumps(results, indent=1) + "\n")
    for name, rate in results["trials_per_minute"].items():
        print(f"{name:>16}: {rate:6.1f} trials/min (median wall {median[name]:.2f} s)")
    print(f"mean trial {mean_trial:.2f} s; Dask's overhead {1e3 * overhead:.1f} ms per trial "
          f"({100 * results['dask_overhead_fraction']:.1f} % of a trial); 2 workers {results['speedup_2_workers_over_1']:.2f}x 1 "
          f"-> {output}")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "--direct-child":
        run_direct_child(sys.argv[2], sys.argv[3])
    else:
        main()
