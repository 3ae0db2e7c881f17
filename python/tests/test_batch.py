"""sinew_batch (docs/batch.md) on a small study written here: arm26 motions, a hand load, inverse dynamics and
tensions. The outputs are checked byte for byte against `sinew inverse-dynamics` and `sinew tensions` on the
same inputs; then resume (what reruns after which edit), a failing trial amid good ones, and a write that
fails or a worker that is killed mid-trial, which must leave no file under a final name."""
import csv
import os
import pathlib
import signal
import subprocess
import sys

import numpy as np
import pytest

import sinew
import sinew_batch
from conftest import ARM26_YAML, run_cli
from test_dynamics import write_arm26_motion

LOADS_XML = """<?xml version="1.0" encoding="UTF-8"?>
<OpenSimDocument Version="40000">
  <ExternalLoads name="hand_push">
    <objects>
      <ExternalForce name="push">
        <applied_to_body>r_ulna_radius_hand</applied_to_body>
        <force_expressed_in_body>ground</force_expressed_in_body>
        <point_expressed_in_body>ground</point_expressed_in_body>
        <force_identifier>hand_force_v</force_identifier>
        <point_identifier>hand_force_p</point_identifier>
      </ExternalForce>
    </objects>
    <datafile>hand_push.mot</datafile>
  </ExternalLoads>
</OpenSimDocument>
"""


def write_loads(folder, scale=1.0):
    """A push on the hand, growing over the motion; returns the ExternalLoads XML's path."""
    t = np.linspace(0, 0.4, 9)
    force = scale * np.column_stack([5 * t, -20 - 10 * t, 2 * np.ones_like(t)])
    point = np.tile([0.05, 0.3, 0.25], (len(t), 1))
    columns = [f"hand_force_{axis}" for axis in ("vx", "vy", "vz", "px", "py", "pz")]
    sinew.write_storage_file(sinew.StorageTable(columns, t, np.hstack([force, point]), name="hand_push"),
                             str(folder / "hand_push.mot"))
    (folder / "hand_push.xml").write_text(LOADS_XML)
    return folder / "hand_push.xml"


def write_reach(model, path, seed=3):
    """The elbow motion with small smooth perturbations of the elbow angle: a second, different motion."""
    write_arm26_motion(model, path, frames=41)
    table = sinew.read_storage_file(str(path))
    data = table.data
    t = table.times
    rng = np.random.default_rng(seed)
    data[:, table.columns.index("r_elbow")] += 0.05 * np.sin(2 * np.pi * (2 + rng.uniform()) * t + rng.uniform())
    sinew.write_storage_file(sinew.StorageTable(table.columns, t, data, name="arm26 reach"), str(path))
    return path


# The study's trials: what sinew_batch runs, and the CLI command that makes the same files.
TRIALS = [
    ({"motion": "motions/elbow.mot", "pipeline": "inverse-dynamics", "external_loads": "loads/hand_push.xml",
      "lowpass": 6, "start": 0.05, "end": 0.35, "output": "out/elbow"},
     ["inverse-dynamics", "{model}", "{root}/motions/elbow.mot", "--external-loads", "{root}/loads/hand_push.xml",
      "--lowpass", "6", "--start", "0.05", "--end", "0.35", "-o", "{cli}/elbow/inverse_dynamics.sto"]),
    ({"motion": "motions/elbow.mot", "pipeline": "tensions", "method": "lp", "max_tension": 2000,
      "output": "out/elbow"},
     ["tensions", "{model}", "{root}/motions/elbow.mot", "--method", "lp", "--max-tension", "2000",
      "-o", "{cli}/elbow/tensions.sto"]),
    ({"motion": "motions/reach.mot", "pipeline": "tensions", "method": "qp", "max_tension": 2000, "lowpass": 8,
      "external_loads": "loads/hand_push.xml", "output": "out/reach"},
     ["tensions", "{model}", "{root}/motions/reach.mot", "--method", "qp", "--max-tension", "2000", "--lowpass", "8",
      "--external-loads", "{root}/loads/hand_push.xml", "-o", "{cli}/reach/tensions.sto"]),
    ({"motion": "motions/reach.mot", "pipeline": "tensions", "method": "lp", "max_tension": 600, "tolerance": 0.01,
      "start": 0.1, "output": "out/reach_weak"},
     ["tensions", "{model}", "{root}/motions/reach.mot", "--method", "lp", "--max-tension", "600", "--tolerance",
      "0.01", "--start", "0.1", "-o", "{cli}/reach_weak/tensions.sto"]),
]


def write_manifest(path, rows, model=ARM26_YAML):
    """A YAML manifest of `rows` (field -> value) with the model as a default."""
    lines = ["defaults:", f"  model: {model}", "trials:"]
    for row in rows:
        lines.append("  - " + "\n    ".join(f"{field}: {value}" for field, value in row.items()))
    path.write_text("\n".join(lines) + "\n")
    return path


def write_study(root):
    """Motions, loads and the four-trial manifest under `root`; returns the manifest's path."""
    model = sinew.load_model(str(ARM26_YAML))
    (root / "motions").mkdir(parents=True, exist_ok=True)
    (root / "loads").mkdir(exist_ok=True)
    write_arm26_motion(model, root / "motions" / "elbow.mot", frames=41)
    write_reach(model, root / "motions" / "reach.mot")
    write_loads(root / "loads")
    return write_manifest(root / "manifest.yaml", [row for row, _ in TRIALS])


def output_files(root):
    """Relative path -> bytes of every file under root/out (stamps left out: they hold timings)."""
    return {str(path.relative_to(root)): path.read_bytes() for path in sorted((root / "out").rglob("*"))
            if path.is_file() and not path.name.endswith(".batch.json")}


def run_quietly(manifest, **options):
    return sinew_batch.run_batch(manifest, progress=False, echo=None, **options)


@pytest.fixture
def study(tmp_path):
    return write_study(tmp_path)


def test_trials_match_the_cli(study):
    root = study.parent
    records = run_quietly(study)
    assert [r["status"] for r in records] == ["ok"] * len(TRIALS), records
    for _, command in TRIALS:
        run_cli(*[arg.format(model=ARM26_YAML, root=root, cli=root / "cli") for arg in command])
    ours = output_files(root)
    cli_files = {str("out" / path.relative_to(root / "cli")) for path in (root / "cli").rglob("*") if path.is_file()}
    assert set(ours) == cli_files  # the same set of files, the somatosensory tables included
    assert len(ours) == 1 + 3 * 3  # ID; tensions, report and joint loads of each tension trial
    for name, content in ours.items():
        cli_file = root / "cli" / pathlib.Path(name).relative_to("out")
        assert content == cli_file.read_bytes(), name
    # The summary's figures against the CLI's report files
    with open(root / "manifest_summary.csv", newline="") as file:
        summary = list(csv.DictReader(file))
    assert [row["trial"] for row in summary] == [r["trial"] for r in records]
    for row, (trial, _) in zip(summary, TRIALS):
        if trial["pipeline"] == "inverse-dynamics":
            table = sinew.read_storage_file(str(root / "cli" / "elbow" / "inverse_dynamics.sto"))
            assert int(row["frames"]) == len(table) and 25 < len(table) < 41  # the motion cut to 0.05-0.35 s
            continue
        report = sinew.read_storage_file(str(root / "cli" / pathlib.Path(trial["output"]).name / "tensions_report.sto"))
        residuals = [j for j, c in enumerate(report.columns) if c.endswith("_residual") and c != "unactuated_residual"]
        assert int(row["frames"]) == len(report)
        assert int(row["infeasible_frames"]) == int(np.sum(report.column("status") == 1))
        assert float(row["worst_residual"]) == pytest.approx(np.abs(report.data[:, residuals]).max(), rel=1e-12)
    # The weak wires make frames infeasible, the strong ones on the same motion do not: the counts have teeth
    assert int(summary[3]["infeasible_frames"]) > 0 and int(summary[2]["infeasible_frames"]) == 0


def test_opensim_arm26_static_optimization_trial_matches_the_cli(tmp_path, opensim_arm26):
    manifest = write_manifest(tmp_path / "so.yaml", [
        {"motion": opensim_arm26 / "arm26_InverseKinematics.mot", "pipeline": "tensions", "method": "so",
         "output": "out/so"}], model=opensim_arm26 / "arm26.osim")
    [record] = run_quietly(manifest)
    assert record["status"] == "ok" and record["frames"] == 121, record
    run_cli("tensions", opensim_arm26 / "arm26.osim", opensim_arm26 / "arm26_InverseKinematics.mot", "--method", "so",
            "-o", tmp_path / "cli" / "so" / "tensions.sto")
    ours = output_files(tmp_path)
    assert "out/so/tensions_activations.sto" in ours
    for name, content in ours.items():
        assert content == (tmp_path / "cli" / pathlib.Path(name).relative_to("out")).read_bytes(), name


def statuses(manifest):
    return [record["status"] for record in run_quietly(manifest)]


def test_second_run_skips_and_an_edited_input_reruns_only_its_trials(study):
    root = study.parent
    assert statuses(study) == ["ok"] * 4
    before = output_files(root)
    times = {path: path.stat().st_mtime_ns for path in (root / "out").rglob("*")}
    assert statuses(study) == ["skipped"] * 4
    assert {path: path.stat().st_mtime_ns for path in (root / "out").rglob("*")} == times  # nothing rewritten

    os.utime(root / "motions" / "reach.mot")  # a newer time, the same content: still up to date
    assert statuses(study) == ["skipped"] * 4
    write_reach(sinew.load_model(str(ARM26_YAML)), root / "motions" / "reach.mot", seed=4)
    assert statuses(study) == ["skipped", "skipped", "ok", "ok"]
    assert output_files(root)["out/elbow/tensions.sto"] == before["out/elbow/tensions.sto"]
    assert output_files(root)["out/reach/tensions.sto"] != before["out/reach/tensions.sto"]

    write_loads(root / "loads", scale=1.5)  # the loads' data file, which the XML names
    assert statuses(study) == ["ok", "skipped", "ok", "skipped"]

    rows = [dict(row) for row, _ in TRIALS]
    rows[1]["max_tension"] = 2500  # a row's option
    write_manifest(study, rows)
    assert statuses(study) == ["skipped", "ok", "skipped", "skipped"]

    (root / "out" / "reach_weak" / "tensions_report.sto").unlink()  # a missing output
    assert statuses(study) == ["skipped", "skipped", "skipped", "ok"]
    with open(root / "out" / "reach" / "tensions.sto", "a") as file:  # an output edited after the run
        file.write("0.5\t1\t2\t3\t4\t5\t6\n")
    assert statuses(study) == ["skipped", "skipped", "ok", "skipped"]
    assert [r["status"] for r in run_quietly(study, force=True)] == ["ok"] * 4


def test_failing_trial_is_recorded_and_the_others_run(study):
    root = study.parent
    rows = [dict(row) for row, _ in TRIALS]
    rows[1]["motion"] = "motions/no_such_motion.mot"
    rows[2]["lowpass"] = 80  # refused as `sinew tensions --lowpass 80` refuses it: the motion is sampled at 100 Hz
    write_manifest(study, rows)
    done = subprocess.run([sys.executable, "-m", "sinew_batch", str(study), "-o", str(root / "summary.csv")],
                          capture_output=True, text=True)
    assert done.returncode == 1, done.stdout + done.stderr  # a trial failed; the batch still finished
    assert "4 trials: 2 ran, 0 skipped (outputs up to date), 2 failed" in done.stdout
    with open(root / "summary.csv", newline="") as file:
        summary = list(csv.DictReader(file))
    assert [row["status"] for row in summary] == ["ok", "failed", "failed", "ok"]
    assert "manifest.yaml:" in summary[1]["error"] and "no_such_motion.mot' does not exist" in summary[1]["error"]
    assert "lowpass 80 Hz is at or above the Nyquist frequency 50 Hz" in summary[2]["error"]
    assert not (root / "out" / "elbow" / "tensions.sto").exists()
    assert (root / "out" / "reach_weak" / "tensions.sto").exists()


def test_manifest_error_stops_before_any_trial(study):
    rows = [dict(row) for row, _ in TRIALS]
    rows[3]["lowpas"] = 6
    write_manifest(study, rows)
    done = subprocess.run([sys.executable, "-m", "sinew_batch", str(study)], capture_output=True, text=True)
    assert done.returncode == 2 and "unknown field 'lowpas'" in done.stderr, done.stderr
    assert not (study.parent / "out").exists()


def final_and_temporary(folder):
    names = sorted(path.name for path in folder.iterdir()) if folder.exists() else []
    return [n for n in names if ".incomplete-" not in n], [n for n in names if ".incomplete-" in n]


def test_a_failed_write_leaves_no_file_under_a_final_name(study, monkeypatch):
    folder = study.parent / "out" / "reach"
    real_write = sinew.write_storage_file

    def write_then_fail(table, path):
        real_write(table, path)
        if path.startswith(str(folder / "tensions_report.sto")):  # after the tensions were written in full
            raise OSError(28, "No space left on device", path)

    monkeypatch.setattr(sinew, "write_storage_file", write_then_fail)
    records = run_quietly(study)
    assert [r["status"] for r in records] == ["ok", "ok", "failed", "ok"]
    assert "No space left on device" in records[2]["error"]
    assert final_and_temporary(folder) == ([], [])  # the tensions were whole, yet not under their name

    monkeypatch.setattr(sinew, "write_storage_file", real_write)
    assert statuses(study) == ["skipped", "skipped", "ok", "skipped"]
    good = output_files(study.parent)
    monkeypatch.setattr(sinew, "write_storage_file", write_then_fail)
    [record] = run_quietly([t for t in sinew_batch.load_manifest(study) if t.output == str(folder)], force=True)
    assert record["status"] == "failed"
    assert output_files(study.parent) == good  # the previous run's files and stamp stand as they were
    assert final_and_temporary(folder)[1] == []
    monkeypatch.setattr(sinew, "write_storage_file", real_write)
    assert statuses(study) == ["skipped"] * 4


KILLED_RUN = """
import os, signal, sys
import sinew, sinew_batch
def kill_on_second_call(real):
    calls = []
    def call(*args):
        calls.append(args)
        if len(calls) == 2:
            os.kill(os.getpid(), signal.SIGKILL)
        return real(*args)
    return call
if sys.argv[2] == "write":  # while the tables are written
    sinew.write_storage_file = kill_on_second_call(sinew.write_storage_file)
else:  # between the renames into place
    os.replace = kill_on_second_call(os.replace)
sinew_batch.run_batch(sys.argv[1], progress=False, echo=None)
"""


@pytest.mark.parametrize("moment", ["write", "rename"])
def test_a_killed_worker_leaves_no_partial_file_and_the_rerun_completes(study, tmp_path, moment):
    root = study.parent
    reference = tmp_path / "reference"
    run_quietly(write_study(reference))
    rows = [dict(row) for row, _ in TRIALS]
    write_manifest(study, [rows[2]])  # the qp trial with loads: tensions, report and joint loads
    killed = subprocess.run([sys.executable, "-c", KILLED_RUN, str(study), moment], capture_output=True, text=True)
    assert killed.returncode == -signal.SIGKILL, killed.stdout + killed.stderr
    final, temporary = final_and_temporary(root / "out" / "reach")
    temporary = [name.split(".incomplete-")[0] for name in temporary]
    if moment == "write":  # the tensions written, the report not yet: nothing under a final name
        assert (final, temporary) == ([], ["tensions.sto"])
    else:  # the tensions renamed, whole; without their stamp the trial is not done
        assert (final, temporary) == (["tensions.sto"],
                                      ["tensions.batch.json", "tensions_joint_loads.sto", "tensions_report.sto"])
    assert statuses(study) == ["ok"]
    assert final_and_temporary(root / "out" / "reach") == (
        ["tensions.batch.json", "tensions.sto", "tensions_joint_loads.sto", "tensions_report.sto"], [])
    assert output_files(root) == {name: content for name, content in output_files(reference).items()
                                  if name.startswith("out/reach/")}
