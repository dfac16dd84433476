"""Which method solves which kernel: the refusals that follow from the material and the bodies alone,
not from the point (speed, step), so that a scene is refused at planning, before any work, rather
than storing every point as ``invalid-input``.

The runners keep their own checks for what only a point shows (whether a two-body modulus has an
exponential sum from t = 0 over that contact's window: ``vcor.solvers.ive.kernel_terms``).
"""

from __future__ import annotations

import math

__all__ = ["IVE_KERNELS", "IVE_VOLTERRA", "PAPER_NO_DIRAC", "form_b_singular", "refusal"]

#: what ``ive`` and ``ive-numba`` take, in words
IVE_KERNELS = ("a Prony kernel (sls, butyl-prony3, prony, elastic, kelvin-voigt) or a two-body contact modulus "
               "that is a sum of exponentials from t = 0")
#: the refusals the runners raise too (for callers that reach them without :func:`refusal`)
IVE_VOLTERRA = ("solver option volterra: the second-order term of method 'ive' needs a Prony kernel (its G_k > 0); "
                "a two-body contact modulus takes it with method 'direct'")
PAPER_NO_DIRAC = "method 'paper' has no Dirac (Kelvin-Voigt) term; use 'direct'"


def form_b_singular(kind: str) -> str:
    """The refusal of ``direct``'s form b for a kernel of ``kind`` singular at t = 0."""
    return f"form 'b' needs a finite k(0) and an integrable kdot; material {kind!r} is singular at t = 0: use form 'a'"


def refusal(material, options) -> str:
    """The reason ``options.method`` (a :class:`~vcor.solvers.options.SolverOptions`) cannot solve an
    impact whose contact kernel is ``material`` (``Impact.material``: a two-body contact's Eq. 1
    modulus where the bodies differ), naming the method that can; "" when it can.

    Examples
    --------
    >>> from vcor.materials import presets
    >>> from vcor.solvers.options import SolverOptions
    >>> print(refusal(presets.get("butyl-fc"), SolverOptions(method="ive")))  # doctest: +ELLIPSIS
    method 'ive' needs a Prony kernel ... got 'fractional': use method 'adaptive' (or 'direct')
    >>> refusal(presets.get("sls"), SolverOptions(method="ive"))
    ''
    """
    method, mat = options.method, material
    if method in ("ive", "ive-numba"):
        two_body = mat.kind == "eq1" and math.isfinite(mat.glassy)
        if not (mat.is_prony or two_body):
            return (f"method {method!r} needs {IVE_KERNELS}; got {mat.kind!r}: use method 'adaptive' "
                    f"(or 'direct')")
        if method == "ive" and options.volterra and not mat.is_prony:
            return IVE_VOLTERRA
    if method == "paper" and mat.viscosity > 0:
        return PAPER_NO_DIRAC
    if method == "direct" and options.form == "b" and not math.isfinite(mat.glassy):
        return form_b_singular(mat.kind)
    return ""
