"""One trial, run through the bindings exactly as `sinew inverse-dynamics` and `sinew tensions` run it (same
readers, options and writers, so the files are the CLI's byte for byte), or skipped when its stamp matches.
run_trial never raises for a trial's own failure: the error becomes the trial's record and the batch goes on."""
import functools
import time

import numpy as np

import sinew

from .input_digest import DIGEST_FORMAT, input_digest
from .output_set import OutputSet

# sinew tensions' status for a motion row with NaN or empty coordinates (tools/tension_motion.hpp)
MISSING_INPUT_STATUS = 3


@functools.lru_cache(maxsize=8)
def _load_model(path, sha256):
    """Models are immutable, so a worker reuses one across its trials; the content hash in the key makes an
    edited model file load again."""
    return sinew.load_model(path)


def _check_lowpass(cutoff, motion, path):
    """The CLI's --lowpass check (cli/arguments.cpp): the library would quietly lower such a cut-off."""
    if cutoff is None or len(motion.times) < 2:
        return
    nyquist = 0.5 / np.min(np.diff(motion.times))
    if cutoff >= nyquist:
        raise sinew.Error(f"lowpass {cutoff:g} Hz is at or above the Nyquist frequency {nyquist:g} Hz of {path} "
                          "(half its sampling rate, from its smallest time step)")


def _inverse_dynamics(trial, model, loads):
    motion = sinew.read_storage_file(trial.motion)
    _check_lowpass(trial.lowpass, motion, trial.motion)
    times = {key: value for key, value in (("start_time", trial.start), ("final_time", trial.end)) if value is not None}
    table = sinew.run_inverse_dynamics(model, motion, loads, lowpass_cutoff_hz=trial.lowpass or -1.0, **times)
    return {"inverse_dynamics.sto": table}, {"frames": len(table)}


def _worst_residual(report):
    """The largest |tau - produced| of any DOF on any frame that had input (unactuated DOFs included)."""
    data = report.data
    columns = [j for j, name in enumerate(report.columns) if name.endswith("_residual") and name != "unactuated_residual"]
    rows = data[:, report.columns.index("status")] != MISSING_INPUT_STATUS
    return float(np.abs(data[np.ix_(rows, columns)]).max()) if rows.any() and columns else 0.0


def _tensions(trial, model, loads):
    options = sinew.TensionMotionOptions()
    options.analysis.method = trial.method
    if trial.max_tension is not None:
        options.analysis.max_tension = np.full(model.num_wires, trial.max_tension)
    if trial.tolerance is not None:
        options.analysis.problem.torque_tolerance = trial.tolerance
    if trial.lowpass is not None:
        options.lowpass_cutoff_hz = trial.lowpass
    if trial.start is not None:
        options.start_time = trial.start
    if trial.end is not None:
        options.final_time = trial.end
    options.contact = trial.contact
    motion = sinew.read_storage_file(trial.motion, allow_non_finite=True)
    _check_lowpass(trial.lowpass, motion, trial.motion)
    result = sinew.run_tension_analysis(model, motion, loads, options=options)
    tables = {"tensions.sto": result.tensions, "tensions_report.sto": result.report}
    optional = (("tensions_activations.sto", result.activations), ("tensions_contact.sto", result.contact),
                ("tensions_joint_loads.sto", result.joint_loads), ("tensions_ligament_stress.sto", result.ligament_stress))
    for name, table in optional:
        if table.columns:
            tables[name] = table
    figures = {"frames": len(result.report), "infeasible_frames": result.infeasible_frames,
               "failed_frames": result.failed_frames, "missing_rows": len(result.missing_rows),
               "worst_residual": _worst_residual(result.report)}
    return tables, figures


PIPELINES = {"inverse-dynamics": _inverse_dynamics, "tensions": _tensions}


def _message(error):
    # sinew's messages name their file and line already; others get their type, which is often the clue
    return str(error) if isinstance(error, (sinew.Error, FileNotFoundError)) else f"{type(error).__name__}: {error}"


def trial_record(trial, status, **fields):
    return {"trial": trial.name, "pipeline": trial.pipeline, "method": trial.method, "output": trial.output,
            "status": status, **fields}


def run_trial(trial, force=False):
    """Runs `trial` unless (force off) its stamp matches its inputs; returns its record: trial, pipeline,
    method, output, status (ok, skipped or failed), the figures (frames, infeasible_frames, failed_frames,
    missing_rows, worst_residual, seconds) and, on failure, error."""
    started = time.perf_counter()
    try:
        loads = sinew.read_external_loads(trial.external_loads) if trial.external_loads else None
        digest, inputs = input_digest(trial, loads)
        outputs = OutputSet(trial)
        recorded = None if force else outputs.recorded_figures(digest)
        if recorded is not None:
            return trial_record(trial, "skipped", **recorded)
        model = _load_model(trial.model, inputs["model"]["sha256"])
        tables, figures = PIPELINES[trial.pipeline](trial, model, loads)
        figures["seconds"] = time.perf_counter() - started
        outputs.commit(tables, {"format": DIGEST_FORMAT, "trial": trial.name, "input_sha256": digest,
                                "inputs": inputs, "options": trial.options(), "figures": figures})
        return trial_record(trial, "ok", **figures)
    except Exception as error:  # the trial's failure is its record; the batch goes on
        return trial_record(trial, "failed", error=_message(error), seconds=time.perf_counter() - started)
