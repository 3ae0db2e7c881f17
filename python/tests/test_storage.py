"""read_storage_file / write_storage_file against a plain-text parse of the same files (written here by
hand, or by the CLI), and the error path naming file:line."""
import numpy as np
import pytest

import sinew
from conftest import ARM26_YAML, run_cli


def parse_by_hand(path):
    """Labels and the numeric table after `endheader`, with no help from sinew."""
    lines = path.read_text().splitlines()
    start = next(i for i, l in enumerate(lines) if l.strip() == "endheader") + 1
    labels = lines[start].split("\t")
    values = np.array([[float(x) for x in l.split("\t")] for l in lines[start + 1:] if l.strip()])
    return labels, values


def test_reads_a_hand_written_file(tmp_path):
    path = tmp_path / "hand.mot"
    path.write_text("hand\nversion=1\nnRows=3\nnColumns=3\ninDegrees=yes\nendheader\n"
                    "time\ta\tb\n0\t1.5\t-2\n0.01\t2.5\t-3\n0.02\t3.5\t1e-3\n")
    table = sinew.read_storage_file(str(path))
    assert table.name == "hand" and table.in_degrees and table.columns == ["a", "b"]
    np.testing.assert_array_equal(table.times, [0, 0.01, 0.02])
    np.testing.assert_array_equal(table.data, [[1.5, -2], [2.5, -3], [3.5, 1e-3]])
    np.testing.assert_array_equal(table.column("b"), [-2, -3, 1e-3])
    assert len(table) == 3 and table.where.endswith("hand.mot:7")


def test_written_file_reads_back_bit_for_bit(tmp_path):
    rng = np.random.default_rng(3)
    data = rng.normal(size=(7, 4)) * 10.0 ** rng.integers(-8, 8, size=(7, 4))
    table = sinew.StorageTable(["w", "x", "y", "z"], np.linspace(0, 0.06, 7), data, name="random")
    path = tmp_path / "random.sto"
    sinew.write_storage_file(table, str(path))
    labels, values = parse_by_hand(path)
    assert labels == ["time", "w", "x", "y", "z"]
    np.testing.assert_array_equal(values[:, 1:], data)
    back = sinew.read_storage_file(str(path))
    np.testing.assert_array_equal(back.data, data)
    np.testing.assert_array_equal(back.times, table.times)


def test_reads_what_the_cli_writes(tmp_path):
    run_cli("simulate", ARM26_YAML, "--engine", "sinew", "--hang-by", "base", "--duration", "0.02", "-o", tmp_path)
    path = next(tmp_path.glob("*_coordinates.sto"))
    labels, values = parse_by_hand(path)
    table = sinew.read_storage_file(str(path))
    assert ["time"] + table.columns == labels
    np.testing.assert_array_equal(np.column_stack([table.times, table.data]), values)


def test_malformed_row_names_file_and_line(tmp_path):
    path = tmp_path / "bad.sto"
    path.write_text("bad\nversion=1\nnRows=2\nnColumns=2\nendheader\ntime\ta\n0\t1\n0.01\tpear\n")
    with pytest.raises(sinew.Error, match="bad.sto:8"):
        sinew.read_storage_file(str(path))
    with pytest.raises(sinew.Error, match="nope"):
        sinew.StorageTable(["a"], [0.0], [[1.0]]).column("nope")


def test_non_finite_cells_refused_unless_allowed(tmp_path):
    path = tmp_path / "gap.sto"
    path.write_text("gap\nversion=1\nnRows=2\nnColumns=2\nendheader\ntime\ta\n0\t1\n0.01\tnan\n")
    with pytest.raises(sinew.Error, match="gap.sto:8"):
        sinew.read_storage_file(str(path))
    assert np.isnan(sinew.read_storage_file(str(path), allow_non_finite=True).data[1, 0])
