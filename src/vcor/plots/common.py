"""What every figure shares: pyplot on first use, failed points drawn as red crosses, points outside the
model's stated range drawn open on a dashed segment, selections of a sweep, saving (PNG for the report,
PDF for print)."""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

__all__ = ["FLAGGED_STYLE", "PNG_DPI", "Drawn", "axis_label", "cor_line", "fixed_axes", "flag_legend",
           "flag_reasons", "flagged_label", "json_materials", "mark_failed", "plt", "point", "run_label", "save",
           "solver_label", "status_name", "sweep_line", "unit_label", "v0_line", "validity_of"]

#: UDUNITS strings of the datasets -> the one unit style of the figures
_UNIT_LABELS = {"m s-1": "m/s", "kg m-3": "kg/m³", "s-1": "1/s", "rad s-1": "rad/s", "degC": "°C", "s-1/2": "1/√s",
                "m-1.5": "m⁻¹·⁵", "1": "", "cm s-1": "cm/s"}
#: method tags of the datasets -> words
_SOLVER_LABELS = {"direct-a": "direct", "direct-b": "direct, form b", "direct-a+volterra": "direct + Volterra term",
                  "ive-Radau": "internal variables (Radau)", "ive-BDF": "internal variables (BDF)",
                  "ive": "internal variables (solve_ivp)", "ive-numba": "internal variables, fixed step",
                  "soe": "exponential-sum history, fixed step", "adaptive": "adaptive (extrapolated)",
                  "adaptive-plain": "adaptive (not extrapolated)",
                  "paper-explicit": "explicit baseline (paper's scheme)", "paper": "explicit baseline (paper's scheme)"}


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
    """Points that are not ok (``~ok``) as red crosses on the x axis, labelled with their count.
    Returns the count."""
    bad = ~ok
    if np.any(bad):
        ax.plot(x[bad], np.zeros(bad.sum()), "x", color="red", ms=7, clip_on=False, transform=ax.get_xaxis_transform(),
                label=f"{label} ({bad.sum()})")
    return int(bad.sum())


#: how an ok point outside the model's stated range is drawn, in every figure: an open marker, and a
#: dashed segment to each neighbour (a valid point has a filled marker on a solid line)
FLAGGED_STYLE = {"marker": "o", "mfc": "none", "ls": "--"}


@dataclass(kw_only=True, frozen=True)
class Drawn:
    """What :func:`sweep_line` drew: the line's colour, how many points were not ok (red crosses),
    how many were ok but flagged (open markers), and the union of their validity flags."""

    color: str
    not_ok: int
    flagged: int
    flags: int

    @classmethod
    def total(cls, drawn) -> Drawn:
        """The counts and flags of several :class:`Drawn` together (no colour)."""
        drawn = list(drawn)
        return cls(color="", not_ok=sum(d.not_ok for d in drawn), flagged=sum(d.flagged for d in drawn),
                   flags=int(np.bitwise_or.reduce([d.flags for d in drawn], initial=0)))

    def note(self, newline=False) -> str:
        """The counts for a title: " (2 not ok, 5 outside the model's range)" (on a line of its own with
        ``newline``), or "" when all are ok and valid."""
        parts = []
        if self.not_ok:
            parts.append(f"{self.not_ok} not ok")
        if self.flagged:
            parts.append(f"{self.flagged} outside the model's range")
        if not parts:
            return ""
        return ("\n" if newline else " ") + f"({', '.join(parts)})"


def validity_of(d) -> np.ndarray:
    """The validity flags (:mod:`vcor.solvers.validity`) of the points of ``d`` (a Dataset with
    ``status``), shaped like its status; zeros for a dataset without a ``validity`` variable."""
    if "validity" in d:
        return np.asarray(d["validity"].values, dtype=np.int64)
    return np.zeros(np.shape(d["status"].values), dtype=np.int64)


def flag_reasons(flags: int) -> str:
    """The reasons of a union of validity flags in a few words, with the limits of
    :mod:`vcor.solvers.validity` (e.g. ``s_max/r > 0.1; fast impact, v0 > 0.1 c (wave speed)``); "" for 0."""
    from ..solvers import validity as V  # the limits' one source; imported when a figure is drawn

    words = {"large_indentation": f"s_max/r > {V.MAX_INDENTATION:g}",
             "fast_impact": f"fast impact, v0 > {V.MAX_SPEED_FRACTION:g} c (wave speed)",
             "energy_residual": f"energy balance off by > {V.MAX_ENERGY_RESIDUAL:g}",
             "under_resolved": "damping under-resolved by the fixed step",
             "no_rebound": "no rebound, sphere still approaching",
             "grids_disagree": "t0 ill-conditioned, grids disagree",
             "uncertain_extrapolation": "t0 not held to the solver's accuracy"}
    out = [words.get(name, name.replace("_", " ")) for name, mask in V.FLAGS.items() if flags & mask]
    known = sum(V.FLAGS.values())
    if flags & ~known:
        out.append(f"flag bits {flags & ~known}")
    return "; ".join(out)


def flagged_label(flags: int) -> str:
    """The legend text of the flagged style for the union ``flags`` of the points drawn (the reasons on a
    second line when they are long, to keep legends narrow)."""
    reasons = flag_reasons(flags)
    return f"outside the model's range{chr(10) if len(reasons) > 24 else ' '}({reasons})"


def flag_legend(ax, flags: int) -> None:
    """Add the legend entry of the flagged style (grey open marker on a dashed line) to ``ax`` when
    ``flags`` is not 0; call it before ``ax.legend()``."""
    if flags:
        ax.plot([], [], color="0.35", ms=4, label=flagged_label(int(flags)), **FLAGGED_STYLE)


def sweep_line(ax, x, y, status, validity=None, *, label=None, color=None, ms=3.0) -> Drawn:
    """``y`` against ``x`` for the ok points (status 0), joined in order: valid points filled on a solid
    line, flagged points (validity != 0) open with dashed segments to their neighbours, in the same
    colour; points not ok as red crosses on the axis. Returns what was drawn (:class:`Drawn`)."""
    x, y, status = np.asarray(x, float), np.asarray(y, float), np.asarray(status)
    validity = np.zeros(status.shape, np.int64) if validity is None else np.asarray(validity, np.int64)
    ok = status == 0
    xs, ys, flagged = x[ok], y[ok], validity[ok] != 0
    line, = ax.plot(xs, np.where(flagged, np.nan, ys), "o-", ms=ms, color=color, label=label)
    color = line.get_color()
    if flagged.any():
        ax.plot(xs[flagged], ys[flagged], ls="none", marker="o", mfc="none", ms=ms + 1, color=color)
        seg = [i for i in range(xs.size - 1) if flagged[i] or flagged[i + 1]]
        if seg:
            px = np.concatenate([[xs[i], xs[i + 1], np.nan] for i in seg])
            py = np.concatenate([[ys[i], ys[i + 1], np.nan] for i in seg])
            ax.plot(px, py, ls="--", color=color, lw=line.get_linewidth())
    not_ok = mark_failed(ax, x, ok)
    return Drawn(color=color, not_ok=not_ok, flagged=int(flagged.sum()),
                 flags=int(np.bitwise_or.reduce(validity[ok], initial=0)))


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


def cor_line(ax, d, label) -> Drawn:
    """COR against v0 of the line ``d`` (:func:`sweep_line`: flagged points open and dashed, points not
    ok as red crosses)."""
    drawn = sweep_line(ax, d["v0"].values, d["cor"].values, d["status"].values, validity_of(d), label=label)
    ax.set_xlabel("v0 [m/s]")
    ax.set_ylabel("COR [-]")
    return drawn


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


#: resolution of the PNG (for the report), dots per inch
PNG_DPI = 130


def _layout_once(fig, dpi) -> None:
    """Run ``fig``'s layout engine once, at the resolution ``dpi`` of the first file written, and switch
    the engine off: ``savefig`` with an engine draws the figure twice (an invisible draw that lays it out,
    then the real one, which lays it out again), and every later file would repeat both."""
    import matplotlib

    engine = fig.get_layout_engine()
    if engine is None:
        return
    dpi0 = fig.dpi
    fig.dpi = dpi
    try:
        engine.execute(fig)
    finally:
        fig.dpi = dpi0
    with matplotlib.rc_context({"figure.autolayout": False, "figure.constrained_layout.use": False}):
        fig.set_layout_engine(None)


def save(fig, png, pdf) -> None:
    """Write ``fig`` as PNG (:data:`PNG_DPI`, for the report) and PDF (for print), then close it. The layout
    is computed once, for the PNG, and both files reuse it (:func:`_layout_once`); log axes compute only
    the minor ticks in view (:mod:`vcor.plots.ticks`); the PDF's rasterized parts (colorbars) keep the
    figure's own resolution."""
    from ..io.receipts import atomic
    from .ticks import minor_ticks_in_view

    dpi = fig.dpi
    minor_ticks_in_view(fig)
    _layout_once(fig, PNG_DPI)
    with atomic(png) as tmp:
        fig.savefig(tmp, dpi=PNG_DPI, format="png")
    with atomic(pdf) as tmp:
        fig.savefig(tmp, dpi=dpi, metadata={"CreationDate": None}, format="pdf")
    plt.close(fig)
