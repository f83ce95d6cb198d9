#!/usr/bin/python3
"""Collect xpl C3D8R block benchmark runs into a CSV, a PNG plot and a markdown table.

Input: the run summaries JOB.summary.json of `xpl run` (one per run; the run scripts keep a
copy of each beside its log), or the stdout logs of older runs, which end with the summary

    xpl: element cycles per second: 1.234567e+07 (97336 elements x 300 increments, 2 threads)
    xpl: phase setup: 0.123 s
    ... (internal force, contact search, contact force, integration, output)
    xpl: peak memory: 123.4 MB

For each thread count the best run (highest element cycles per second) is kept and
appended to the CSV; the plot is redrawn from the newest measurement in the CSV.
Needs matplotlib: run with /usr/bin/python3 (Debian's python3-matplotlib).
"""

import argparse
import csv
import datetime
import json
import os
import pathlib
import platform
import re
import sys

PHASES = ["setup", "internal force", "contact search", "contact force", "integration", "output"]
PHASE_COLUMNS = [p.replace(" ", "_") + "_s" for p in PHASES]
COLUMNS = (["date", "machine", "elements", "increments", "threads", "element_cycles_per_s"]
           + PHASE_COLUMNS + ["peak_memory_mb", "bytes_per_element"])

BYTES_PER_MB = 1024 * 1024  # the solver reports peak resident memory (ru_maxrss) in MiB

CYCLES_RE = re.compile(
    r"^xpl: element cycles per second: (?P<rate>\S+) \((?P<elements>\d+) elements x "
    r"(?P<increments>\d+) increments, (?P<threads>\d+) threads?\)\s*$")
PHASE_RE = re.compile(r"^xpl: phase (?P<name>[a-z ]+): (?P<seconds>\S+) s\s*$")
MEMORY_RE = re.compile(r"^xpl: peak memory: (?P<mb>\S+) MB\s*$")


class SummaryError(ValueError):
    """A log without a complete xpl summary."""


def parse_summary(text, source="log"):
    """Return the summary of one run as a dict of CSV columns (without date, machine)."""
    run = {}
    for line in text.splitlines():
        if m := CYCLES_RE.match(line):
            run["element_cycles_per_s"] = float(m["rate"])
            run["elements"] = int(m["elements"])
            run["increments"] = int(m["increments"])
            run["threads"] = int(m["threads"])
        elif m := PHASE_RE.match(line):
            name = m["name"].strip()
            if name in PHASES:
                run[name.replace(" ", "_") + "_s"] = float(m["seconds"])
            else:
                print(f"hex_benchmark: {source}: unknown phase '{name}' ignored", file=sys.stderr)
        elif m := MEMORY_RE.match(line):
            run["peak_memory_mb"] = float(m["mb"])
    missing = [c for c in COLUMNS[2:-1] if c not in run]
    if missing:
        raise SummaryError(f"{source}: no xpl summary value for {', '.join(missing)}")
    run["bytes_per_element"] = round(run["peak_memory_mb"] * BYTES_PER_MB / run["elements"], 1)
    return run


def summary_from_json(summary, source="summary"):
    """The CSV columns of one run from its JOB.summary.json (apps/summary.schema.json)."""
    if summary.get("status") != "completed":
        raise SummaryError(f"{source}: the run did not complete (status {summary.get('status')!r})")
    run = {
        "element_cycles_per_s": summary["element_cycles_per_second"],
        "elements": summary["model"]["elements"],
        "increments": summary["increments"],
        "threads": summary["threads"],
        "peak_memory_mb": summary["peak_memory_mb"],
    }
    for name, column in zip(PHASES, PHASE_COLUMNS):
        run[column] = summary["wall_time"][name.replace(" ", "_")]
    run["bytes_per_element"] = round(run["peak_memory_mb"] * BYTES_PER_MB / run["elements"], 1)
    return run


def read_run(path):
    """One run from a JOB.summary.json, or from a stdout log."""
    if path.name.endswith(".summary.json"):
        try:
            return summary_from_json(json.loads(path.read_text()), str(path))
        except (KeyError, TypeError, json.JSONDecodeError) as error:
            raise SummaryError(f"{path}: not an xpl run summary ({error})") from error
    return parse_summary(path.read_text(), str(path))


def machine_description():
    """CPU model and core count, e.g. 'AMD EPYC 7B13 (2 cores, x86_64)'."""
    model = platform.processor() or platform.machine()
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model} ({os.cpu_count()} cores, {platform.machine()})"


def best_per_thread_count(runs):
    """Highest element cycles per second for each thread count, sorted by threads."""
    best = {}
    for run in runs:
        t = run["threads"]
        if t not in best or run["element_cycles_per_s"] > best[t]["element_cycles_per_s"]:
            best[t] = run
    return [best[t] for t in sorted(best)]


def append_csv(path, rows):
    new_file = not path.exists() or path.stat().st_size == 0
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("a", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        if new_file:
            writer.writeheader()
        for row in rows:
            writer.writerow({c: row[c] for c in COLUMNS})


def read_csv(path):
    with path.open(newline="") as f:
        return list(csv.DictReader(f))


def markdown_rows(rows):
    """Table rows: date, machine, elements, increments, threads, Mcycles/s, speed-up,
    phase seconds, peak memory, bytes/element."""
    base = next((r["element_cycles_per_s"] for r in rows if r["threads"] == 1), None)
    lines = []
    for r in rows:
        speedup = f"{r['element_cycles_per_s'] / base:.2f}" if base else "-"
        phases = " | ".join(f"{r[c]:.3f}" for c in PHASE_COLUMNS)
        lines.append(f"| {r['date'][:10]} | {r['machine']} | {r['elements']} | {r['increments']} "
                     f"| {r['threads']} | {r['element_cycles_per_s'] / 1e6:.2f} | {speedup} "
                     f"| {phases} | {r['peak_memory_mb']:.1f} | {r['bytes_per_element']:.0f} |")
    return lines


MARKDOWN_HEADER = [
    "| date | machine | elements | increments | threads | Mcycles/s | speed-up | setup s "
    "| internal force s | contact search s | contact force s | integration s | output s "
    "| peak memory MB | bytes/element |",
    "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
]


def loop_seconds(row):
    """Wall time of the time loop, s: elements x increments / element cycles per second."""
    return float(row["elements"]) * float(row["increments"]) / float(row["element_cycles_per_s"])


def untimed_seconds(row):
    """Loop time in no phase timer (e.g. applying loads), s; setup is outside the loop."""
    return max(0.0, loop_seconds(row) - sum(float(row[c]) for c in PHASE_COLUMNS[1:]))


def plot(csv_path, png_path, title="C3D8R block", show_untimed=False):
    """Element cycles per second and phase times against threads, newest measurement.
    show_untimed adds the loop time outside the phase timers as a last bar segment."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = read_csv(csv_path)
    if not rows:
        return
    newest = max(r["date"] for r in rows)
    rows = sorted((r for r in rows if r["date"] == newest), key=lambda r: int(r["threads"]))
    threads = [int(r["threads"]) for r in rows]
    labels = [str(t) for t in threads]
    rate = [float(r["element_cycles_per_s"]) / 1e6 for r in rows]

    fig, (ax_rate, ax_phase) = plt.subplots(1, 2, figsize=(10, 4))
    ax_rate.bar(labels, rate, color="tab:blue")
    for i, value in enumerate(rate):
        ax_rate.annotate(f"{value:.2f}", (i, value), ha="center", va="bottom")
    ax_rate.set_xlabel("threads")
    ax_rate.set_ylabel("element cycles per second (millions)")
    ax_rate.set_title(f"{title}, {rows[0]['elements']} elements")

    bottom = [0.0] * len(rows)
    for phase, column in zip(PHASES, PHASE_COLUMNS):
        seconds = [float(r[column]) for r in rows]
        ax_phase.bar(labels, seconds, bottom=bottom, label=phase)
        bottom = [b + s for b, s in zip(bottom, seconds)]
    if show_untimed:
        ax_phase.bar(labels, [untimed_seconds(r) for r in rows], bottom=bottom,
                     label="untimed (loads, checks)", color="lightgray")
    ax_phase.set_xlabel("threads")
    ax_phase.set_ylabel("wall time (s)")
    ax_phase.set_title(f"phases, {rows[0]['increments']} increments")
    ax_phase.legend(fontsize="small")

    fig.suptitle(f"{rows[0]['machine']}, {newest[:16]}", fontsize="small")
    fig.tight_layout()
    png_path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png_path, dpi=120)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("logs", nargs="+", type=pathlib.Path,
                        help="JOB.summary.json files (or stdout logs) of xpl runs")
    parser.add_argument("--csv", type=pathlib.Path, required=True, help="CSV to append to")
    parser.add_argument("--png", type=pathlib.Path, required=True, help="plot to write")
    parser.add_argument("--machine", default=None, help="machine description (default: CPU)")
    args = parser.parse_args(argv)

    try:
        runs = [read_run(log) for log in args.logs]
    except (OSError, SummaryError) as error:
        print(f"hex_benchmark: {error}", file=sys.stderr)
        return 1

    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    machine = args.machine or machine_description()
    rows = best_per_thread_count(runs)
    for row in rows:
        row["date"] = date
        row["machine"] = machine
    append_csv(args.csv, rows)
    plot(args.csv, args.png)

    print("\n".join(MARKDOWN_HEADER + markdown_rows(rows)))
    print(f"\nhex_benchmark: appended {len(rows)} rows to {args.csv}; plot {args.png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
