"""sinew_batch manifests: a CSV and a YAML manifest of the same study give the same trials, relative paths are
taken from the manifest's folder, and a bad row stops the batch with an error naming file:line and field."""
import pytest

import sinew_batch
from sinew_batch import ManifestError

YAML = """\
defaults:
  model: ../models/arm26.yaml
  pipeline: tensions
  contact: no
trials:
  - motion: motions/elbow.mot
    pipeline: inverse-dynamics
    external_loads: loads/hand_push.xml
    lowpass: 6
    output: out/elbow
  - {motion: motions/elbow.mot, method: lp, max_tension: 2000, output: out/elbow}
  - {name: reach qp, motion: /data/reach.mot, method: qp, start: 0.1, end: 0.3, tolerance: 0.01, contact: yes,
     output: out/reach}
"""

CSV = """\
name,model,motion,external_loads,pipeline,method,lowpass,start,end,max_tension,tolerance,contact,output
,../models/arm26.yaml,motions/elbow.mot,loads/hand_push.xml,inverse-dynamics,,6,,,,,,out/elbow
,../models/arm26.yaml,motions/elbow.mot,,tensions,lp,,,,2000,,false,out/elbow

reach qp,../models/arm26.yaml,/data/reach.mot,,tensions,qp,,0.1,0.3,,0.01,,out/reach
"""


def test_csv_and_yaml_manifests_give_the_same_trials(tmp_path):
    study = tmp_path / "study"
    study.mkdir()
    (study / "batch.yaml").write_text(YAML)
    (study / "batch.csv").write_text(CSV)
    from_yaml = sinew_batch.load_manifest(study / "batch.yaml")
    from_csv = sinew_batch.load_manifest(study / "batch.csv")
    strip = lambda trials: [{**vars(t), "source": None} for t in trials]  # noqa: E731 (only the lines differ)
    assert strip(from_yaml) == strip(from_csv)
    first, second, third = from_yaml
    assert first.model == str(tmp_path / "models" / "arm26.yaml")
    assert first.external_loads == str(study / "loads" / "hand_push.xml")
    assert (first.name, first.pipeline, first.lowpass, first.method) == (
        "out/elbow/inverse_dynamics", "inverse-dynamics", 6, None)
    assert (second.name, second.contact, second.max_tension) == ("out/elbow/tensions", False, 2000)
    assert (third.name, third.motion, third.start, third.end, third.contact) == (
        "reach qp", "/data/reach.mot", 0.1, 0.3, True)
    assert [t.source for t in from_yaml] == [f"{study / 'batch.yaml'}:{line}" for line in (6, 11, 12)]
    assert [t.source for t in from_csv] == [f"{study / 'batch.csv'}:{line}" for line in (2, 3, 5)]
    assert first.stamp_file == "inverse_dynamics.batch.json" and second.stamp_file == "tensions.batch.json"
    # the digest covers the settings that change numbers, not the name
    assert first.options() != second.options() and "name" not in third.options()


ROW = "  - {motion: a.mot, pipeline: tensions, method: qp, output: out/a}\n"


@pytest.mark.parametrize("trials, line, message", [
    ("  - {motion: a.mot, pipeline: tensions, method: qp, output: out/a, lowpas: 6}\n", 4, "unknown field 'lowpas'"),
    ("  - {pipeline: tensions, method: qp, output: out/a}\n", 4, "field 'motion' is missing"),
    ("  - {motion: a.mot, pipeline: tensions, output: out/a}\n", 4, "field 'method' is missing"),
    ("  - {motion: a.mot, pipeline: statics, output: out/a}\n", 4,
     "field 'pipeline' expects inverse-dynamics or tensions, got 'statics'"),
    ("  - {motion: a.mot, pipeline: inverse-dynamics, method: qp, output: out/a}\n", 4,
     "field 'method' applies to the tensions pipeline, not inverse-dynamics"),
    ("  - {motion: a.mot, pipeline: tensions, method: qp, lowpass: -6, output: out/a}\n", 4,
     "field 'lowpass' expects a number > 0, got '-6'"),
    ("  - {motion: a.mot, pipeline: tensions, method: qp, start: soon, output: out/a}\n", 4,
     "field 'start' expects a finite number, got 'soon'"),
    ("  - {motion: a.mot, pipeline: tensions, method: qp, start: 0.3, end: 0.1, output: out/a}\n", 4,
     "field 'end' (0.1) expects a time after start (0.3)"),
    ("  - {motion: a.mot, pipeline: tensions, method: qp, contact: maybe, output: out/a}\n", 4,
     "field 'contact' expects true or false, got 'maybe'"),
    (ROW + "  - {motion: b.mot, pipeline: tensions, method: lp, output: out/a}\n", 5,
     "already holds the tensions of the trial at"),
    (ROW + "  - {name: out/a/tensions, motion: b.mot, pipeline: tensions, method: lp, output: out/b}\n", 5,
     "trial name 'out/a/tensions' is already used at"),
])
def test_bad_rows_are_refused_at_their_line(tmp_path, trials, line, message):
    path = tmp_path / "batch.yaml"
    path.write_text("defaults:\n  model: m.yaml\ntrials:\n" + trials)
    with pytest.raises(ManifestError) as error:
        sinew_batch.load_manifest(path)
    assert str(error.value).startswith(f"{path}:{line}: ") and message in str(error.value), str(error.value)


def test_bad_csv_rows_are_refused_at_their_line(tmp_path):
    path = tmp_path / "batch.csv"
    path.write_text("model,motion,pipeline,method,output\n"
                    "m.yaml,a.mot,tensions,qp,out/a\n"
                    "m.yaml,b.mot,tensions,qp,out/b,extra\n")
    with pytest.raises(ManifestError, match=r"batch.csv:3: 6 cells for a header of 5 fields"):
        sinew_batch.load_manifest(path)


@pytest.mark.parametrize("text, message", [
    ("trials: {motion: a.mot}\n", "expected a list of trials"),
    ("defaults: {}\nruns: []\n", ":1: unknown key 'runs'"),
    ("trials: [\n", "not valid YAML"),
    ("trials: []\n", "no trials"),
])
def test_bad_manifests_are_refused(tmp_path, text, message):
    path = tmp_path / "batch.yaml"
    path.write_text(text)
    with pytest.raises(ManifestError, match=message):
        sinew_batch.load_manifest(path)
