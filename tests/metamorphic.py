"""What the property-based suites (``test_metamorphic_*.py``) share: the example budget and a scene that prints
as the recipe that drew it."""

from hypothesis import HealthCheck, settings

FAST = dict(suppress_health_check=[HealthCheck.too_slow])


def budget(examples: int) -> int:
    """``examples`` at the default profile's 100 examples, scaled with the loaded profile (``thorough``: 10x)."""
    return max(1, examples * settings().max_examples // 100)


class Scene(tuple):
    """A drawn scene, printed by its parameters (a falsifying example then reads as a recipe, not an array)."""

    def __new__(cls, items, description):
        self = super().__new__(cls, items)
        self.description = description
        return self

    def __repr__(self):
        return f"Scene({self.description})"
