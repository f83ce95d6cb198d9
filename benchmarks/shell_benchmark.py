#!/usr/bin/python3
"""Collect xpl S4R plate benchmark runs into a CSV, a PNG plot and a markdown table.

Same logs, CSV columns and best-of rule as hex_benchmark.py (whose functions this uses):
for each thread count the best run (highest element cycles per second) is kept and
appended to the CSV; the plot is redrawn from the newest measurement in the CSV.

With --sweep the logs may come from several mesh sizes: the best run of each (elements,
threads) pair is appended, and the plot shows element cycles per second against the number
of elements, one line per thread count.
Needs matplotlib: run with /usr/bin/python3 (Debian's python3-matplotlib).
"""

import argparse
import datetime
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import hex_benchmark as hb  # noqa: E402

TITLE = "S4R plate"
PROG = "shell_benchmark"
DESCRIPTION = __doc__.split("\n\n")[0]


def best_per_size_and_threads(runs):
    """Highest element cycles per second for each (elements, threads), sorted."""
    best = {}
    for run in runs:
        key = (run["elements"], run["threads"])
        if key not in best or run["element_cycles_per_s"] > best[key]["element_cycles_per_s"]:
            best[key] = run
    return [best[k] for k in sorted(best)]


def sweep_markdown(rows):
    lines = ["| elements | increments | threads | Mcycles/s | internal force s | integration s "
             "| untimed s | peak memory MB | bytes/element |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['elements']} | {r['increments']} | {r['threads']} "
                     f"| {r['element_cycles_per_s'] / 1e6:.2f} | {r['internal_force_s']:.3f} "
                     f"| {r['integration_s']:.3f} | {hb.untimed_seconds(r):.3f} "
                     f"| {r['peak_memory_mb']:.1f} "
                     f"| {r['bytes_per_element']:.0f} |")
    return lines


def plot_sweep(csv_path, png_path):
    """Element cycles per second against elements, one line per thread count (newest)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = hb.read_csv(csv_path)
    if not rows:
        return
    newest = max(r["date"] for r in rows)
    rows = [r for r in rows if r["date"] == newest]
    fig, (ax_rate, ax_mem) = plt.subplots(1, 2, figsize=(10, 4))
    for threads in sorted({int(r["threads"]) for r in rows}):
        mine = sorted((r for r in rows if int(r["threads"]) == threads),
                      key=lambda r: int(r["elements"]))
        elements = [int(r["elements"]) for r in mine]
        ax_rate.plot(elements, [float(r["element_cycles_per_s"]) / 1e6 for r in mine], "o-",
                     label=f"{threads} thread{'s' if threads > 1 else ''}")
        ax_mem.plot(elements, [float(r["bytes_per_element"]) for r in mine], "o-",
                    label=f"{threads} thread{'s' if threads > 1 else ''}")
    for ax in (ax_rate, ax_mem):
        ax.set_xscale("log")
        ax.set_xlabel("S4R elements")
        ax.legend(fontsize="small")
    ax_rate.set_ylabel("element cycles per second (millions)")
    ax_rate.set_ylim(bottom=0)
    ax_rate.set_title(f"{TITLE}, mesh-size sweep")
    ax_mem.set_ylabel("peak memory per element (bytes)")
    ax_mem.set_ylim(bottom=0)
    ax_mem.set_title("peak memory per element")
    fig.suptitle(f"{rows[0]['machine']}, {newest[:16]}", fontsize="small")
    fig.tight_layout()
    png_path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png_path, dpi=120)
    plt.close(fig)


def markdown_rows(rows):
    """hex_benchmark's table rows with one more column: loop time in no phase timer."""
    return [line + f" {hb.untimed_seconds(r):.3f} |"
            for line, r in zip(hb.markdown_rows(rows), rows)]


MARKDOWN_HEADER = [hb.MARKDOWN_HEADER[0] + " untimed s |", hb.MARKDOWN_HEADER[1] + "---:|"]


def collect(argv):
    """Parse the arguments and logs: (args, best rows with date and machine) or None."""
    sweep = "--sweep" in argv
    parser = argparse.ArgumentParser(prog=PROG, description=DESCRIPTION)
    parser.add_argument("logs", nargs="+", type=pathlib.Path,
                        help="JOB.summary.json files (or stdout logs) of xpl runs")
    parser.add_argument("--csv", type=pathlib.Path, required=True, help="CSV to append to")
    parser.add_argument("--png", type=pathlib.Path, required=True, help="plot to write")
    parser.add_argument("--machine", default=None, help="machine description (default: CPU)")
    parser.add_argument("--sweep", action="store_true",
                        help="logs of several mesh sizes: best per (elements, threads)")
    args = parser.parse_args(argv)
    try:
        runs = [hb.read_run(log) for log in args.logs]
    except (OSError, hb.SummaryError) as error:
        print(f"{PROG}: {error}", file=sys.stderr)
        return None
    rows = best_per_size_and_threads(runs) if sweep else hb.best_per_thread_count(runs)
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    machine = args.machine or hb.machine_description()
    for row in rows:
        row["date"] = date
        row["machine"] = machine
    return args, rows


def main(argv=None):
    collected = collect(sys.argv[1:] if argv is None else list(argv))
    if collected is None:
        return 1
    args, rows = collected
    hb.append_csv(args.csv, rows)
    if args.sweep:
        plot_sweep(args.csv, args.png)
        print("\n".join(sweep_markdown(rows)))
    else:
        hb.plot(args.csv, args.png, title=TITLE, show_untimed=True)
        print("\n".join(MARKDOWN_HEADER + markdown_rows(rows)))
    print(f"\n{PROG}: appended {len(rows)} rows to {args.csv}; plot {args.png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
