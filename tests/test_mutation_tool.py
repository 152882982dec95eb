"""The mutation report's sampling (tools/mutation.py): a fixed uniform sample and the kill
rate's Wilson interval, checked against scipy's."""

import importlib.util
import sys
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.stats import binomtest

SPEC = importlib.util.spec_from_file_location(
    "mutation_tool", Path(__file__).resolve().parents[1] / "tools" / "mutation.py")
mutation = importlib.util.module_from_spec(SPEC)
sys.modules[SPEC.name] = mutation  # dataclasses look their module up
SPEC.loader.exec_module(mutation)

names = st.lists(st.from_regex(r"weavecut\.[a-z]{1,6}\.x_[a-z]{1,6}__mutmut_[0-9]{1,3}",
                               fullmatch=True), unique=True, max_size=60)


@pytest.mark.slow
@given(names, names, st.integers(0, 40))
def test_a_sample_keeps_its_mutants_when_others_are_added(old, new, size):
    status = dict.fromkeys(old, "not checked")
    equivalent = dict.fromkeys(old[::3], "reason")
    before = mutation.sample_of(status, equivalent, size)
    after = mutation.sample_of({**status, **dict.fromkeys(new, "killed")}, equivalent, size)
    assert len(before) == min(size, len(set(old) - set(equivalent)))
    assert not set(before) & set(equivalent)
    assert before == mutation.sample_of(dict(reversed(status.items())), equivalent, size)
    # new mutants only push old ones out: every old mutant in the new sample was sampled before
    assert {m for m in after if m in status} <= set(before)


@pytest.mark.parametrize("killed, tested", [(0, 1), (1, 1), (97, 100), (45, 50), (3, 7)])
def test_the_interval_is_wilsons(killed, tested):
    ci = binomtest(killed, tested).proportion_ci(confidence_level=0.95, method="wilson")
    assert mutation.wilson(killed, tested) == pytest.approx((ci.low, ci.high), abs=1e-4)


def test_a_sample_spreads_over_the_functions():
    status = {f"weavecut.m.x_f{f}__mutmut_{k}": "not checked" for f in range(10)
              for k in range(1, 101)}
    sample = mutation.sample_of(status, {}, 100)
    per_function = [sum(m.startswith(f"weavecut.m.x_f{f}__") for m in sample) for f in range(10)]
    assert min(per_function) >= 3 and max(per_function) <= 20, per_function
