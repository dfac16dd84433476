"""Validation of scalar inputs: one place for "a finite number in this interval" checks.

Every public entry point (materials, geometry, impact speed, spheres, fits) validates its numbers
here, so a boolean, a string or a NaN where a number is expected gets the same clear
``ValueError`` that names the parameter and the allowed range, before any work is done.
"""

from __future__ import annotations

import functools
import math
import numbers

__all__ = ["interned", "number", "positive", "shown", "text_hint"]


def _interval(lo, hi, lo_open, hi_open) -> str:
    return f"{'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"


def number(name: str, value, lo: float = -math.inf, hi: float = math.inf, *, lo_open: bool = True,
           hi_open: bool = True, unit: str = "") -> float:
    """``value`` as a float if it is a real number (not a bool) in the interval, else ValueError
    naming ``name`` and the interval (with ``unit``)."""
    if type(value) is not float and (isinstance(value, bool) or not isinstance(value, numbers.Real)):
        raise ValueError(f"{name} must be in {_where(lo, hi, lo_open, hi_open, unit)} (a number), got {shown(value)}"
                         + text_hint(value))
    try:
        v = float(value)
    except (OverflowError, ValueError):  # an int beyond the float range, an exotic Real
        raise ValueError(f"{name} must be in {_where(lo, hi, lo_open, hi_open, unit)} (a number within the "
                         f"floating-point range), got {shown(value)}") from None
    inside = (v > lo if lo_open else v >= lo) and (v < hi if hi_open else v <= hi)
    if not (math.isfinite(v) and inside):
        raise ValueError(f"{name} must be in {_where(lo, hi, lo_open, hi_open, unit)}, got {shown(value)}")
    return v


def text_hint(value) -> str:
    """For a number that arrived as text, why, and how to write it: PyYAML (YAML 1.1) reads a number with
    an exponent as a number only with a dot in the mantissa and a sign in the exponent (``3.0e+7``;
    ``3.0e7``, ``3e+7`` and ``1e-9`` are text); otherwise a quoted number. The same text reaches a Python
    caller who passed a string, so the hint with an exponent speaks to both. "" for any other value.

    Examples
    --------
    >>> hint = text_hint("3e7")
    >>> hint.startswith(": text, not a number (from Python, write it without quotes;"), hint.endswith("write 3.0e+7)")
    (True, True)
    >>> text_hint("2.5")
    ': text, not a number (write it without quotes)'
    """
    if not isinstance(value, str):
        return ""
    try:
        float(value)
    except ValueError:
        return ""
    text = value.strip().lower()
    if "e" in text:
        mantissa, exponent = text.split("e", 1)
        if "." not in mantissa:
            mantissa += ".0"
        if exponent[:1] not in "+-":
            exponent = "+" + exponent
        return (f": text, not a number (from Python, write it without quotes; in a YAML file a number with an "
                f"exponent needs a dot and a signed exponent: write {mantissa}e{exponent})")
    return ": text, not a number (write it without quotes)"


def shown(value) -> str:
    """``repr(value)``, shortened for an error message (a 400-digit integer is not read by anyone)."""
    text = repr(value)
    return text if len(text) <= 40 else f"{text[:20]}...{text[-8:]} ({len(text)} characters)"


def _where(lo, hi, lo_open, hi_open, unit) -> str:
    # formatted only for an error message (validation runs per Prony term, per sweep point)
    return _interval(lo, hi, lo_open, hi_open) + (f" {unit}" if unit else "")


def positive(name: str, value, *, allow_zero: bool = False, unit: str = "") -> float:
    """A finite number > 0 (or >= 0 with ``allow_zero``)."""
    return number(name, value, 0.0, math.inf, lo_open=not allow_zero, unit=unit)


def interned(factory, maxsize: int = 256):
    """``factory(**kw)`` (a validating constructor of an immutable object), cached by value: sweeps and
    simulate calls build the same few option sets and geometries again and again. The key holds each
    value's type, so that True and 1 (equal in Python) stay different inputs and a bool still gets
    its error; unhashable values are passed to ``factory`` uncached (which names the bad parameter)."""

    @functools.lru_cache(maxsize=maxsize)
    def cached(key):
        return factory(**{k: v for k, _, v in key})

    @functools.wraps(factory)
    def build(**kw):
        if not kw:  # the defaults (simulate without options or geometry): the key of no keywords
            return cached(())
        key = tuple((k, type(v), v) for k, v in sorted(kw.items()))
        try:
            hash(key)
        except TypeError:
            return factory(**kw)
        return cached(key)

    return build
