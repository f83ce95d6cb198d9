#!/usr/bin/python3
"""Contact on tied slave nodes: a tied node keeps no mass (its master corners carry it), and
contact must read its share of the corners' mass (ContactStage::set_tie_slaves).

Usage: check_tie_contact.py XPL OUT_DIR [CASE]   (CASE: merged, shared, swapped, joined;
       default all)
       check_tie_contact.py --write-deck OUT.inp [skin|swapped]   (a case's deck alone, for
       tests/mpi: the tied skin, default, or the swapped ties deck)

Cases (units m, kg, s; steel):
- merged: a 4 x 4 S4R skin on the top of a 4 x 4 x 1 C3D8R block with its base held, struck at
  20 m/s by a 3 x 3 x 2 C3D8R block through contact (both views: striker nodes on the skin's
  faces, skin nodes on the striker's). Once with the skin's own nodes tied to the block's top
  (*TIE, ADJUST=YES: each skin node on one block node, weight 1) and once with the skin on
  the block's nodes. The tie moves a slave exactly with its corner, so the two runs are the
  same equations: ALLKE, ALLIE and ALLPW histories agree to 1e-9 of their largest value
  (round-off: 1e-15 measured). With the tied nodes read as massless they differed by 18-40 %
  (their springs zero, their faces rigid masters).
- shared: a 16 x 16 S4R skin tied on one C3D8R element (289 slaves on one master face), struck
  at 50 m/s by a single C3D8R element: the contact springs give back no energy (ALLPW >= 0 at
  every history point, within 1e-4 of ETOTAL). With each slave's kinematic mass alone
  (1/m* = sum N_I^2/m_I) the springs of the slaves summed on the block's corners and gave
  back 2.7 % of the energy (ALLPW -0.13 J).
- joined: a 10 x 10 skin tied on a 2 x 2 x 1 block with general contact ALL EXTERIOR: the
  skin nodes lie half its 1 mm thickness inside the block, deeper than the automatic limit
  (15 % of its 2 mm facets: ignored, C2); the .msg says the tie holds each of them (not that
  the penalty pushes it out). On the 4 x 4 skin they are within the limit: offsets, reason tie.
- swapped: tests/mpi/make_tie_ranks.py's deck with its SKIN tie turned round (the coarse plate,
  which strikes a bar through contact, becomes the slave of the fine one): completes with
  ETOTAL balanced; it stopped at increment 29 on "contact created energy" (the bar's springs
  sized for a rigid master where light fine-plate corners moved).
"""

import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

SRC = pathlib.Path(__file__).resolve().parents[2]
W, H = 0.02, 0.01  # m: the block's width and height


def check(condition, message):
    if not condition:
        sys.exit(f"check_tie_contact.py: FAILED: {message}")


def skin_deck(merged, skin=4, block=4, striker=3, speed=20.0, everything=False):
    """The struck skin deck: a skin x skin S4R skin tied to the top of a block x block x 1
    block, or on the block's own nodes (skin == block), struck at `speed` by a striker x
    striker x max(1, striker - 1) block; `everything`: general contact over ALL EXTERIOR (the
    tied pair included) instead of striker against skin."""
    lines = ["*HEADING", f"A {skin} x {skin} S4R skin on a block, struck at {speed} m/s"]
    nodes = []

    def node(x, y, z):
        nodes.append((len(nodes) + 1, x, y, z))
        return len(nodes)

    def brick(n, nz, x0, z0, h, hz):
        ids = {(i, j, k): node(x0 + i * h, x0 + j * h, z0 + k * hz)
               for k in range(nz + 1) for j in range(n + 1) for i in range(n + 1)}
        return ids, [[ids[i, j, k], ids[i + 1, j, k], ids[i + 1, j + 1, k], ids[i, j + 1, k],
                      ids[i, j, k + 1], ids[i + 1, j, k + 1], ids[i + 1, j + 1, k + 1],
                      ids[i, j + 1, k + 1]]
                     for k in range(nz) for j in range(n) for i in range(n)]

    block_ids, block_elements = brick(block, 1, 0.0, 0.0, W / block, H)
    nodes_of = {(i, j): block_ids[i, j, 1] if merged else node(i * W / skin, j * W / skin, H)
                for j in range(skin + 1) for i in range(skin + 1)}
    skin_elements = [[nodes_of[i, j], nodes_of[i + 1, j], nodes_of[i + 1, j + 1],
                      nodes_of[i, j + 1]] for j in range(skin) for i in range(skin)]
    # The striker 0.5 mm above the skin's top (half its 1 mm thickness above the mid-surface).
    layers = max(1, striker - 1)
    _, striker_elements = brick(striker, layers, 0.005, H + 0.001, 0.01 / striker,
                                0.005 / layers)
    lines.append("*NODE")
    lines += [f"{i}, {x:.9g}, {y:.9g}, {z:.9g}" for i, x, y, z in nodes]
    first = {}
    number = 0
    for kind, name, elements in (("C3D8R", "BLOCK", block_elements),
                                 ("S4R", "SKIN", skin_elements),
                                 ("C3D8R", "STRIKER", striker_elements)):
        lines.append(f"*ELEMENT, TYPE={kind}, ELSET={name}")
        first[name] = number + 1
        for corners in elements:
            number += 1
            lines.append(f"{number}, " + ", ".join(map(str, corners)))
    lines.append("*SURFACE, NAME=BLOCK_TOP, TYPE=ELEMENT")
    lines += [f"{first['BLOCK'] + k}, S2" for k in range(len(block_elements))]
    for name, side in (("SKIN_BOTTOM", "SNEG"), ("SKIN_TOP", "SPOS")):
        lines.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        lines += [f"{first['SKIN'] + k}, {side}" for k in range(len(skin_elements))]
    lines.append("*SURFACE, NAME=STRIKER_ALL, TYPE=ELEMENT")
    lines += [f"{first['STRIKER'] + k}, S{f}" for k in range(len(striker_elements))
              for f in range(1, 7)]
    if not merged:
        lines += ["*TIE, NAME=SKIN_TIE, ADJUST=YES", "SKIN_BOTTOM, BLOCK_TOP"]
    lines += ["*NSET, NSET=BASE"] + [str(block_ids[i, j, 0]) for j in range(block + 1)
                                     for i in range(block + 1)]
    lines += ["*NSET, NSET=STRIKER_NODES, ELSET=STRIKER",
              "*MATERIAL, NAME=STEEL", "*DENSITY", "7850.", "*ELASTIC", "2.1e11, 0.3",
              "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
              "*SOLID SECTION, ELSET=STRIKER, MATERIAL=STEEL",
              "*SHELL SECTION, ELSET=SKIN, MATERIAL=STEEL", "0.001, 5",
              "*INITIAL CONDITIONS, TYPE=VELOCITY", f"STRIKER_NODES, 3, {-speed}",
              "*STEP, NAME=HIT", "*DYNAMIC, EXPLICIT", ", 6e-05", "*BOUNDARY", "BASE, 1, 3",
              "*CONTACT", *(["*CONTACT INCLUSIONS, ALL EXTERIOR"] if everything else
                            ["*CONTACT INCLUSIONS", "STRIKER_ALL, SKIN_TOP"]),
              "*OUTPUT, FIELD, NUMBER INTERVAL=4", "*NODE OUTPUT", "U, V",
              "*OUTPUT, HISTORY, TIME INTERVAL=1e-06", "*ENERGY OUTPUT", "*END STEP"]
    return "\n".join(lines) + "\n"


def run(binary, directory, name, text):
    directory.mkdir(parents=True, exist_ok=True)
    deck = directory / f"{name}.inp"
    deck.write_text(text)
    r = subprocess.run([binary, "run", deck.name], cwd=directory, capture_output=True, text=True,
                       timeout=300)
    check(r.returncode == 0, f"{name}: exit {r.returncode}: {(r.stdout + r.stderr)[-600:]}")
    return directory / f"{name}.h5"


def energy(path, key):
    with h5py.File(path, "r") as f:
        return np.asarray(f[f"history/step_1/energy/{key}"][()], dtype=float)


def merged(binary, out):
    tied = run(binary, out / "tied", "skin_tied", skin_deck(merged=False))
    whole = run(binary, out / "merged", "skin_merged", skin_deck(merged=True))
    for key in ("ALLKE", "ALLIE", "ALLPW"):
        a, b = energy(tied, key), energy(whole, key)
        check(a.shape == b.shape, f"{key}: {a.shape} history rows tied, {b.shape} merged")
        scale = float(np.max(np.abs(b)))
        check(scale > 0.0, f"{key}: zero throughout")
        difference = float(np.max(np.abs(a - b))) / scale
        print(f"merged: {key} tied against merged nodes: largest difference {difference:.3g} "
              "of its largest value")
        check(difference <= 1e-9, f"{key}: tied and merged differ by {difference:.3g}")
    # The striker was stopped by the skin: the kinetic energy fell and contact took work.
    ke = energy(whole, "ALLKE")
    check(float(np.min(ke)) < 0.8 * float(ke[0]), "the striker's kinetic energy never fell")


def shared(binary, out):
    result = run(binary, out, "skin_shared",
                 skin_deck(merged=False, skin=16, block=1, striker=1, speed=50.0))
    work, total = energy(result, "ALLPW"), energy(result, "ETOTAL")
    scale = float(np.max(np.abs(total)))
    print(f"shared: least ALLPW {float(np.min(work)):.4g} J, ETOTAL up to {scale:.4g} J")
    check(float(np.min(work)) >= -1e-4 * scale,
          f"the springs gave back {-float(np.min(work)):.4g} J (ALLPW < 0)")


def joined(binary, out):
    """The fine skin with general contact over everything: its nodes lie half its thickness
    inside the block, deeper than the automatic limit, and the .msg says the tie holds them."""
    run(binary, out, "skin_joined", skin_deck(merged=False, skin=10, block=2, everything=True))
    msg = (out / "skin_joined.msg").read_text()
    held = msg.count("a *TIE joins it to this face")
    print(f"joined: {held} ignored tied nodes reported as held by their tie")
    check(held > 0, "no ignored node reported as held by its tie")
    check("the penalty will push it out" not in msg, "a tied node said to be pushed out")


def swapped_deck(directory):
    """make_tie_ranks.py's deck with the SKIN tie turned round."""
    directory.mkdir(parents=True, exist_ok=True)
    deck = directory / "tie_ranks_unswapped.inp"
    subprocess.run(["/usr/bin/python3", str(SRC / "tests/mpi/make_tie_ranks.py"), str(deck)],
                   check=True, capture_output=True)
    text = deck.read_text()
    check("\nSKIN_FINE, SKIN_COARSE\n" in text, "make_tie_ranks.py's SKIN tie line not found")
    return text.replace("\nSKIN_FINE, SKIN_COARSE\n", "\nSKIN_COARSE, SKIN_FINE\n")


def swapped(binary, out):
    run(binary, out, "tie_swapped", swapped_deck(out))
    msg = (out / "tie_swapped.msg").read_text()
    check("contact created energy" not in msg, "contact created energy")
    print("swapped: completed")


CASES = {"merged": merged, "shared": shared, "swapped": swapped, "joined": joined}


def main():
    if len(sys.argv) in (3, 4) and sys.argv[1] == "--write-deck":
        target = pathlib.Path(sys.argv[2])
        which = sys.argv[3] if len(sys.argv) == 4 else "skin"
        check(which in ("skin", "swapped"), f"unknown deck {which}; expected skin or swapped")
        text = skin_deck(merged=False) if which == "skin" else swapped_deck(target.parent)
        target.write_text(text)
        return
    if len(sys.argv) not in (3, 4) or (len(sys.argv) == 4 and sys.argv[3] not in CASES):
        sys.exit(__doc__)
    binary, out = str(pathlib.Path(sys.argv[1]).resolve()), pathlib.Path(sys.argv[2])
    if out.exists():
        shutil.rmtree(out)
    for name in [sys.argv[3]] if len(sys.argv) == 4 else list(CASES):
        CASES[name](binary, out / name)
    print("check_tie_contact.py: passed")


if __name__ == "__main__":
    main()
