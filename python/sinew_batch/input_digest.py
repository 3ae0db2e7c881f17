"""What a trial's outputs depend on, as one SHA-256: the contents (not the paths or times) of the model, motion
and external loads files (the loads' XML and the data file it names), and the row's settings. Moving a study
folder or touching a file without changing it reruns nothing; editing any byte of an input reruns the trial."""
import hashlib
import json
import os

# Raised when the digest's recipe changes, so that every stamp written before is out of date.
DIGEST_FORMAT = 2  # 2: tension trials write joint loads and ligament stress too


def file_sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as file:
        for block in iter(lambda: file.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def input_files(trial, loads):
    """Role -> path of every file the trial reads; `loads` is the trial's sinew.ExternalLoads or None."""
    files = {"model": trial.model, "motion": trial.motion}
    if loads is not None:
        files["external_loads"] = trial.external_loads
        files["external_loads_data"] = os.fspath(loads.data_file)
    return files


def input_digest(trial, loads):
    """(digest, inputs): the hex SHA-256 over the inputs, and role -> {path, sha256} for the stamp."""
    inputs = {}
    for role, path in input_files(trial, loads).items():
        if not os.path.isfile(path):
            raise FileNotFoundError(f"{trial.source}: {role} file '{path}' does not exist")
        inputs[role] = {"path": path, "sha256": file_sha256(path)}
    recipe = {"format": DIGEST_FORMAT, "options": trial.options(),
              "files": {role: entry["sha256"] for role, entry in inputs.items()}}
    return hashlib.sha256(json.dumps(recipe, sort_keys=True).encode()).hexdigest(), inputs
