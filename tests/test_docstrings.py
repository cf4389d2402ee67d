"""Every public name has a numpydoc docstring with the sections a user needs, and its examples run.

The public names are those of each public module's ``__all__`` (submodules excluded; ``contactlib.accuracy`` and
``contactlib.resolution``, which have no ``__all__``, contribute the functions and classes they define without a
leading underscore) and the functions of each module of ``contactlib.reference``: the names the API reference
(``docs/_ext/api_pages.py``) documents.

Checks, on the docstring parsed by ``numpydoc.docscrape`` (numpydoc.validate's codes in brackets):

* a one-line summary [GL08, SS01];
* every parameter of the signature documented, and no documented parameter that is not in the signature [PR01,
  PR02]; a class's parameters may be documented under ``Attributes`` (dataclasses document their fields there);
* a ``Returns`` (or ``Yields``) section for a function that returns something [RT01];
* a ``Raises`` section for a function or class whose own body raises, and for every entry point (the solvers and
  ``surfaces.read``, which raise from the validation they call);
* every ``Examples`` section runs as a doctest (``test_examples_run``).

Not checked: the See Also [SA01] and extended-summary [ES01] sections, section order, and punctuation of the
summary line [SS03, SS05, SS06]: style, which review keeps, not correctness.
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import re
import textwrap

import pytest
from numpydoc.docscrape import ClassDoc, FunctionDoc

MODULES = ["contactlib", "contactlib.surfaces", "contactlib.analysis", "contactlib.two_scale", "contactlib.accuracy",
           "contactlib.resolution", "contactlib.invariants"]
REFERENCE = "contactlib.reference"
ENTRY_POINTS = {"contactlib.solve", "contactlib.solve_transient", "contactlib.solve_reciprocating",
                "contactlib.solve_speeds", "contactlib.solve_tolerances", "contactlib.adhesion_curve",
                "contactlib.two_scale.solve", "contactlib.two_scale.solve_transient", "contactlib.surfaces.read",
                "contactlib.surfaces.self_affine"}


def _public(module_name: str) -> list[tuple[str, object]]:
    module = importlib.import_module(module_name)
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n, v in vars(module).items() if not n.startswith("_") and
                 (inspect.isfunction(v) or inspect.isclass(v)) and v.__module__ == module_name]
    out = []
    for name in names:
        obj = getattr(module, name)
        if inspect.isfunction(obj) or inspect.isclass(obj):
            out.append((f"{module_name}.{name}", obj))
    return out


def public_objects() -> list[tuple[str, object]]:
    found = [item for m in MODULES for item in _public(m)]
    reference = importlib.import_module(REFERENCE)
    for sub in reference.__all__:
        found += _public(f"{REFERENCE}.{sub}")
    return found


OBJECTS = public_objects()
IDS = [name for name, _ in OBJECTS]


def _doc(obj):
    return ClassDoc(obj, config={"show_class_members": False}) if inspect.isclass(obj) else FunctionDoc(obj)


def _documented(section) -> set[str]:
    names = set()
    for param in section:
        for name in param.name.split(","):
            names.add(name.strip().lstrip("*"))
    return names


def _signature_names(obj) -> list[str]:
    try:
        signature = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    return [p.name for p in signature.parameters.values() if p.name not in ("self", "cls")]


def _own_body_raises(obj) -> bool:
    try:
        source = inspect.getsource(obj.__init__ if inspect.isclass(obj) and "__init__" in vars(obj) else obj)
    except (OSError, TypeError):
        return False
    body = re.sub(r'"""(.|\n)*?"""', "", source)  # the docstring's own words do not count
    return re.search(r"^\s+raise \w", body, flags=re.M) is not None


def test_the_public_names_are_found():
    assert len(OBJECTS) > 100 and "contactlib.solve" in IDS and "contactlib.reference.hertz.sphere_load" in IDS


@pytest.mark.parametrize("name, obj", OBJECTS, ids=IDS)
def test_numpydoc_sections(name, obj):
    assert inspect.getdoc(obj), f"{name}: no docstring"
    doc = _doc(obj)
    problems = []
    if not "".join(doc["Summary"]).strip():
        problems.append("no summary line")
    documented = _documented(doc["Parameters"]) | _documented(doc["Other Parameters"])
    if inspect.isclass(obj):
        documented |= _documented(doc["Attributes"])
    signature = _signature_names(obj)
    missing = [n for n in signature if n not in documented]
    if missing:
        problems.append(f"parameters not documented: {missing}")
    extra = sorted(documented - set(signature) - {"kwargs", "args"}) if not inspect.isclass(obj) else []
    if extra and signature:
        problems.append(f"documented but not in the signature: {extra}")
    if not inspect.isclass(obj):
        returns_nothing = inspect.signature(obj).return_annotation in (None, "None")
        if not returns_nothing and not (doc["Returns"] or doc["Yields"]):
            problems.append("no Returns section")
    if (_own_body_raises(obj) or name in ENTRY_POINTS) and not doc["Raises"]:
        problems.append("no Raises section")
    assert not problems, f"{name}: " + "; ".join(problems)


@pytest.mark.parametrize("name, obj", [(n, o) for n, o in OBJECTS if ">>>" in (inspect.getdoc(o) or "")],
                         ids=[n for n, o in OBJECTS if ">>>" in (inspect.getdoc(o) or "")])
def test_examples_run(name, obj):
    module = inspect.getmodule(obj)
    parser, runner = doctest.DocTestParser(), doctest.DocTestRunner(optionflags=doctest.ELLIPSIS |
                                                                    doctest.NORMALIZE_WHITESPACE)
    test = parser.get_doctest(textwrap.dedent(inspect.getdoc(obj)), dict(vars(module)), name, module.__file__, 0)
    result = runner.run(test)
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples failed"


def test_help_names_every_entry_point_on_its_first_screen():
    """``help(contactlib)``'s first screen (its docstring's first 24 lines) names every public callable, the
    submodules' entry points and the errors a user meets."""
    import contactlib

    first_screen = "\n".join(contactlib.__doc__.splitlines()[:24])
    names = [n for n in contactlib.__all__ if n != "__version__"]
    names += ["two_scale.solve", "two_scale.solve_transient", "surfaces", "read", "InvariantError", "AccuracyWarning",
              "contactlib solve", "snakemake"]
    missing = [n for n in names if n not in first_screen]
    assert not missing, f"not on help(contactlib)'s first screen: {missing}"
