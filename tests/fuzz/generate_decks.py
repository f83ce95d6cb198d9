"""Generated decks for the fuzzer (fuzz_decks.py --generate): small models built around the
keywords whose values decide the physics, drawn from plausible, boundary and nonsense values.

Each deck is a few hexahedra (two blocks, one on top of the other, C3D8R or C3D8), optionally a
plate of S4R shells above them and a rigid wall below, with:
- *PLASTIC (a table or Johnson-Cook) and *RATE DEPENDENT (Cowper-Symonds or Johnson-Cook),
- *TIE between the blocks (position tolerance, ADJUST=YES/NO),
- *FIXED MASS SCALING (FACTOR=, DT=, TYPE=, ELSET=, a rigid set among them),
- *CONTACT with *CONTACT INCLUSIONS and *CONTACT EXCLUSIONS (pairs repeated, trailing
  commas, a second step with OP=MOD or OP=NEW),
- an initial velocity and one or two short steps (tens to hundreds of increments).
The decks are small and short so that the accepted ones can be run, not only checked, under
the sanitizers in seconds. Everything is drawn from one random.Random: a seed gives the same
deck.
"""

import json
import math
import subprocess
import time

H = 0.01  # element size, m: steel's stable increment is ~1.7 µs

# Chance of a boundary or nonsense value in place of a plausible one, drawn per deck: half the
# decks have none (so that most of them run), the others one value in five.
NONSENSE_RATES = (0.0, 0.0, 0.2)
_nonsense_rate = 0.0
NONSENSE = ["0", "-1", "1e-300", "1e300", "1e-20", "1e20", "nan", "inf", "", "abc", "0.5",
            "1e-5", "1e5", "1e8", "1e-12", "2147483648"]


def number(rng, low, high, extremes=()):
    """A log-uniform value in [low, high] as text, or (now and then) a boundary or nonsense
    value."""
    if rng.random() >= _nonsense_rate:
        value = math.exp(rng.uniform(math.log(low), math.log(high)))
        return f"{value:.6g}"
    return rng.choice(list(extremes) + NONSENSE)


def block(first_node, first_element, origin, nx, ny, nz, kind, elset):
    """Nodes and elements of a block of nx × ny × nz hexahedra of size H at `origin`."""
    nodes, elements = [], []
    def nid(i, j, k):
        return first_node + i + (nx + 1) * (j + (ny + 1) * k)
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                x, y, z = (origin[0] + i * H, origin[1] + j * H, origin[2] + k * H)
                nodes.append(f"{nid(i, j, k)}, {x:.6g}, {y:.6g}, {z:.6g}")
    e = first_element
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                corners = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                           nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1),
                           nid(i, j + 1, k + 1)]
                elements.append(f"{e}, " + ", ".join(map(str, corners)))
                e += 1
    return (["*NODE"] + nodes + [f"*ELEMENT, TYPE={kind}, ELSET={elset}"] + elements)


def plate(first_node, first_element, z, nx, ny):
    """A plate of nx × ny S4R elements at height z."""
    lines = ["*NODE"]
    def nid(i, j):
        return first_node + i + (nx + 1) * j
    for j in range(ny + 1):
        for i in range(nx + 1):
            lines.append(f"{nid(i, j)}, {i * H:.6g}, {j * H:.6g}, {z:.6g}")
    lines.append("*ELEMENT, TYPE=S4R, ELSET=PLATE")
    e = first_element
    for j in range(ny):
        for i in range(nx):
            lines.append(f"{e}, {nid(i, j)}, {nid(i + 1, j)}, {nid(i + 1, j + 1)}, {nid(i, j + 1)}")
            e += 1
    return lines


def material(rng):
    lines = ["*MATERIAL, NAME=STEEL", "*DENSITY", "7800.", "*ELASTIC", "2.1e11, 0.3"]
    if rng.random() < 0.7:
        if rng.random() < 0.5:
            first = number(rng, 1e8, 1e9, ["1e-300", "1e300"])
            lines += ["*PLASTIC", f"{first}, 0"]
            try:
                stress = float(first)
            except ValueError:
                stress = 2.5e8
            strain = 0.0
            for _ in range(rng.randrange(0, 3)):
                stress *= rng.choice([1.0, 1.2, 1.5, 0.8])
                strain += rng.choice([0.01, 0.1, 0.5])
                lines.append(f"{stress:.6g}, {strain:.6g}")
        else:
            lines += ["*PLASTIC, HARDENING=JOHNSON COOK",
                      f"{number(rng, 1e8, 1e9)}, {number(rng, 1e7, 1e9, ['0'])}, "
                      f"{number(rng, 0.01, 1.0, ['0.001', '5', '400'])}, 1., 1800., 293."]
        if rng.random() < 0.6:
            if rng.random() < 0.5:
                lines += ["*RATE DEPENDENT, TYPE=POWER LAW",
                          f"{number(rng, 1e-2, 1e4, ['1e-300', '1e-6'])}, "
                          f"{number(rng, 0.01, 20.0, ['0.05', '1e-3', '1e-310', '100'])}"]
            else:
                lines += ["*RATE DEPENDENT, TYPE=JOHNSON COOK",
                          f"{number(rng, 1e-4, 1.0, ['0', '1e308'])}, "
                          f"{number(rng, 1e-3, 1e3, ['1e-310'])}"]
    return lines


def surfaces(with_plate, with_wall):
    lines = ["*SURFACE, NAME=LOWER_TOP", "LOWER, S2", "*SURFACE, NAME=LOWER_BOTTOM", "LOWER, S1",
             "*SURFACE, NAME=UPPER_BOTTOM", "UPPER, S1", "*SURFACE, NAME=UPPER_TOP", "UPPER, S2"]
    if with_plate:
        lines += ["*SURFACE, NAME=SKIN", "PLATE"]
    if with_wall:
        lines += ["*SURFACE, NAME=WALL_TOP", "WALL, S2"]
    return lines


def contact(rng, names, op=""):
    """*CONTACT with inclusions and exclusions among `names`: repeated pairs, reversed pairs,
    self contact written as `A,` (a trailing comma) or `A, A`."""
    lines = ["*CONTACT" + (f", OP={op}" if op else "")]
    if rng.random() < 0.3:
        lines.append("*CONTACT INCLUSIONS, ALL EXTERIOR")
    else:
        lines.append("*CONTACT INCLUSIONS")
        for _ in range(rng.randrange(1, 4)):
            a, b = rng.choice(names), rng.choice(names)
            lines.append(rng.choice([f"{a}, {b}", f"{b}, {a}", f"{a},", f"{a}", f", {a}"]))
    if rng.random() < 0.5:
        lines.append("*CONTACT EXCLUSIONS")
        for _ in range(rng.randrange(1, 3)):
            a, b = rng.choice(names), rng.choice(names)
            lines.append(rng.choice([f"{a}, {b}", f"{a},", f"{a}"]))
    return lines


def mass_scaling(rng, sets):
    parameters = []
    if rng.random() < 0.6:
        parameters.append(f"FACTOR={number(rng, 1.0, 100.0, ['0.5', '1e-300', '1e300', '1e6'])}")
    if rng.random() < 0.5 or not parameters:
        parameters.append(f"DT={number(rng, 1e-7, 1e-5, ['1e-300', '1e300', '1'])}")
        if rng.random() < 0.5:
            parameters.append(rng.choice(["TYPE=BELOW MIN", "TYPE=UNIFORM"]))
    if rng.random() < 0.5:
        parameters.append("ELSET=" + rng.choice(sets))
    return ["*FIXED MASS SCALING, " + ", ".join(parameters)]


def generated_deck(rng):
    """One generated deck (text) and a short description of what it holds."""
    global _nonsense_rate
    _nonsense_rate = rng.choice(NONSENSE_RATES)
    kind = rng.choice(["C3D8R", "C3D8R", "C3D8"])
    nx, ny = rng.choice([(1, 1), (2, 1), (2, 2)])
    gap = rng.choice([0.0, 0.0, 1e-5, 2e-4, 0.003, 0.02])
    lines = ["*HEADING", "generated deck"]
    lines += block(1, 1, (0.0, 0.0, 0.0), nx, ny, 1, kind, "LOWER")
    lines += block(1001, 101, (0.0, 0.0, H + gap), nx, ny, 1, kind, "UPPER")
    with_plate = rng.random() < 0.4
    with_wall = rng.random() < 0.4
    if with_plate:
        lines += plate(2001, 201, 2 * H + gap + rng.choice([0.0, 1e-4, 0.002]), nx, ny)
    if with_wall:
        lines += block(3001, 301, (0.0, 0.0, -H - rng.choice([0.0, 1e-4, 0.001])), 1, 1, 1,
                       "C3D8R", "WALL")
        lines += ["*NODE", "3999, 0.005, 0.005, -0.005",
                  "*RIGID BODY, REF NODE=3999, ELSET=WALL"]
    lines += surfaces(with_plate, with_wall)
    lines += material(rng)
    lines += ["*SOLID SECTION, ELSET=LOWER, MATERIAL=STEEL",
              "*SOLID SECTION, ELSET=UPPER, MATERIAL=STEEL"]
    if with_wall:
        lines.append("*SOLID SECTION, ELSET=WALL, MATERIAL=STEEL")
    if with_plate:
        lines += ["*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL", "0.001"]
    tie = rng.random() < 0.5
    if tie:
        parameters = ["NAME=GLUE"]
        if rng.random() < 0.6:
            parameters.append(f"POSITION TOLERANCE={number(rng, 1e-5, 0.05, ['0', '1e300'])}")
        if rng.random() < 0.5:
            parameters.append(rng.choice(["ADJUST=YES", "ADJUST=NO"]))
        lines += ["*TIE, " + ", ".join(parameters), "UPPER_BOTTOM, LOWER_TOP"]
    speed = number(rng, 1.0, 300.0, ["0", "1e5"])
    lines += ["*NSET, NSET=MOVING, ELSET=UPPER", "*INITIAL CONDITIONS, TYPE=VELOCITY",
              f"MOVING, 3, -{speed}"]
    names = ["LOWER_TOP", "LOWER_BOTTOM", "UPPER_BOTTOM", "UPPER_TOP"]
    names += ["SKIN"] if with_plate else []
    names += ["WALL_TOP"] if with_wall else []
    sets = ["LOWER", "UPPER"] + (["WALL"] if with_wall else []) + (["PLATE"] if with_plate else [])
    period = rng.choice(["2e-6", "1e-5", "4e-5", "1e-4"])
    steps = rng.choice([1, 1, 2])
    for s in range(steps):
        lines += [f"*STEP, NAME=S{s + 1}", "*DYNAMIC, EXPLICIT", f", {period}"]
        if s == 0 and rng.random() < 0.5:
            lines += mass_scaling(rng, sets)
        if with_wall:
            lines += ["*BOUNDARY", "3999, ENCASTRE"]
        if s == 0 or rng.random() < 0.7:
            lines += contact(rng, names, "" if s == 0 else rng.choice(["", "MOD", "NEW"]))
        lines += ["*OUTPUT, FIELD, NUMBER INTERVAL=5", "*NODE OUTPUT", "U, V",
                  "*ELEMENT OUTPUT", "S", "*OUTPUT, HISTORY, NUMBER INTERVAL=10",
                  "*ENERGY OUTPUT", "*END STEP"]
    what = f"{kind} {nx}x{ny}, gap {gap}, plate {with_plate}, wall {with_wall}, tie {tie}, " \
           f"{steps} step(s) of {period} s, nonsense rate {_nonsense_rate}"
    return "\n".join(lines) + "\n", what


def run_outcome(xpl, deck_path, out_dir, timeout, env, sanitizer_marks):
    """`xpl run` of a deck that `xpl check` accepted: (outcome, exit code, stderr, seconds).
    Exit 0 (completed), 3 (the analysis failed) and 1 (what only a run refuses) are fine when
    the summary agrees (status completed with 0, failed with 3); a signal, a sanitizer report,
    a run past the time limit, exit 4 or another code, or a summary that says otherwise is a
    finding."""
    start = time.monotonic()
    try:
        p = subprocess.run([str(xpl), "run", str(deck_path), "-o", str(out_dir), "--quiet"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
                           timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired as e:
        return "run hang", None, (e.stderr or b"")[-4000:], time.monotonic() - start
    elapsed = time.monotonic() - start
    err = p.stderr[-8000:]
    text = err.decode("utf-8", "replace")
    if any(mark in text for mark in sanitizer_marks):
        return "run sanitizer", p.returncode, err, elapsed
    if p.returncode < 0:
        return "run signal", p.returncode, err, elapsed
    if p.returncode not in (0, 1, 3):
        return f"run exit {p.returncode}", p.returncode, err, elapsed
    if p.returncode in (0, 3):
        summary = out_dir / (deck_path.stem + ".summary.json")
        try:
            status = json.loads(summary.read_text())["status"]
        except (OSError, ValueError, KeyError) as e:
            return "run without summary", p.returncode, err + str(e).encode(), elapsed
        expected = "completed" if p.returncode == 0 else "failed"
        if status != expected:
            return f"run exit {p.returncode} with status {status}", p.returncode, err, elapsed
    return "ok", p.returncode, err, elapsed
