#!/usr/bin/env python3
"""Mutation fuzzer for the deck reader: mutates seed decks and runs `xpl check` on each.

Every mutated deck must end as a deck error (exit 1) or a clean data check (exit 0): a
signal, a sanitizer report, a run past the time limit, or any other exit code (an internal
error on bad input, exit 4, included) is a finding. Findings are written to the keep
directory as `finding-NNNN.inp` with the mutation and the output beside them, so that each
can be turned into a regression deck (tests/fuzz/regressions/).

Two ways to check a deck:
- process per deck (--xpl): `xpl check` as a process of its own, the whole command line
  (exit codes, signals, the re-exec for the OpenMP wait policy); about 0.25 s of CPU per deck
  under the sanitizers, most of it starting the process.
- in process (--in-process): tests/fuzz/xpl_fuzz_check checks a batch of decks in one process
  through the same code (xpl::apps::run_job, as `xpl check --quiet`), each deck isolated
  (exceptions, captured messages, a watchdog for the time limit, a leak check per deck under
  ASan); a deck that kills the process is attributed from the driver's "start K" line and the
  batch goes on in a new process. There, deck text echoed with raw control bytes (on the
  terminal, in .msg or .sta) is a finding too.
The mutations are the same in both modes (the same seed gives the same decks).

Generated decks (--generate, or --generated-fraction of the decks): small models of the
keywords that decide the physics (*PLASTIC, *RATE DEPENDENT, *TIE, *FIXED MASS SCALING,
*CONTACT INCLUSIONS/EXCLUSIONS; generate_decks.py) with plausible, boundary and nonsense
values, a third of them mutated once more. With --run (process per deck) every deck that
`xpl check` accepts is also run (`xpl run`, seconds each): a signal, a sanitizer report, a
hang, an exit code other than 0, 1 or 3, or a summary whose status disagrees with the exit
code is a finding.

The mutations are deck-aware (lines, keyword parameters, numbers, ids) plus raw byte damage,
driven by one seed so that a run is reproducible:

    fuzz_decks.py --xpl build/sanitize/apps/xpl --count 300 --seed 1
    fuzz_decks.py --in-process build/sanitize/tests/fuzz/xpl_fuzz_check --count 3000 --seed 1
    fuzz_decks.py --xpl build/release/apps/xpl --replay tests/fuzz/regressions
    fuzz_decks.py --xpl build/sanitize/apps/xpl --generate --run --count 80 --seed 3

Exit code: 0 when no finding, 1 otherwise, 2 on a usage error.
"""

import argparse
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import generate_decks  # noqa: E402  (beside this file)

REPO = Path(__file__).resolve().parents[2]
DEFAULT_SEEDS = [REPO / "examples", REPO / "tests" / "data" / "decks"]
ACCEPTED_EXIT = {0, 1}
SANITIZER_MARKS = ("AddressSanitizer", "LeakSanitizer", "UndefinedBehaviorSanitizer",
                   "runtime error:")

EXTREME_NUMBERS = ["0", "-0", "-1", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf",
                   "2147483647", "2147483648", "-2147483649", "9223372036854775808",
                   "99999999999999999999999", "1e999", "0x10", "1,", "", "abc", "1.5.5",
                   "1e", "+", "-", "."]
EXTREME_PARAMETERS = ["", "=", "==", "ALL", "-1", "0", "1e-20", "1e20", "NAN", "YES",
                      "NO", "X" * 300, "\"", "'", "A\x1b[31mB", "\x07"]
RAW_BYTES = [b"\x00", b"\x1b[31m", b"\x07", b"\xff\xfe", b"\r", b"\t", b"**", b"*",
             b",,,,", b"\n*\n", b"\xc3\x28", b"\x7f"]
NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")


def seed_decks(paths):
    decks = []
    for p in paths:
        p = Path(p)
        decks.extend(sorted(p.rglob("*.inp")) if p.is_dir() else [p])
    return [d for d in decks if d.stat().st_size < 2_000_000]


def keyword_lines(decks):
    """Every keyword line of the seeds (the vocabulary of the insert mutation)."""
    vocabulary = set()
    for deck in decks:
        for line in deck.read_bytes().splitlines():
            if line.startswith(b"*") and not line.startswith(b"**"):
                vocabulary.add(line)
    return sorted(vocabulary)


def mutate_numbers(line, rng):
    matches = list(NUMBER.finditer(line))
    if not matches:
        return line
    m = rng.choice(matches)
    return line[:m.start()] + rng.choice(EXTREME_NUMBERS) + line[m.end():]


def mutate_parameter(line, rng):
    parts = line.split(",")
    if len(parts) < 2:
        return line + "," + rng.choice(["NAME", "ELSET", "TYPE", "INPUT"]) + "=" + \
            rng.choice(EXTREME_PARAMETERS)
    i = rng.randrange(1, len(parts))
    key = parts[i].split("=")[0]
    choice = rng.random()
    if choice < 0.4:
        parts[i] = key + "=" + rng.choice(EXTREME_PARAMETERS)
    elif choice < 0.6:
        parts[i] = key
    elif choice < 0.8:
        del parts[i]
    else:
        parts.append(parts[i])
    return ",".join(parts)


def mutate(text, rng, vocabulary, other_seeds):
    """One mutation of a deck (bytes in, bytes out) and its description."""
    lines = text.split(b"\n")
    kind = rng.randrange(11)
    i = rng.randrange(len(lines)) if lines else 0
    if kind == 0 and len(lines) > 1:
        del lines[i]
        return b"\n".join(lines), f"delete line {i + 1}"
    if kind == 1:
        lines.insert(i, lines[i])
        return b"\n".join(lines), f"duplicate line {i + 1}"
    if kind == 2 and len(lines) > 1:
        j = rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
        return b"\n".join(lines), f"swap lines {i + 1} and {j + 1}"
    if kind in (3, 4):
        line = lines[i].decode("latin-1")
        lines[i] = mutate_numbers(line, rng).encode("latin-1")
        return b"\n".join(lines), f"number on line {i + 1}"
    if kind == 5:
        starts = [k for k, l in enumerate(lines) if l.startswith(b"*") and not l.startswith(b"**")]
        if starts:
            i = rng.choice(starts)
            lines[i] = mutate_parameter(lines[i].decode("latin-1"), rng).encode("latin-1")
            return b"\n".join(lines), f"parameter on line {i + 1}"
    if kind == 6 and vocabulary:
        lines.insert(i, rng.choice(vocabulary))
        return b"\n".join(lines), f"insert keyword at line {i + 1}"
    if kind == 7:
        cut = rng.randrange(len(text) + 1)
        return text[:cut], f"truncate at byte {cut}"
    if kind == 8:
        pos = rng.randrange(len(text) + 1)
        return text[:pos] + rng.choice(RAW_BYTES) + text[pos:], f"bytes at {pos}"
    if kind == 9 and other_seeds:
        other = rng.choice(other_seeds).read_bytes().split(b"\n")
        a = rng.randrange(len(other))
        chunk = other[a:a + rng.randrange(1, 40)]
        lines[i:i] = chunk
        return b"\n".join(lines), f"splice {len(chunk)} lines at {i + 1}"
    if kind == 10:
        # Repeat a data block: duplicate ids, sets and definitions.
        j = min(len(lines), i + rng.randrange(1, 30))
        lines[j:j] = lines[i:j]
        return b"\n".join(lines), f"repeat lines {i + 1}-{j}"
    return text + b"\n" + rng.choice(RAW_BYTES), "append bytes"


def check_environment():
    return dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="PASSIVE",
                ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:exitcode=86",
                UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=87")


def run_check(xpl, deck_path, out_dir, timeout):
    env = check_environment()
    start = time.monotonic()
    try:
        p = subprocess.run([str(xpl), "check", str(deck_path), "-o", str(out_dir)],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
                           timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired as e:
        return "hang", None, (e.stderr or b"")[-4000:], time.monotonic() - start
    elapsed = time.monotonic() - start
    err = p.stderr[-8000:]
    text = err.decode("utf-8", "replace")
    if any(mark in text for mark in SANITIZER_MARKS):
        return "sanitizer", p.returncode, err, elapsed
    if p.returncode < 0:
        return "signal", p.returncode, err, elapsed
    if p.returncode not in ACCEPTED_EXIT:
        return f"exit {p.returncode}", p.returncode, err, elapsed
    return "ok", p.returncode, err, elapsed


def prepare_workspace(seed, work_root, index):
    """A private copy of the seed's directory (for its *INCLUDE files) and an output dir."""
    work = work_root / f"w{index}"
    if work.exists():
        shutil.rmtree(work)
    shutil.copytree(seed.parent, work / "deck", ignore=shutil.ignore_patterns("*.h5", "*.xdmf"))
    (work / "out").mkdir()
    return work / "deck" / seed.name, work / "out"


GENERATED = Path("generated.inp")  # the "seed" of a generated deck (written beside a seed's copy)


def mutated_deck(args, index, seeds, vocabulary):
    """Deck number `index` of the run: its seed deck (GENERATED for a generated one), the
    mutations and the text."""
    rng = random.Random(args.seed * 1_000_003 + index)
    if args.generate or rng.random() < args.generated_fraction:
        text, what = generate_decks.generated_deck(rng)
        text = text.encode()
        steps = [f"generated: {what}"]
        if rng.random() < 0.3:
            text, what = mutate(text, rng, vocabulary, seeds)
            steps.append(what)
        return seeds[0].parent / GENERATED, steps, text
    seed = rng.choice(seeds)
    text = seed.read_bytes()
    steps = []
    for _ in range(rng.choice([1, 1, 2, 3])):
        text, what = mutate(text, rng, vocabulary, seeds)
        steps.append(what)
    return seed, steps, text


def fuzz_one(args, index, seeds, vocabulary, work_root):
    seed, steps, text = mutated_deck(args, index, seeds, vocabulary)
    deck_path, out_dir = prepare_workspace(seed, work_root, index)
    deck_path.write_bytes(text)
    outcome, rc, err, elapsed = run_check(args.xpl, deck_path, out_dir, args.timeout)
    if args.run and outcome == "ok" and rc == 0:
        outcome, rc, err, run_time = generate_decks.run_outcome(
            args.xpl, deck_path, out_dir, args.timeout, check_environment(), SANITIZER_MARKS)
        elapsed += run_time
    shutil.rmtree(deck_path.parent.parent, ignore_errors=True)
    return index, seed, steps, text, outcome, rc, err, elapsed


def seed_copies(seeds, work_root):
    """One private copy of each seed deck's directory (for its *INCLUDE files), shared by the
    mutated decks of that seed: {seed directory: copy}."""
    copies = {}
    for seed in seeds:
        if seed.parent not in copies:
            copy = work_root / "seeds" / str(len(copies))
            shutil.copytree(seed.parent, copy,
                            ignore=shutil.ignore_patterns("*.h5", "*.xdmf", "*.sta", "*.msg"))
            copies[seed.parent] = copy
    return copies


def sanitizer_or_signal(returncode, err):
    text = err.decode("utf-8", "replace")
    if any(mark in text for mark in SANITIZER_MARKS):
        return "sanitizer"
    if returncode < 0:
        return "signal"
    return f"driver exit {returncode}"


def run_batch(args, batch, seeds, vocabulary, copies, work_root, number):
    """Checks the decks `batch` (indices) with xpl_fuzz_check; returns one result per deck
    as fuzz_one does. A deck that ends the driver is the finding; the rest of the batch goes
    on in a new driver process."""
    decks = []
    for index in batch:
        seed, steps, text = mutated_deck(args, index, seeds, vocabulary)
        path = copies[seed.parent] / f"fuzz{index:06d}.inp"
        path.write_bytes(text)
        decks.append((index, seed, steps, text, path))
    results = []
    out_dir = work_root / f"out{number}"
    env = check_environment()
    pending = decks
    while pending:
        listing = work_root / f"batch{number}.txt"
        listing.write_text("".join(f"{d[4]}\n" for d in pending))
        # The driver's watchdog ends a deck at the limit; this is the backstop.
        limit = args.timeout * len(pending) + 60
        with open(work_root / f"batch{number}.err", "w+b") as err_file:
            try:
                p = subprocess.run([str(args.in_process), str(listing), str(out_dir),
                                    "--timeout", str(args.timeout)],
                                   stdout=subprocess.PIPE, stderr=err_file, env=env,
                                   timeout=limit, stdin=subprocess.DEVNULL)
                returncode, out = p.returncode, p.stdout
            except subprocess.TimeoutExpired as e:
                returncode, out = -9, e.stdout or b""
            err_file.seek(0)
            err = err_file.read()[-8000:]
        done = {}
        started = None
        hung = None
        for line in out.decode("utf-8", "replace").splitlines():
            words = line.split()
            if len(words) >= 2 and words[0] == "start":
                started = int(words[1])
            elif len(words) >= 4 and words[0] == "done":
                done[int(words[1])] = (int(words[2]), float(words[3]), words[4:])
            elif len(words) >= 2 and words[0] == "hang":
                hung = int(words[1])
        for k, (rc, elapsed, flags) in done.items():
            index, seed, steps, text, path = pending[k]
            outcome = "ok"
            if rc not in ACCEPTED_EXIT:
                outcome = f"exit {rc}"
            elif "leak" in flags:
                outcome = "leak"
            elif "raw-control" in flags:
                outcome = "raw control"
            stderr_path = Path(str(path) + ".stderr")
            text_err = stderr_path.read_bytes() if stderr_path.exists() else b""
            results.append((index, seed, steps, text, outcome, rc, text_err, elapsed))
        if len(done) == len(pending) and returncode == 0:
            break
        # The driver ended early (or not cleanly): the deck it had started is the finding.
        culprit = started if started is not None and started not in done else None
        if culprit is None:
            # Every deck reported, then the process failed (a report at exit).
            index, seed, steps, text, path = pending[-1]
            results.append((index, seed, steps, text, sanitizer_or_signal(returncode, err),
                            returncode, err, 0.0))
            break
        index, seed, steps, text, path = pending[culprit]
        outcome = "hang" if hung == culprit else sanitizer_or_signal(returncode, err)
        results.append((index, seed, steps, text, outcome, returncode, err,
                         args.timeout if outcome == "hang" else 0.0))
        pending = pending[culprit + 1:]
    for index, seed, steps, text, path in decks:
        for p in (path, Path(str(path) + ".stderr")):
            p.unlink(missing_ok=True)
    return results


def keep_finding(keep, number, seed, steps, text, outcome, err):
    keep.mkdir(parents=True, exist_ok=True)
    base = keep / f"finding-{number:04d}"
    base.with_suffix(".inp").write_bytes(text)
    base.with_suffix(".txt").write_text(
        f"seed deck: {seed}\nmutations: {'; '.join(steps)}\noutcome: {outcome}\n\n" +
        err.decode("utf-8", "replace"))


def replay(args):
    decks = sorted(Path(args.replay).glob("*.inp"))
    findings = 0
    with tempfile.TemporaryDirectory() as tmp:
        for k, deck in enumerate(decks):
            out = Path(tmp) / f"o{k}"
            out.mkdir()
            outcome, rc, err, _ = run_check(args.xpl, deck, out, args.timeout)
            if outcome != "ok":
                findings += 1
                print(f"{deck.name}: {outcome}\n{err.decode('utf-8', 'replace')[-2000:]}")
    print(f"replayed {len(decks)} regression decks: {findings} findings")
    return 1 if findings else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--xpl", type=Path, help="the xpl program: one process per deck")
    parser.add_argument("--in-process", type=Path, metavar="XPL_FUZZ_CHECK",
                        help="the in-process driver (tests/fuzz/xpl_fuzz_check): decks in "
                             "batches, one process per batch")
    parser.add_argument("--batch", type=int, default=250,
                        help="decks per driver process in --in-process mode")
    parser.add_argument("--seeds", nargs="*", type=Path, default=DEFAULT_SEEDS,
                        help="seed decks or directories (default: examples, tests/data/decks)")
    parser.add_argument("--count", type=int, default=3000, help="decks to run")
    parser.add_argument("--seed", type=int, default=1, help="random seed")
    parser.add_argument("--timeout", type=float, default=10.0, help="seconds per deck")
    parser.add_argument("--jobs", type=int, default=2, help="decks checked at once")
    parser.add_argument("--keep", type=Path, default=Path("fuzz-findings"),
                        help="directory for findings")
    parser.add_argument("--replay", type=Path, help="run the decks of a directory instead")
    parser.add_argument("--generate", action="store_true",
                        help="generated decks only (generate_decks.py), not mutated seeds")
    parser.add_argument("--generated-fraction", type=float, default=0.0,
                        help="fraction of the decks that are generated (without --generate)")
    parser.add_argument("--run", action="store_true",
                        help="also run (xpl run) every deck xpl check accepts (--xpl only)")
    args = parser.parse_args()
    program = args.in_process or args.xpl
    if (args.xpl is None) == (args.in_process is None) or (args.replay and args.in_process) or \
            (args.run and args.in_process):
        print("fuzz_decks: give --xpl or --in-process (--replay and --run need --xpl)",
              file=sys.stderr)
        return 2
    if not program.exists():
        print(f"fuzz_decks: {program} does not exist", file=sys.stderr)
        return 2
    if args.replay:
        return replay(args)

    seeds = seed_decks(args.seeds)
    if not seeds:
        print("fuzz_decks: no seed decks", file=sys.stderr)
        return 2
    vocabulary = keyword_lines(seeds)
    outcomes = {}
    exit_codes = {}
    findings = 0
    slowest = 0.0
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="xpl-fuzz-") as tmp:
        work_root = Path(tmp)
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            if args.in_process:
                copies = seed_copies(seeds, work_root)
                batches = [range(i, min(args.count, i + args.batch))
                           for i in range(0, args.count, args.batch)]
                futures = [pool.submit(run_batch, args, b, seeds, vocabulary, copies, work_root,
                                       n) for n, b in enumerate(batches)]
            else:
                futures = [pool.submit(lambda i: [fuzz_one(args, i, seeds, vocabulary,
                                                           work_root)], i)
                           for i in range(args.count)]
            results = (r for future in concurrent.futures.as_completed(futures)
                       for r in future.result())
            for index, seed, steps, text, outcome, rc, err, elapsed in results:
                outcomes[outcome] = outcomes.get(outcome, 0) + 1
                exit_codes[rc] = exit_codes.get(rc, 0) + 1
                slowest = max(slowest, elapsed)
                if outcome != "ok":
                    findings += 1
                    keep_finding(args.keep, index, seed, steps, text, outcome, err)
                    print(f"finding {index}: {outcome} from {seed.name} ({'; '.join(steps)})")
    wall = time.monotonic() - start
    codes = ", ".join(f"{k}: {v}" for k, v in sorted(exit_codes.items(), key=lambda kv: str(kv[0])))
    mode = "in process" if args.in_process else "one process each"
    if args.run:
        mode += ", accepted ones run"
    kind = "generated" if args.generate else "mutated"
    print(f"fuzz_decks: {args.count} {kind} decks ({mode}) from {len(seeds)} seeds "
          f"(seed {args.seed}) in {wall:.0f} s, slowest {slowest:.1f} s; exit codes {{{codes}}}; "
          f"findings: {findings} "
          f"({', '.join(f'{k} {v}' for k, v in sorted(outcomes.items()) if k != 'ok') or 'none'})")
    if findings:
        print(f"fuzz_decks: findings kept in {args.keep}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
