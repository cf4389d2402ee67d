"""The package's layout rules, read from its source: no module imports another module's private name, and no
context variable carries solver state between calls (a prepared problem holds its caches as fields)."""

import ast
from pathlib import Path

import contactlib

PACKAGE = Path(contactlib.__file__).parent

CONTEXT_VARIABLES_ALLOWED = {
    # resolution.recording(): collects the resolution warnings of the solves inside a sweep so that the sweep warns
    # once; it records what was said, not state any solve reads back, so no answer depends on it
    ("resolution.py", "_RECORDER"),
}


def _modules():
    return sorted(p for p in PACKAGE.rglob("*.py"))


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _package_of(path: Path) -> list[str]:
    return list(path.relative_to(PACKAGE.parent).with_suffix("").parts[:-1])


def _target(path: Path, node: ast.ImportFrom) -> Path | None:
    """The file or package directory an import-from names (inside contactlib), else None."""
    if node.level:
        parts = _package_of(path)[: len(_package_of(path)) - node.level + 1]
    elif node.module and node.module.split(".")[0] == "contactlib":
        parts = []
    else:
        return None
    parts = parts + (node.module.split(".") if node.module else [])
    return PACKAGE.parent.joinpath(*parts)


def private_imports(sources=None):
    """``(module, imported name)`` for every import of a private name of another module: ``from .x import _y`` where
    ``_y`` is not a submodule of a package (a package's private submodules serve their siblings), and
    ``x._y`` on a module imported by name. ``sources``: ``(path, text)`` pairs, default the package's modules."""
    found = []
    for path, text in sources if sources is not None else ((p, p.read_text()) for p in _modules()):
        tree = ast.parse(text, filename=str(path))
        modules = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                target = _target(path, node)
                if target is None:
                    continue
                for alias in node.names:
                    is_submodule = (target / f"{alias.name}.py").exists() or (target / alias.name).is_dir()
                    if is_submodule:
                        modules.add(alias.asname or alias.name)
                    elif _private(alias.name):
                        found.append((str(path.relative_to(PACKAGE)), alias.name))
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name.startswith("contactlib"):
                        modules.add(alias.asname or alias.name.split(".")[0])
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in modules
                    and _private(node.attr)):
                found.append((str(path.relative_to(PACKAGE)), f"{node.value.id}.{node.attr}"))
    return found


def context_variables():
    """``(module, name)`` of every ``contextvars.ContextVar`` created in the package."""
    found = []
    for path in _modules():
        tree = ast.parse(path.read_text(), filename=str(path))
        for node in ast.walk(tree):
            if isinstance(node, (ast.Assign, ast.AnnAssign)) and isinstance(node.value, ast.Call):
                func = node.value.func
                name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
                if name == "ContextVar":
                    targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                    found += [(str(path.relative_to(PACKAGE)), t.id) for t in targets if isinstance(t, ast.Name)]
    return found


def test_no_module_imports_another_modules_private_name():
    assert private_imports() == []


def test_the_private_import_check_sees_one():
    """The check itself: a module that imports a private name, or reads one off a module, is found."""
    probe = "from .problems.contact import _setup\nfrom . import _version\nfrom .core import _numba, fft\nfft._plan\n"
    found = private_imports([(PACKAGE / "probe.py", probe)])
    assert found == [("probe.py", "_setup"), ("probe.py", "fft._plan")]  # private submodules of a package pass


def test_no_context_variable_holds_solver_state():
    assert set(context_variables()) <= CONTEXT_VARIABLES_ALLOWED
    assert ("resolution.py", "_RECORDER") in context_variables()  # the check sees the one there is


LAYERS = [
    ("core", "errors", "_version"),
    ("kernels",),
    ("model",),
    ("solvers",),
    ("surfaces", "analysis", "reference"),
    ("accuracy", "resolution", "invariants"),
    ("distributed",),
    ("problems",),
    ("two_scale",),
    ("pipeline", "studies", "cli", "testing", "__init__"),
]
"""The package's layers from the bottom up (the README's package map): a module imports only its own layer and
those below it."""


def _layer(parts: list[str]) -> int:
    top = parts[1] if len(parts) > 1 else "__init__"
    return next(k for k, names in enumerate(LAYERS) if top in names)


def upward_imports():
    """``(module, imported module)`` for every import of a module in a higher layer."""
    found = []
    for path in _modules():
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__" and len(parts) > 2:
            parts = parts[:-1]
        own = _layer(parts)
        for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
            if isinstance(node, ast.ImportFrom):
                target = _target(path, node)
                if target is None:
                    continue
                imported = list(target.relative_to(PACKAGE.parent).parts)
                names = [imported + [a.name] for a in node.names] if len(imported) == 1 else [imported]
                for name in names:
                    if len(name) > 1 and name[1] in {n for layer in LAYERS for n in layer} and _layer(name) > own:
                        found.append((str(path.relative_to(PACKAGE)), ".".join(name)))
    return found


def test_no_module_imports_a_higher_layer():
    assert upward_imports() == []
