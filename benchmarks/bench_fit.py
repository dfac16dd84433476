"""Fit benchmark: time of each fit (median of 5) and its worst relative error. Run:
python benchmarks/bench_fit.py"""

from pathlib import Path

from timing import timed

from vcor import fit


def main():
    data = fit.bagley_torvik_data()
    rows = []
    t_auto, auto = timed(lambda: fit.fit_prony(data, None, tol=0.01))
    rows.append((f"Prony, automatic N (= {auto.n_terms}), tol 1 %", t_auto, auto.max_error))
    t_cerf, cerf = timed(lambda: fit.fit_cerf(data))
    rows.append(("CERF", t_cerf, cerf.max_error))
    for n in (3, 7, 9, 12):
        t, r = timed(lambda n=n: fit.fit_prony(data, n), 3)
        rows.append((f"Prony, N = {n}", t, r.max_error))
    # measured data: pyvisco's raw DMA example (superposition + WLF + Prony, one term per decade)
    raw = Path(__file__).resolve().parents[1] / "data/pyvisco/freq_user_raw.csv"
    spec = {"model": "prony", "data": {"file": str(raw), "T_ref": -5.0}}
    t, (r, _, _) = timed(lambda: fit.run_fit(spec), 3)
    rows.append((f"pyvisco raw DMA, superposition + N = {r.n_terms}", t, r.max_error))
    print(f"{'fit':40s} {'median':>10s} {'worst rel. error':>18s}")
    for name, t, e in rows:
        print(f"{name:40s} {t * 1e3:8.1f} ms {e:18.3e}")
    print(f"{'material stage (automatic Prony + CERF)':40s} {(t_auto + t_cerf) * 1e3:8.1f} ms   target: well under 1 s")


if __name__ == "__main__":
    main()
