"""Link poses, wire lengths and speeds and the wire Jacobian, each against something computed another way:
central finite differences of the lengths along q (on the configuration manifold), J u against the wire
speeds, -J^T f against the one-pass generalized forces, and the pin joint's rotation against its angle."""
import numpy as np
import pytest

import sinew


def random_state(model, seed):
    rng = np.random.default_rng(seed)
    u = rng.uniform(-1, 1, model.nu)
    # a pose near the default one, reached along the manifold so quaternions stay unit
    q = sinew.integrate_coordinates(model, model.default_q, rng.uniform(-0.3, 0.3, model.nu), 1.0)
    return q, u


def finite_difference_jacobian(model, q, h=1e-6):
    J = np.empty((model.num_wires, model.nu))
    for k in range(model.nu):
        e = np.zeros(model.nu)
        e[k] = 1
        plus = sinew.calc_wire_lengths(model, sinew.integrate_coordinates(model, q, e, h))
        minus = sinew.calc_wire_lengths(model, sinew.integrate_coordinates(model, q, e, -h))
        J[:, k] = (plus - minus) / (2 * h)
    return J


@pytest.mark.parametrize("name", ["arm26", "whole_body"])
def test_jacobian_matches_finite_differences_of_lengths(name, request):
    model = request.getfixturevalue(name)
    q, _ = random_state(model, 11)
    J = sinew.calc_wire_jacobian(model, q)
    assert J.shape == (model.num_wires, model.nu)
    error = np.abs(J - finite_difference_jacobian(model, q))
    # central differences at h = 1e-6: truncation ~ h^2 |l'''|, roundoff ~ 1e-16 l / h
    assert error.max() < 1e-8 * (1 + np.abs(J).max()), (error.max(), np.unravel_index(error.argmax(), error.shape))


@pytest.mark.parametrize("name", ["arm26", "whole_body"])
def test_jacobian_times_u_is_the_wire_speed_and_its_transpose_the_wire_forces(name, request):
    model = request.getfixturevalue(name)
    q, u = random_state(model, 5)
    J = sinew.calc_wire_jacobian(model, q)
    speeds = sinew.calc_wire_speeds(model, q, u)
    np.testing.assert_allclose(J @ u, speeds, rtol=0, atol=1e-12 * (1 + np.abs(speeds).max()))
    f = np.random.default_rng(2).uniform(0, 100, model.num_wires)
    tau = sinew.calc_wire_generalized_forces(model, q, f)
    np.testing.assert_allclose(tau, -J.T @ f, rtol=0, atol=1e-10 * (1 + np.abs(tau).max()))


def test_link_poses_follow_the_joints(arm26):
    q = arm26.default_q.copy()
    R, p = sinew.calc_link_poses(arm26, q)
    assert R.shape == (3, 3, 3) and p.shape == (3, 3)
    # the base is welded to ground at parent_point [0, 0.8, 0] (models/arm26.yaml)
    np.testing.assert_array_equal(p[arm26.find_link("base")], [0, 0.8, 0])
    for Ri in R:
        np.testing.assert_allclose(Ri.T @ Ri, np.eye(3), atol=1e-14)
    # turning the elbow (a pin) by d turns the forearm relative to the humerus by d about a fixed axis
    humerus, forearm = arm26.find_link("r_humerus"), arm26.find_link("r_ulna_radius_hand")
    d = 0.3
    q2 = q.copy()
    q2[arm26.find_coordinate("r_elbow")] += d
    R2, p2 = sinew.calc_link_poses(arm26, q2)
    turn = (R2[humerus].T @ R2[forearm]) @ (R[humerus].T @ R[forearm]).T
    assert np.arccos((np.trace(turn) - 1) / 2) == pytest.approx(d, abs=1e-12)
    np.testing.assert_array_equal(p2[humerus], p[humerus])
