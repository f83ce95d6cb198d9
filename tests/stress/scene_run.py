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
