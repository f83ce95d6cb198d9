"""What check_seed_overclosures.py, check_pass_through.py and check_rigid_bounce.py share:
their arguments and one scene written, run with one thread and checked by impact_check.py
(whose verdict on all the criteria is not theirs). Standard library only."""

import json
import pathlib
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent


def arguments(doc, defaults):
    """(xpl, work folder, scene ids) from sys.argv `XPL WORK_DIR [ID ...]`, or None after
    printing `doc` when they are missing."""
    if len(sys.argv) < 3:
        print(doc)
        return None
    ids = [int(a) for a in sys.argv[3:]] or list(defaults)
    return sys.argv[1], pathlib.Path(sys.argv[2]), ids


def run_scene(xpl, work, scene):
    """Writes, runs and checks scene `scene` under `work`: (impact_check.py's report, the
    scene's folder, its JOB.summary.json)."""
    report = subprocess.run([sys.executable, str(HERE / "impact_check.py"), "run", xpl,
                             str(scene), "--work", str(work), "--no-threads"],
                            capture_output=True, text=True, check=False).stdout
    folder = work / f"scene_{scene}"
    summary = json.loads((folder / f"scene_{scene}.summary.json").read_text())
    return report, folder, summary


def check_scenes(doc, defaults, check):
    """Runs each scene of the command line (arguments(): `XPL WORK_DIR [ID ...]`, `defaults`
    without IDs) and judges it by `check(scene, report, folder, summary)` -> (ok, lines):
    prints `scene N: ok|FAILED: ` and the first line, the others indented. Returns the exit code:
    0 when every scene is ok, 1 otherwise, 2 without arguments (after printing `doc`)."""
    args = arguments(doc, defaults)
    if args is None:
        return 2
    xpl, work, ids = args
    failures = 0
    for scene in ids:
        report, folder, summary = run_scene(xpl, work, scene)
        ok, lines = check(scene, report, folder, summary)
        print(f"scene {scene}: {'ok' if ok else 'FAILED'}: {lines[0]}")
        for line in lines[1:]:
            print(f"  {line}")
        failures += 0 if ok else 1
    return 1 if failures else 0
