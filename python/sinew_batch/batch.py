"""A whole batch: the manifest's trials run where asked, with progress, and their summary."""
import os
import time

from .executors import run_trials
from .manifest import load_manifest
from .progress import Progress
from .summary import format_table, write_summary_csv


def default_summary_path(manifest):
    stem = os.path.splitext(os.path.abspath(manifest))[0]
    return stem + "_summary.csv"


def run_batch(manifest, summary=None, workers=1, dask=None, force=False, progress=True, echo=print):
    """Runs every trial of `manifest` (a path, or a list of Trials) and returns their records in manifest order.

    workers > 1: a local process pool; dask: a scheduler address or a dask.distributed Client (then workers
    is the cluster's business). force: run even trials whose stamps match. summary: the CSV to write
    (default for a manifest path: MANIFEST_summary.csv beside it; None with a list writes none). echo prints
    the summary table (None: nothing printed)."""
    trials = load_manifest(manifest) if isinstance(manifest, (str, os.PathLike)) else list(manifest)
    if summary is None and isinstance(manifest, (str, os.PathLike)):
        summary = default_summary_path(manifest)
    started = time.perf_counter()
    bar = Progress(len(trials)) if progress else None
    records = [None] * len(trials)
    for index, record in run_trials(trials, force=force, workers=workers, dask=dask):
        records[index] = record
        if bar:
            bar.update(record)
    if bar:
        bar.finish()
    if echo:
        echo(format_table(records, time.perf_counter() - started))
    if summary:
        write_summary_csv(records, summary)
    return records
