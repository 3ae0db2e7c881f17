"""sinew_batch: many trials of inverse dynamics and tensions through the `sinew` module, resumable, locally or
on a Dask cluster (docs/batch.md). `python3 -m sinew_batch MANIFEST` runs a manifest from the shell."""
from .batch import run_batch
from .manifest import ManifestError, Trial, load_manifest
from .summary import counts
from .trial import run_trial

__all__ = ["ManifestError", "Trial", "counts", "load_manifest", "run_batch", "run_trial"]
