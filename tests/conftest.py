"""Shared test settings: a hypothesis profile with no deadline (the first call of a compiled kernel
compiles it) and a fixed seed of examples per test, so CI runs are repeatable in time."""
import os

from hypothesis import HealthCheck, settings

settings.register_profile(
    "scara",
    max_examples=int(os.environ.get("SCARA_HYPOTHESIS_EXAMPLES", "200")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    derandomize=True,
)
settings.load_profile("scara")
