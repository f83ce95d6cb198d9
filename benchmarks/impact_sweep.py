#!/usr/bin/python3
"""The impact stress sweep (issue 32, item 7; SPEC R6): run many scenes of
tests/stress/impact_scenes.py and tabulate pass/fail per class, per criterion and per speed.

Usage: impact_sweep.py XPL [--first 0] [--count 320] [--work DIR] [--jobs 2]
                       [--threads-every 5] [--csv OUT.csv] [--table OUT.md] [--reuse]

Each scene runs with one thread (--jobs scenes side by side); every --threads-every-th scene
also runs with two threads for the 1 = 2 threads criterion (the others show "-" there; 5 is
prime to the 16 classes, so every class gets its share). The
criteria are impact_check.py's. The table (markdown) goes to stdout and --table; one row per
scene to --csv (id, class, parameters, each criterion's result and message, CPU seconds).
One scene again, for debugging: tests/stress/impact_check.py run XPL ID (prints the deck).
"""

import argparse
import concurrent.futures
import csv
import math
import pathlib
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "tests" / "stress"))
import impact_check as ic  # noqa: E402
import impact_scenes as sc  # noqa: E402

SPEED_BANDS = ((1.0, 10.0), (10.0, 100.0), (100.0, 300.0))


def one(xpl, scene_id, work, threads, reuse):
    timing = {}
    deck, results = ic.run_scene(xpl, scene_id, work, threads=threads, timing=timing,
                                 reuse=reuse)
    return scene_id, results, timing


def table(rows):
    """Markdown: per class, per speed band and per body/material kind, the scenes that pass
    every criterion and the failures of each criterion."""
    criteria = ic.CRITERIA

    def line(label, group):
        n = len(group)
        passed = sum(all(r[c] is not False for c in criteria) for r in group)
        cells = []
        for c in criteria:
            checked = [r for r in group if r[c] is not None]
            failed = sum(r[c] is False for r in checked)
            cells.append(f"{failed}/{len(checked)}" if checked else "-")
        return f"| {label} | {n} | {passed} | " + " | ".join(cells) + " |"

    head = ("| {} | scenes | pass all | " + " | ".join(f"{c} failed" for c in criteria) + " |",
            "|---|---:|---:|" + "---:|" * len(criteria))
    out = [head[0].format("class (projectile-target-support)"), head[1]]
    for cls in sc.CLASSES:
        group = [r for r in rows if r["class"] == cls]
        if group:
            out.append(line(cls, group))
    out.append(line("**all**", rows))
    out += ["", head[0].format("speed, m/s"), head[1]]
    for lo, hi in SPEED_BANDS:
        group = [r for r in rows if lo <= r["speed"] < hi or (hi == 300.0 and r["speed"] == hi)]
        if group:
            out.append(line(f"{lo:g}-{hi:g}", group))
    out += ["", head[0].format("kind"), head[1]]
    for label, test in (("elastic (no *PLASTIC)", lambda r: not r["plastic"]),
                        ("plastic (either body)", lambda r: r["plastic"]),
                        ("head-on (0 degrees)", lambda r: r["angle"] == 0.0),
                        ("oblique (5-60 degrees)", lambda r: r["angle"] > 0.0),
                        ("scene rotated", lambda r: r["rotated"]),
                        ("scene aligned", lambda r: not r["rotated"]),
                        ("with C3D8", lambda r: r["c3d8"])):
        group = [r for r in rows if test(r)]
        if group:
            out.append(line(label, group))
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xpl")
    parser.add_argument("--first", type=int, default=0)
    parser.add_argument("--count", type=int, default=320)
    parser.add_argument("--work", type=pathlib.Path)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--threads-every", type=int, default=5)
    parser.add_argument("--csv", type=pathlib.Path)
    parser.add_argument("--table", type=pathlib.Path)
    parser.add_argument("--reuse", action="store_true",
                        help="check the runs already in --work again (no xpl run, no CPU times)")
    args = parser.parse_args()
    work = args.work or pathlib.Path(tempfile.mkdtemp(prefix="impact_sweep_"))
    ids = range(args.first, args.first + args.count)
    rows = []
    start = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(one, args.xpl, i, work,
                               args.threads_every > 0 and i % args.threads_every == 0,
                               args.reuse)
                   for i in ids]
        for future in futures:
            scene_id, results, timing = future.result()
            p = sc.draw(scene_id)
            row = {"id": scene_id, "class": p["class"], "speed": p["speed"], "angle": p["angle"],
                   "tilt": p["tilt"], "rotated": p["rotated"],
                   "plastic": p["projectile_plastic"] or p["target_plastic"],
                   "c3d8": "C3D8" in (p["projectile_element"] if p["projectile"] == "solid"
                                      else "", p["target_element"] if p["target"] == "solid"
                                      else ""),
                   "cpu_1": timing.get("cpu_1", math.nan), "cpu_2": timing.get("cpu_2", math.nan)}
            for criterion, ok, message in results:
                row[criterion] = ok
                row[f"{criterion}_message"] = message
            rows.append(row)
            lines, failed = ic.report(scene_id, results)
            print(lines[0] + f"  [{row['cpu_1']:.2f} s CPU]", flush=True)
            for text in lines[1:]:
                if text.lstrip().startswith("FAIL"):
                    print(text, flush=True)
    cpu = sum(r["cpu_1"] + (0.0 if math.isnan(r["cpu_2"]) else r["cpu_2"]) for r in rows)
    text = table(rows)
    text += (f"\n{len(rows)} scenes (ids {args.first}-{args.first + args.count - 1}), "
             f"{sum(1 for r in rows if r['threads'] is not None)} also with 2 threads; "
             f"xpl CPU time {cpu:.0f} s, wall time {time.time() - start:.0f} s with {args.jobs} "
             f"jobs.\n")
    print(text)
    if args.table:
        args.table.write_text(text)
    if args.csv:
        fields = list(rows[0].keys())
        with args.csv.open("w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=fields)
            writer.writeheader()
            writer.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
