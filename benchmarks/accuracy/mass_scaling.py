"""What *FIXED MASS SCALING gains and what it costs (issue 18, deliver 3), on the bar impact of
the P3 fronts (cases.BarWall: 100 mm steel bar at 10 m/s on a fixed end, nu = 0).

Two families, each run without and with mass scaling, at 1 thread:

  uniform     the regular 40-element bar, the whole bar scaled (FACTOR= f): the increment
              grows by sqrt(f) and so does every wave's travel time; the errors of the
              plateau (rho c0 v A) and of the return time (2 L / c0) show the price.
  small       the same bar with one element at the fixed end 10x shorter than the others
              (a mesh detail that governs the increment: the common case for mass
              scaling), scaled with DT= the regular elements' increment and
              TYPE=BELOW MIN: only that element gets mass, the increment grows ~10x, and
              the errors stay those of the regular bar.

Writes benchmarks/accuracy/results/mass_scaling_nxN.csv and prints a markdown table for
benchmarks/RESULTS.md. Timing: CPU seconds of the run (user + sys, start-up included), best
of REPEAT (3).

  /usr/bin/python3 benchmarks/accuracy/mass_scaling.py [--nx 40] [--xpl build/release/apps/xpl]
"""
import argparse
import csv
import json
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import cases  # noqa: E402
import solvers  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
NX = 40  # elements along the bar (--nx)


def bar_deck(scaling_lines, short, stretch):
    """The BarWall deck at NX elements with scaling_lines after the step's *DYNAMIC line and
    the step time times `stretch` (a scaled bar's wave takes longer to come back); with
    `short` (a fraction), the first element (at x = 0) is that fraction of the regular length
    and the others share the rest of the bar, so that the bar keeps its length L."""
    text, ref = cases.BarWall().deck(NX, "xpl")
    lines = text.splitlines()
    at = next(k for k, line in enumerate(lines) if line.upper().startswith("*DYNAMIC")) + 1
    lines[at] = ", " + cases.fmt(stretch * float(lines[at].split(",")[1]))
    if short is not None:
        h = cases.BAR_L / NX
        first = short * h
        rest = (cases.BAR_L - first) / (NX - 1)
        out, in_nodes = [], False
        for line in lines:
            if line.startswith("*"):
                in_nodes = line.split(",")[0].strip().upper() == "*NODE"
                out.append(line)
                continue
            if in_nodes:
                fields = [f.strip() for f in line.split(",")]
                x = float(fields[1])
                i = round(x / h)
                fields[1] = cases.fmt(0.0 if i == 0 else first + (i - 1) * rest)
                out.append(", ".join(fields))
                continue
            out.append(line)
        lines = out
    at = next(k for k, line in enumerate(lines) if line.upper().startswith("*DYNAMIC")) + 2
    lines[at:at] = scaling_lines
    return "\n".join(lines) + "\n", ref


def element_increment(msg_path):
    """xpl's smallest element increment before scaling, from the .msg line "... smallest
    element increment A s -> B s" of a scaled run."""
    for line in msg_path.read_text().splitlines():
        if line.strip().startswith("fixed mass scaling: model mass"):
            return float(line.split("smallest element increment")[1].split()[0])
    raise RuntimeError(f"no mass-scaling line in {msg_path}")


def variants(dt_regular):
    """(family, label, *FIXED MASS SCALING lines, short end element or None, time stretch)."""
    # DT= just below the regular elements' own increment: only the short element is scaled.
    below_min = [f"*FIXED MASS SCALING, DT={0.999 * dt_regular:.6e}, TYPE=BELOW MIN"]
    return [
        ("uniform", "none", [], None, 1.0),
        ("uniform", "FACTOR=1.21", ["*FIXED MASS SCALING, FACTOR=1.21"], None, 1.1),
        ("uniform", "FACTOR=4", ["*FIXED MASS SCALING, FACTOR=4"], None, 2.0),
        ("short 0.5 h", "none", [], 0.5, 1.0),
        ("short 0.5 h", "DT=regular, BELOW MIN", below_min, 0.5, 1.0),
        ("short 0.1 h", "none", [], 0.1, 1.0),
        ("short 0.1 h", "DT=regular, BELOW MIN", below_min, 0.1, 1.0),
    ]


def added_mass_percent(msg_path):
    """The model total's percent of added mass from the .msg line "fixed mass scaling: model
    mass M kg, added A kg (+P %)" (0 when nothing was scaled)."""
    for line in msg_path.read_text().splitlines():
        line = line.strip()
        if line.startswith("fixed mass scaling: model mass") and "(+" in line:
            return float(line.split("(+")[1].split()[0])
    return 0.0


def main(argv=None):
    global NX
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--xpl", default=str(cases.REPO / "build/release/apps/xpl"))
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--work", default=str(cases.REPO / "build/bench/mass_scaling"))
    parser.add_argument("--nx", type=int, default=NX, help="elements along the bar (40)")
    args = parser.parse_args(argv)
    NX = args.nx
    work = pathlib.Path(args.work) / f"nx{NX}"
    rows = []
    case = cases.BarWall()
    # The regular element's increment, from a one-increment probe of the bar scaled by 1.
    probe_text, _ = bar_deck(["*FIXED MASS SCALING, FACTOR=1"], None, 1.0)
    probe = work / "probe.inp"
    probe.parent.mkdir(parents=True, exist_ok=True)
    probe.write_text(probe_text)
    solvers.run_xpl(args.xpl, probe, 1, work / "probe")
    dt_regular = element_increment(work / "probe" / "probe.msg")
    for index, (family, label, scaling, short, stretch) in enumerate(variants(dt_regular)):
        text, ref = bar_deck(scaling, short, stretch)
        name = f"bar_{index}"
        deck = work / f"{name}.inp"
        deck.parent.mkdir(parents=True, exist_ok=True)
        deck.write_text(text)
        runs = [solvers.run_xpl(args.xpl, deck, 1, work / name) for _ in range(args.repeat)]
        best = min(runs, key=lambda r: r["cpu"])
        errors = case.measure(best, ref)
        msg = work / name / f"{name}.msg"
        rows.append({
            "family": family, "scaling": label,
            # Increments over the unscaled bar's step time 1.25 * 2L/c0 (the scaled decks run
            # `stretch` times longer so that their slower wave comes back within the step).
            "increments": round(best["increments"] / stretch),
            "first_increment_s": best["summary"]["first_increment"],
            "cpu_s": round(best["cpu"], 4), "added_mass_percent": added_mass_percent(msg),
            # Signed: measure() gives |error|.
            "plateau_error": errors["plateau_value"] / ref["force"] - 1.0,
            "return_time_error": errors["return_time_value"] / ref["T"] - 1.0,
            "energy_error": errors["energy"]})
        print(json.dumps(rows[-1]), flush=True)
    out = HERE / "results" / f"mass_scaling_nx{NX}.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print("\n| bar | mass scaling | added mass | first increment | increments to 2.5 L/c0 | CPU s | "
          "plateau error | return-time error | energy error |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['family']} | {r['scaling']} | {r['added_mass_percent']:.3g} % | "
              f"{r['first_increment_s']:.3e} s | {r['increments']} | {r['cpu_s']:.3f} | "
              f"{100 * r['plateau_error']:+.2f} % | {100 * r['return_time_error']:+.2f} % | "
              f"{100 * r['energy_error']:.3f} % |")


if __name__ == "__main__":
    main()
