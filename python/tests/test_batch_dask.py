"""sinew_batch's scale-out: the study of test_batch.py run on a dask.distributed LocalCluster of two worker
processes (through its scheduler address, as --dask takes a cluster's) and on a local process pool gives the
serial run's files byte for byte, and the same resume rule holds there."""
import json
import os
import pathlib
import signal
import subprocess
import sys

import pytest

from test_batch import output_files, run_quietly, write_study

distributed = pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")
# tornado, under Debian's distributed 2022.12, warns of its own deprecated call on every cluster start
pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    root = tmp_path_factory.mktemp("serial")
    assert [r["status"] for r in run_quietly(write_study(root))] == ["ok"] * 4
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
    assert [r["status"] for r in records] == ["ok"] * 4, records
    assert output_files(tmp_path) == output_files(serial)
    assert stamps(tmp_path) == stamps(serial)  # the digests do not depend on where the study lives
    assert [r["status"] for r in run_quietly(manifest, dask=cluster.scheduler_address)] == ["skipped"] * 4
    # a serial run over the cluster's outputs has nothing to do either
    assert [r["status"] for r in run_quietly(manifest)] == ["skipped"] * 4


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
        assert [r["status"] for r in records] == ["ok"] * 4, records
        assert output_files(tmp_path) == output_files(serial)
        assert not [path for path in (tmp_path / "out").rglob("*") if ".incomplete-" in path.name]


def test_process_pool_gives_the_serial_outputs(serial, tmp_path):
    manifest = write_study(tmp_path)
    done = subprocess.run([sys.executable, "-m", "sinew_batch", str(manifest), "--workers", "2"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "4 trials: 4 ran, 0 skipped" in done.stdout
    assert output_files(tmp_path) == output_files(serial)
