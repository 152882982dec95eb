"""The result cache: what is put is got back whole; beyond its size the least recently used
results go first (checked against a plain model of an LRU cache over random sequences of puts
and gets); any number of processes may put and get at once without a torn result."""

from __future__ import annotations

import multiprocessing
from collections import OrderedDict

from hypothesis import given, settings, strategies as st

from weavecut.web.cache import Cache
from weavecut.web.jobs import JobResult, failed

KEYS = [f"{n:02x}" * 32 for n in range(8)]  # 64 hex digits; two share no subfolder


def result_of(key: str, size: int) -> JobResult:
    return JobResult(True, key.encode()[:4] * size, "application/zip", {"key": key})


def stored(result: JobResult) -> int:
    return len(result.to_bytes())


class Model:
    """An LRU cache by the book: an ordered dict, most recently used last."""

    def __init__(self, max_bytes: int) -> None:
        self.max_bytes, self.items = max_bytes, OrderedDict()

    def get(self, key):
        if key in self.items:
            self.items.move_to_end(key)
            return self.items[key]
        return None

    def put(self, key, result):
        if stored(result) > self.max_bytes:
            return
        self.items[key] = result
        self.items.move_to_end(key)
        while sum(stored(r) for r in self.items.values()) > self.max_bytes:
            oldest = next(iter(self.items))
            del self.items[oldest]


operations = st.lists(st.tuples(st.sampled_from(["get", "put"]), st.sampled_from(KEYS),
                                st.integers(0, 300)), max_size=40)


@settings(max_examples=40)
@given(operations, st.integers(200, 2000))
def test_the_cache_keeps_what_an_lru_cache_keeps(tmp_path_factory, ops, max_bytes):
    cache = Cache(tmp_path_factory.mktemp("cache"), max_bytes)
    model = Model(max_bytes)
    for op, key, size in ops:
        if op == "put":
            cache.put(key, result_of(key, size))
            model.put(key, result_of(key, size))
        else:
            assert cache.get(key) == model.get(key)
        assert [k for _, k, _ in cache.entries()] == list(model.items)
        assert cache.size() <= max_bytes


def test_a_result_comes_back_whole_and_refusals_are_not_kept(tmp_path):
    cache = Cache(tmp_path / "cache", 10_000)
    good = JobResult(True, b"PK\x03\x04 and more\n\nbytes", "application/zip",
                     {"pages": 4, "warnings": ["a"]})
    cache.put(KEYS[0], good)
    assert cache.get(KEYS[0]) == good
    cache.put(KEYS[1], failed(422, "the kit took more than 1 s of CPU"))
    assert cache.get(KEYS[1]) is None
    cache.put(KEYS[2], result_of(KEYS[2], 20_000))  # larger than the whole cache
    assert cache.get(KEYS[2]) is None and cache.get(KEYS[0]) == good


def test_a_damaged_or_foreign_file_is_a_miss(tmp_path):
    cache = Cache(tmp_path, 10_000)
    cache.put(KEYS[0], result_of(KEYS[0], 10))
    cache.path(KEYS[0]).write_bytes(b"not a result")
    assert cache.get(KEYS[0]) is None
    for bad in ("../etc", "ab", "AB" * 32, "ab" * 32 + "/x"):
        try:
            cache.path(bad)
        except ValueError:
            continue
        raise AssertionError(f"{bad!r} became a path")


def sized(key: str, size: int) -> JobResult:
    """A result that says how it was made, so a torn one shows."""
    return JobResult(True, key.encode()[:4] * size, "application/zip", {"key": key,
                                                                        "size": size})


def _hammer(folder: str, worker: int, rounds: int, max_bytes: int, queue) -> None:
    """Put and read in turn; count every file found that is not a whole result, and every
    result got back different from what was put."""
    cache = Cache(folder, max_bytes)
    bad = 0
    for n in range(rounds):
        key = KEYS[(n + worker) % len(KEYS)]
        cache.put(key, sized(key, 5_000 + (n * 7919 + worker * 104729) % 40_000))
        other = KEYS[(n * 3 + worker) % len(KEYS)]
        try:
            data = cache.path(other).read_bytes()
        except FileNotFoundError:
            continue
        try:
            got = JobResult.from_bytes(data)
        except ValueError:
            bad += 1
            continue
        if got != sized(other, got.summary["size"]):
            bad += 1
    queue.put(bad)


def test_concurrent_puts_and_gets_from_processes_never_tear_a_result(tmp_path):
    max_bytes = 400_000
    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    workers = [context.Process(target=_hammer, args=(str(tmp_path), w, 300, max_bytes, queue))
               for w in range(4)]
    for w in workers:
        w.start()
    for w in workers:
        w.join(120)
    assert [w.exitcode for w in workers] == [0] * 4
    assert sum(queue.get(timeout=5) for _ in workers) == 0
    cache = Cache(tmp_path, max_bytes)
    assert cache.size() <= max_bytes
    for _, key, _ in cache.entries():
        got = cache.get(key)
        assert got is not None and got == sized(key, got.summary["size"])
    leftovers = [p for p in tmp_path.rglob("*") if p.is_file() and p.name not in KEYS]
    assert leftovers == []  # no temporary file of an atomic write is left
