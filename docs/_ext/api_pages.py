"""Sphinx extension: write ``docs/api/<module>.rst``, one autosummary page per public module, from its ``__all__``.

The pages are generated at every build (``config-inited``), so a name added to a module's ``__all__`` appears in the
reference without editing the docs. Modules without ``__all__`` (``contactlib.accuracy``, ``contactlib.resolution``)
list the functions and classes they define whose names do not start with an underscore.
"""

from __future__ import annotations

import importlib
import inspect
from pathlib import Path

MODULES = {
    "contactlib": "Entry points, materials, bodies and errors",
    "contactlib.surfaces": "Surfaces: synthetic and measured",
    "contactlib.analysis": "Analysis of surfaces and contact fields",
    "contactlib.two_scale": "The two-scale asperity method",
    "contactlib.accuracy": "Accuracy rules: grid and tolerance for a target error",
    "contactlib.resolution": "Resolution rules and the resolution guard",
    "contactlib.invariants": "Invariants checked before a result is returned",
    "contactlib.reference.hertz": "Reference: Hertz",
    "contactlib.reference.westergaard": "Reference: Westergaard",
    "contactlib.reference.adhesive": "Reference: adhesive contact (JKR, the JKR limit, Johnson)",
    "contactlib.reference.maugis": "Reference: the Maugis-Dugdale sphere",
    "contactlib.reference.hunter": "Reference: Hunter's viscoelastic cylinder",
    "contactlib.reference.sliding_cylinder": "Reference: a cylinder sliding with friction",
    "contactlib.reference.viscoelastic_profile": "Reference: real-space viscoelastic profile",
}


def public_names(module_name: str) -> list[str]:
    """The documented names of a module: its ``__all__`` less submodules, or its own public functions and classes."""
    module = importlib.import_module(module_name)
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n, v in vars(module).items() if not n.startswith("_") and
                 (inspect.isfunction(v) or inspect.isclass(v)) and v.__module__ == module_name]
    return [n for n in names if not inspect.ismodule(getattr(module, n)) and not n.startswith("__")]


def page(module_name: str, title: str) -> str:
    module = importlib.import_module(module_name)
    names = public_names(module_name)
    functions = [n for n in names if callable(getattr(module, n)) and not inspect.isclass(getattr(module, n))]
    classes = [n for n in names if inspect.isclass(getattr(module, n))]
    data = [n for n in names if n not in functions and n not in classes]
    heading = f"``{module_name}``: {title}"
    lines = [heading, "=" * len(heading), ""]
    if module_name == "contactlib":  # its docstring is a plain-text map of the package (help()'s first screen)
        lines += [".. module:: contactlib", "", ".. code-block:: text", ""]
        lines += ["   " + line if line else "" for line in inspect.cleandoc(module.__doc__).splitlines()] + [""]
    else:
        lines += [f".. automodule:: {module_name}", "   :no-members:", ""]
    lines += [f".. currentmodule:: {module_name}", ""]
    for label, group in (("Functions", functions), ("Classes", classes)):
        if group:
            lines += [label, "-" * len(label), "", ".. autosummary::", "   :toctree: generated", ""]
            lines += [f"   {n}" for n in group] + [""]
    if data:
        lines += ["Constants", "---------", ""]
        lines += [f"``{n}`` = ``{getattr(module, n)!r}``" + "\n" for n in data]
    return "\n".join(lines) + "\n"


def write_pages(app, config=None) -> None:
    folder = Path(app.srcdir) / "api"
    folder.mkdir(exist_ok=True)
    toc = ["API reference", "=============", "",
           "Every name in each public module's ``__all__``, with its numpydoc docstring "
           "(``tests/test_docstrings.py`` checks their sections).", "", ".. toctree::", "   :maxdepth: 1", ""]
    for module_name, title in MODULES.items():
        text = page(module_name, title)
        path = folder / f"{module_name}.rst"
        if not path.exists() or path.read_text() != text:  # unchanged pages keep their time stamp: no rebuild
            path.write_text(text)
        toc.append(f"   {module_name}")
    index = folder / "index.rst"
    text = "\n".join(toc) + "\n"
    if not index.exists() or index.read_text() != text:
        index.write_text(text)
    # a name moved to another module leaves its autosummary stub behind in a built tree, which -W refuses as in no
    # toctree (contactlib.reference.adhesive.maugis_* after the Maugis functions moved): only current names keep one
    current = {f"{m}.{n}.rst" for m in MODULES for n in public_names(m)}
    for stub in (folder / "generated").glob("*.rst"):
        if stub.name not in current:
            stub.unlink()


def setup(app):
    app.connect("config-inited", write_pages)  # before the sources are found: autosummary then sees the pages
    return {"parallel_read_safe": True, "version": "1"}
