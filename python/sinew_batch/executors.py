"""Where the trials run: in this process, in a local process pool, or as one task per trial on a Dask cluster.
Each yields (index, record) as trials finish. The trial function decides resume itself, on the worker, so all
three follow the same rule; a worker that dies takes only its trial's record with it, which reads as failed
here and runs again on the next batch run (its outputs were never renamed into place)."""
import concurrent.futures
import multiprocessing

from .allocator import keep_freed_memory
from .trial import run_trial, trial_record


def run_serial(trials, force):
    for index, trial in enumerate(trials):
        yield index, run_trial(trial, force)


def run_process_pool(trials, force, workers):
    # spawn, not fork: a forked child would inherit the parent's threads' locks (OpenMP, Ipopt) mid-state
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(workers, mp_context=context) as pool:
        futures = {pool.submit(run_trial, trial, force): index for index, trial in enumerate(trials)}
        for future in concurrent.futures.as_completed(futures):
            index = futures[future]
            try:
                yield index, future.result()
            except concurrent.futures.process.BrokenProcessPool as error:
                yield index, trial_record(trials[index], "failed", error=f"worker process died: {error}", seconds=0.0)


def run_trial_on_worker(trial, force):
    keep_freed_memory()
    return run_trial(trial, force)


def run_dask(trials, force, scheduler):
    """`scheduler`: a dask.distributed Client, or the address of a scheduler to connect to (tcp://host:8786;
    a SLURMCluster's or KubeCluster's scheduler_address)."""
    from dask.distributed import Client, as_completed  # imported only here: local runs do not need Dask

    client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
    try:
        futures = client.map(run_trial_on_worker, trials, force=force, pure=False)
        index_of = {future.key: index for index, future in enumerate(futures)}
        for future in as_completed(futures):
            index = index_of[future.key]
            try:
                yield index, future.result()
            except Exception as error:  # KilledWorker and the like: the task's trial failed, the rest go on
                yield index, trial_record(trials[index], "failed", error=f"{type(error).__name__}: {error}", seconds=0.0)
            future.release()
    finally:
        if client is not scheduler:
            client.close()


def run_trials(trials, force=False, workers=1, dask=None):
    if dask is not None:
        return run_dask(trials, force, dask)
    if workers > 1:
        return run_process_pool(trials, force, workers)
    return run_serial(trials, force)
