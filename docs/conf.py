"""Sphinx configuration of the vcor documentation (MyST Markdown pages, autosummary API)."""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

import vcor  # noqa: E402  (installed from ../src, editable)

project = "vcor"
author = "the vcor developers"
release = vcor.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "vcor_docs",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_generated", "test_docs_build.py", "**/.pytest_cache"]
templates_path = ["_templates"]
smartquotes = False  # s' is a derivative, not a closing quote

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"  # numpydoc renders Parameters itself; "description" would add a second list
numpydoc_show_class_members = False

html_theme = "furo"
html_title = f"vcor {release}"
html_static_path = ["_static"]
html_css_files = ["custom.css"]
