"""What every figure shares: pyplot on first use, failed points drawn as red crosses, selections of a
sweep, saving (PNG for the report, PDF for print)."""

from __future__ import annotations

import json

import numpy as np

__all__ = ["axis_label", "cor_line", "fixed_axes", "json_materials", "mark_failed", "plt", "point", "run_label", "save",
           "solver_label", "status_name", "unit_label", "v0_line"]

#: UDUNITS strings of the datasets -> the one unit style of the figures
_UNIT_LABELS = {"m s-1": "m/s", "kg m-3": "kg/m³", "s-1": "1/s", "rad s-1": "rad/s", "degC": "°C", "s-1/2": "1/√s",
                "m-1.5": "m⁻¹·⁵", "1": "", "cm s-1": "cm/s"}
#: method tags of the datasets -> words
_SOLVER_LABELS = {"direct-a": "direct", "direct-b": "direct, form b", "direct-a+volterra": "direct + Volterra term",
                  "ive-Radau": "internal variables (Radau)", "ive-BDF": "internal variables (BDF)",
                  "ive": "internal variables (solve_ivp)", "ive-numba": "internal variables, fixed step",
                  "soe": "exponential-sum history, fixed step", "adaptive": "adaptive (extrapolated)",
                  "adaptive-plain": "adaptive (not extrapolated)", "paper-explicit": "explicit baseline (paper's scheme)",
                  "paper": "explicit baseline (paper's scheme)"}


def unit_label(units: str) -> str:
    """A UDUNITS string as the figures write units (m/s, kg/m³, 1/s, °C; "" for dimensionless)."""
    return _UNIT_LABELS.get(units, units)


def axis_label(ds, name: str) -> str:
    """"long name, symbol [unit]" of a coordinate or variable of ``ds``."""
    attrs = ds[name].attrs
    unit = unit_label(attrs.get("units", ""))
    long = attrs.get("long_name", "")
    text = f"{long}, {name}" if long and long != name else name
    return f"{text} [{unit}]" if unit else text


def solver_label(tag: str) -> str:
    """A dataset's method tag (``direct-a``, ``ive-Radau``, ...) in words."""
    return _SOLVER_LABELS.get(tag, tag)


def run_label(run: str) -> str:
    """A histories run ``material/method`` as ``material (method in words)``."""
    material, _, method = run.partition("/")
    return f"{material} ({solver_label(method)})" if method else material


class _Pyplot:
    """``matplotlib.pyplot`` (Agg backend), imported on first use: the workflow's Snakefile imports
    this module for ``FIGURES`` and ``needs`` only, and importing pyplot cost ~0.5 s of every
    ``snakemake`` start (also of a no-op re-run)."""

    def __getattr__(self, name):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot

        return getattr(matplotlib.pyplot, name)


plt = _Pyplot()


def mark_failed(ax, x, ok, label="not ok"):
    bad = ~ok
    if np.any(bad):
        ax.plot(x[bad], np.zeros(bad.sum()), "x", color="red", ms=7, clip_on=False, transform=ax.get_xaxis_transform(),
                label=f"{label} ({bad.sum()})")
    return int(bad.sum())


def status_name(var) -> str:
    """Status name of a scalar status variable (CF flag_meanings)."""
    codes = dict(zip(var.attrs["flag_values"].tolist(), var.attrs["flag_meanings"].split()))
    return codes.get(int(var), "unknown").replace("_", "-")


def v0_line(sweep, material):
    """The sweep along v0 for one material (first value of any other axis)."""
    d = sweep.sel(material=material)
    for extra in [k for k in d.dims if k != "v0"]:
        d = d.isel({extra: 0})
    return d


def cor_line(ax, d, label):
    """COR against v0 for the ok points; the others as red crosses. Returns how many were not ok."""
    ok = d["status"].values == 0
    ax.plot(d["v0"].values[ok], d["cor"].values[ok], "o-", ms=3, label=label)
    ax.set_xlabel("v0 [m/s]")
    ax.set_ylabel("COR [-]")
    return mark_failed(ax, d["v0"].values, ok)


def point(sweep, material, v0, **sel):
    """Scalars at the grid point nearest to v0 (and the given other coordinates)."""
    ds = sweep.sel(material=material)
    for k, v in sel.items():
        if k in ds.dims:
            ds = ds.sel({k: v}, method="nearest")
    ds = ds.sel(v0=v0, method="nearest")
    for d in list(ds.dims):
        ds = ds.isel({d: 0})
    return ds


def fixed_axes(sweep, opts, free):
    """Selection of the axes a line figure does not draw: an option naming the axis picks its value
    (e.g. ``nu: 0.5``), else the first value. Returns (selection dict, label suffix)."""
    sel = {}
    for d in sweep["cor"].dims:
        if d in free:
            continue
        if d in opts:
            values = sweep[d].values
            if opts[d] not in values:
                raise ValueError(f"figure option {d}: {opts[d]!r} is not on the sweep's {d} axis {list(values)}")
            sel[d] = opts[d]
        else:
            sel[d] = sweep[d].values[0]
    units = {d: unit_label(sweep[d].attrs.get("units", "")) for d in sel}
    text = ", ".join(f"{d} = {v:g} {units[d]}".rstrip() for d, v in sel.items())
    return sel, (f" ({text})" if text else "")


def json_materials(ds) -> dict:
    """The material parameter dicts stored in a sweep dataset's attributes."""
    return json.loads(ds.attrs["materials"])


def save(fig, png, pdf) -> None:
    """Write ``fig`` as PNG (130 dpi, for the report) and PDF (for print), then close it. The PDF
    reuses the layout computed for the PNG (the layout engine is switched off after the first save):
    constrained layout costs up to a second per save on the many log axes of work_precision."""
    from ..io.receipts import atomic

    with atomic(png) as tmp:
        fig.savefig(tmp, dpi=130, format="png")
    fig.set_layout_engine("none")
    with atomic(pdf) as tmp:
        fig.savefig(tmp, metadata={"CreationDate": None}, format="pdf")
    plt.close(fig)

