"""Sphinx extension: MathJax served with the site, from a packaged copy (no CDN).

The manual is read on clusters without internet, where MathJax from a CDN leaves every formula as raw
LaTeX. The PyPI package ``sphinx-mathjax-offline`` ships MathJax 3 (the ``es5`` build); this
extension copies the part the pages use into ``_static/mathjax`` of the built site and points
``mathjax_path`` there:

- ``tex-chtml.js``: TeX input, HTML-CSS output, the context menu and assistive MathML in one file;
- ``output/chtml/fonts/woff-v2``: the fonts it loads;
- ``input/tex/extensions``: TeX packages loaded on demand (``autoload``), and ``a11y``, ``ui``,
  ``adaptors``: modules the context menu loads when a reader turns an option on.

Left out: the other combined builds and SVG output (unused) and the speech-rule engine ``sre`` (several
MB of language maps; MathJax fetches it only when a reader turns speech on in the menu).
"""

from __future__ import annotations

import shutil
from importlib import metadata
from pathlib import Path

#: the PyPI distribution that ships MathJax, and MathJax's folder inside it
DISTRIBUTION = "sphinx-mathjax-offline"
PACKAGED = "sphinx-mathjax-offline/static/mathjax"
#: the entry point, relative to _static (Sphinx's mathjax_path)
ENTRY = "mathjax/tex-chtml.js"
#: what is copied, relative to MathJax's folder
PARTS = ("tex-chtml.js", "output/chtml", "input/tex/extensions", "a11y", "ui", "adaptors")


def mathjax_source() -> Path:
    """MathJax's folder in the installed distribution (ImportError naming the package when absent)."""
    try:
        root = Path(metadata.distribution(DISTRIBUTION).locate_file(PACKAGED))
    except metadata.PackageNotFoundError:
        raise ImportError(f"the manual serves MathJax from the package {DISTRIBUTION!r}: install the docs extra, "
                          f"python -m pip install -e '.[docs]'") from None
    if not (root / "tex-chtml.js").is_file():
        raise ImportError(f"{DISTRIBUTION}: no tex-chtml.js under {root}")
    return root


def copy_mathjax(app, exception) -> None:
    """Copy :data:`PARTS` into the built site's ``_static/mathjax`` (HTML builders, successful builds)."""
    if exception is not None or app.builder.format != "html":
        return
    source, target = mathjax_source(), Path(app.outdir) / "_static" / "mathjax"
    for part in PARTS:
        src, dst = source / part, target / part
        if src.is_dir():
            shutil.copytree(src, dst, dirs_exist_ok=True)
        else:
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst)


def setup(app):
    mathjax_source()  # fail at the start of a build, not after it (conf.py sets mathjax_path = ENTRY)
    app.connect("build-finished", copy_mathjax)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
