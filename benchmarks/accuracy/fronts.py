#!/usr/bin/env python3
"""Error against run time over mesh refinement, xpl beside CalculiX (issue 16, item 1).

For every case of cases.py and every mesh level, the deck is written for each solver and
run at 1 and 2 threads; the solvers alternate (xpl, CalculiX, xpl, CalculiX, ... within a
level) so that a change in the machine's load hits both. Each run's errors against the
analytic answer go to RESULTS_DIR/CASE.csv (date, machine and load in CASE.meta.txt), the
fronts (each error against CPU time, log-log) to RESULTS_DIR/CASE.png, and the tables and
equal-error speed ratios of every case with a CSV to RESULTS_DIR/fronts.md.

Usage: fronts.py XPL [--ccx CCX] [--cases bar_wall,bar_bar,...] [--levels N ...]
                 [--repeat R] [--work DIR] [--results DIR] [--report-only]
Needs numpy, h5py and matplotlib (/usr/bin/python3 on the team machine).
"""
import argparse
import csv
import datetime
import math
import os
import pathlib
import platform
import subprocess
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import cases  # noqa: E402
import solvers  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent

COLUMNS = ["case", "solver", "threads", "level", "mesh_size", "elements", "increments",
           "wall_s", "cpu_s", "solver_elapsed_s"]


def machine_line():
    cpu = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} logical cores, {platform.system()} {platform.release()}"


def uptime():
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return "uptime unavailable"


def run_case(case, xpl, ccx, levels, repeat, work, log):
    rows, failures = [], []
    for level in levels:
        decks = {}
        for solver in ("xpl", "calculix"):
            if solver == "calculix" and not ccx:
                continue
            if solver not in getattr(case, "solvers", ("xpl", "calculix")):
                continue
            if solver == "calculix" and level > getattr(case, "ccx_max_level", level):
                continue
            text, ref = case.deck(level, solver)
            path = work / case.name / f"{case.name}_{level}_{solver}.inp"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
            decks[solver] = (path, ref)
        for rep in range(repeat):
            for threads in (1, 2):
                for solver, (path, ref) in decks.items():
                    run_dir = work / case.name / f"{level}_{solver}_t{threads}_r{rep}"
                    try:
                        if solver == "xpl":
                            run = solvers.run_xpl(xpl, path, threads, run_dir)
                        else:
                            run = solvers.run_ccx(ccx, path, threads, run_dir)
                        errors = case.measure(run, ref)
                    except (RuntimeError, KeyError, IndexError, ValueError) as error:
                        log(f"  {case.name} {level} {solver} t{threads}: FAILED: {error}")
                        failures.append(f"{solver} {case.level_name} {level}, {threads} "
                                        f"thread(s) failed: {str(error).split('; see')[0]}")
                        continue
                    row = {"case": case.name, "solver": solver, "threads": threads,
                           "level": level, "mesh_size": case.mesh_size(level),
                           "elements": ref["elements"], "increments": run["increments"],
                           "wall_s": run["wall"], "cpu_s": run["cpu"],
                           "solver_elapsed_s": run["summary"]["wall_time"]["elapsed"]
                           if solver == "xpl" else ""}
                    row.update(errors)
                    rows.append(row)
                    log(f"  {case.name} {level:>4} {solver:8} t{threads} inc {run['increments']:>6}"
                        f" wall {run['wall']:8.3f} s cpu {run['cpu']:8.3f} s  " +
                        " ".join(f"{k} {v:.4g}" for k, v in errors.items()))
    notes = []
    if hasattr(case, "finish"):  # errors against a reference made from the runs
        notes.append(case.finish(rows))
        log(f"  {case.name}: {notes[-1]}")
    return rows, "; ".join(notes + failures)


def write_csv(path, rows):
    keys = list(COLUMNS)
    for row in rows:
        keys += [k for k in row if k not in keys]
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v)
                             for k, v in row.items()})


def read_csv(path):
    rows = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            for k, v in row.items():
                try:
                    row[k] = int(v)
                except ValueError:
                    try:
                        row[k] = float(v)
                    except ValueError:
                        pass
            rows.append(row)
    return rows


def best_runs(rows, solver, threads):
    """One point per level: the run with the least CPU time (repeats)."""
    best = {}
    for row in rows:
        if row["solver"] == solver and row["threads"] == threads:
            if row["level"] not in best or row["cpu_s"] < best[row["level"]]["cpu_s"]:
                best[row["level"]] = row
    return [best[k] for k in sorted(best)]


def front(points):
    """Pareto front of (time, error): sorted by time, keeping only points that lower the
    error (a finer mesh that is not more accurate does not extend the front)."""
    out = []
    for t, e in sorted(points):
        if e > 0 and (not out or e < out[-1][1]):
            out.append((t, e))
    return out


def time_at_error(fr, error):
    """Time the front needs for `error` (log-log interpolation); nan outside its range."""
    if len(fr) < 1:
        return math.nan
    errors = [e for _, e in fr]
    if not (min(errors) <= error <= max(errors)):
        return math.nan
    if len(fr) == 1:
        return fr[0][0]
    for (t0, e0), (t1, e1) in zip(fr, fr[1:]):
        if e1 <= error <= e0:
            if e0 == e1:
                return t0
            s = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0)))
    return math.nan


def speed_ratio(rows, error_name, threads, clock="cpu_s"):
    """CalculiX time / xpl time at equal error, over the errors both fronts reach: (ratio
    at the geometric middle of the overlap, lowest, highest, overlap range) or None."""
    fronts = {}
    for solver in ("xpl", "calculix"):
        fronts[solver] = front([(r[clock], r[error_name])
                                for r in best_runs(rows, solver, threads)])
    if not fronts["xpl"] or not fronts["calculix"]:
        return None
    lo = max(min(e for _, e in fronts[s]) for s in fronts)
    hi = min(max(e for _, e in fronts[s]) for s in fronts)
    if lo > hi:
        return {"overlap": None, "xpl": fronts["xpl"], "calculix": fronts["calculix"]}
    samples = np.exp(np.linspace(math.log(lo), math.log(hi), 9)) if hi > lo else [lo]
    ratios = []
    for e in samples:
        tx, tc = time_at_error(fronts["xpl"], e), time_at_error(fronts["calculix"], e)
        if tx > 0 and tc > 0:
            ratios.append(tc / tx)
    if not ratios:
        return {"overlap": None, "xpl": fronts["xpl"], "calculix": fronts["calculix"]}
    middle = math.sqrt(lo * hi)
    mid = time_at_error(fronts["calculix"], middle) / time_at_error(fronts["xpl"], middle)
    return {"overlap": (lo, hi), "ratio": mid, "min": min(ratios), "max": max(ratios)}


def observed_order(rows, error_name, solver):
    """Least-squares slope of log(error) against log(mesh size), 1 thread."""
    pts = [(r["mesh_size"], r[error_name]) for r in best_runs(rows, solver, 1)
           if r[error_name] > 0]
    if len(pts) < 2:
        return math.nan
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    return float(np.polyfit(x, y, 1)[0])


def plot(case, rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(case.errors) + ["energy"]
    cols = min(3, len(names))
    nrows = math.ceil(len(names) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.6 * cols, 3.8 * nrows), squeeze=False)
    styles = {("xpl", 1): ("C0", "o", "-"), ("xpl", 2): ("C0", "s", "--"),
              ("calculix", 1): ("C3", "o", "-"), ("calculix", 2): ("C3", "s", "--")}
    for ax, name in zip(axes.flat, names):
        for (solver, threads), (color, marker, line) in styles.items():
            runs = best_runs(rows, solver, threads)
            pts = [(r["cpu_s"], r[name], r["level"]) for r in runs if r[name] > 0]
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=color, marker=marker,
                    linestyle=line, label=f"{'CalculiX 2.20' if solver == 'calculix' else 'xpl'}"
                    f", {threads} thread{'s' if threads > 1 else ''}")
            if threads == 1:
                for t, e, level in pts:
                    ax.annotate(str(level), (t, e), textcoords="offset points", xytext=(3, 3),
                                fontsize=7, color=color)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("CPU time of the run, s (user + sys)")
        ax.set_ylabel(f"relative error: {name}")
        ax.grid(True, which="both", alpha=0.3)
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=7)
    fig.suptitle(f"{case.title}: error against time over mesh refinement "
                 f"(labels: {case.level_name})", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def report(case, rows):
    """Markdown: the table of every run and the equal-error speed ratios."""
    names = list(case.errors) + ["energy"]
    out = [f"### {case.title} (`{case.name}`)", "", case.__doc__.strip().split("\n\n")[0]
           .replace("\n    ", " ").replace("\n", " "), ""]
    out.append(f"| solver | thr | {case.level_name} | elements | increments | wall s | CPU s | "
               + " | ".join(names) + " |")
    out.append("|---" * (7 + len(names)) + "|")
    for solver in ("xpl", "calculix"):
        for threads in (1, 2):
            for r in best_runs(rows, solver, threads):
                out.append(f"| {'CalculiX' if solver == 'calculix' else 'xpl'} | {threads} | "
                           f"{r['level']} | {r['elements']} | {r['increments']} | "
                           f"{r['wall_s']:.3g} | {r['cpu_s']:.3g} | "
                           + " | ".join(f"{r[n]:.3g}" for n in names) + " |")
    out.append("")
    out.append("Observed order (slope of log error against log mesh size, 1 thread): " + "; ".join(
        f"{n}: xpl {observed_order(rows, n, 'xpl'):.2f}, CalculiX "
        f"{observed_order(rows, n, 'calculix'):.2f}" for n in case.errors) + ".")
    out.append("")
    out.append("At equal error (CPU time, 1 thread, the fastest of the repeats; CalculiX time / "
               "xpl time on the interpolated fronts, at the middle of the errors both reach):")
    out.append("")
    for n in case.errors:  # not energy: the two solvers' energy errors measure different things
        ratio = speed_ratio(rows, n, 1)
        ratio2 = speed_ratio(rows, n, 2)
        if ratio is None:
            out.append(f"- {n}: no CalculiX runs")
        elif ratio["overlap"] is None:
            fx, fc = ratio["xpl"], ratio["calculix"]
            bound = ""
            best_x, best_c = fx[-1], fc[-1]  # the most accurate point of each front
            if best_x[1] <= best_c[1]:  # xpl reaches CalculiX's best error: how fast?
                t_x = min(t for t, e in fx if e <= best_c[1])
                bound = f"; xpl is at least {best_c[0] / t_x:.3g}× faster"
            else:
                t_c = min(t for t, e in fc if e <= best_x[1])
                bound = f"; xpl is at least {best_x[0] / t_c:.3g}× slower"
            out.append(f"- {n}: the fronts do not overlap (xpl reaches {min(e for _, e in fx):.3g}"
                       f"–{max(e for _, e in fx):.3g} in {fx[0][0]:.3g}–{fx[-1][0]:.3g} s, "
                       f"CalculiX {min(e for _, e in fc):.3g}–{max(e for _, e in fc):.3g} in "
                       f"{fc[0][0]:.3g}–{fc[-1][0]:.3g} s){bound}")
        else:
            two = "" if ratio2 is None or ratio2.get("overlap") is None else \
                f"; 2 threads {ratio2['ratio']:.3g}×"
            out.append(f"- {n}: xpl is {ratio['ratio']:.3g}× faster (range {ratio['min']:.3g}–"
                       f"{ratio['max']:.3g}× over errors {ratio['overlap'][0]:.3g}–"
                       f"{ratio['overlap'][1]:.3g}){two}")
    out.append("")
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("xpl", type=pathlib.Path)
    parser.add_argument("--ccx", default=solvers.find_ccx(),
                        help="CalculiX executable (default: ccx on PATH; none: xpl only)")
    parser.add_argument("--cases", default=",".join(cases.CASES))
    parser.add_argument("--levels", type=int, nargs="*",
                        help="mesh levels (default: each case's own)")
    parser.add_argument("--repeat", type=int, default=1, help="runs per configuration")
    parser.add_argument("--work", type=pathlib.Path, default=pathlib.Path("/tmp/xpl_fronts"))
    parser.add_argument("--results", type=pathlib.Path, default=HERE / "results")
    parser.add_argument("--report-only", action="store_true",
                        help="re-read the CSVs and rewrite plots and fronts.md")
    args = parser.parse_args(argv)
    args.xpl = args.xpl.resolve()
    args.results.mkdir(parents=True, exist_ok=True)
    names = [n for n in args.cases.split(",") if n]
    for name in names:
        if name not in cases.CASES:
            parser.error(f"unknown case {name}; known: {', '.join(cases.CASES)}")

    def log(text):
        print(text, flush=True)

    if not args.report_only:
        ccx_text = f"{args.ccx} {solvers.ccx_version(args.ccx)}" if args.ccx else "absent"
        for name in names:
            case = cases.CASES[name]
            meta = [f"date: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC",
                    f"machine: {machine_line()}", f"xpl: {args.xpl}",
                    f"calculix: {ccx_text}", f"load before: {uptime()}"]
            log(f"{name}: {case.title}")
            rows, note = run_case(case, args.xpl, args.ccx, args.levels or case.levels,
                                  args.repeat, args.work, log)
            write_csv(args.results / f"{name}.csv", rows)
            meta.append(f"load after: {uptime()}")
            if note:
                meta.append(f"notes: {note}")
            (args.results / f"{name}.meta.txt").write_text("\n".join(meta) + "\n")
    text = ["## Error against time, xpl and CalculiX 2.20 (issue 16, item 1)", ""]
    for name in cases.CASES:
        path = args.results / f"{name}.csv"
        if not path.exists():
            continue
        case = cases.CASES[name]
        rows = read_csv(path)
        plot(case, rows, args.results / f"{name}.png")
        text += report(case, rows)
        meta_path = args.results / f"{name}.meta.txt"
        if meta_path.exists():
            text += ["Run: " + "; ".join(meta_path.read_text().splitlines()) + ".", ""]
        text.append(f"![{name}](accuracy/results/{name}.png)")
        text.append("")
    (args.results / "fronts.md").write_text("\n".join(text) + "\n")
    log(f"wrote {args.results / 'fronts.md'}")


if __name__ == "__main__":
    main()
