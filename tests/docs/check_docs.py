#!/usr/bin/python3
"""Checks of the documentation (issue 36 item 5).

Usage: check_docs.py links|spec REPO
       check_docs.py deck REPO XPL OUT_DIR

  links  every relative link and image in README.md, docs/ and the other Markdown files of the
         repository points at a file or folder that exists, and a link with `#anchor` into a
         Markdown file at one of its headings (GitHub's anchors); web links are not fetched
  spec   every requirement id the source, tests, scripts and docs cite (`SPEC C7`, `SPEC
         C7–C10`, or a parenthesised list of ids such as `(C2)`, `(S7, C6)`, `(R5: ...)`) is
         defined in docs/spec.md (a line `- **C7** ...`)
  deck   the deck of README.md's "A first deck" runs as the README says (beside the gmsh mesh
         it includes): exit 0, status completed, the warning about default output, and the
         frames and energies of the defaults in JOB.h5

Prints what it checked; exits 1 with one line per problem (file:line: what), 0 when clean.
"""

import json
import pathlib
import re
import shutil
import subprocess
import sys

SKIP_DIRS = {".git", "build"}


def tracked_files(repo):
    """The repository's files: git's list where there is one, else a walk without build/."""
    try:
        out = subprocess.run(["git", "-C", str(repo), "ls-files"], capture_output=True, text=True,
                             check=True).stdout
        files = [repo / line for line in out.splitlines() if line]
        if files:
            return [f for f in files if f.is_file()]
    except (OSError, subprocess.CalledProcessError):
        pass
    return [p for p in repo.rglob("*")
            if p.is_file() and not SKIP_DIRS & set(p.relative_to(repo).parts)]


def strip_code(text):
    """The text with fenced code blocks and inline code blanked out (lines kept)."""
    out, fenced = [], False
    for line in text.split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            out.append("")
            continue
        out.append("" if fenced else re.sub(r"`[^`]*`", lambda m: " " * len(m.group(0)), line))
    return out


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"`([^`]*)`", r"\1", heading.strip()).lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen, result = {}, set()
        fenced = False
        for line in path.read_text(encoding="utf-8").split("\n"):
            if line.lstrip().startswith("```"):
                fenced = not fenced
            m = None if fenced else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
            if m:
                base = slug(m.group(1))
                n = seen.get(base, 0)
                seen[base] = n + 1
                result.add(base if n == 0 else f"{base}-{n}")
        cache[path] = result
    return cache[path]


LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def check_links(repo):
    problems, checked = [], 0
    # Generated Markdown (benchmarks/accuracy/results/fronts.md: tables to paste into
    # benchmarks/RESULTS.md, its links relative to that file) is not a document of its own.
    documents = [f for f in tracked_files(repo) if f.suffix == ".md"
                 and not {"references", "results"} & set(f.relative_to(repo).parts)]
    for doc in sorted(documents):
        for number, line in enumerate(strip_code(doc.read_text(encoding="utf-8")), 1):
            for m in LINK.finditer(line):
                target = m.group(1)
                if re.match(r"[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                checked += 1
                where = f"{doc.relative_to(repo)}:{number}"
                path_part, _, anchor = target.partition("#")
                dest = doc if not path_part else (doc.parent / path_part).resolve()
                if not dest.exists():
                    problems.append(f"{where}: link to {target}: no such file or folder")
                    continue
                if repo.resolve() not in [dest, *dest.parents]:
                    problems.append(f"{where}: link to {target} leaves the repository")
                    continue
                if anchor and dest.suffix == ".md" and anchor not in anchors(dest):
                    problems.append(f"{where}: link to {target}: no heading with anchor "
                                    f"#{anchor} in {dest.relative_to(repo.resolve())}")
    print(f"{checked} relative links in {len(documents)} Markdown files checked")
    return problems


ID = r"[SECIPRM]\d{1,2}"
RANGE = rf"{ID}(?:\s*(?:–|-|\.\.)\s*[SECIPRM]?\d{{1,2}})?"
SPEC_CITE = re.compile(rf"\bSPEC\s+({RANGE}(?:\s*,\s*{RANGE})*)")
GROUP = re.compile(r"\(([^()\n]*)\)")
ITEM_OK = re.compile(rf"^(?:SPEC\s+)?({RANGE})(?::.*)?$")
ITEM_NEUTRAL = re.compile(r"^(?:issues?|items?|issue \d+ items?)\s+[\d ,and]+$|^$")
TENSOR = re.compile(r"^[SI][1-3][1-3]$")
SOURCE_SUFFIXES = {".cpp", ".hpp", ".h", ".c", ".py", ".sh", ".cmake", ".md", ".txt", ".json"}


def expand(cite):
    """The ids of `C7`, `C7–C10`, `C7-10`."""
    m = re.match(r"([SECIPRM])(\d{1,2})(?:\s*(?:–|-|\.\.)\s*[SECIPRM]?(\d{1,2}))?$", cite.strip())
    if not m:
        return []
    first = int(m.group(2))
    last = int(m.group(3)) if m.group(3) else first
    return [f"{m.group(1)}{n}" for n in range(first, max(first, last) + 1)]


def citations(text):
    """(line, id) of every requirement id cited in `text`."""
    found = []
    for number, line in enumerate(text.split("\n"), 1):
        for m in SPEC_CITE.finditer(line):
            for cite in re.split(r"\s*,\s*", m.group(1)):
                found += [(number, i) for i in expand(cite)]
        for m in GROUP.finditer(line):
            items = [s.strip() for s in re.split(r"[,;]", m.group(1))]
            ids = [ITEM_OK.match(s) for s in items]
            if not any(ids):
                continue
            if all(ok or ITEM_NEUTRAL.match(s) or s.startswith("SPEC ") for ok, s in
                   zip(ids, items)):
                for ok in ids:
                    # (S11, S22, S12) are stress components, (I11, I22) rotary inertias.
                    if ok and not TENSOR.match(ok.group(1)):
                        found += [(number, i) for i in expand(ok.group(1))]
    return sorted(set(found))


def check_spec(repo):
    spec = repo / "docs" / "spec.md"
    defined = set(re.findall(r"^- \*\*([SECIPRM]\d{1,2})\*\*", spec.read_text(encoding="utf-8"),
                             re.M))
    problems, count, files = [], 0, 0
    for f in sorted(tracked_files(repo)):
        rel = f.relative_to(repo)
        if f == spec or f.suffix not in SOURCE_SUFFIXES and f.name != "CMakeLists.txt":
            continue
        if rel.parts[0] == "tests" and "data" in rel.parts:  # decks and their READMEs: ids are data
            continue
        try:
            text = f.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        files += 1
        for number, cited in citations(text):
            count += 1
            if cited not in defined:
                problems.append(f"{rel}:{number}: cites {cited}, which docs/spec.md does not "
                                "define")
    print(f"{count} requirement citations in {files} files checked against the {len(defined)} "
          "ids of docs/spec.md")
    return problems


def check_deck(repo, xpl, out):
    readme = (repo / "README.md").read_text(encoding="utf-8")
    section = readme.split("## A first deck", 1)[1].split("\n## ", 1)[0]
    deck = re.search(r"```inp\n(.*?)```", section, re.S).group(1)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    (out / "block.inp").write_text(deck)
    shutil.copy(repo / "tests/data/decks/gmsh_block/block_mesh.inp", out / "block_mesh.inp")
    run = subprocess.run([str(xpl), "run", "block.inp", "-o", "out", "--quiet"], cwd=out,
                         capture_output=True, text=True, timeout=300)
    problems = []
    if run.returncode != 0:
        return [f"xpl run of README's deck: exit {run.returncode}\n{run.stdout}{run.stderr}"]
    summary = json.loads((out / "out" / "block.summary.json").read_text())
    if summary["status"] != "completed":
        problems.append(f"README's deck: status {summary['status']}, expected completed")
    if "no output request" not in (out / "out" / "block.msg").read_text().lower():
        problems.append("README's deck: block.msg does not warn that the deck has no output "
                        "request, as the README says")
    import h5py  # /usr/bin/python3 has it
    with h5py.File(out / "out" / "block.h5", "r") as f:
        frames = sorted(f["frames"])
        last = f["frames"][frames[-1]]
        for name in ("U", "V", "S"):
            if name not in last:
                problems.append(f"README's deck: the last frame has no {name}")
        if len(frames) != 2:
            problems.append(f"README's deck: {len(frames)} frames, the README says 2 (0 and last)")
        if "ALLKE" not in f["history/step_1/energy"]:
            problems.append("README's deck: no ALLKE history")
    print(f"README's deck ran: {summary['increments']} increments, frames {frames}, "
          f"ALLKE at the end {summary['energies']['ALLKE']:.4g}")
    return problems


def main(argv):
    if not (len(argv) == 3 and argv[1] in ("links", "spec") or len(argv) == 5
            and argv[1] == "deck"):
        print(__doc__, file=sys.stderr)
        return 2
    repo = pathlib.Path(argv[2]).resolve()
    if argv[1] == "deck":
        problems = check_deck(repo, pathlib.Path(argv[3]).resolve(), pathlib.Path(argv[4]))
    else:
        problems = check_links(repo) if argv[1] == "links" else check_spec(repo)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
