#!/usr/bin/env python3
"""Runs the bad-input corpus (cases.txt) against phongsim.

    tests/badinput/run.py PHONGSIM SOURCE_DIR [CATEGORY...]

Every case must exit with status 2, print exactly one line on stderr that matches its pattern,
leave its folder as it found it and its temp directory empty. The fixtures (fixtures.txt) are
unpacked once and must not change either. Prints one line per case; exits 1 if any failed.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def read_cases(path):
    cases, pending = [], ""
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if pending:
                line, pending = pending + line.lstrip(), ""
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            if line.endswith("\\"):
                pending = line[:-1]
                continue
            fields = [x.strip() for x in line.split(" :: ")]
            if len(fields) not in (4, 5):
                sys.exit(f"{path}:{number}: expected 4 or 5 fields separated by ' :: '")
            category, name, pattern, args = fields[:4]
            cases.append({"line": number, "category": category, "name": name,
                          "pattern": re.compile(pattern), "args": args,
                          "setup": fields[4] if len(fields) == 5 else None})
    return cases


def unpack_fixtures(path, folder):
    name, lines = None, []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("=== "):
                if name:
                    with open(os.path.join(folder, name), "w", encoding="utf-8") as out:
                        out.write("".join(lines))
                name, lines = line[4:].strip(), []
            elif name:
                lines.append(line)
    if name:
        with open(os.path.join(folder, name), "w", encoding="utf-8") as out:
            out.write("".join(lines))


def snapshot(folder):
    """Every entry below `folder`, with its type and content (what "left behind" compares)."""
    seen = {}
    for root, dirs, files in os.walk(folder):
        for d in dirs:
            p = os.path.join(root, d)
            seen[os.path.relpath(p, folder)] = "link" if os.path.islink(p) else "dir"
        for name in files:
            p = os.path.join(root, name)
            rel = os.path.relpath(p, folder)
            if os.path.islink(p):
                seen[rel] = "link->" + os.readlink(p)
            elif os.path.isfile(p):
                with open(p, "rb") as f:
                    seen[rel] = f.read()
            else:
                seen[rel] = "special"
    return seen


def main():
    phongsim, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    wanted = set(sys.argv[3:])
    cases = read_cases(os.path.join(HERE, "cases.txt"))
    if wanted:
        cases = [c for c in cases if c["category"] in wanted]
    if not cases:
        sys.exit("no cases selected")
    work = tempfile.mkdtemp(prefix="phongsim-badinput.")
    failures = 0
    try:
        fixtures = os.path.join(work, "fixtures")
        os.mkdir(fixtures)
        unpack_fixtures(os.path.join(HERE, "fixtures.txt"), fixtures)
        before = snapshot(fixtures)
        for i, case in enumerate(cases):
            folder = os.path.join(work, f"case{i}")
            tmp = os.path.join(work, f"tmp{i}")
            os.mkdir(folder)
            os.mkdir(tmp)
            # No heartbeat lines: a slow case must still print its one line.
            env = dict(os.environ, TMPDIR=tmp, PHONGSIM_PROGRESS_AFTER="86400")
            env.pop("PHONGSIM_QUICK", None)
            if case["setup"]:
                subprocess.run(["bash", "-c", case["setup"]], cwd=folder, check=True,
                               env=dict(env, F=fixtures, T=folder, SRC=source))
            setup = snapshot(folder)
            args = case["args"].replace("$F", fixtures).replace("$T", folder)
            args = args.replace("$SRC", source)
            argv = [phongsim] + shlex.split(args)
            try:
                r = subprocess.run(argv, cwd=folder, env=env, capture_output=True, timeout=120,
                                   stdin=subprocess.DEVNULL)
                rc, err = r.returncode, r.stderr.decode("utf-8", "replace")
            except subprocess.TimeoutExpired:
                rc, err = "timeout", ""
            lines = err.rstrip("\n").split("\n") if err.strip() else []
            problems = []
            if rc != 2:
                problems.append(f"exit status {rc}, expected 2")
            if len(lines) != 1:
                problems.append(f"{len(lines)} stderr lines, expected 1")
            elif not case["pattern"].search(lines[0]):
                problems.append(f"stderr does not match /{case['pattern'].pattern}/")
            left = snapshot(folder)
            if left != setup:
                extra = sorted(set(left) - set(setup)) or sorted(
                    k for k in left if left[k] != setup.get(k))
                problems.append(f"left behind or changed: {extra}")
            if os.listdir(tmp):
                problems.append(f"left in TMPDIR: {os.listdir(tmp)}")
            label = f"{case['category']}/{case['name']} (cases.txt:{case['line']})"
            if problems:
                failures += 1
                print(f"FAIL {label}: {'; '.join(problems)}\n  $ phongsim {args}\n"
                      f"  stderr: {err.strip()}")
            else:
                print(f"ok   {label}: {lines[0]}")
            shutil.rmtree(folder, ignore_errors=True)
            shutil.rmtree(tmp, ignore_errors=True)
        if snapshot(fixtures) != before:
            failures += 1
            print("FAIL the fixtures changed")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"{len(cases) - failures} of {len(cases)} bad inputs handled")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
