"""simulate with either engine against `sinew simulate` (same options, same files' numbers), and the two
engines against each other."""
import numpy as np
import pytest

import sinew
from conftest import ARM26_YAML, run_cli


def options(duration=0.1):
    o = sinew.ForwardSimulationOptions()
    o.hang_by = "base"
    o.duration = duration
    o.integrator = sinew.Integrator.RungeKutta4Fixed
    o.fixed_step = 1e-3
    return o


@pytest.mark.parametrize("engine", ["sinew", "simbody"])
def test_simulation_matches_the_cli(tmp_path, arm26, engine):
    run_cli("simulate", ARM26_YAML, "--engine", engine, "--integrator", "rk4", "--step", "1e-3", "--hang-by", "base",
            "--duration", "0.1", "-o", tmp_path)
    result = sinew.simulate(arm26, options(), engine=engine)
    assert result.q.shape == (11, arm26.nq) and result.summary.frames == 11
    for name, ours in (("coordinates", result.q), ("speeds", result.u), ("tensions", result.tensions)):
        table = sinew.read_storage_file(str(next(tmp_path.glob(f"*_{name}.sto"))))
        np.testing.assert_allclose(table.times, result.time, rtol=0, atol=1e-15)
        np.testing.assert_allclose(ours, table.data, rtol=1e-12, atol=1e-12, err_msg=name)
    assert table.columns == arm26.wire_names


def test_the_engines_agree(arm26):
    ours = sinew.simulate(arm26, options(0.2), engine="sinew")
    theirs = sinew.simulate(arm26, options(0.2), engine="simbody")
    np.testing.assert_allclose(ours.q, theirs.q, rtol=0, atol=1e-6)
    np.testing.assert_allclose(ours.kinetic_energy, theirs.kinetic_energy, rtol=1e-5, atol=1e-9)


def test_unknown_engine_raises(arm26):
    with pytest.raises(sinew.Error, match="engine expects sinew or simbody, got 'warp'"):
        sinew.simulate(arm26, options(), engine="warp")
