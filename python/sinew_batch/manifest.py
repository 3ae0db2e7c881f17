"""The manifest: one row per trial (YAML or CSV with a header), checked in full before any trial runs, so a
typo in row 900 does not surface after 899 trials. Errors name the manifest's file:line and the field."""
import csv
import dataclasses
import math
import os
from typing import Optional

PIPELINES = ("inverse-dynamics", "tensions")
# The files each pipeline writes into the trial's output folder: the primary table first, then what
# `sinew tensions -o tensions.sto` writes beside it (activations for so, contact forces for a model with feet).
OUTPUT_FILES = {
    "inverse-dynamics": ("inverse_dynamics.sto",),
    "tensions": ("tensions.sto", "tensions_report.sto", "tensions_activations.sto", "tensions_contact.sto",
                 "tensions_joint_loads.sto", "tensions_ligament_stress.sto"),
}
TENSION_FIELDS = ("method", "max_tension", "tolerance", "contact")


class ManifestError(ValueError):
    """A manifest that cannot be run as written; the message names file:line and the field."""


@dataclasses.dataclass(frozen=True)
class Trial:
    """One manifest row, paths absolute. Plain data: it travels to process-pool and Dask workers."""
    name: str
    pipeline: str
    model: str
    motion: str
    output: str
    source: str  # manifest file:line, for messages
    external_loads: Optional[str] = None
    method: Optional[str] = None
    lowpass: Optional[float] = None
    start: Optional[float] = None
    end: Optional[float] = None
    max_tension: Optional[float] = None
    tolerance: Optional[float] = None
    contact: bool = True

    @property
    def output_files(self):
        return OUTPUT_FILES[self.pipeline]

    @property
    def stamp_file(self):
        """The resume stamp beside the outputs, named for the pipeline so that one folder can hold a motion's
        inverse dynamics and its tensions."""
        return os.path.splitext(self.output_files[0])[0] + ".batch.json"

    def options(self):
        """The row's settings that change the numbers (what the input digest covers besides the files)."""
        return {"pipeline": self.pipeline, "method": self.method, "lowpass": self.lowpass, "start": self.start,
                "end": self.end, "max_tension": self.max_tension, "tolerance": self.tolerance,
                "contact": self.contact if self.pipeline == "tensions" else None}


# Each field's reader: (value as YAML or CSV gives it, file:line, field name, manifest folder) -> value.
def _text(value, where, field, base):
    return str(value).strip()


def _number(value, where, field, positive):
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number) or isinstance(value, bool) or (positive and number <= 0):
        expected = "a number > 0" if positive else "a finite number"
        raise ManifestError(f"{where}: field '{field}' expects {expected}, got '{value}'")
    return number


def _finite(value, where, field, base):
    return _number(value, where, field, positive=False)


def _positive(value, where, field, base):
    return _number(value, where, field, positive=True)


def _boolean(value, where, field, base):
    if isinstance(value, bool):
        return value
    words = {"true": True, "yes": True, "1": True, "false": False, "no": False, "0": False}
    if str(value).strip().lower() not in words:
        raise ManifestError(f"{where}: field '{field}' expects true or false, got '{value}'")
    return words[str(value).strip().lower()]


def _path(value, where, field, base):
    if not isinstance(value, str) or not value.strip():
        raise ManifestError(f"{where}: field '{field}' expects a file or folder path, got '{value}'")
    return os.path.abspath(os.path.join(base, os.path.expanduser(value.strip())))


FIELDS = {"name": _text, "model": _path, "motion": _path, "external_loads": _path, "pipeline": _text,
          "method": _text, "lowpass": _positive, "start": _finite, "end": _finite, "max_tension": _positive,
          "tolerance": _positive, "contact": _boolean, "output": _path}


def make_trial(row, where, base):
    """A Trial from one row (a mapping of field to value; None or '' leaves a field unset)."""
    unknown = sorted(set(row) - set(FIELDS))
    if unknown:
        raise ManifestError(f"{where}: unknown field '{unknown[0]}' (fields: {', '.join(FIELDS)})")
    values = {field: FIELDS[field](value, where, field, base) for field, value in row.items()
              if value is not None and not (isinstance(value, str) and not value.strip())}
    for field in ("model", "motion", "pipeline", "output"):
        if field not in values:
            raise ManifestError(f"{where}: field '{field}' is missing")
    pipeline = values["pipeline"]
    if pipeline not in PIPELINES:
        raise ManifestError(f"{where}: field 'pipeline' expects {' or '.join(PIPELINES)}, got '{pipeline}'")
    if pipeline == "tensions" and "method" not in values:
        raise ManifestError(f"{where}: field 'method' is missing (tensions expects lp, qp, so or ipopt)")
    if pipeline == "inverse-dynamics":
        extra = [field for field in TENSION_FIELDS if field in values]
        if extra:
            raise ManifestError(f"{where}: field '{extra[0]}' applies to the tensions pipeline, not inverse-dynamics")
    if "start" in values and "end" in values and values["end"] <= values["start"]:
        raise ManifestError(f"{where}: field 'end' ({values['end']:g}) expects a time after start ({values['start']:g})")
    if "name" not in values:
        folder = os.path.relpath(values["output"], base)
        values["name"] = f"{folder}/{os.path.splitext(OUTPUT_FILES[pipeline][0])[0]}"
    return Trial(source=where, **values)


def _check_unique(trials):
    seen_names, seen_outputs = {}, {}
    for trial in trials:
        key = (trial.output, trial.pipeline)
        if key in seen_outputs:
            raise ManifestError(f"{trial.source}: output '{trial.output}' already holds the {trial.pipeline} of "
                                f"the trial at {seen_outputs[key]}")
        if trial.name in seen_names:
            raise ManifestError(f"{trial.source}: trial name '{trial.name}' is already used at {seen_names[trial.name]}")
        seen_names[trial.name] = seen_outputs[key] = trial.source


def _read_csv(path, base):
    trials = []
    with open(path, newline="", encoding="utf-8") as file:
        reader = csv.DictReader(file)
        if not reader.fieldnames:
            raise ManifestError(f"{path}:1: expected a header row naming the fields ({', '.join(FIELDS)})")
        for row in reader:
            where = f"{path}:{reader.line_num}"
            if None in row:
                raise ManifestError(f"{where}: {len(row) - 1 + len(row[None])} cells for a header of "
                                    f"{len(reader.fieldnames)} fields")
            if all(not (value or "").strip() for value in row.values()):
                continue
            trials.append(make_trial(row, where, base))
    return trials


class LinedDict(dict):
    """A YAML mapping with the manifest line it starts on."""
    line = 0


def _read_yaml(path, base):
    import yaml  # only YAML manifests need PyYAML

    class LineLoader(yaml.SafeLoader):
        """Remembers the line each mapping starts on, so that errors name the trial's line."""

    def mapping_with_line(loader, node):
        mapping = LinedDict(loader.construct_mapping(node, deep=True))
        mapping.line = node.start_mark.line + 1
        return mapping

    LineLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, mapping_with_line)
    with open(path, encoding="utf-8") as file:
        try:
            document = yaml.load(file, Loader=LineLoader)
        except yaml.YAMLError as error:
            raise ManifestError(f"{path}: not valid YAML: {error}") from None
    defaults, rows = {}, document
    if isinstance(document, dict):
        unknown = sorted(set(document) - {"defaults", "trials"})
        if unknown:
            raise ManifestError(f"{path}:{document.line}: unknown key '{unknown[0]}' (expected defaults and trials)")
        defaults, rows = document.get("defaults") or {}, document.get("trials")
        if not isinstance(defaults, dict):
            raise ManifestError(f"{path}:{document.line}: 'defaults' expects a mapping of field to value")
    if not isinstance(rows, list):
        raise ManifestError(f"{path}: expected a list of trials, or a mapping with 'trials:' (and 'defaults:')")
    trials = []
    for index, row in enumerate(rows):
        if not isinstance(row, dict):
            raise ManifestError(f"{path}: trial {index + 1} expects a mapping of field to value, got '{row}'")
        merged = {**defaults, **row}
        if str(merged.get("pipeline", "")).strip() == "inverse-dynamics":
            # a default's tension settings are for the tension rows; only a row's own are an error here
            merged = {field: value for field, value in merged.items() if field in row or field not in TENSION_FIELDS}
        trials.append(make_trial(merged, f"{path}:{row.line}", base))
    return trials


def load_manifest(path):
    """The trials of a .yaml/.yml or .csv manifest; relative paths are taken from the manifest's folder."""
    path = os.fspath(path)
    base = os.path.dirname(os.path.abspath(path))
    extension = os.path.splitext(path)[1].lower()
    if extension not in (".yaml", ".yml", ".csv"):
        raise ManifestError(f"{path}: expected a .yaml, .yml or .csv manifest")
    if not os.path.isfile(path):
        raise ManifestError(f"{path}: no such manifest")
    trials = _read_csv(path, base) if extension == ".csv" else _read_yaml(path, base)
    if not trials:
        raise ManifestError(f"{path}: no trials")
    _check_unique(trials)
    return trials
