"""Forward dynamics against inverse dynamics (the round trip), and run_inverse_dynamics against
`sinew inverse-dynamics` on the same model and motion."""
import numpy as np
import pytest

import sinew
from conftest import ARM26_YAML, run_cli


def random_state(model, seed):
    rng = np.random.default_rng(seed)
    q = sinew.integrate_coordinates(model, model.default_q, rng.uniform(-0.5, 0.5, model.nu), 1.0)
    return q, rng.uniform(-1, 1, model.nu), rng


def test_forward_and_inverse_dynamics_round_trip(arm26):
    fd = sinew.ForwardDynamics(arm26)
    for seed in range(5):
        q, u, rng = random_state(arm26, seed)
        tau = rng.uniform(-5, 5, arm26.nu)
        forces = rng.uniform(-2, 2, (arm26.num_links, 6))
        udot = fd.calc(q, u, tau, forces)
        back = sinew.calc_inverse_dynamics(arm26, q, u, udot, forces)
        np.testing.assert_allclose(back, tau, rtol=0, atol=1e-10 * (1 + np.abs(tau).max()))


def test_whole_body_forward_dynamics_with_its_loop_forces_round_trips(whole_body):
    # Inverse dynamics ignores loops, so the loop forces forward dynamics reports (on link B at its loop point,
    # the opposite on link A) go back in as applied forces; the default pose has the loops closed.
    model = whole_body
    assert model.num_loops == 4
    q = model.default_q.copy()
    R, p = sinew.calc_link_poses(model, q)
    virtual = np.zeros(model.nu, bool)
    for link, joint in zip(model.links, model.joints):
        if link.is_virtual:
            virtual[joint.u_start:joint.u_start + joint.nu] = True
    rng = np.random.default_rng(1)
    u = np.where(virtual, 0.0, rng.uniform(-1, 1, model.nu))
    tau = np.where(virtual, 0.0, rng.uniform(-1, 1, model.nu))
    fd = sinew.ForwardDynamics(model)
    udot = fd.calc(q, u, tau)
    assert np.all(udot[virtual] == 0) and fd.loop_forces.shape == (4, 3)
    applied = np.zeros((model.num_links, 6))
    for loop, force in zip(model.loops, fd.loop_forces):
        for link, point, sign in ((loop.link_b, loop.p_B, 1), (loop.link_a, loop.p_A, -1)):
            applied[link, :3] += sign * np.cross(R[link] @ point, force)  # moment about the link origin
            applied[link, 3:] += sign * force
    assert np.abs(fd.loop_forces).max() > 1  # the loops carry load, so the check has teeth
    back = sinew.calc_inverse_dynamics(model, q, u, udot, applied)
    np.testing.assert_allclose(back, tau, rtol=0, atol=1e-9)


def test_hang_by_unknown_link_raises(arm26):
    with pytest.raises(sinew.Error, match="hang_by expects a link of model 'arm26', got 'head'"):
        sinew.ForwardDynamics(arm26, hang_by="head")


def write_arm26_motion(model, path, frames=41):
    """A smooth elbow flexion with the shoulder turning about a fixed axis (unit quaternions)."""
    t = np.linspace(0, 0.4, frames)
    angle = 0.4 * np.sin(2 * np.pi * t)
    axis = np.array([0.3, 0.2, 0.9]) / np.linalg.norm([0.3, 0.2, 0.9])
    data = np.zeros((frames, model.nq))
    names = model.coordinate_names
    quaternion = [names.index(f"r_shoulder_{c}") for c in ("qw", "qx", "qy", "qz")]
    data[:, quaternion[0]] = np.cos(angle / 2)
    data[:, quaternion[1:]] = np.outer(np.sin(angle / 2), axis)
    data[:, names.index("r_elbow")] = 1.0 + 0.5 * np.sin(2 * np.pi * 1.5 * t)
    sinew.write_storage_file(sinew.StorageTable(names, t, data, name="arm26 motion"), str(path))
    return path


def assert_tables_equal(ours, theirs, rtol=1e-12):
    assert ours.columns == theirs.columns
    np.testing.assert_array_equal(ours.times, theirs.times)
    scale = 1 + np.abs(theirs.data).max()
    np.testing.assert_allclose(ours.data, theirs.data, rtol=0, atol=rtol * scale)


def test_inverse_dynamics_matches_the_cli(tmp_path, arm26):
    motion = write_arm26_motion(arm26, tmp_path / "arm26_motion.mot")
    out = tmp_path / "id.sto"
    run_cli("inverse-dynamics", ARM26_YAML, motion, "--lowpass", "6", "-o", out)
    table = sinew.run_inverse_dynamics(arm26, sinew.read_storage_file(str(motion)), lowpass_cutoff_hz=6)
    assert_tables_equal(table, sinew.read_storage_file(str(out)))


def test_inverse_dynamics_of_opensim_arm26_matches_the_cli(tmp_path, opensim_arm26):
    model_path, motion = opensim_arm26 / "arm26.osim", opensim_arm26 / "arm26_InverseKinematics.mot"
    out = tmp_path / "id.sto"
    run_cli("inverse-dynamics", model_path, motion, "-o", out)
    table = sinew.run_inverse_dynamics(sinew.load_model(str(model_path)), sinew.read_storage_file(str(motion)))
    assert_tables_equal(table, sinew.read_storage_file(str(out)))
