"""python3 -m sinew_batch MANIFEST [--dask ADDRESS | --workers N] [-o SUMMARY.csv] [--force]"""
import argparse
import sys

from .batch import default_summary_path, run_batch
from .manifest import ManifestError
from .summary import counts

DESCRIPTION = """Runs every trial of a manifest (YAML or CSV, one row per trial: model, motion, external_loads,
pipeline inverse-dynamics or tensions, method lp|qp|so|ipopt, lowpass, start, end, max_tension, tolerance,
contact, output folder) through sinew, skipping trials whose outputs are up to date with their inputs, and
prints and writes a summary per trial. Exit status 0 when no trial failed, 1 when one did, 2 for a manifest
that cannot be run. See docs/batch.md."""


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m sinew_batch", description=DESCRIPTION)
    parser.add_argument("manifest", help="the manifest, .yaml/.yml or .csv")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--dask", metavar="ADDRESS",
                       help="a Dask scheduler to submit one task per trial to (tcp://host:8786); its workers need "
                            "sinew and sinew_batch importable and the files at the same paths")
    where.add_argument("--workers", type=int, default=1, metavar="N",
                       help="local worker processes (default 1: this process)")
    parser.add_argument("-o", "--output", metavar="SUMMARY.csv",
                        help="the summary (default: MANIFEST_summary.csv beside the manifest)")
    parser.add_argument("--force", action="store_true", help="run every trial, up to date or not")
    args = parser.parse_args(argv)
    if args.workers < 1:
        parser.error(f"--workers expects at least 1, got {args.workers}")
    try:
        records = run_batch(args.manifest, summary=args.output or default_summary_path(args.manifest),
                            workers=args.workers, dask=args.dask, force=args.force)
    except ManifestError as error:
        print(f"sinew_batch: {error}", file=sys.stderr)
        return 2
    return 1 if counts(records)["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
