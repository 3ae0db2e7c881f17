"""A progress bar on stderr: redrawn in place on a terminal, one line per finished trial otherwise (a log)."""
import sys


class Progress:
    def __init__(self, total, stream=None):
        self.total, self.done, self.failed, self.skipped = total, 0, 0, 0
        self.stream = stream or sys.stderr
        self.terminal = self.stream.isatty()

    def update(self, record):
        self.done += 1
        self.failed += record["status"] == "failed"
        self.skipped += record["status"] == "skipped"
        if self.terminal:
            filled = round(30 * self.done / self.total)
            self.stream.write(f"\r[{'#' * filled}{'.' * (30 - filled)}] {self.done}/{self.total} trials, "
                              f"{self.skipped} skipped, {self.failed} failed")
        else:
            took = "" if record["status"] == "skipped" else f" ({record['seconds']:.2f} s)"
            self.stream.write(f"[{self.done}/{self.total}] {record['trial']}: {record['status']}{took}\n")
        self.stream.flush()

    def finish(self):
        if self.terminal:
            self.stream.write("\n")
            self.stream.flush()
