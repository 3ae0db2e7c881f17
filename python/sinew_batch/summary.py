"""The batch's summary: one row per trial, in manifest order, printed as a table and written as CSV."""
import csv
import os

COLUMNS = ("trial", "pipeline", "method", "status", "frames", "infeasible_frames", "failed_frames", "missing_rows",
           "worst_residual", "seconds", "output", "error")
# Printed columns (the CSV has them all); the error goes on a line of its own under the table.
TABLE_COLUMNS = ("trial", "pipeline", "method", "status", "frames", "infeasible_frames", "worst_residual", "seconds")
HEADINGS = {"infeasible_frames": "infeasible", "worst_residual": "worst residual"}


def _cell(record, column):
    value = record.get(column)
    if value is None:
        return ""
    if column == "seconds":
        return f"{value:.3f}"
    if column == "worst_residual":
        return f"{value:.4g}"
    return str(value)


def counts(records):
    """status -> number of trials."""
    tally = {"ok": 0, "skipped": 0, "failed": 0}
    for record in records:
        tally[record["status"]] += 1
    return tally


def format_table(records, seconds):
    rows = [[HEADINGS.get(column, column) for column in TABLE_COLUMNS]]
    rows += [[_cell(record, column) for column in TABLE_COLUMNS] for record in records]
    widths = [max(len(row[j]) for row in rows) for j in range(len(TABLE_COLUMNS))]
    lines = ["  ".join(text.ljust(width) for text, width in zip(row, widths)).rstrip() for row in rows]
    lines.insert(1, "  ".join("-" * width for width in widths))
    lines += [f"{record['trial']}: {record['error']}" for record in records if record["status"] == "failed"]
    tally = counts(records)
    lines.append(f"{len(records)} trials: {tally['ok']} ran, {tally['skipped']} skipped (outputs up to date), "
                 f"{tally['failed']} failed; {seconds:.2f} s")
    return "\n".join(lines)


def write_summary_csv(records, path):
    """Written to a temporary beside `path`, then renamed, as the trials' outputs are."""
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    temporary = f"{path}.incomplete-{os.getpid()}"
    try:
        with open(temporary, "w", newline="", encoding="utf-8") as file:
            writer = csv.writer(file)
            writer.writerow(COLUMNS)
            for record in records:
                writer.writerow([record.get(column) if record.get(column) is not None else "" for column in COLUMNS])
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise
