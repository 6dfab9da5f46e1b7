#!/usr/bin/env python3
"""Runs every `./build/phongsim ...` command shown in README.md, as written, so the README cannot
drift from the program.

    tests/docs_test.py BUILD_DIR SOURCE_DIR

The commands run in a scratch folder laid out like a checkout: build/phongsim is the build's
program, configs/, sweeps/ and rtl/ are the source tree's; the README's own placeholders are made
there first (my.toml: a copy of configs/lirp/default.toml; my/lyon: a copy of rtl/lyon). Every
command runs with PHONGSIM_QUICK=1 (docs/cosim.md: the same command at a reduced size) and must
exit 0; the commands run in README order, so a command that needs a file an earlier one writes
(eval after vectors) fails if the order is wrong. Exits 1 on the first failure, naming the
command and its stderr.
"""
import os
import shlex
import shutil
import subprocess
import sys
import tempfile


def readme_commands(path):
    """The README's indented code lines starting with ./build/phongsim (continuations joined,
    trailing # comments dropped)."""
    commands, pending = [], None
    with open(path, encoding="utf-8") as f:
        for line in f:
            if pending is not None:
                pending += " " + line.strip()
            elif line.startswith("    ./build/phongsim "):
                pending = line.strip()
            else:
                continue
            code = pending.split(" #")[0].rstrip()
            if code.endswith("\\"):
                pending = code[:-1].rstrip()
                continue
            commands.append(shlex.split(code))
            pending = None
    return commands


def main():
    build, src = (os.path.abspath(a) for a in sys.argv[1:3])
    commands = readme_commands(os.path.join(src, "README.md"))
    # A floor, so that a README reformatted past this parser fails instead of testing nothing.
    if len(commands) < 20:
        sys.exit(f"README.md: only {len(commands)} ./build/phongsim commands found")
    with tempfile.TemporaryDirectory(prefix="phongsim-docs.") as work:
        os.mkdir(os.path.join(work, "build"))
        os.symlink(os.path.join(build, "phongsim"), os.path.join(work, "build", "phongsim"))
        for d in ("configs", "sweeps", "rtl"):
            os.symlink(os.path.join(src, d), os.path.join(work, d))
        shutil.copy(os.path.join(src, "configs/lirp/default.toml"), os.path.join(work, "my.toml"))
        shutil.copytree(os.path.join(src, "rtl/lyon"), os.path.join(work, "my/lyon"))
        env = dict(os.environ, PHONGSIM_QUICK="1")
        before = sorted(os.walk(os.path.join(src, "configs")))
        for words in commands:
            shown = shlex.join(words)
            r = subprocess.run(words, cwd=work, env=env, stdin=subprocess.DEVNULL,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            if r.returncode != 0:
                print(f"FAIL (exit {r.returncode}): {shown}\n{r.stderr[-2000:]}")
                return 1
            print(f"ok: {shown}")
        # configs/ is the source tree's: a command writing into it (sweep search without --out)
        # would change the checkout.
        after = sorted(os.walk(os.path.join(src, "configs")))
        if after != before:
            print("FAIL: the commands changed the source tree's configs/")
            return 1
    print(f"PASS: {len(commands)} README commands")
    return 0


if __name__ == "__main__":
    sys.exit(main())
