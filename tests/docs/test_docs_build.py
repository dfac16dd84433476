"""The documentation: it builds with warnings as errors, and neither its pages, the README nor the
code's comments and docstrings tell history (that is CHANGELOG.md's and the commit messages')."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = next(p for p in Path(__file__).resolve().parents if (p / "docs" / "conf.py").is_file())
DOCS = ROOT / "docs"


#: MathJax from a CDN (the manual must render formulas offline)
CDN_MATHJAX = re.compile(r"(?i)(cdn\.jsdelivr\.net|cdnjs\.cloudflare\.com|unpkg\.com|cdn\.mathjax\.org)[^\"']*mathjax")
#: images that are not figures of the manual's content (the landing figure, gallery thumbnails, the theme's)
NOT_FIGURES = re.compile(r"overview\.svg|thumb|_static/")


@pytest.fixture(scope="module")
def built_site(tmp_path_factory):
    """The manual built once with warnings as errors (the test extra installs the documentation
    packages, so the build is never skipped): the HTML folder."""
    html = tmp_path_factory.mktemp("docs") / "html"
    out = subprocess.run([sys.executable, "-m", "sphinx", "-W", "-b", "html", "-q", str(DOCS), str(html)],
                         cwd=ROOT, capture_output=True, text=True, timeout=900, check=False)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-6000:]
    return html


@pytest.mark.slow
def test_docs_build_without_warnings(built_site):
    assert (built_site / "index.html").is_file()


@pytest.mark.slow
def test_gallery_runs_every_example_and_shows_its_output(built_site):
    """Each example of examples/ has a page with its printed output and at least one figure, drawn
    by this build."""
    examples = sorted(p.stem for p in (ROOT / "examples").glob("plot_*.py"))
    assert len(examples) >= 6, examples
    for name in examples:
        page = built_site / "gallery" / f"{name}.html"
        assert page.is_file(), f"no gallery page for examples/{name}.py"
        text = page.read_text(encoding="utf-8")
        assert "sphx-glr-script-out" in text, f"{name}: no printed output on its page"
        assert re.search(rf'src="[^"]*sphx_glr_{name}_\d+\.png"', text), f"{name}: no figure on its page"


def _figures(html: Path) -> set[str]:
    """Image files shown by the pages, less those :data:`NOT_FIGURES` names."""
    shown = set()
    for page in html.rglob("*.html"):
        for src in re.findall(r'<img[^>]+src="([^"]+)"', page.read_text(encoding="utf-8")):
            name = Path(src).name
            if not NOT_FIGURES.search(src) and (html / "_images" / name).is_file():
                shown.add(name)
    return shown


@pytest.mark.slow
def test_the_manual_shows_at_least_ten_figures_besides_the_landing_one(built_site):
    figures = _figures(built_site)
    assert len(figures) >= 10, sorted(figures)


@pytest.mark.slow
def test_user_guide_pages_show_gallery_figures(built_site):
    """The pages the examples belong to show their figures (not only the gallery)."""
    for page in ("user-guide/materials", "user-guide/dma", "user-guide/uncertainty", "validation", "benchmarks",
                 "getting-started"):
        text = (built_site / f"{page}.html").read_text(encoding="utf-8")
        assert re.search(r'<img[^>]+src="[^"]*sphx_glr_plot_\w+\.png"', text), f"{page}: no gallery figure"


@pytest.mark.slow
def test_mathjax_is_served_with_the_site(built_site):
    """No page loads MathJax from a CDN; the pages with formulas load the copy in _static."""
    entry = built_site / "_static" / "mathjax" / "tex-chtml.js"
    assert entry.is_file() and entry.stat().st_size > 100_000, entry
    assert (built_site / "_static" / "mathjax" / "output" / "chtml" / "fonts" / "woff-v2").is_dir()
    pages = sorted(built_site.rglob("*.html"))
    cdn = [str(p.relative_to(built_site)) for p in pages if CDN_MATHJAX.search(p.read_text(encoding="utf-8"))]
    assert not cdn, f"MathJax from a CDN in {cdn[:10]}"
    theory = (built_site / "theory.html").read_text(encoding="utf-8")
    assert re.search(r'<script[^>]+src="_static/mathjax/tex-chtml\.js', theory), "theory.html loads no MathJax"


@pytest.mark.slow
def test_api_module_tables_are_not_reprs(built_site):
    """Module tables of the API reference show names and summaries, not Python reprs."""
    bad = []
    for page in sorted((built_site / "api").glob("*.html")):
        text = re.sub(r"<[^>]+>", "", page.read_text(encoding="utf-8"))  # the text a reader sees
        hits = re.findall(r"&lt;(?:module|function|class)\s+[\w.']+&gt;|object at 0x[0-9a-f]+", text)
        if hits:
            bad.append(f"{page.name}: {hits[:3]}")
    assert not bad, bad


# ----------------------------------------------------------------------------- history words
#: narration of how the code came to be; the pages describe what is (history: CHANGELOG.md only)
HISTORY = {
    "issue number": r"\b[Ii]ssues?\s+#?\d+|(?<![\w&/#])#\d+\b",
    "commit hash": r"\b(?=[0-9a-f]*[0-9])(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}\b",
    "session": r"(?i)(?<!scope=\")\bsessions?\b",  # pytest's fixture scope is not a work session
    # "X used to do Y", not the passive "X is used to compute Y"
    "used to": r"(?i)(?<!\bis )(?<!\bare )(?<!\bbe )(?<!\bbeen )(?<!\bbeing )(?<!\bwas )(?<!\bwere )\bused to\b",
    "tried and not kept": r"(?i)\btried,?\s+(and\s+)?not\s+kept\b|\bnot kept\b",
    "was": r"(?i)\bwas\b",
    "no longer": r"(?i)\bno longer\b|\b(is|are) now\b",
    "earlier versions": r"(?i)\b(earlier|previous|older|old) (READMEs?|versions?|commits?|code|sessions?)\b",
    "time of writing": r"(?i)\bat the time of writing\b",
    "former": r"(?i)\b(former|formerly|today|always did|before this)\b",
}
#: fenced code blocks with a language (or none); MyST directives (```{name}) are checked like text
CODE_FENCE = re.compile(r"^(`{3,}|~{3,})(?!\{)[^\n]*\n.*?^\1[ \t]*$", re.MULTILINE | re.DOTALL)
#: the pages: every Markdown file of the site (not the generated benchmark tables, not work notes)
NOT_PAGES = {"DOCSTRING_WARNINGS.md"}


def _pages():
    skip = {DOCS / d for d in ("_build", "_generated", "api")}
    pages = [p for p in sorted(DOCS.rglob("*.md")) if not any(s in p.parents for s in skip) and p.name not in NOT_PAGES]
    return pages + [ROOT / "README.md"]


def history_hits(text: str) -> list[str]:
    """(kind: the line) for every history word outside code blocks."""
    text = CODE_FENCE.sub(lambda m: "\n" * m.group(0).count("\n"), text)
    hits = []
    for lineno, line in enumerate(text.splitlines(), 1):
        for kind, pattern in HISTORY.items():
            if re.search(pattern, line):
                hits.append(f"line {lineno} ({kind}): {line.strip()[:160]}")
    return hits


@pytest.mark.parametrize("page", _pages(), ids=lambda p: str(p.relative_to(ROOT)))
def test_pages_tell_no_history(page):
    hits = history_hits(page.read_text(encoding="utf-8"))
    assert not hits, f"{page.relative_to(ROOT)}: history belongs in CHANGELOG.md:\n" + "\n".join(hits[:40])


#: in code, "was", "no longer", "used to" and "before this" describe what a program does at run time ("the
#: size it was written with", "the steps before this one"), so they and their kin ("former", "today",
#: "always did") are checked on the pages only; the narration words are the rest
CODE_HISTORY = {k: v for k, v in HISTORY.items() if k not in ("was", "no longer", "used to", "former")}


def _code_files():
    files = [*sorted((ROOT / "src" / "vcor").rglob("*.py")), *sorted((ROOT / "workflow").rglob("*")),
             ROOT / "Snakefile", ROOT / "config.yaml", *sorted((ROOT / "profiles").rglob("*.yaml"))]
    return [p for p in files if p.is_file() and p.suffix in (".py", ".smk", ".rst", ".yaml", ".sh", "")]


#: tests hold hexadecimal-looking numbers (1.75545e6, fingerprints of fake shards): no hash check there
TEST_HISTORY = {k: v for k, v in CODE_HISTORY.items() if k != "commit hash"}


@pytest.mark.parametrize("path", _code_files() + sorted((ROOT / "tests").rglob("*.py")),
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_code_tells_no_history(path):
    words = TEST_HISTORY if path.relative_to(ROOT).parts[0] == "tests" else CODE_HISTORY
    if path.name == Path(__file__).name:
        return  # this file spells the patterns out
    hits = [f"line {n} ({kind}): {line.strip()[:160]}" for n, line in enumerate(path.read_text().splitlines(), 1)
            for kind, pattern in words.items() if re.search(pattern, line)]
    assert not hits, f"{path.relative_to(ROOT)}: history belongs in CHANGELOG.md:\n" + "\n".join(hits[:40])


@pytest.mark.parametrize("text", [
    "Fixed in issue 11, see #12.",
    "three runs at fdfae6b gave 53.9 s",
    "before session 4 the cases used case 3's densities",
    "the solver used to stop at the step budget",
    "a warm-up of every method (tried and not kept)",
    "the default was direct",
    "simulate no longer defaults to direct",
    "earlier READMEs said 98 s",
    "longer than the former three-grid extrapolation did",
    "files written before this encoding read as they always did",
    "the same data written today",
])
def test_history_narration_is_caught(text):
    assert history_hits(text)


@pytest.mark.parametrize("text", [
    "The contact-time estimate is used to choose the step.",
    "Prony rates divided by a_T; C2 in K; 1e-12 relative; 4000000 steps; 0.0003.",
    "```bash\ngit log 0123abc\n```\n",
    "## Heading with a number 3",
    "E* = N_a N_b / (N_a D_b + N_b D_a)",
])
def test_todays_text_passes(text):
    assert not history_hits(text)


def test_benchmarks_page_types_no_timing():
    """Timings reach the benchmarks page only through the generated tables it includes."""
    text = CODE_FENCE.sub("", (DOCS / "benchmarks.md").read_text(encoding="utf-8"))
    typed = re.findall(r"\b\d+(?:\.\d+)?\s*(?:s|ms|µs|us|min|h|seconds?|minutes?|hours?)\b", text)
    assert not typed, typed
