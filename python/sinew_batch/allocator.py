"""glibc's allocator on a Dask worker. Dask's nanny starts its workers with MALLOC_TRIM_THRESHOLD_=65536
(distributed.nanny.pre-spawn-environ, to hand freed memory back to the system). Setting any such threshold
turns off glibc's adaptive mmap threshold, so every block above 128 KiB is mapped and unmapped again: Clp
frees and reallocates its factorisation arrays at every refactorisation, and a tension trial of the kick made
about 1,400 such pairs per 0.5 s window and ran 10-15 % slower than the same trial in a plain process. A
worker that runs sinew's trials keeps those blocks on its heap instead, and gives memory back above 64 MiB."""
import ctypes
import ctypes.util

_M_TRIM_THRESHOLD = -1
_M_MMAP_THRESHOLD = -3
_tuned = False


def keep_freed_memory():
    """Once per process; a no-op where the C library has no mallopt (not glibc). Returns whether it is set."""
    global _tuned
    if _tuned:
        return True
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    _tuned = bool(mallopt(_M_MMAP_THRESHOLD, 32 << 20)) and bool(mallopt(_M_TRIM_THRESHOLD, 64 << 20))
    return _tuned
