"""Outputs of geomipmap-bench: frames.csv (every frame of every method), summary.md
(mean / median / p95 per DEM, method and tau, ratios against brute force and the fill floor
of the same run)
and bench.png (log-log frame time against measured max error, one panel per DEM).
"""

import csv
import json
import math
import os
import platform

import numpy as np

COLUMNS = ("dem", "nx", "ny", "method", "tau", "build_s", "frame", "lod_ms", "upload_ms",
           "render_ms", "total_ms", "triangles", "err_max_px", "err_p99_px", "err_mean_px",
           "samples_in_view", "uncovered", "depth_bad_frac", "shade_diff_frac", "certified_px")


class Output:
    def __init__(self, folder, command, args):
        self.folder, self.command, self.args = folder, command, args
        self.csv_path = os.path.join(folder, "frames.csv")
        self.summary_path = os.path.join(folder, "summary.md")
        self.plot_path = os.path.join(folder, "bench.png")
        self.rows, self.skips, self.notes = [], [], []
        self._f = open(self.csv_path, "w", newline="")
        self._w = csv.DictWriter(self._f, COLUMNS, extrasaction="ignore")
        self._w.writeheader()

    def frame(self, ctx, method, tau, build_s, row):
        r = dict(ctx, method=method, tau="" if tau is None else tau, build_s=build_s, **row)
        r.setdefault("certified_px", "")
        self.rows.append(r)
        self._w.writerow(r)

    def skip(self, dem, method, why):
        self.skips.append((dem, method, why))

    def note(self, dem, text):
        self.notes.append((dem, text))
        print(f"[{dem}] {text}", flush=True)

    def flush(self):
        """Frames so far, and the run's description / skips / notes (notes.json) for
        --replot."""
        self._f.flush()
        a = self.args
        meta = {"command": self.command, "machine": machine(), "size": list(a.size),
                "frames": a.frames, "path": a.path, "skips": self.skips, "notes": self.notes}
        with open(os.path.join(self.folder, "notes.json"), "w") as f:
            json.dump(meta, f, indent=1)

    def finish(self):
        self.flush()
        self._f.close()
        write_report([self.folder], self.folder)


def machine():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((ln.split(":", 1)[1].strip() for ln in f if ln.startswith("model name")),
                       cpu)
    except OSError:
        pass
    return f"{platform.node()}: {cpu}, {os.cpu_count()} CPUs, Python {platform.python_version()}"


def write_report(folders, out_folder):
    """summary.md and bench.png in out_folder from the frames.csv / notes.json of one or
    more runs (geomipmap-bench --replot merges runs, one section and panel per DEM)."""
    rows, metas = [], []
    for d in folders:
        with open(os.path.join(d, "frames.csv"), newline="") as f:
            for r in csv.DictReader(f):
                r["tau"] = float(r["tau"]) if r["tau"] not in ("", None) else ""
                rows.append(r)
        with open(os.path.join(d, "notes.json")) as f:
            metas.append(json.load(f))
    groups = summarise(rows)
    os.makedirs(out_folder, exist_ok=True)
    with open(os.path.join(out_folder, "summary.md"), "w") as f:
        f.write(markdown(groups, metas))
    plot(groups, os.path.join(out_folder, "bench.png"))


def _stats(v):
    v = np.asarray(v, float)
    return float(v.mean()), float(np.median(v)), float(np.percentile(v, 95))


def summarise(rows):
    """One record per (dem, method, tau), in run order."""
    keys = []
    by = {}
    for r in rows:
        k = (r["dem"], r["method"], r["tau"])
        if k not in by:
            keys.append(k)
            by[k] = []
        by[k].append(r)
    out = []
    for k in keys:
        rs = by[k]
        col = lambda name: [float(r[name]) for r in rs]  # noqa: E731
        tau = rs[0]["tau"]
        g = {"dem": k[0], "method": k[1], "tau": tau, "frames": len(rs),
             "build_s": float(rs[0]["build_s"]), "triangles": float(np.mean(col("triangles"))),
             "err_max": max(col("err_max_px")), "err_p99": max(col("err_p99_px")),
             "err_mean": float(np.mean(col("err_mean_px"))),
             "uncovered": float(np.mean(col("uncovered"))),
             "depth": float(np.mean(col("depth_bad_frac"))),
             "shade": (float(np.mean(col("shade_diff_frac")))
                       if all(r.get("shade_diff_frac", "") != "" for r in rs) else float("nan")),
             "shade_max": (max(col("shade_diff_frac"))
                           if all(r.get("shade_diff_frac", "") != "" for r in rs) else float("nan"))}
        for name in ("total_ms", "lod_ms", "upload_ms", "render_ms"):
            g[name] = _stats(col(name))
        g["within_tau"] = (all(e <= float(tau) for e in col("err_max_px")) if tau != "" else None)
        out.append(g)
    for g in out:
        brute = next((b for b in out if b["dem"] == g["dem"] and b["method"] == "brute"), None)
        g["speedup"] = brute["total_ms"][1] / g["total_ms"][1] if brute else float("nan")
        floor = next((b for b in out if b["dem"] == g["dem"] and b["method"] == "floor"), None)
        g["over_floor"] = g["total_ms"][1] / floor["total_ms"][1] if floor else float("nan")
    return out


# The mapper: as configured by default (automatic normals), shaded per fragment or per vertex
# at every tau, and per vertex without geomorphing.
OURS = ("ours", "ours-fn", "ours-vn", "ours-vn-nomorph")


def pareto(groups, dem, method="ours"):
    """(dominant, list of other-method points not beaten by a `method` point with <= error)."""
    ours = [g for g in groups if g["dem"] == dem and g["method"] == method]
    losses = []
    for g in groups:
        if g["dem"] != dem or g["method"] in OURS + ("brute", "floor"):
            continue
        beaten = any(o["err_max"] <= g["err_max"] and o["total_ms"][1] < g["total_ms"][1]
                     for o in ours)
        if not beaten:
            losses.append(g)
    return not losses and bool(ours), losses


def _f(x, nd=2):
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{nd}f}"


def markdown(groups, metas):
    lines = ["# geomipmap-bench results", ""]
    for m in metas:
        lines += [f"Command: `{m['command']}`  ", f"Machine: {m['machine']}  ",
                  f"Window {m['size'][0]} x {m['size'][1]}, {m['frames']} frames per method, "
                  f"path {m['path']}.", ""]
    lines += ["Frame times are wall times of Render() + WaitForCompletion() (glFinish); "
              "'x brute' = brute force's median frame time / this median; 'x floor' = this "
              "median / the fill floor's (ours at its coarsest with normals per vertex: the "
              "same pixels with the fewest triangles and the cheapest shading; brute's 'x "
              "floor' is the most any of ours can gain over brute force on this renderer). "
              "Errors are "
              "measured (vtkGeoMipMapScreenError): max and p99 are the worst frame's, mean "
              "is over frames. 'uncovered': in-view samples without a triangle above or "
              "below (mean per frame). 'depth diff': pixels whose depth differs from the "
              "full-resolution rendering by more than one depth step (mean per frame). "
              "'shading diff': terrain pixels whose colour differs from the "
              "full-resolution rendering by more than 24 levels (mean and worst frame).", ""]
    skips = [tuple(s) for m in metas for s in m["skips"]]
    notes = [tuple(n) for m in metas for n in m["notes"]]
    for dem in dict.fromkeys(g["dem"] for g in groups):
        lines += [f"## {dem}", "",
                  "| method | tau | triangles | build s | frame ms mean / median / p95 | "
                  "LOD ms | upload ms | render ms | x brute | x floor | err max px | p99 | mean | "
                  "uncovered | depth diff % | shading diff % mean / max |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for g in (g for g in groups if g["dem"] == dem):
            t = g["total_ms"]
            lines.append(
                f"| {g['method']} | {g['tau']} | {g['triangles']:.0f} | {_f(g['build_s'], 1)} | "
                f"{t[0]:.1f} / {t[1]:.1f} / {t[2]:.1f} | {g['lod_ms'][0]:.2f} | "
                f"{g['upload_ms'][0]:.2f} | {g['render_ms'][0]:.1f} | {_f(g['speedup'], 1)} | "
                f"{_f(g['over_floor'], 2)} | "
                f"{g['err_max']:.3f} | {g['err_p99']:.3f} | {g['err_mean']:.4f} | "
                f"{g['uncovered']:.0f} | {_f(100 * g['depth'], 2)} | "
                f"{_f(100 * g['shade'], 2)} / {_f(100 * g['shade_max'], 2)} |")
        for method in (x for x in OURS if any(g["dem"] == dem and g["method"] == x
                                                for g in groups)):
            dom, losses = pareto(groups, dem, method)
            lines += ["", f"Pareto of {method} (for every greedy / uniform / quadric point, an "
                      f"{method} point with <= measured max error and lower median frame time; "
                      f"brute force, 0 px, is the reference): {'yes' if dom else 'no'}"]
            if losses:
                lines.append(f"{method} beats every other point whose measured max error is "
                             f"below {min(g['err_max'] for g in losses):.2f} px; not beaten:")
            for g in losses:
                lines.append(f"- not beaten: {g['method']} tau {g['tau']} "
                             f"({g['err_max']:.3f} px, {g['total_ms'][1]:.1f} ms median)")
        lines.append("")
        for d, text in notes:
            if d == dem:
                lines.append(f"- {text}")
        lines.append("")
    if skips:
        lines += ["## Skipped", ""] + [f"- {d}: {m}: {w}" for d, m, w in skips] + [""]
    return "\n".join(lines)


def plot(groups, filename):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    dems = list(dict.fromkeys(g["dem"] for g in groups))
    if not dems:
        return
    cols = min(len(dems), 3)
    rows = (len(dems) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.2 * rows), squeeze=False)
    # Fixed colours: the same method looks the same in every panel.
    style = {"ours": ("o-", "C0"), "ours-fn": ("X-", "C6"), "ours-vn": ("D-", "C4"),
             "ours-vn-nomorph": ("P-", "C5"),
             "greedy": ("s--", "C1"),
             "uniform": ("^--", "C2"), "quadric": ("v--", "C3")}
    floor = 0.05  # log axes: a measured 0 px is drawn at this floor
    for ax, dem in zip(axes.ravel(), dems):
        gs = [g for g in groups if g["dem"] == dem]
        for method, (mk, colour) in style.items():
            pts = sorted(((g["tau"], max(g["err_max"], floor), g["total_ms"][1])
                          for g in gs if g["method"] == method), reverse=True)
            pts = [(e, t, tau) for tau, e, t in pts]  # joined in order of tau
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], mk, color=colour,
                        label=method)
                if method in OURS:
                    for e, t, tau in pts:
                        ax.annotate(f"τ={tau:g}", (e, t), fontsize=7, xytext=(3, 3),
                                    textcoords="offset points")
        for g in gs:
            if g["method"] == "brute":
                ax.axhline(g["total_ms"][1], color="k", ls=":",
                           label=f"brute force (0 px error)")
            if g["method"] == "floor":
                ax.axhline(g["total_ms"][1], color="0.5", ls="--",
                           label=f"fill floor (ours at its coarsest)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(f"measured max screen error, worst frame (px; 0 drawn at {floor})")
        ax.set_ylabel("median frame time (ms)")
        ax.set_title(dem, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    for ax in axes.ravel()[len(dems):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(filename, dpi=110)
    plt.close(fig)
