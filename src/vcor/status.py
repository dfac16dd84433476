"""One status vocabulary for results and every dataset (sweeps, histories, convergence, spheres).

===============  ====  =========================================================================
status           code  meaning
===============  ====  =========================================================================
ok               0     separated; every output is valid
no-separation    1     the force did not return to zero for a physical reason the message names
diverged         2     the numerical method failed (Newton, non-finite state, solve_ivp failure)
invalid-input    3     a parameter or option was refused (ValueError before any work)
failed           4     an unexpected exception, stored with its type and message
step-budget      5     stopped by a step or time budget before a verdict (never no-separation)
===============  ====  =========================================================================

Codes are stable (archived datasets keep their meaning); new statuses get new codes.
Datasets store the code as a small integer with CF ``flag_values`` / ``flag_meanings``.
"""

from __future__ import annotations

import traceback

import numpy as np

__all__ = ["STATUS_CODES", "STATUS_NAMES", "cf_attrs", "code", "codes_of", "guarded"]

STATUS_CODES = {"ok": 0, "no-separation": 1, "diverged": 2, "invalid-input": 3, "failed": 4, "step-budget": 5}
STATUS_NAMES = {v: k for k, v in STATUS_CODES.items()}


def code(name: str) -> int:
    """Integer code of a status name (ValueError for a name outside the vocabulary).

    Examples
    --------
    >>> from vcor.status import code
    >>> code("ok"), code("no-separation")
    (0, 1)
    """
    try:
        return STATUS_CODES[name]
    except KeyError:
        raise ValueError(f"unknown status {name!r}; allowed: {sorted(STATUS_CODES)}") from None


def codes_of(names) -> np.ndarray:
    """int8 array of codes for a sequence of status names.

    Examples
    --------
    >>> from vcor.status import codes_of
    >>> codes_of(["ok", "step-budget", "failed"])
    array([0, 5, 4], dtype=int8)
    """
    return np.array([code(n) for n in names], dtype=np.int8)


def cf_attrs(long_name: str = "solver status") -> dict:
    """CF attributes of a status variable.

    Examples
    --------
    >>> from vcor.status import cf_attrs
    >>> cf_attrs()["flag_meanings"]
    'ok no_separation diverged invalid_input failed step_budget'
    """
    items = sorted(STATUS_CODES.items(), key=lambda kv: kv[1])
    return {
        "long_name": long_name,
        "standard_name": "status_flag",
        "units": "1",
        "flag_values": np.array([c for _, c in items], dtype=np.int8),
        "flag_meanings": " ".join(k.replace("-", "_") for k, _ in items),
    }


def guarded(fn, *args, **kwargs):
    """``(value, status, message)`` of ``fn(*args, **kwargs)``: a run that raises is classified, never
    re-raised, so one failed point never sinks the others. ``ValueError`` -> invalid-input (its
    message names the parameter); an exception with a ``status`` attribute (e.g.
    ``vcor.spheres.SolverFailure``) -> that status; any other exception -> failed, stored with its
    type, message and the last frames of the traceback. ``value`` is None when it raised.

    Examples
    --------
    >>> import vcor
    >>> from vcor.status import guarded
    >>> guarded(float, "2.5")
    (2.5, 'ok', '')
    >>> value, status, message = guarded(vcor.simulate, "sls", -1.0)
    >>> value, status, message
    (None, 'invalid-input', 'v0 must be in [1e-09, 100000] m/s, got -1.0')
    """
    try:
        return fn(*args, **kwargs), "ok", ""
    except ValueError as exc:
        return None, "invalid-input", str(exc)
    except Exception as exc:  # noqa: BLE001 - classified and stored, see the docstring
        name = getattr(exc, "status", None)
        if isinstance(name, str) and name in STATUS_CODES:
            return None, name, str(exc)
        return None, "failed", f"{type(exc).__name__}: {exc} | {traceback.format_exc(limit=2)}"
