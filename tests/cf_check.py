"""The IOOS compliance checker's CF-1.10 verdict on a NetCDF file, as its command line gives it
(``compliance-checker --test cf:1.10``): errors are the failed high-priority checks, warnings the failed
medium ones; a check that raises (a defect of the checker the file may have triggered) is an error too.
Importable from every test folder (pytest puts the folder of tests/conftest.py on sys.path)."""

import pytest

CHECKER = "cf:1.10"


def cf_problems(path) -> tuple[list[str], list[str]]:
    """``(errors, warnings)`` of the file at ``path``, each ``"<section>: <message>"``."""
    suite = pytest.importorskip("compliance_checker.suite", reason="the IOOS compliance checker is in the test "
                                "extra: pip install -e '.[test]'")
    cs = suite.CheckSuite()
    cs.load_all_available_checkers()
    ds = cs.load_dataset(str(path))
    try:
        groups, raised = cs.run_all(ds, [CHECKER])[CHECKER]
    finally:
        ds.close()
    errors = [f"{name}: raised {exc!r}" for name, (exc, _) in raised.items()]
    warnings = []
    for g in groups:
        if g.value[0] < g.value[1]:
            found = errors if g.weight >= 3 else warnings if g.weight == 2 else None
            if found is not None:
                found.extend(f"{g.name}: {m}" for m in (g.msgs or ["failed"]))
    return errors, warnings
