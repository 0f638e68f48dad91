#!/usr/bin/python3
"""Tabulates and plots the stability stress suite's output (benchmarks/stability.cpp), which
scripts/stability.sh keeps in out/stability/: rewrites the text between each
`<!-- begin generated: NAME -->` and `<!-- end generated: NAME -->` in docs/stability.md (run,
in-brief, scene-<scene>, run-time) and writes docs/images/stability_*.png. The prose around the
blocks is written by hand in docs/stability.md.

    /usr/bin/python3 scripts/plot_stability.py out/stability
"""
import csv
import datetime
import math
import pathlib
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent

METHODS = ["ForwardEuler", "SymplecticEuler", "RK4", "BackwardEuler-linearized",
           "BackwardEuler-Newton", "LocalGlobal"]
SHORT = {"ForwardEuler": "FE", "SymplecticEuler": "SE", "RK4": "RK4",
         "BackwardEuler-linearized": "BE-lin", "BackwardEuler-Newton": "BE-Newton",
         "LocalGlobal": "LG"}
EXPLICIT = ["ForwardEuler", "SymplecticEuler", "RK4"]
OUTCOME_CODE = {"stable": 0, "growing": 1, "diverged": 2}
COLOURS = ["#4caf50", "#ffa726", "#e53935"]  # stable, growing, diverged
# A stable LocalGlobal run whose largest kinetic energy stays below this fraction of M |g| D
# barely moved: its 50 iterations per step did not get far from the previous positions.
FROZEN = 1e-3
# massspring::default_stability_safety: stable_time_step() = SAFETY x stability_limit(). The CSV's
# bound_dt is the limit; at_or_below_bound is 1 when dt <= SAFETY x bound_dt (checked in main()).
SAFETY = 0.5


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def fnum(s):
    return float(s) if s not in ("", None) else math.nan


def fmt_k(k):
    return f"1e{int(round(math.log10(k)))}"


def fmt_t(t):
    return f"{t:.2g}" if t < 1 else f"{t:.1f}"


def fmt_dt(dt):
    if abs(dt - 1 / 30) < 1e-9:
        return "1/30"
    return f"{dt:.0e}".replace("e-0", "e-")


def frozen(r):
    return (r["integrator"] == "LocalGlobal" and r["outcome"] == "stable"
            and fnum(r["KE_max"]) < FROZEN * motion_scale(r))


def motion_scale(r):
    # W = max(M g D, KE_max); M g D alone is what the scene's drop releases.
    return SCENE_MOTION[r["scene"]]


SCENE_MOTION = {}


def cell(r):
    o = r["outcome"]
    if o == "stable":
        return "ok*" if frozen(r) else "ok"
    if o == "growing":
        return "G"
    if o == "diverged":
        return f"D@{fmt_t(fnum(r['fail_time']))}"
    return o


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_stability.py OUT_DIR (e.g. out/stability)")
    out = pathlib.Path(sys.argv[1])
    rows = read_csv(out / "results.csv")
    meta = {r["key"]: r["value"] for r in read_csv(out / "meta.csv")}
    traces = {}
    for t in read_csv(out / "traces.csv"):
        traces.setdefault(int(t["run"]), []).append((fnum(t["t_mid"]), fnum(t["energy"])))
    for i, r in enumerate(rows):
        r["id"] = i
    machine = (out / "machine.txt").read_text().strip() if (out / "machine.txt").exists() else ""

    # M |g| D per scene: W of a run that never moved much (W = max(M g D, KE_max) >= M g D).
    for r in rows:
        if r["W"] and r["scene"] not in SCENE_MOTION and r["outcome"] == "stable":
            SCENE_MOTION[r["scene"]] = min(fnum(x["W"]) for x in rows
                                           if x["scene"] == r["scene"] and x["W"])
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    grid = [r for r in rows if r["kind"] == "grid"]
    bound = [r for r in rows if r["kind"] == "bound"]
    ks = sorted({fnum(r["k"]) for r in rows})
    dts = sorted({fnum(r["dt"]) for r in grid})
    factors = sorted({fnum(r["factor"]) for r in bound}, reverse=True)
    for r in rows:
        limit = fnum(r["bound_dt"])
        if r["at_or_below_bound"] == "1" and fnum(r["dt"]) > SAFETY * limit * (1 + 1e-6):
            sys.exit(f"plot_stability.py: SAFETY = {SAFETY} does not match the driver's "
                     f"at_or_below_bound (run {r['id']}); update SAFETY")

    images = ROOT / "docs" / "images"
    images.mkdir(parents=True, exist_ok=True)
    for s in scenes:
        plot_grid(s, grid, bound, ks, dts, meta["end_time"], images / f"stability_{s}.png")
    plot_bound_energy(bound, traces, scenes, images / "stability_bound_energy.png")

    wall = fnum(meta["wall_s"])
    blocks = {
        "run": (f"Last run: {datetime.date.today().isoformat()}, mode `{meta['mode']}`, "
                f"{meta['runs']} runs of {meta['end_time']} simulated seconds each, "
                f"**{wall / 60:.1f} minutes** wall clock on one core"
                + (f" ({machine})" if machine else "") + "."),
        "in-brief": in_brief(grid, bound, meta),
        "run-time": run_time(rows, scenes, wall),
    }
    for s in scenes:
        blocks[f"scene-{s}"] = scene_tables(s, grid, bound, ks, dts, factors)
    path = ROOT / "docs" / "stability.md"
    text = path.read_text()
    for name, body in blocks.items():
        text = replace_block(text, name, body)
    path.write_text(text)
    print(f"wrote docs/stability.md (generated blocks) and docs/images/stability_*.png from {out}")


def replace_block(text, name, body):
    """Text with the part between the markers of block `name` replaced by `body`."""
    begin, end = f"<!-- begin generated: {name} -->", f"<!-- end generated: {name} -->"
    pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        print(f"plot_stability.py: docs/stability.md has no marker for {name}", file=sys.stderr)
        return text
    return pattern.sub(lambda _: f"{begin}\n{body}\n{end}", text)


def in_brief(grid, bound, meta):
    L = []
    for m in METHODS:
        mine = [r for r in grid if r["integrator"] == m]
        counts = {o: sum(r["outcome"] == o for r in mine) for o in OUTCOME_CODE}
        extra = ""
        if m == "LocalGlobal":
            extra = f", of which {sum(frozen(r) for r in mine)} barely moved (ok*)"
        L.append(f"- **{m}**: {counts['stable']} stable{extra}, {counts['growing']} growing, "
                 f"{counts['diverged']} diverged of {len(mine)} cells.")
    return "\n".join(L) + "\n\n" + summary_checks(grid, bound, meta)


def scene_tables(s, grid, bound, ks, dts, factors):
    L = []
    w = L.append
    w(f"![{s}](images/stability_{s}.png)")
    w("")
    cols = [(m, dt) for m in METHODS for dt in dts]
    w("| k [N/m] | " + " | ".join(f"{SHORT[m]} {fmt_dt(dt)}" for m, dt in cols) + " |")
    w("|---|" + "---|" * len(cols))
    for k in ks:
        cells = []
        for m, dt in cols:
            r = find(grid, s, k, m, dt=dt)
            cells.append(cell(r) if r else "")
        w(f"| {fmt_k(k)} | " + " | ".join(cells) + " |")
    w("")
    w(f"### {s}: at factors of the limit")
    w("")
    head = ["k [N/m]"]
    for m in ["SymplecticEuler", "RK4"]:
        head.append(f"{SHORT[m]} limit [s]")
        head += [f"{SHORT[m]} x{f:g}" for f in factors]
    w("| " + " | ".join(head) + " |")
    w("|---|" + "---|" * (len(head) - 1))
    for k in ks:
        cells = [fmt_k(k)]
        for m in ["SymplecticEuler", "RK4"]:
            rs = [r for r in bound if r["scene"] == s and fnum(r["k"]) == k
                  and r["integrator"] == m]
            cells.append(f"{fnum(rs[0]['bound_dt']):.3g}" if rs else "")
            for f in factors:
                r = next((x for x in rs if fnum(x["factor"]) == f), None)
                if r is None:
                    cells.append("")
                    continue
                g = fnum(r["gain"])
                extra = f" ({100 * g:+.1f}%)" if not math.isnan(g) else ""
                cells.append(cell(r) + extra)
        w("| " + " | ".join(cells) + " |")
    w("")
    w(f"### {s}: deformation")
    w("")
    head = ["k [N/m]"]
    for f in (SAFETY, 1.0):
        head += [f"x{f:g} outcome", f"x{f:g} min l/l0", f"x{f:g} max l/l0",
                 f"x{f:g} min limit / limit(0)"]
    w("| " + " | ".join(head) + " |")
    w("|---|" + "---|" * (len(head) - 1))
    for k in ks:
        cells = [fmt_k(k)]
        for f in (SAFETY, 1.0):
            r = find_bound(bound, s, k, "SymplecticEuler", f)
            if r is None:
                cells += ["", "", "", ""]
                continue
            cells += [cell(r), f"{fnum(r['stretch_min']):.3g}", f"{fnum(r['stretch_max']):.3g}",
                      f"{fnum(r['limit_ratio_min']):.3g}"]
        w("| " + " | ".join(cells) + " |")
    return "\n".join(L)


def run_time(rows, scenes, wall):
    L = [f"Total {wall:.0f} s ({wall / 60:.1f} min).", "",
         "| integrator | " + " | ".join(scenes) + " |", "|---|" + "---:|" * len(scenes)]
    for m in METHODS:
        L.append(f"| {m} | " + " | ".join(
            f"{sum(fnum(r['wall_s']) for r in rows if r['integrator'] == m and r['scene'] == s):.1f} s"
            for s in scenes) + " |")
    slow = sorted(rows, key=lambda r: -fnum(r["wall_s"]))[:5]
    L += ["", "Slowest runs: " + "; ".join(
        f"{r['scene']} k={fmt_k(fnum(r['k']))} {r['integrator']} "
        f"{r['dt_label'] if r['kind'] == 'grid' else 'at ' + r['factor'] + ' x the limit'} "
        f"({fnum(r['steps_done']):.0f} steps): {fnum(r['wall_s']):.1f} s" for r in slow) + "."]
    return "\n".join(L)


def find(rows, scene, k, m, dt=None):
    for r in rows:
        if (r["scene"] == scene and fnum(r["k"]) == k and r["integrator"] == m
                and (dt is None or abs(fnum(r["dt"]) - dt) < 1e-15)):
            return r
    return None


def find_bound(bound, scene, k, m, factor):
    for r in bound:
        if (r["scene"] == scene and fnum(r["k"]) == k and r["integrator"] == m
                and abs(fnum(r["factor"]) - factor) < 1e-12):
            return r
    return None


def limit_ratio(r):
    return fnum(r["dt"]) / fnum(r["bound_dt"])


def summary_checks(grid, bound, meta):
    L = []
    w = L.append
    n, ok = int(meta["explicit_at_or_below_bound"]), int(meta["explicit_at_or_below_bound_stable"])
    w(f"**explicit runs at or below stable_time_step ({SAFETY:g} x the limit): {n}, all stable: "
      f"{'yes' if n == ok else 'no'}** ({ok} stable; ForwardEuler's runs at factors of the limit "
      f"skipped {meta['forward_euler_bound_skipped']} times: its limit is 0 without damping).")
    parts = []
    for f in sorted({fnum(r["factor"]) for r in bound}, reverse=True):
        rs = [r for r in bound if fnum(r["factor"]) == f and r["outcome"] != "skipped"]
        se = [r for r in rs if r["integrator"] == "SymplecticEuler"]
        tag = " (= stable_time_step)" if abs(f - SAFETY) < 1e-12 else ""
        n_ok, se_ok = sum(r["outcome"] == "stable" for r in rs), sum(
            r["outcome"] == "stable" for r in se)
        parts.append(f"at {f:g} x the limit{tag} {n_ok} of {len(rs)} stable (symplectic Euler "
                     f"{se_ok} of {len(se)})")
    below = [r for r in grid if r["at_or_below_bound"] == "1"]
    worst = max((limit_ratio(r) for r in below), default=math.nan)
    parts.append(f"grid cells at or below stable_time_step (all at <= {worst:.2f} x the limit) "
                 f"{sum(r['outcome'] == 'stable' for r in below)} of {len(below)} stable")
    w("")
    w("By where they ran: " + "; ".join(parts) + ".")

    def failures(title, rows):
        if rows:
            w("")
            w(title)
            w("")
            for r in rows:
                w(f"- {failure_line(r)}")

    failures("Not stable at or below stable_time_step:",
             [r for r in grid + bound if r["at_or_below_bound"] == "1" and r["outcome"] != "stable"])
    failures("Not stable at the factors above stable_time_step (the margin the safety factor buys):",
             [r for r in bound if r["at_or_below_bound"] == "0"
              and r["outcome"] not in ("stable", "skipped")])
    # Known cases.
    w("")
    w("Known cases:")
    w("")
    for m in ["SymplecticEuler", "RK4"]:
        rs = [r for r in grid if r["integrator"] == m]
        lo = [r for r in rs if r["at_or_below_bound"] == "1"]
        mid = [r for r in rs if r["at_or_below_bound"] == "0" and limit_ratio(r) <= 1 + 1e-12]
        hi = [r for r in rs if limit_ratio(r) > 1 + 1e-12]
        between = (f"between it and the limit: {sum(r['outcome'] == 'stable' for r in mid)} of "
                   f"{len(mid)} stable" if mid else "none between it and the limit")
        w(f"- {m} grid cells at or below stable_time_step: "
          f"{sum(r['outcome'] == 'stable' for r in lo)} of {len(lo)} stable; {between}; above the "
          f"limit: {sum(r['outcome'] == 'diverged' for r in hi)} of {len(hi)} diverged"
          + (f", {sum(r['outcome'] == 'growing' for r in hi)} growing" if any(
              r["outcome"] == "growing" for r in hi) else "") + ".")
    fe = [r for r in grid if r["integrator"] == "ForwardEuler"]
    fe_ok = [r for r in fe if r["outcome"] == "stable"]
    w(f"- ForwardEuler (no stable step without damping): {len(fe) - len(fe_ok)} of {len(fe)} cells "
      "growing or diverged." + (
          " Classified stable: " + ", ".join(
              f"{r['scene']} k={fmt_k(fnum(r['k']))} dt {r['dt_label']} (gain "
              f"{100 * fnum(r['gain']):+.2g}%)" for r in fe_ok)
          + "." if fe_ok else ""))
    for m in ["BackwardEuler-Newton", "BackwardEuler-linearized", "LocalGlobal"]:
        mine = [r for r in grid if r["integrator"] == m]
        notok = [r for r in mine if r["outcome"] != "stable"]
        line = f"- {m}: {len(mine) - len(notok)} of {len(mine)} cells stable"
        if notok:
            line += "; not stable: " + ", ".join(
                f"{r['scene']} k={fmt_k(fnum(r['k']))} dt {r['dt_label']}: {cell(r)}"
                + (f" (energy peak {fnum(r['E_max']) - fnum(r['E0']):.3g} J; "
                   f"{r['indefinite_solves']} of {r['steps_done']} steps solved an indefinite "
                   "system)" if m.startswith("BackwardEuler") else "")
                for r in notok)
        if m == "BackwardEuler-Newton":
            unc = [r for r in mine if int(r["unconverged_steps"]) > 0]
            if unc:
                line += (". Steps that stopped at iterations: " + ", ".join(
                    f"{r['scene']} k={fmt_k(fnum(r['k']))} dt {r['dt_label']}: "
                    f"{r['unconverged_steps']} of {r['steps_done']}" for r in unc))
        w(line + ".")
    return "\n".join(L)


def failure_line(r):
    if r["kind"] == "bound":
        where = f"{fnum(r['factor']):g} x the limit"
    else:
        where = f"dt {r['dt_label']} = {limit_ratio(r):.2g} x the limit"
    what = cell(r)
    if r["outcome"] == "growing":
        what += f" (gain {100 * fnum(r['gain']):+.1f}% of W)"
    return (f"{r['scene']} k={fmt_k(fnum(r['k']))} {r['integrator']} at {where} "
            f"(dt {fnum(r['dt']):.3g} s): {what}")


def plot_grid(scene, grid, bound, ks, dts, end_time, path):
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5), sharex=True, sharey=True)
    cmap = ListedColormap(COLOURS)
    lx = [math.log10(d) for d in dts]
    # cell edges halfway between the (log) time steps
    ex = [lx[0] - 0.5] + [(a + b) / 2 for a, b in zip(lx, lx[1:])] + [lx[-1] + 0.25]
    ly = [math.log10(k) for k in ks]
    ey = [ly[0] - 0.5] + [(a + b) / 2 for a, b in zip(ly, ly[1:])] + [ly[-1] + 0.5]
    for ax, m in zip(axes.flat, METHODS):
        z = [[OUTCOME_CODE.get((find(grid, scene, k, m, dt=dt) or {}).get("outcome"), math.nan)
              for dt in dts] for k in ks]
        ax.pcolormesh(ex, ey, z, cmap=cmap, vmin=-0.5, vmax=2.5, edgecolors="white", linewidth=1)
        for i, k in enumerate(ks):
            for j, dt in enumerate(dts):
                r = find(grid, scene, k, m, dt=dt)
                if r is None:
                    continue
                txt = cell(r)
                ax.text((ex[j] + ex[j + 1]) / 2, ly[i], txt, ha="center", va="center", fontsize=7)
        if m in ("SymplecticEuler", "RK4"):
            pts = sorted((fnum(r["k"]), fnum(r["bound_dt"])) for r in bound
                         if r["scene"] == scene and r["integrator"] == m and fnum(r["factor"]) == 1)
            ax.plot([math.log10(b) for _, b in pts], [math.log10(k) for k, _ in pts], "k--", lw=1.2,
                    label="stability_limit")
            ax.plot([math.log10(SAFETY * b) for _, b in pts], [math.log10(k) for k, _ in pts], "k:",
                    lw=1.4, label=f"stable_time_step ({SAFETY:g} x)")
            ax.legend(loc="lower left", fontsize=7)
        ax.set_title(m, fontsize=10)
        ax.set_xlim(ex[0], ex[-1])
        ax.set_ylim(ey[0], ey[-1])
        ax.set_xticks(lx)
        ax.set_xticklabels([fmt_dt(d) for d in dts])
        ax.set_yticks(ly)
        ax.set_yticklabels([fmt_k(k) for k in ks])
    for ax in axes[1]:
        ax.set_xlabel("time step dt [s]")
    for ax in axes[:, 0]:
        ax.set_ylabel("stiffness k [N/m]")
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in COLOURS]
    fig.legend(handles, ["stable (ok; ok*: barely moved)", "energy growing (G)",
                         "diverged (D@t: at t seconds)"], loc="lower center", ncol=3, fontsize=9)
    fig.suptitle(f"{scene}: outcome of {end_time} simulated seconds per stiffness and time step",
                 fontsize=11)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_bound_energy(bound, traces, scenes, path):
    factors = sorted({fnum(r["factor"]) for r in bound}, reverse=True)
    fig, axes = plt.subplots(len(scenes), len(factors), figsize=(5 * len(factors), 3.4 * len(scenes)),
                             squeeze=False, sharex=True, sharey="row")
    cm = plt.get_cmap("viridis")
    for i, s in enumerate(scenes):
        rs = [r for r in bound if r["scene"] == s and r["integrator"] == "SymplecticEuler"
              and r["outcome"] != "skipped"]
        ks = sorted({fnum(r["k"]) for r in rs})
        for j, f in enumerate(factors):
            ax = axes[i][j]
            for r in rs:
                if fnum(r["factor"]) != f:
                    continue
                k = fnum(r["k"])
                pts = [(t, (e - fnum(r["E0"])) / fnum(r["W"] or "nan"))
                       for t, e in traces[r["id"]] if not math.isnan(e)]
                c = cm(ks.index(k) / max(1, len(ks) - 1))
                ax.plot([p[0] for p in pts], [p[1] for p in pts], color=c, lw=1,
                        label=fmt_k(k) + (" (D)" if r["outcome"] == "diverged" else ""))
            ax.axhline(0.05, color="grey", ls=":", lw=1)
            ax.set_yscale("symlog", linthresh=1e-3)
            what = " = stable_time_step" if abs(f - SAFETY) < 1e-12 else ""
            ax.set_title(f"{s}: SymplecticEuler at {f:g} x the limit{what}", fontsize=10)
            ax.set_ylabel("(E - E0) / W")
            if i == len(scenes) - 1:
                ax.set_xlabel("t [s]")
            ax.legend(fontsize=6, ncol=3, title="k [N/m]", title_fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
