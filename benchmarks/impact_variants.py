#!/usr/bin/python3
"""Twins of the impact stress scenes (tests/stress/impact_scenes.py) that tell the physics of a
coarse one-point mesh from a spurious hourglass energy (issue 32, items 5 and 7).

For each scene ID (or deck NAME of examples/impacts made of hexes: blocks_600 ... blocks_3000)
the same draw (same speed, angles, materials, sizes) is written as
  base    the scene as the stress test runs it
  c3d8    every deformable C3D8R turned C3D8 (fully integrated, no hourglass control): its peak
          ALLIE is what the mesh stores without the one-point element's hourglass modes
  fine    every element count doubled (2x finer mesh, 8x the hexes, 4x the shells)
  fine_c3d8  both
  fine4   every element count times four; fine4_c3d8 with C3D8
and run with one thread; each run is checked by impact_check.py's criteria. One line per run:
the hourglass share (largest ALLAE / ALLIE over the checked rows, as the test reports it), peak
ALLIE and ALLAE, ALLAE / ALLIE at the end, ETOTAL drift, the failed criteria.

Usage:
  impact_variants.py XPL ID-OR-NAME... [--variants base,c3d8,fine] [--work DIR] [--json FILE]
      writes WORK/VARIANT/scene_ID/ (default ./impact_variants); --json appends one record a
      run; --reuse checks the runs already there
Used for benchmarks/RESULTS.md, "Known stress failures re-measured", and the causes in
tests/stress/known_failures.txt.
Needs numpy and h5py (/usr/bin/python3).
"""

import argparse
import json
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests" / "stress"))
import impact_check  # noqa: E402
import impact_scenes  # noqa: E402

sys.path.insert(0, str(HERE.parent / "examples" / "impacts"))
import make_impact_decks  # noqa: E402

VARIANTS = ("base", "c3d8", "fine", "fine_c3d8", "fine4", "fine4_c3d8")


def parameters(scene_id, variant):
    """The scene's draw, changed for the variant."""
    p = impact_scenes.draw(scene_id)
    if variant.endswith("c3d8"):
        if p["projectile"] == "solid":
            p["projectile_element"] = "C3D8"
        if p["target"] == "solid" and p["support"] != "rigid":
            p["target_element"] = "C3D8"
    if variant.startswith("fine"):
        factor = 4 if variant.startswith("fine4") else 2
        p["projectile_counts"] = [factor * n for n in p["projectile_counts"]]
        p["target_counts"] = [factor * n for n in p["target_counts"]]
    return p


def deck_variant(name, variant):
    """An examples/impacts deck made by solid_block (blocks_*): C3D8 for every C3D8R, or every
    solid_block's counts doubled (times four)."""
    if variant.startswith("fine"):
        factor = 4 if variant.startswith("fine4") else 2
        block = impact_scenes.solid_block
        impact_scenes.solid_block = lambda n, size, counts, kind: block(
            n, size, [factor * c for c in counts], kind)
        try:
            text, meta = make_impact_decks.DECKS[name]()
        finally:
            impact_scenes.solid_block = block
    else:
        text, meta = make_impact_decks.DECKS[name]()
    if variant.endswith("c3d8"):
        text = text.replace("TYPE=C3D8R,", "TYPE=C3D8,")
    return text, meta


def write(scene_id, variant, work):
    if isinstance(scene_id, str):
        text, meta = deck_variant(scene_id, variant)
    else:
        text, meta = impact_scenes.deck_text(parameters(scene_id, variant))
    folder = pathlib.Path(work) / variant / f"scene_{scene_id}"
    folder.mkdir(parents=True, exist_ok=True)
    deck = folder / f"scene_{scene_id}.inp"
    deck.write_text(text)
    (folder / f"scene_{scene_id}.json").write_text(json.dumps(meta, indent=1) + "\n")
    return deck


def energies(deck):
    run = impact_check.read_run(deck.parent, deck.stem)
    e = run.get("energy", {})
    if "ALLIE" not in e:
        return {}
    ie, ae = e["ALLIE"], e["ALLAE"]
    return {"peak_allie": float(ie.max()), "peak_allae": float(ae.max()),
            "end_share": float(ae[-1] / ie[-1]) if ie[-1] > 0 else 0.0,
            "end_allie": float(ie[-1])}


def bodies(p):
    """Deformable bodies: element type, elastic/plastic, elements across."""
    out = []
    for role in ("projectile", "target"):
        kind = p[role]
        if role == "projectile" and kind == "rigid":
            continue
        if role == "target" and p["support"] == "rigid":
            continue
        element = "S4R" if kind == "shell" else p[f"{role}_element"]
        counts = p[f"{role}_counts"][:2] if role == "target" and kind == "shell" \
            else p[f"{role}_counts"]
        out.append(f"{role} {element} {'plastic' if p[f'{role}_plastic'] else 'elastic'} "
                   f"{'x'.join(str(n) for n in counts)}")
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xpl")
    parser.add_argument("ids", nargs="+", help="scene ids or examples/impacts deck names")
    parser.add_argument("--variants", default=",".join(VARIANTS))
    parser.add_argument("--work", default="impact_variants")
    parser.add_argument("--json", help="append one JSON line per run to this file")
    parser.add_argument("--reuse", action="store_true", help="check runs already made")
    args = parser.parse_args(argv)
    variants = args.variants.split(",")
    for scene_id in args.ids:
        scene_id = int(scene_id) if scene_id.isdigit() else scene_id
        for variant in variants:
            if variant not in VARIANTS:
                raise SystemExit(f"unknown variant {variant}; expected one of {VARIANTS}")
            if isinstance(scene_id, str):
                p = {"class": scene_id}
            else:
                p = parameters(scene_id, variant)
                plain = parameters(scene_id, variant.replace("c3d8", "").strip("_") or "base")
                if variant.endswith("c3d8") and p == plain:
                    continue  # no deformable C3D8R: the same deck as base (fine)
            deck = write(scene_id, variant, args.work)
            results = impact_check.run_deck(args.xpl, deck, threads=False, reuse=args.reuse)
            messages = {c: (ok, m) for c, ok, m in results}
            failed = [c for c, ok, _ in results if ok is False]
            e = energies(deck)
            described = bodies(p) if "projectile" in p else ["(deck)"]
            record = {"id": scene_id, "variant": variant, "class": p["class"],
                      "bodies": described, "failed": failed,
                      "messages": {c: m for c, (_, m) in messages.items()}, **e}
            print(f"{scene_id!s:>3} {variant:5s} {p['class']:18s} {'; '.join(described)}: "
                  f"{messages['hourglass'][1]}; peak ALLIE {e.get('peak_allie', 0):.4g} J, "
                  f"peak ALLAE {e.get('peak_allae', 0):.4g} J; {messages['drift'][1]}; "
                  f"failed: {','.join(failed) or '-'}", flush=True)
            if args.json:
                with open(args.json, "a") as f:
                    f.write(json.dumps(record) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
