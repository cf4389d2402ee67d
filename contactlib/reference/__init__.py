"""Analytic reference solutions, shared by tests, benchmarks and figures."""

from . import hertz, westergaard

__all__ = ["hertz", "westergaard"]
