"""TensionAnalysis per frame against inverse dynamics and the one-pass wire forces (the tensions must
produce tau less the reported residual), and run_tension_analysis against `sinew tensions`."""
import numpy as np
import pytest

import sinew
from conftest import ARM26_YAML, run_cli
from test_dynamics import write_arm26_motion


@pytest.mark.parametrize("method", ["lp", "qp", "so"])
def test_frame_tensions_reproduce_the_inverse_dynamics_torques(arm26, method):
    options = sinew.TensionAnalysisOptions()
    options.method = method
    options.max_tension = np.full(arm26.num_wires, 2000.0)
    options.use_muscle_physiology = False
    analysis = sinew.TensionAnalysis(arm26, options)
    assert analysis.solves_activations == (method == "so")
    rng = np.random.default_rng(7)
    for _ in range(10):
        q = rng.uniform(0.2, 1.2, arm26.nq)
        u, udot = rng.uniform(-1, 1, arm26.nu), rng.uniform(-1, 1, arm26.nu)
        frame = analysis.calc_frame(q, u, udot)
        tau = sinew.calc_inverse_dynamics(arm26, q, u, udot)
        np.testing.assert_allclose(frame.tau, tau, rtol=0, atol=1e-12 * (1 + np.abs(tau).max()))
        produced = sinew.calc_wire_generalized_forces(arm26, q, frame.tension)
        np.testing.assert_allclose(tau - produced, frame.residual, rtol=0, atol=1e-8 * (1 + np.abs(tau).max()))
        assert frame.torque_error == pytest.approx(0.5 * np.sum((tau - produced) ** 2), abs=1e-9 * (1 + tau @ tau))
        assert np.all(frame.tension >= -1e-9) and np.all(frame.tension <= 2000 + 1e-6)
        assert frame.unactuated.dtype == bool and not frame.unactuated.any()


def test_frame_on_the_whole_body_leaves_the_root_as_residual(whole_body):
    model = whole_body
    options = sinew.TensionAnalysisOptions()
    options.max_tension = np.full(model.num_wires, 5000.0)  # qp
    analysis = sinew.TensionAnalysis(model, options)
    q, u, udot = model.default_q, np.zeros(model.nu), np.zeros(model.nu)
    frame = analysis.calc_frame(q, u, udot)
    assert frame.status == sinew.DistributionStatus.Optimal and frame.tension.shape == (model.num_wires,)
    tau = sinew.calc_inverse_dynamics(model, q, u, udot)
    np.testing.assert_array_equal(frame.tau, tau)
    # The floating root and the virtual links' own DOFs are unactuated. The loop forces are internal to the
    # body, so on those DOFs the residual is what the wires leave of tau, and nothing else.
    assert frame.unactuated.sum() >= 6
    produced = sinew.calc_wire_generalized_forces(model, q, frame.tension)
    np.testing.assert_allclose((tau - produced)[frame.unactuated], frame.residual[frame.unactuated],
                               rtol=0, atol=1e-8 * (1 + np.abs(tau).max()))
    assert np.abs(frame.residual[frame.unactuated]).max() > 1  # the body's weight, held by no wire


def test_bad_method_raises_sinew_error(arm26):
    options = sinew.TensionAnalysisOptions()
    options.method = "simplex-of-dreams"
    with pytest.raises(sinew.Error, match="simplex-of-dreams"):
        sinew.TensionAnalysis(arm26, options)


def compare_with_cli(tmp_path, model_path, motion, method, max_tension=None):
    """run_tension_analysis and `sinew tensions` on the same files: the same tables, to the files' digits."""
    out = tmp_path / "tensions.sto"
    run_cli("tensions", model_path, motion, "--method", method, "-o", out,
            *(["--max-tension", max_tension] if max_tension else []))
    model = sinew.load_model(str(model_path))
    options = sinew.TensionMotionOptions()
    options.analysis.method = method
    if max_tension:
        options.analysis.max_tension = np.full(model.num_wires, float(max_tension))
    result = sinew.run_tension_analysis(model, sinew.read_storage_file(str(motion), allow_non_finite=True),
                                        options=options)
    files = [(result.tensions, out), (result.report, tmp_path / "tensions_report.sto")]
    if method == "so":
        files.append((result.activations, tmp_path / "tensions_activations.sto"))
    for ours, file in files:
        theirs = sinew.read_storage_file(str(file))
        assert ours.columns == theirs.columns
        np.testing.assert_array_equal(ours.times, theirs.times)
        np.testing.assert_allclose(ours.data, theirs.data, rtol=1e-12, atol=1e-12, err_msg=str(file))
    summary = sinew.summarize_tension_motion(model, result)
    assert summary.frames == len(result.tensions) and summary.solved_frames == summary.frames
    return result


@pytest.mark.parametrize("method", ["lp", "qp"])
def test_motion_tensions_match_the_cli(tmp_path, arm26, method):
    motion = write_arm26_motion(arm26, tmp_path / "arm26_motion.mot", frames=21)
    result = compare_with_cli(tmp_path, ARM26_YAML, motion, method, max_tension="2000")
    assert len(result.tensions) == 21 and result.tensions.columns == arm26.wire_names


def test_static_optimization_of_opensim_arm26_matches_the_cli(tmp_path, opensim_arm26):
    # OpenSim's arm26 has Thelen muscles, which static optimization's muscle physiology needs
    result = compare_with_cli(tmp_path, opensim_arm26 / "arm26.osim", opensim_arm26 / "arm26_InverseKinematics.mot", "so")
    assert result.activations.columns == result.tensions.columns
