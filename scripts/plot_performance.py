#!/usr/bin/python3
"""Tabulates and plots the JSON that scripts/performance.sh keeps in out/perf/.

    /usr/bin/python3 scripts/plot_performance.py out/perf

Reads machine.json and the Google Benchmark JSON of bench_step, bench_options,
bench_acceleration, bench_threads and bench_factorization (step.json, options.json, ...), and
bench_scale's scale.json (and million.json when there). Rewrites the text between each
`<!-- begin generated: NAME -->` and `<!-- end generated: NAME -->` in docs/performance.md with
table NAME, and writes docs/images/perf_iteration.png and perf_scale.png. A table whose input is
missing becomes a note saying which file; a marker missing from the page is reported.

Times are Google Benchmark's medians over the repetitions (a single run where there are none):
CPU time for one thread, wall clock (real_time) where two threads run.
"""
import json
import math
import pathlib
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "performance.md"
IMAGES = ROOT / "docs" / "images"
UNIT_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
SCENES = ["cloth32", "cloth64", "cloth128", "curtain", "flag", "skirt"]
FACTORIZATIONS = {
    "EigenAMD": "Eigen SimplicialLLT, AMD",
    "EigenND": "Eigen SimplicialLLT, nested dissection",
    "EigenCOLAMD": "Eigen SimplicialLLT, COLAMD",
    "EigenNatural": "Eigen SimplicialLLT, natural order",
    "CholmodDefault": "CHOLMOD supernodal, its choice",
    "CholmodAMD": "CHOLMOD supernodal, AMD",
    "CholmodMETIS": "CHOLMOD supernodal, METIS",
    "CholmodNESDIS": "CHOLMOD supernodal, NESDIS",
}


CONTEXT = ("context",)  # the key of a program's Google Benchmark context in load_gbench()'s result


class Missing(Exception):
    """An input file is not there."""


def load_gbench(path):
    """{(what, solver, scene): run} from Google Benchmark JSON: the median aggregate where the
    benchmark has repetitions, else its single run; each run with cpu_ms and real_ms added."""
    if not path.exists():
        raise Missing(path.name)
    runs = {}
    data = json.loads(path.read_text())
    runs[CONTEXT] = data["context"]
    for b in data["benchmarks"]:
        if b.get("error_occurred"):
            continue
        key = tuple(b["run_name"].split("/")[:3])
        median = b.get("run_type") == "aggregate" and b.get("aggregate_name") == "median"
        if b.get("run_type") == "aggregate" and not median:
            continue
        if key in runs and not median:
            continue  # a repetition: the median follows
        scale = UNIT_MS[b.get("time_unit", "ns")]
        b["cpu_ms"] = b["cpu_time"] * scale
        b["real_ms"] = b["real_time"] * scale
        runs[key] = b
    return runs


def load_scale(path):
    if not path.exists():
        raise Missing(path.name)
    return json.loads(path.read_text())["benchmarks"]


def ratio(a, b):
    return a / b if a is not None and b else None


def fmt(x, spec):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def table(header, rows):
    align = ["---" if h.startswith(("scene", "method", "factorization")) else "---:"
             for h in header]
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join(align) + "|"]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def when(runs, program):
    """The line under a table: which program, when, and the load average at its start."""
    c = runs[CONTEXT]
    load = ", ".join(f"{x:.2f}" for x in c.get("load_avg", []))
    return (f"\n\n`{program}`, {c['date'][:16].replace('T', ' ')}, load average {load or '-'} "
            "at its start.")


def scenes_in(runs):
    names = {k[2] for k in runs if len(k) == 3}
    return [s for s in SCENES if s in names] + sorted(names - set(SCENES))


def get(runs, what, solver, scene, field="cpu_ms"):
    r = runs.get((what, solver, scene))
    return None if r is None else r.get(field)


# ---- the tables -------------------------------------------------------------------------------


def machine_block(perf):
    path = perf / "machine.json"
    if not path.exists():
        raise Missing(path.name)
    m = json.loads(path.read_text())
    cpu = {e["field"].rstrip(":"): e["data"] for e in m["lscpu"] if "data" in e}
    flags = cpu.get("Flags", "").split()
    parts = [f"{cpu.get('Model name', 'unknown CPU')}, {cpu.get('CPU(s)', m.get('nproc'))} CPUs"]
    if "CPU max MHz" in cpu:
        parts.append(f"{float(cpu['CPU max MHz']):.0f} MHz max")
    caches = [f"{c} {cpu[c + ' cache']}" for c in ("L1d", "L2", "L3") if c + " cache" in cpu]
    if caches:
        parts.append(", ".join(caches))
    simd = [f for f in ("avx2", "fma", "avx512f") if f in flags]
    parts.append("SIMD: " + (", ".join(simd) if simd else "no AVX2"))
    load_end = f"; at the end {', '.join(m['load_end'])}" if "load_end" in m else ""
    return (f"Run of {m['date'][:10]} on {'; '.join(parts)} (lscpu). {m['compiler']}, "
            f"`{m['flags']}`, Eigen {m.get('eigen') or '(version unknown)'}. Load average "
            f"(1, 5, 15 min) at the start {', '.join(m['load_start'])}{load_end}.")


def scene_table(runs, header, row, program):
    """The table of one row per scene of `runs` (row(runs, scene): the cells, or None to leave
    the scene out), then when(runs, program)."""
    rows = [r for r in (row(runs, s) for s in scenes_in(runs)) if r is not None]
    return table(header, rows) + when(runs, program)


def step_row(runs, s):
    ours, seed = get(runs, "Step", "Sparse", s), get(runs, "Step", "Seed", s)
    floor, eigen = get(runs, "Floor", "Sparse", s), get(runs, "Floor", "EigenSolve", s)
    paired = get(runs, "Paired", "Sparse", s, "it_per_floor")
    r = runs.get(("Step", "Sparse", s), {})
    it = r.get("iterations_per_step") or 50
    return [
        s, fmt(r.get("points"), ".0f"), fmt(r.get("springs"), ".0f"),
        fmt(r.get("nnz_L"), ".0f"), fmt(ours, ".2f"), fmt(ratio(ours, it), ".3f"),
        fmt(floor, ".3f"), fmt(paired, ".2f"), fmt(seed, ".2f"),
        fmt(ratio(seed, ours), ".1f") + "x", fmt(ratio(ratio(seed, 50), floor), ".1f"),
        fmt(ratio(eigen, floor), ".1f"),
        fmt(get(runs, "Precompute", "Sparse", s), ".1f"),
        fmt(get(runs, "Precompute", "Seed", s), ".1f"),
        fmt(get(runs, "Step", "Seed", s, "first_step_diff"), ".0e")]


def step_block(perf):
    return scene_table(
        load_gbench(perf / "step.json"),
        ["scene", "points", "springs", "nnz(L)", "ours ms/step", "ours ms/iteration",
         "floor ms", "ours iteration/floor", "seed ms/step", "seed/ours",
         "seed iteration/floor", "Eigen solve/floor", "ours precompute ms",
         "seed precompute ms", "ours - seed after one step"], step_row, "bench_step")


def acceleration_row(runs, s):
    seed, plain = get(runs, "Step", "Seed", s), get(runs, "Step", "Sparse", s)
    cheb, anderson = get(runs, "Step", "Chebyshev", s), get(runs, "Step", "Anderson", s)
    cheb2 = get(runs, "Step", "ChebyshevThreads2", s, "real_ms")
    seed_wall = get(runs, "Step", "Seed", s, "real_ms")
    k = {n: get(runs, "Step", n, s, "iterations_per_step") for n in ("Chebyshev", "Anderson")}
    return [
        s, fmt(get(runs, "Step", "Sparse", s, "plain_error"), ".2g"),
        fmt(plain, ".2f"), fmt(seed, ".2f"),
        fmt(k["Chebyshev"], ".0f"), fmt(cheb, ".2f"), fmt(ratio(plain, cheb), ".1f") + "x",
        fmt(ratio(seed, cheb), ".1f") + "x",
        fmt(k["Anderson"], ".0f"), fmt(anderson, ".2f"),
        fmt(ratio(plain, anderson), ".1f") + "x", fmt(ratio(seed, anderson), ".1f") + "x",
        fmt(ratio(seed_wall, cheb2), ".1f") + "x"]


def acceleration_block(perf):
    return scene_table(
        load_gbench(perf / "acceleration.json"),
        ["scene", "step error of 50 plain iterations", "plain 50 ms", "seed 50 ms",
         "Chebyshev iterations", "Chebyshev ms", "plain/Chebyshev", "seed/Chebyshev",
         "Anderson iterations", "Anderson ms", "plain/Anderson", "seed/Anderson",
         "seed/Chebyshev on 2 threads (wall)"], acceleration_row, "bench_acceleration")


# bench_options' variants: (variant, the variant it is divided by, column name)
OPTION_VARIANTS = [("SparseNoSimd", "Sparse", "simd = false"),
                   ("SparseExact", "Sparse", "exact pins"),
                   ("SparseFloat", "SparseExact", "float / double, exact pins"),
                   ("SparseAMD", "Sparse", "AMD order")]


def options_row(runs, s):
    row = [s, fmt(get(runs, "Step", "Sparse", s), ".2f")]
    for v, base, _ in OPTION_VARIANTS:
        row.append(fmt(ratio(get(runs, "Step", v, s), get(runs, "Step", base, s)), ".2f"))
    row.append(fmt(get(runs, "Floor", "Sparse", s), ".3f"))
    for v, base, _ in OPTION_VARIANTS:
        row.append(fmt(ratio(get(runs, "Floor", v, s), get(runs, "Floor", base, s)), ".2f"))
    return row


def options_block(perf):
    header = (["scene", "default ms/step"] + [f"step: {n}" for _, _, n in OPTION_VARIANTS]
              + ["default floor ms"] + [f"floor: {n}" for _, _, n in OPTION_VARIANTS])
    return scene_table(load_gbench(perf / "options.json"), header, options_row, "bench_options")


def dense_row(runs, s):
    if ("Step", "Dense", s) not in runs:
        return None
    r = runs[("Step", "Dense", s)]
    return [s, fmt(r.get("points"), ".0f"),
            fmt(get(runs, "Precompute", "Dense", s), ".1f"),
            fmt(get(runs, "Precompute", "Sparse", s), ".1f"),
            fmt(get(runs, "Step", "Dense", s), ".2f"),
            fmt(get(runs, "Step", "Sparse", s), ".2f"),
            fmt(ratio(ratio(get(runs, "Step", "Dense", s), 50),
                      get(runs, "Floor", "Dense", s)), ".2f"),
            fmt(ratio(ratio(get(runs, "Step", "Sparse", s), 50),
                      get(runs, "Floor", "Sparse", s)), ".2f")]


def dense_block(perf):
    return scene_table(
        load_gbench(perf / "options.json"),
        ["scene", "points", "Dense precompute ms", "Sparse precompute ms",
         "Dense ms/step", "Sparse ms/step", "Dense iteration/floor",
         "Sparse iteration/floor"], dense_row, "bench_options")


def threads_block(perf):
    runs = load_gbench(perf / "threads.json")
    rows = []
    for s in sorted(scenes_in(runs), key=lambda s: get(runs, "Floor", "Threads1", s, "nnz_L") or 0):
        f1, f2 = (get(runs, "Floor", t, s, "real_ms") for t in ("Threads1", "Threads2"))
        s1, s2 = (get(runs, "Step", t, s, "real_ms") for t in ("Threads1", "Threads2"))
        rows.append([s, fmt(get(runs, "Floor", "Threads1", s, "points"), ".0f"),
                     fmt(get(runs, "Floor", "Threads1", s, "nnz_L"), ".0f"),
                     fmt(f1, ".4f"), fmt(f2, ".4f"), fmt(ratio(f1, f2), ".2f") + "x",
                     fmt(s1, ".2f"), fmt(s2, ".2f"), fmt(ratio(s1, s2), ".2f") + "x"])
    return table(["scene", "points", "nnz(L)", "floor ms, 1 thread", "floor ms, 2 threads",
                  "floor speed-up", "step ms, 1 thread", "step ms, 2 threads", "step speed-up"],
                 rows) + when(runs, "bench_threads")


def factorization_block(perf):
    runs = load_gbench(perf / "factorization.json")
    rows = []
    scenes = list(dict.fromkeys(k[2] for k in runs if len(k) == 3))
    for s in scenes:
        for m, name in FACTORIZATIONS.items():
            r = runs.get(("Factorize", m, s))
            if r is None:
                continue
            rows.append([s, name, fmt(r.get("nnz_L"), ".0f"), fmt(r["cpu_ms"], ".1f"),
                         fmt(r.get("solve_ms"), ".3f")])
    return table(["scene", "factorization", "nnz(L)", "factorize ms", "one n x 3 solve ms"],
                 rows) + when(runs, "bench_factorization")


def scale_rows(rows):
    out = []
    for r in rows:
        n = r["points"]
        nlogn = n * math.log2(n)
        two = r["iteration_threads2_ms"] if r["iteration_threads2_ms"] >= 0 else None
        out.append([
            f"{r['grid']}^2", r["points"], r["springs"], fmt(r["precompute_s"], ".3f"),
            fmt(r["nnz_L"], ".0f"), fmt(r["factor_mib"], ".1f"), fmt(r["iteration_ms"], ".3f"),
            fmt(r["floor_ms"], ".3f"), fmt(ratio(r["iteration_ms"], r["floor_ms"]), ".2f"),
            fmt(r["iteration_ms"] * 1e6 / nlogn, ".2f"),
            fmt(r["iteration_ms"] * 1e6 / r["nnz_L"], ".2f"), fmt(two, ".3f"),
            fmt(ratio(r["iteration_ms"], two), ".2f") + "x", fmt(r["peak_rss_mib"], ".0f"),
            "yes" if r["finite"] else "NO"])
    return out


SCALE_HEADER = ["grid", "points", "springs", "precompute s", "nnz(L)", "factor MiB",
                "ms/iteration", "floor ms", "iteration/floor", "ns/iteration / (n log2 n)",
                "ns/iteration / nnz(L)", "ms/iteration, 2 threads", "2-thread speed-up",
                "peak RSS MiB", "finite"]


def scale_block(perf):
    return table(SCALE_HEADER, scale_rows(load_scale(perf / "scale.json")))


def million_block(perf):
    return table(SCALE_HEADER, scale_rows(load_scale(perf / "million.json")))


BLOCKS = {
    "machine": (machine_block, "machine.json"),
    "step": (step_block, "step.json"),
    "acceleration": (acceleration_block, "acceleration.json"),
    "options": (options_block, "options.json"),
    "dense": (dense_block, "options.json"),
    "threads": (threads_block, "threads.json"),
    "factorization": (factorization_block, "factorization.json"),
    "scale": (scale_block, "scale.json"),
    "million": (million_block, "million.json"),
}


# ---- the plots --------------------------------------------------------------------------------


def plot_iteration(perf):
    runs = load_gbench(perf / "step.json")
    scenes = scenes_in(runs)
    ours = [get(runs, "Paired", "Sparse", s, "it_per_floor") or math.nan for s in scenes]
    seed = [ratio(ratio(get(runs, "Step", "Seed", s), 50), get(runs, "Floor", "Sparse", s))
            or math.nan for s in scenes]
    eigen = [ratio(get(runs, "Floor", "EigenSolve", s), get(runs, "Floor", "Sparse", s))
             or math.nan for s in scenes]
    x = range(len(scenes))
    fig, ax = plt.subplots(figsize=(8, 3.8))
    w = 0.27
    ax.bar([i - w for i in x], ours, w, label="ours: one iteration", color="tab:blue")
    ax.bar(list(x), eigen, w, label="Eigen's SimplicialLLT::solve alone", color="tab:orange")
    ax.bar([i + w for i in x], seed, w, label="reference solver: one iteration", color="tab:gray")
    ax.axhline(1, color="black", lw=0.8)
    ax.set_xticks(list(x))
    ax.set_xticklabels(scenes)
    ax.set_ylabel("time / floor (one L, L^T solve)")
    top = max([v for v in ours + eigen + seed if not math.isnan(v)], default=1)
    ax.set_ylim(0, 1.3 * top)
    ax.legend(fontsize=8, ncol=3, loc="upper center")
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(IMAGES / "perf_iteration.png", dpi=110)
    plt.close(fig)


def plot_scale(perf):
    rows = load_scale(perf / "scale.json")
    if (perf / "million.json").exists():
        rows += load_scale(perf / "million.json")
    n = [r["points"] for r in rows]
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.loglog(n, [r["iteration_ms"] for r in rows], "o-", label="one iteration [ms]")
    ax.loglog(n, [r["floor_ms"] for r in rows], "^-", label="floor: one L, L^T solve [ms]")
    two = [(x, r["iteration_threads2_ms"]) for x, r in zip(n, rows)
           if r["iteration_threads2_ms"] >= 0]
    if two:
        ax.loglog([p[0] for p in two], [p[1] for p in two], "v--",
                  label="one iteration, 2 threads [ms]")
    ax.loglog(n, [r["precompute_s"] * 1e3 for r in rows], "s-", label="precompute [ms]")
    c = rows[0]["iteration_ms"] / (n[0] * math.log2(n[0]))
    ax.loglog(n, [c * x * math.log2(x) for x in n], "k:", label="n log n (through the first)")
    ax.set_xlabel("points n")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(IMAGES / "perf_scale.png", dpi=110)
    plt.close(fig)


# ---- the page ---------------------------------------------------------------------------------


def replace_block(text, name, body):
    begin, end = f"<!-- begin generated: {name} -->", f"<!-- end generated: {name} -->"
    pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        print(f"plot_performance.py: docs/performance.md has no marker for {name}",
              file=sys.stderr)
        return text
    return pattern.sub(lambda _: f"{begin}\n{body}\n{end}", text)


def main(perf):
    perf = pathlib.Path(perf)
    IMAGES.mkdir(parents=True, exist_ok=True)
    text = DOC.read_text()
    for name, (make, source) in BLOCKS.items():
        try:
            body = make(perf)
        except Missing as e:
            body = f"(not in this run: {perf}/{e} is missing)"
        text = replace_block(text, name, body)
    DOC.write_text(text)
    for plot in (plot_iteration, plot_scale):
        try:
            plot(perf)
        except Missing as e:
            print(f"plot_performance.py: {plot.__name__} skipped, {e} is missing", file=sys.stderr)
    print("wrote docs/performance.md (generated blocks) and docs/images/perf_*.png")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/perf")
