"""Evaluating a sweep's queries in worker processes without changing its output (standard
library only, so that sweeps without numpy can use it too)."""
from multiprocessing import Pool


def ordered_map(fn, items, jobs, chunksize=8):
    """`fn` over `items`, results in their order: in this process for `jobs` <= 1, else in a
    pool of `jobs` workers (so a sweep's output does not depend on `jobs`)."""
    if jobs <= 1:
        yield from map(fn, items)
        return
    with Pool(jobs) as pool:
        yield from pool.imap(fn, items, chunksize=chunksize)
