"""sinew_batch.allocator against glibc's own count of mapped blocks (mallinfo2().hblks), in a process started
as Dask's nanny starts a worker (MALLOC_TRIM_THRESHOLD_=65536): a 1 MiB block is mapped before the tuning and
comes from the heap after it."""
import ctypes
import os
import subprocess
import sys

import pytest

PROBE = r"""
import ctypes
from sinew_batch.allocator import keep_freed_memory

class MallInfo2(ctypes.Structure):
    _fields_ = [(name, ctypes.c_size_t) for name in
                ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks", "fordblks", "keepcost")]

libc = ctypes.CDLL("libc.so.6")
libc.mallinfo2.restype = MallInfo2
libc.malloc.restype = ctypes.c_void_p
libc.malloc.argtypes = [ctypes.c_size_t]
libc.free.argtypes = [ctypes.c_void_p]

def blocks_mapped_for(size):
    block = libc.malloc(size)
    holding = libc.mallinfo2().hblks
    libc.free(block)
    return holding - libc.mallinfo2().hblks

before = blocks_mapped_for(1 << 20)
assert keep_freed_memory() and keep_freed_memory()
after = blocks_mapped_for(1 << 20)
print(before, after)
"""


def glibc_has_mallinfo2():
    try:
        return hasattr(ctypes.CDLL("libc.so.6"), "mallinfo2")
    except OSError:
        return False


@pytest.mark.skipif(not glibc_has_mallinfo2(), reason="needs glibc >= 2.33 (mallinfo2) to count mapped blocks")
def test_a_dask_worker_keeps_large_blocks_on_its_heap():
    env = dict(os.environ, MALLOC_TRIM_THRESHOLD_="65536")
    env["PYTHONPATH"] = os.pathsep.join(sys.path)
    out = subprocess.run([sys.executable, "-c", PROBE], env=env, capture_output=True, text=True, check=True).stdout
    before, after = (int(word) for word in out.split())
    assert before == 1, "with MALLOC_TRIM_THRESHOLD_ set, glibc maps a 1 MiB block (no adaptive threshold)"
    assert after == 0, "after keep_freed_memory() the block comes from the heap"
