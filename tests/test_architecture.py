"""The package layout: imports run one way (no circle, imports inside functions included; layers from
the bottom up), no function anywhere has more than 12 parameters, functions and modules short enough to
read (at most 60 lines of code per function, 600 lines per module, outside the numba kernels and the
NumPy reference), result records keyword-only, no module uses another's private names, and the public
surface stays what the documentation promises."""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "vcor"
#: the architecture from the bottom up: a module may import its own layer and the ones below
LAYERS = (
    ("checks", "status", "provenance", "threads", "version"),
    ("io",),
    ("materials",),
    ("contact",),
    ("solvers",),
    ("spheres",),
    ("fitting",),
    ("dem",),
    ("plots",),
    ("study",),
    ("cli", "cli_study", "__main__"),
)
MAX_PARAMETERS = 12
#: lines of code per function (no docstring, blank or comment lines) and lines per module
MAX_FUNCTION_LINES, MAX_MODULE_LINES = 60, 600
#: the stated exceptions to both: the numba kernels (one march per function, so that numba compiles
#: it as one unit) and the plain NumPy reference solvers (each mirrors a kernel line by line)
LONG_ALLOWED = ("solvers/_adaptive_kernels.py", "solvers/_fixed_kernels.py", "solvers/_step.py",
                "solvers/_separation.py", "solvers/reference.py")


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _resolve(module: str, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    is_package = MODULES[module].name == "__init__.py"
    base = module.split(".")
    base = base if is_package else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def imports_of(module: str) -> set[str]:
    """The vcor modules ``module`` imports anywhere in its file (module level or inside functions)."""
    out = set()
    for node in ast.walk(ast.parse(MODULES[module].read_text())):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names if a.name in MODULES}
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(module, node)
            if target not in MODULES:
                continue
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                out.add(sub if sub in MODULES else target)
    out.discard(module)
    return out


GRAPH = {m: imports_of(m) for m in MODULES}


def _unit(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "vcor"


def _layer(module: str) -> int:
    unit = _unit(module)
    if unit == "vcor":
        return -1  # the package's __init__ (lazy names only)
    return next(i for i, names in enumerate(LAYERS) if unit in names)


def test_every_module_has_a_layer():
    for module in MODULES:
        _layer(module)


def test_no_import_circle():
    """Depth-first search for a cycle in the import graph (imports inside functions count)."""
    state, stack = {}, []

    def visit(m):
        state[m] = "open"
        stack.append(m)
        for n in sorted(GRAPH[m]):
            if state.get(n) == "open":
                cycle = stack[stack.index(n):] + [n]
                raise AssertionError("import circle: " + " -> ".join(cycle))
            if n not in state:
                visit(n)
        stack.pop()
        state[m] = "done"

    for m in sorted(GRAPH):
        if m not in state:
            visit(m)


def test_imports_run_one_way():
    wrong = [(m, n) for m, targets in GRAPH.items() for n in targets if _layer(n) > _layer(m) and _layer(m) >= 0]
    assert not wrong, "imports from a lower layer into a higher one: " + ", ".join(f"{m} -> {n}" for m, n in wrong)


def _python_files():
    for folder in ("src", "workflow", "tests", "benchmarks"):
        yield from sorted((ROOT / folder).rglob("*.py"))


def test_no_function_has_more_than_12_parameters():
    wide = []
    for path in _python_files():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                a = node.args
                n = (len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + (a.vararg is not None)
                     + (a.kwarg is not None))
                if n > MAX_PARAMETERS:
                    wide.append(f"{path.relative_to(ROOT)}:{node.lineno} {getattr(node, 'name', 'lambda')} ({n})")
    assert not wide, wide


def _src_files():
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).as_posix()
        if rel not in LONG_ALLOWED:
            yield path, rel


def code_lines(node: ast.AST, lines: list[str]) -> int:
    """Lines of code of a function: its body without the docstring, blank lines and comments."""
    body = node.body
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
            and isinstance(body[0].value.value, str):
        start = body[0].end_lineno + 1
    else:
        start = body[0].lineno
    return sum(1 for line in lines[start - 1 : node.end_lineno] if line.strip() and not line.strip().startswith("#"))


def test_functions_fit_on_a_screen():
    long = []
    for path, rel in _src_files():
        text = path.read_text()
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = code_lines(node, text.splitlines())
                if n > MAX_FUNCTION_LINES:
                    long.append(f"{rel}:{node.lineno} {node.name} ({n} lines)")
    assert not long, f"functions over {MAX_FUNCTION_LINES} lines of code: {long}"


def test_modules_hold_one_idea():
    big = [f"{rel} ({n} lines)" for path, rel in _src_files()
           if (n := len(path.read_text().splitlines())) > MAX_MODULE_LINES]
    assert not big, f"modules over {MAX_MODULE_LINES} lines: {big}"


def _dataclass_kw_only(node: ast.ClassDef) -> bool | None:
    """True/False for a dataclass (keyword-only or not), None for any other class."""
    for d in node.decorator_list:
        call = d if isinstance(d, ast.Call) else None
        name = ast.unparse(call.func if call else d)
        if name.split(".")[-1] == "dataclass":
            return bool(call) and any(k.arg == "kw_only" and getattr(k.value, "value", False) for k in call.keywords)
    return None


def _fields(node: ast.ClassDef) -> int:
    return sum(isinstance(s, ast.AnnAssign) and "ClassVar" not in ast.unparse(s.annotation) for s in node.body)


#: records of at most this many fields may stay positional (a pair, a triple)
POSITIONAL_FIELDS = 3
#: values a user writes positionally, in the order the papers name them: a material model
#: (``EqOne(E, nu, ...)`` like ``SLS(E_glassy, alpha, beta)``) and measured data (``CorData(v0, cor)``)
POSITIONAL_ALLOWED = {"materials/eq_one.py": "EqOne", "fitting/cor_data.py": "CorData"}


def test_result_records_are_keyword_only():
    positional = []
    for path, rel in _src_files():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ClassDef) and _dataclass_kw_only(node) is False \
                    and _fields(node) > POSITIONAL_FIELDS and POSITIONAL_ALLOWED.get(rel) != node.name:
                positional.append(f"{rel}:{node.lineno} {node.name} ({_fields(node)} fields)")
    assert not positional, f"dataclasses of more than {POSITIONAL_FIELDS} fields without kw_only=True: {positional}"


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def private_uses(path: Path, package: str | None) -> list[str]:
    """Uses of another vcor module's private names in ``path``: ``from m import _x``, ``m._x`` with m a
    vcor module, and a private module imported from outside its own package (``package``: the vcor
    package the file belongs to, None outside src)."""
    tree = ast.parse(path.read_text())
    module = _module_name(path) if package is not None else None
    bound, out = set(), []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("vcor"):
                    bound.add(a.asname or a.name.split(".")[0])
                    if any(_private(p) for p in a.name.split(".")):
                        out.append(f"{path.name}:{node.lineno} import {a.name}")
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(module, node) if (node.level and module) else (node.module or "")
            if not target.startswith("vcor"):
                continue
            owner = target.rsplit(".", 1)[0] if _private(target.rsplit(".", 1)[-1]) else target
            for a in node.names:
                name = f"{target}.{a.name}"
                if name in MODULES:
                    bound.add(a.asname or a.name)
                    if _private(a.name) and package != target:
                        out.append(f"{path.name}:{node.lineno} from {target} import {a.name}")
                elif _private(a.name):
                    out.append(f"{path.name}:{node.lineno} from {target} import {a.name}")
            if any(_private(p) for p in target.split(".")) and package != owner:
                out.append(f"{path.name}:{node.lineno} from {target} import ...")
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and _private(node.attr):
            base = node.value
            if isinstance(base, ast.Name) and base.id in bound:
                out.append(f"{path.name}:{node.lineno} {base.id}.{node.attr}")
    return out


def test_no_module_uses_another_modules_private_names():
    uses = []
    for path in _python_files():
        inside = PACKAGE in path.parents
        package = _module_name(path).rsplit(".", 1)[0] if inside and path.name != "__init__.py" else (
            _module_name(path) if inside else None)
        uses += private_uses(path, package)
    assert not uses, uses


#: the public surface the documentation promises (module: names)
PUBLIC = {
    "vcor": ["simulate", "Result", "SolverOptions", "sweep", "fit", "calibrate", "dem_export", "__version__",
             "materials", "contact", "solvers", "fitting",
             "study", "io", "plots", "spheres", "status"],
    "vcor.materials": ["get", "from_file", "from_dict", "PRESETS", "Catalogue", "Material", "SLS", "Prony",
                       "FractionalPower", "Cerf", "KelvinVoigt", "Elastic", "EqOne"],
    "vcor.solvers": ["simulate", "Result", "Histories", "SolverOptions", "METHODS"],
    "vcor.solvers.options": ["SolverOptions", "DEFAULT_METHOD", "METHOD_NAMES", "OPTION_HELP", "OPTION_UNITS"],
    "vcor.spheres": ["cor_numeric", "cor_series", "cor_pade", "cor_pade_force", "cor_root", "b_group", "g_star",
                     "cor_spheres", "dissipative_constant"],
    "vcor.status": ["STATUS_CODES", "STATUS_NAMES", "cf_attrs", "code", "guarded"],
}


@pytest.mark.parametrize("module", sorted(PUBLIC))
def test_public_surface(module):
    mod = importlib.import_module(module)
    missing = [n for n in PUBLIC[module] if not hasattr(mod, n)]
    assert not missing, (module, missing)


def test_default_method_is_adaptive_everywhere():
    import vcor
    from vcor.solvers.options import DEFAULT_METHOD, SolverOptions

    assert DEFAULT_METHOD == "adaptive" and SolverOptions().method == "adaptive"
    r = vcor.simulate("sls", 10.0, h=1e-3)  # a thin plate: direct would end at its step budget
    assert r.status == "ok" and r.method == "adaptive"
    assert set(vcor.solvers.METHODS) == {"adaptive", "direct", "ive", "ive-numba", "paper", "soe"}
