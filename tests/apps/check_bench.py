#!/usr/bin/python3
"""`xpl bench` (issue 38, item 4): the quick benchmark runs, its JSON has the documented fields
(docs/user/cli.md), its decks are those of the generators in benchmarks/, bad usage exits 2.
No timing is asserted: rates on a shared machine say nothing about correctness.

Usage: check_bench.py XPL SRC OUT
"""

import json
import math
import pathlib
import shlex
import subprocess
import sys

MODELS = ["hex", "shell", "contact", "plastic-hex", "plastic-shell"]
SHARES = ["internal_force", "contact", "integration", "output", "other"]


def fail(message):
    sys.exit(f"FAIL: {message}")


def run(xpl, *args, expect=0):
    r = subprocess.run([xpl, "bench", *args], capture_output=True, text=True, timeout=300)
    if r.returncode != expect:
        fail(f"xpl bench {' '.join(args)}: exit {r.returncode}, expected {expect}\n"
             f"{r.stdout}{r.stderr}")
    return r


def number(value, what, low=-math.inf):
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not value > low:
        fail(f"{what} is {value!r}, expected a number > {low}")


def check_json(xpl):
    report = json.loads(run(xpl, "--quick", "--json").stdout)
    if not isinstance(report.get("xpl_version"), str):
        fail("no xpl_version")
    machine = report.get("machine", {})
    for key in ("cpu", "simd", "compiler", "load_average"):
        if not isinstance(machine.get(key), str) or not machine[key]:
            fail(f"machine.{key} is {machine.get(key)!r}")
    for key in ("cores", "hardware_threads", "simd_bits", "batch_lanes"):
        number(machine.get(key), f"machine.{key}", 0)
    if report.get("repeat") != 1 or report.get("quick") is not True:
        fail(f"repeat {report.get('repeat')!r}, quick {report.get('quick')!r}: expected 1, true")
    names = [m.get("name") for m in report.get("models", [])]
    if names != MODELS:
        fail(f"models {names}, expected {MODELS}")
    for m in report["models"]:
        where = f"model {m['name']}"
        number(m.get("elements"), f"{where}: elements", 0)
        number(m.get("read_seconds"), f"{where}: read_seconds", 0)
        peak = m.get("peak_bytes_per_element")
        if peak is not None:
            number(peak, f"{where}: peak_bytes_per_element", 0)
        if not m.get("deck", "").startswith("benchmarks/"):
            fail(f"{where}: deck {m.get('deck')!r}")
        number(m.get("speed_up"), f"{where}: speed_up", 0)
        if sorted(m.get("threads", {})) != ["1", "2"]:
            fail(f"{where}: threads {sorted(m.get('threads', {}))}, expected 1 and 2")
        for t, runs in m["threads"].items():
            w = f"{where}, {t} thread(s)"
            number(runs.get("cycles_per_second"), f"{w}: cycles_per_second", 0)
            if len(runs.get("cycles_per_second_runs", [])) != 1:
                fail(f"{w}: {runs.get('cycles_per_second_runs')!r}: expected one run")
            number(runs.get("increments"), f"{w}: increments", 0)
            number(runs.get("setup_seconds"), f"{w}: setup_seconds", -1e-300)
            shares = runs.get("phase_shares", {})
            if sorted(shares) != sorted(SHARES):
                fail(f"{w}: phase_shares {sorted(shares)}, expected {sorted(SHARES)}")
            if any(not 0.0 <= s <= 1.0 for s in shares.values()) or \
                    abs(sum(shares.values()) - 1.0) > 1e-9:
                fail(f"{w}: phase shares {shares} are not fractions that sum to 1")
        if m["name"] == "contact" and m["threads"]["1"]["phase_shares"]["contact"] <= 0.0:
            fail("the contact model spends no time in contact")
    print(f"ok: --quick --json: {len(names)} models, every field present")
    return report


def check_decks(xpl, src, out, report):
    """Each model's deck is the one its generator writes for the arguments it names."""
    out.mkdir(parents=True, exist_ok=True)
    for m in report["models"]:
        words = shlex.split(m["deck"])
        script, args = src / words[0], words[1:]
        deck = out / f"{m['name']}.inp"
        if "OUT.inp" in args:
            args[args.index("OUT.inp")] = str(deck)
        else:
            args += ["--out", str(deck)]
        subprocess.run(["/usr/bin/python3", str(script), *args], check=True,
                       capture_output=True, timeout=120)
        ours = run(xpl, "--quick", "--deck", m["name"]).stdout
        if ours != deck.read_text():
            fail(f"{m['name']}: the deck of xpl bench differs from {m['deck']}")
    print("ok: every deck equals its generator's")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, src, out = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    report = check_json(xpl)
    check_decks(xpl, src, out, report)
    table = run(xpl, "--quick", "--models", "hex,contact").stdout
    rows = [line.split()[0] for line in table.splitlines()  # the legend lines are indented
            if line[:1].strip() and line.split()[0] in MODELS]
    if rows != ["hex", "contact"] or "speedup" not in table:
        fail(f"the table of --models hex,contact has rows {rows}:\n{table}")
    print("ok: table with --models")
    for args in (["--repeat", "0"], ["--models", "hex,nope"], ["--deck", "nope"], ["--frob"]):
        r = run(xpl, *args, expect=2)
        if not r.stderr.startswith("xpl bench: ") or r.stdout:
            fail(f"xpl bench {' '.join(args)}: no message on stderr: {r.stdout}{r.stderr}")
    print("ok: usage errors exit 2")


if __name__ == "__main__":
    main()
