#!/usr/bin/env python3
"""MPI test (issue 37 item 3, docs/dev/mpi.md): a deck run on one rank and under mpirun on
2 and 3 ranks with 1 and 2 threads each must give bitwise equal results (`xpl compare
--frames all` at tolerance 0: every field of every frame and every history series, the
energies included). Only in the XPL_MPI=ON build (ctest label mpi).

Usage: mpi_bitwise.py XPL DECK OUT_DIR [--ranks 2,3] [--threads 1,2] [--time-period T]
                      [--run-option=OPTION]... [--msg-has TEXT]...
       mpi_bitwise.py XPL DECK OUT_DIR --refused TEXT   (the deck must be refused on 2 ranks
                                                          with TEXT in the message)
       mpi_bitwise.py XPL DECK OUT_DIR --blocked-output (an error of rank 0 alone must end
                                                          the run on every rank)
--time-period T runs a copy of the deck (in OUT_DIR) whose steps last T s each, to keep a long
example short. Every run is limited to RUN_LIMIT seconds of wall time; a hung run is
reported with where its processes wait and killed with every process it started. OUT_DIR is
removed when every comparison passed and kept otherwise.
Standard library only.
"""

import argparse
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile


def mpirun(ranks):
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)]
    if os.geteuid() == 0:
        cmd.insert(1, "--allow-run-as-root")
    return cmd


# Wall-time limit of one run (one xpl process or one mpirun), s: a hung run is reported with
# where its processes wait and killed with everything it started, so that nothing it leaves
# behind (ranks, OpenMPI's daemons and their session files) can fail the tests after it.
RUN_LIMIT = 240.0


def diagnose(pid, out):
    """Where the processes of a hung run wait: their command lines, and gdb's backtraces of
    xpl's ranks when gdb is there; then how full the disks are."""
    lines = []
    try:
        tree = subprocess.run(["ps", "-o", "pid,stat,etime,time,args", "-s", str(pid)],
                              capture_output=True, text=True, check=False, timeout=10)
        lines.append(tree.stdout)
        for row in tree.stdout.splitlines()[1:]:
            fields = row.split(None, 4)
            if len(fields) == 5 and "xpl" in fields[4].split()[0] and shutil.which("gdb"):
                bt = subprocess.run(["gdb", "-p", fields[0], "-batch", "-ex", "thread apply all bt 12"],
                                    capture_output=True, text=True, check=False, timeout=60)
                lines.append("\n".join(line for line in bt.stdout.splitlines()
                                        if line.startswith(("#", "Thread"))))
        disks = subprocess.run(["df", "-h", str(out), "/tmp", "/dev/shm"], capture_output=True,
                               text=True, check=False, timeout=10)
        lines.append(disks.stdout)
    except (OSError, subprocess.SubprocessError) as error:
        lines.append(f"(diagnosis failed: {error})")
    return "\n".join(lines)


def kill_session(sid):
    """Kills every process of session `sid`: mpirun puts each rank in a process group of its
    own, so killing mpirun's group would leave the ranks running."""
    listed = subprocess.run(["ps", "-o", "pid=", "-s", str(sid)], capture_output=True, text=True,
                            check=False)
    for pid in listed.stdout.split():
        try:
            os.kill(int(pid), signal.SIGKILL)
        except (ProcessLookupError, ValueError):
            pass


def run(cmd, out):
    """Runs `cmd` in its own process group and session directory; returns (exit code, output).
    Exit code None: killed after RUN_LIMIT seconds."""
    env = dict(os.environ)
    # OpenMPI's session files in a directory of this run alone (short: they hold sockets).
    session = tempfile.mkdtemp(prefix="xpl-mpi-")
    env["TMPDIR"] = session
    try:
        with subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              env=env, start_new_session=True) as process:
            try:
                text, _ = process.communicate(timeout=RUN_LIMIT)
                return process.returncode, text
            except subprocess.TimeoutExpired:
                where = diagnose(process.pid, out)
                kill_session(process.pid)
                text, _ = process.communicate()
                return None, f"killed after {RUN_LIMIT:.0f} s: {' '.join(cmd)}\n{where}\n{text}"
    finally:
        shutil.rmtree(session, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xpl")
    parser.add_argument("deck")
    parser.add_argument("out")
    parser.add_argument("--ranks", default="2,3")
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--refused", default=None)
    parser.add_argument("--time-period", default=None)
    parser.add_argument("--blocked-output", action="store_true",
                        help="rank 0 cannot write JOB.xdmf: every rank must end, none hang")
    parser.add_argument("--import-state", default=None,
                        help="with --refused: run with --import of this result file")
    parser.add_argument("--run-option", action="append", default=[],
                        help="an option of the N-rank runs, e.g. --run-option=--contact-redundant")
    parser.add_argument("--msg-has", action="append", default=[],
                        help="a text each N-rank run's JOB.msg must hold")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    if args.time_period is not None:
        # The line after each *DYNAMIC, EXPLICIT holds (initial increment, time period).
        lines = pathlib.Path(args.deck).read_text().splitlines()
        for k in range(len(lines) - 1):
            if lines[k].upper().replace(" ", "").startswith("*DYNAMIC,EXPLICIT"):
                lines[k + 1] = f", {args.time_period}"
        short = out / pathlib.Path(args.deck).name
        short.write_text("\n".join(lines) + "\n")
        args.deck = str(short)
    job = pathlib.Path(args.deck).stem

    if args.blocked_output:
        # Rank 0 alone cannot write JOB.xdmf (a directory stands where its new copy goes): the
        # run must end on every rank with the reason, not leave the others waiting for ever.
        blocker = out / f"{job}.xdmf.tmp"
        blocker.mkdir()
        (blocker / "keep").write_text("a directory where xpl writes a file\n")
        code, text = run(mpirun(2) + [args.xpl, "run", args.deck, "-o", str(out), "--quiet",
                                      "--threads", "1"], out)
        if code is None or code == 0 or "ending the run on every rank" not in text:
            print(f"expected a prompt non-zero exit naming the rank's error, got {code}:\n{text}")
            return 1
        print(f"ended on every rank as expected (exit {code}): "
              f"{next(line for line in text.splitlines() if 'ending the run' in line)}")
        return 0

    if args.refused is not None:
        extra = ["--import", args.import_state] if args.import_state else []
        code, text = run(mpirun(2) + [args.xpl, "run", args.deck, "-o", str(out), "--quiet",
                                      "--threads", "1"] + extra, out)
        if code != 1 or args.refused not in text or "not distributed yet" not in text:
            print(f"expected exit 1 and '{args.refused} ... not distributed yet', got {code}:\n{text}")
            return 1
        if (out / f"{job}.h5").exists():
            print("a refused run wrote results")
            return 1
        print(f"refused on 2 ranks as expected: {text.strip().splitlines()[0]}")
        return 0

    reference = out / "np1"
    code, text = run([args.xpl, "run", args.deck, "-o", str(reference), "--quiet", "--threads", "1"],
                     out)
    if code != 0:
        print(f"one-rank run failed ({code}):\n{text}")
        return 1
    failures = 0
    for ranks in [int(r) for r in args.ranks.split(",")]:
        for threads in [int(t) for t in args.threads.split(",")]:
            case = out / f"np{ranks}_t{threads}"
            code, text = run(mpirun(ranks) + [args.xpl, "run", args.deck, "-o", str(case),
                                              "--quiet", "--threads", str(threads)]
                             + args.run_option, out)
            if code is None:
                print(f"{ranks} ranks x {threads} threads: hung; the runs after it were not made:\n{text}")
                return 1
            if code != 0:
                print(f"{ranks} ranks x {threads} threads: run failed ({code}):\n{text}")
                failures += 1
                continue
            msg = (case / f"{job}.msg").read_text()
            for expected in args.msg_has:
                if expected not in msg:
                    print(f"{ranks} ranks x {threads} threads: '{expected}' not in {job}.msg")
                    failures += 1
            if f"mpi: {ranks} ranks, distributed time loop" not in msg:
                print(f"{ranks} ranks x {threads} threads: the .msg does not report a distributed run")
                failures += 1
            code, text = run([args.xpl, "compare", str(reference / f"{job}.h5"),
                              str(case / f"{job}.h5"), "--frames", "all"], out)
            verdict = text.strip().splitlines()[-1] if text.strip() else ""
            print(f"{ranks} ranks x {threads} threads: {verdict}")
            if code != 0:
                print("\n".join(line for line in text.splitlines() if not line.startswith("pass")))
                failures += 1
    if failures:
        return 1
    # Passed: the results go (about 5 runs of the deck each; a CI machine's disk may be small).
    shutil.rmtree(out, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
