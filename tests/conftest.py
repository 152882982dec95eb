import os

from hypothesis import HealthCheck, Phase, settings

# dev: quick local runs; ci: bounded and reproducible; long: the fuzz suite on demand
# (HYPOTHESIS_PROFILE=long, or `make fuzz`)
settings.register_profile("dev", max_examples=25, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("ci", max_examples=60, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("long", max_examples=2000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
# mutation: tools/mutation.py runs the guarding tests once per mutant, so few examples, and
# the same ones every time (a mutant's verdict must not depend on the draw); no shrinking:
# a failure kills the mutant as it is found, and shrinking it took 20 to 50 s per mutant
settings.register_profile("mutation", max_examples=8, deadline=None, derandomize=True,
                          phases=[Phase.explicit, Phase.reuse, Phase.generate],
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE") or ("ci" if os.environ.get("CI")
                                                               else "dev"))


def pytest_collection_modifyitems(items):
    """The tests marked ``slow`` (each several seconds of CPU) first, in their order: xdist's
    workers share out the quick ones at the end, so neither is left running a long test alone
    while the other waits (a module's slow tests stay together: their fixtures are made once)."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)
