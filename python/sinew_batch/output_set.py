"""A trial's output folder: its tables written as one set, then its stamp, the resume record.

Every table is first written under a temporary name beside its final one ("<name>.incomplete-<pid>", as
io/atomic_file.hpp names its temporaries), and only when all are complete is the old stamp removed, the tables
renamed into place (os.replace: atomic on one file system), the files this run does not produce removed, and
the new stamp written the same way, last. A worker killed at any point therefore leaves no partial file under
a final name, and a folder whose tables changed without their stamp lands reads as not done: the next run
redoes that trial. Temporaries a killed worker left behind are removed when the trial next runs."""
import glob
import json
import os

import sinew

from .input_digest import DIGEST_FORMAT, file_sha256


def _temporary(path):
    return f"{path}.incomplete-{os.getpid()}"


def _remove(path):
    try:
        os.remove(path)
    except FileNotFoundError:
        pass


class OutputSet:
    def __init__(self, trial):
        self.folder = trial.output
        self.names = trial.output_files
        self.stamp_path = os.path.join(self.folder, trial.stamp_file)

    def recorded_figures(self, digest):
        """The figures the stamp recorded when its inputs digest to `digest` and every output it lists is
        there with the content it had; None when the trial has to run."""
        try:
            with open(self.stamp_path, encoding="utf-8") as file:
                stamp = json.load(file)
        except (OSError, ValueError):
            return None
        if stamp.get("format") != DIGEST_FORMAT or stamp.get("input_sha256") != digest:
            return None
        for name, sha256 in stamp.get("outputs", {}).items():
            path = os.path.join(self.folder, name)
            if not os.path.isfile(path) or file_sha256(path) != sha256:
                return None
        return stamp.get("figures")

    def commit(self, tables, stamp):
        """Writes `tables` (file name -> sinew.StorageTable, names from the trial's output files) and then
        `stamp` (a JSON-able dict, given the outputs' hashes here)."""
        os.makedirs(self.folder, exist_ok=True)
        for name in (*self.names, os.path.basename(self.stamp_path)):
            for left in glob.glob(glob.escape(os.path.join(self.folder, name)) + ".incomplete-*"):
                _remove(left)
        staged = []
        try:
            for name, table in tables.items():
                final = os.path.join(self.folder, name)
                staged.append((_temporary(final), final))
                sinew.write_storage_file(table, staged[-1][0])
            stamp = {**stamp, "outputs": {os.path.basename(final): file_sha256(temporary) for temporary, final in staged}}
            stamp_temporary = _temporary(self.stamp_path)
            staged.append((stamp_temporary, self.stamp_path))
            with open(stamp_temporary, "w", encoding="utf-8") as file:
                json.dump(stamp, file, indent=1, sort_keys=True)
                file.write("\n")
        except BaseException:
            for temporary, _ in staged:
                _remove(temporary)
            raise
        # From the stamp's removal to its replacement the folder holds no stamp: an interruption in between
        # leaves whole files that the next run redoes.
        _remove(self.stamp_path)
        for temporary, final in staged[:-1]:
            os.replace(temporary, final)
        for name in self.names:
            if name not in tables:
                _remove(os.path.join(self.folder, name))
        os.replace(stamp_temporary, self.stamp_path)
