"""sinew_batch's scale-out: a study of 20 and more trials (arm26 and, where ../shared has it, OpenSim's gait2354
walk, each motion with its own noise) run on a dask.distributed LocalCluster of two worker processes (through its
scheduler address, as --dask takes a cluster's) and on a local process pool gives the serial run's files byte
for byte, and the same resume rule holds there."""
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys

import numpy as np
import pytest

import sinew
from conftest import ARM26_YAML, OPENSIM_GAIT2354
from test_batch import output_files, run_quietly, write_loads, write_manifest
from test_dynamics import write_arm26_motion

distributed = pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")
# tornado, under Debian's distributed 2022.12, warns of its own deprecated call on every cluster start
pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")


def write_noisy_motion(table, path, seed):
    """`table` with Gaussian noise on every coordinate (1 % of its range: what a marker fit leaves), quaternion
    columns renormalised, so each trial has a motion of its own that the trial's low-pass must smooth."""
    rng = np.random.default_rng(seed)
    data = table.data.copy()
    data += rng.normal(size=data.shape) * (0.01 * np.ptp(data, axis=0) + 1e-9)
    for j, column in enumerate(table.columns):
        if column.endswith("_qw"):
            quaternion = [table.columns.index(column[:-1] + axis) for axis in "wxyz"]
            data[:, quaternion] /= np.linalg.norm(data[:, quaternion], axis=1, keepdims=True)
    sinew.write_storage_file(sinew.StorageTable(table.columns, table.times, data, name=table.name), str(path))
    return path


def study_motions(root):
    """The study's motions: (model, motion folder name, clean table, loads XML or None, tension settings).
    gait2354 joins where ../shared has OpenSim's walk; without it arm26 makes up the number of trials."""
    (root / "motions").mkdir(parents=True, exist_ok=True)
    (root / "loads").mkdir(exist_ok=True)
    arm26 = sinew.load_model(str(ARM26_YAML))
    write_arm26_motion(arm26, root / "motions" / "arm26_clean.mot", frames=41)
    arm26_motion = sinew.read_storage_file(str(root / "motions" / "arm26_clean.mot"))
    arm26_row = (ARM26_YAML, "arm26", arm26_motion, write_loads(root / "loads"), {"method": "lp", "max_tension": 2000})
    gait_model = OPENSIM_GAIT2354 / "subject01_simbody.osim"
    if not gait_model.exists():
        return [arm26_row] * 10
    for name in ("subject01_walk1_grf.xml", "subject01_walk1_grf.mot"):
        shutil.copy(OPENSIM_GAIT2354 / name, root / "loads" / name)
    walk = sinew.read_storage_file(str(OPENSIM_GAIT2354 / "subject01_walk1_ik.mot"))
    gait_row = (gait_model, "walk", walk, root / "loads" / "subject01_walk1_grf.xml", {"method": "lp"})
    return [arm26_row] * 6 + [gait_row] * 4


def write_study(root):
    """Per motion two trials (inverse dynamics and tensions, both low-passed at 6 Hz), 20 in all; returns the
    manifest's path."""
    rows = []
    for seed, (model, label, clean, loads, tension) in enumerate(study_motions(root)):
        motion = write_noisy_motion(clean, root / "motions" / f"{label}_{seed}.mot", seed)
        common = {"model": model, "motion": motion.relative_to(root), "lowpass": 6,
                  "external_loads": loads.relative_to(root), "output": f"out/{label}_{seed}"}
        rows.append({**common, "pipeline": "inverse-dynamics"})
        rows.append({**common, "pipeline": "tensions", **tension})
    return write_manifest(root / "manifest.yaml", rows)


TRIALS = 20


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    root = tmp_path_factory.mktemp("serial")
    records = run_quietly(write_study(root))
    assert [r["status"] for r in records] == ["ok"] * TRIALS, records
    return root


def stamps(root):
    return {str(path.relative_to(root)): json.loads(path.read_text())["input_sha256"]
            for path in sorted((root / "out").rglob("*.batch.json"))}


@pytest.fixture(scope="module")
def cluster():
    # The workers are processes of their own: they find this folder (kill_first_writer) through PYTHONPATH
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("PYTHONPATH", os.pathsep.join([str(pathlib.Path(__file__).parent), os.environ.get("PYTHONPATH", "")]))
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            yield cluster


def test_local_cluster_gives_the_serial_outputs(serial, cluster, tmp_path):
    manifest = write_study(tmp_path)
    records = run_quietly(manifest, dask=cluster.scheduler_address)
    assert [r["status"] for r in records] == ["ok"] * TRIALS, records
    assert output_files(tmp_path) == output_files(serial)
    assert stamps(tmp_path) == stamps(serial)  # the digests do not depend on where the study lives
    assert [r["status"] for r in run_quietly(manifest, dask=cluster.scheduler_address)] == ["skipped"] * TRIALS
    # a serial run over the cluster's outputs has nothing to do either
    assert [r["status"] for r in run_quietly(manifest)] == ["skipped"] * TRIALS


def kill_first_writer(flag):
    """Arms this worker: the first of them to write a table once `flag` exists kills itself, mid-trial."""
    import sinew

    real_write = sinew.write_storage_file

    def write(table, path):
        real_write(table, path)
        try:
            os.remove(flag)  # only one worker wins the removal
        except FileNotFoundError:
            return
        os.kill(os.getpid(), signal.SIGKILL)

    sinew.write_storage_file = write


def test_a_worker_killed_mid_trial_is_replaced_and_the_outputs_are_whole(serial, cluster, tmp_path):
    manifest = write_study(tmp_path)
    flag = tmp_path / "kill_a_worker"
    flag.touch()
    with distributed.Client(cluster.scheduler_address) as client:
        client.run(kill_first_writer, str(flag))
        records = run_quietly(manifest, dask=client)
        assert not flag.exists()  # a worker did die, with a table written under its temporary name
        # Dask ran the dead worker's trial again on a live one, which cleared the dead one's temporary
        assert [r["status"] for r in records] == ["ok"] * TRIALS, records
        assert output_files(tmp_path) == output_files(serial)
        assert not [path for path in (tmp_path / "out").rglob("*") if ".incomplete-" in path.name]
        assert [r["status"] for r in run_quietly(manifest, dask=client)] == ["skipped"] * TRIALS


def test_process_pool_gives_the_serial_outputs(serial, tmp_path):
    manifest = write_study(tmp_path)
    done = subprocess.run([sys.executable, "-m", "sinew_batch", str(manifest), "--workers", "2"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert f"{TRIALS} trials: {TRIALS} ran, 0 skipped" in done.stdout
    assert output_files(tmp_path) == output_files(serial)
