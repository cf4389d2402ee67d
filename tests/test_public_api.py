"""The public names: every module's ``__all__`` names what the module holds (``from module import *`` works)."""

import importlib
import pkgutil

import contactlib


def test_every_module_defines_what_its_all_lists():
    missing = []
    for info in pkgutil.walk_packages(contactlib.__path__, "contactlib."):
        module = importlib.import_module(info.name)
        missing += [f"{info.name}.{name}" for name in getattr(module, "__all__", ()) if not hasattr(module, name)]
    assert not missing, missing
