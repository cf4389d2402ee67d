"""Sphinx configuration of the contactlib documentation.

Build (from the repository root, with the ``docs`` extra installed): ``sphinx-build -W -b html docs docs/_build/html``.
Every code cell of the user guide and every tutorial notebook is executed by the build (MyST-NB, mode "force").
"""

import os
import sys

sys.path.insert(0, os.path.abspath(".."))  # the checkout's contactlib, also without an installed package
sys.path.insert(0, os.path.abspath("_ext"))

import contactlib  # noqa: E402

project = "contactlib"
author = "contactlib developers"
copyright = "2026, contactlib developers"
release = contactlib.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_nb",
    "api_pages",         # docs/api/*.rst from each public __all__ (docs/_ext/api_pages.py)
    "config_reference",  # the workflow's config reference from its JSON schema (docs/_ext/config_reference.py)
]

exclude_patterns = ["_build", "**.ipynb_checkpoints", "jupyter_execute", "generated"]  # generated/: included pages
templates_path = ["_templates"]

# MyST and MyST-NB: markdown pages with executed code cells; notebooks executed afresh at every build
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
nb_execution_mode = "force"
nb_execution_timeout = 300
nb_execution_raise_on_error = True  # a failing example fails the build
nb_execution_show_tb = True
nb_merge_streams = True

# API reference
autosummary_generate = True
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types
autodoc_default_options = {"members": False}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_validation_checks = set()  # tests/test_docstrings.py checks the sections, with a stated list of checks

html_theme = "pydata_sphinx_theme"
html_title = f"contactlib {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_static_path = []
