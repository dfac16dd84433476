"""Sphinx configuration of the vcor documentation (MyST Markdown pages, autosummary API)."""

import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

import offline_mathjax  # noqa: E402  (docs/_ext)

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
    "sphinx.ext.intersphinx",
    "sphinx.ext.viewcode",
    "sphinx_gallery.gen_gallery",
    "offline_mathjax",
    "vcor_docs",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_generated", "test_docs_build.py", "**/.pytest_cache", "gallery/*.ipynb",
                    "gallery/*.py", "gallery/*.md5", "gallery/*.zip"]
templates_path = ["_templates"]
smartquotes = False  # s' is a derivative, not a closing quote

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

autosummary_generate = True
# autosummary writes docs/api/ (git ignores it) but never removes a page: every build starts from an empty
# folder, so that a module no longer in the package leaves no page behind
shutil.rmtree(HERE / "api", ignore_errors=True)
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"  # numpydoc renders Parameters itself; "description" would add a second list
numpydoc_show_class_members = False

html_theme = "furo"
html_title = f"vcor {release}"
html_static_path = ["_static"]
html_css_files = ["custom.css"]

# MathJax from the site itself (docs/_ext/offline_mathjax.py copies it from the docs extra's package)
mathjax_path = offline_mathjax.ENTRY

# Cross-links to Python, SciPy and xarray from inventories shipped in docs/_ext/inventories (the build
# runs offline; docs/developer.md says where they come from and why NumPy and Matplotlib have none)
INVENTORIES = HERE / "_ext" / "inventories"
intersphinx_mapping = {
    "python": ("https://docs.python.org/3", str(INVENTORIES / "python.inv")),
    "scipy": ("https://docs.scipy.org/doc/scipy", str(INVENTORIES / "scipy.inv")),
    "xarray": ("https://docs.xarray.dev/en/stable", str(INVENTORIES / "xarray.inv")),
}
intersphinx_timeout = 1  # a local file: never wait for a network

# The example gallery (examples/*.py): every build runs every example (no cache: what a page shows is
# what the installed code computes; the examples are short, docs/developer.md gives the budget)
sphinx_gallery_conf = {
    "examples_dirs": str(HERE.parent / "examples"),
    "gallery_dirs": str(HERE / "gallery"),
    "filename_pattern": r"/plot_",
    "within_subsection_order": "gallery_order.ExampleOrder",
    "run_stale_examples": True,
    "abort_on_example_error": True,
    "remove_config_comments": True,
    "download_all_examples": False,
    "show_signature": False,
    "matplotlib_animations": False,
    "image_srcset": [],
    "reset_modules_order": "before",
}
