"""Lengths with units and paper sizes (weavecut.units): the module's own examples, run as
tests here too so that ``make mutation`` (which runs the tests/ files, not the doctests in
src/) reaches them, and what its mutants showed untested."""

from __future__ import annotations

import doctest

import pytest

from weavecut import units


def test_the_examples_in_the_docstrings_hold():
    failed, tried = doctest.testmod(units, optionflags=doctest.ELLIPSIS)
    assert tried >= 4 and failed == 0
