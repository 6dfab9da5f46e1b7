#!/usr/bin/env python3
"""Runs every `./build/phongsim ...` command shown in README.md and docs/*.md, as written,
so the documentation cannot drift from the program.

    tests/docs_test.py BUILD_DIR SOURCE_DIR

Each document's commands run in order in a scratch folder of their own, laid out like a
checkout: build/phongsim is the build's program, configs/, sweeps/, rtl/, data/ and examples/ are
the source tree's; the documents' placeholders (`<your.toml>`, words in angle brackets a reader
replaces with their own files) stand for files of the tree (PLACEHOLDERS below: README's
<your.toml> is a configuration, render.md's <your-scene.toml> a scene), and a placeholder the
table does not know fails the test. Every command runs with PHONGSIM_QUICK=1
(docs/cosim.md: the same command at a reduced size) and must exit 0, or the status EXPECTED
says (a documented failure); running in order means a command that needs a file an earlier one
writes (eval after vectors) fails if the order is wrong. Commands written with placeholders
(`phongsim sweep run SWEEP.toml --out DIR`) are not `./build/phongsim` lines and are not run.
Exits 1 on the first failure, naming the document, the command and its stderr.
"""
import os
import shlex
import subprocess
import sys
import tempfile


def readme_commands(path):
    """A document's indented code lines starting with ./build/phongsim (continuations joined,
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


# Placeholders per document: the word a reader replaces -> a file of the tree that stands for it.
PLACEHOLDERS = {
    "README.md": {"<your.toml>": "configs/lirp/default.toml", "<your/rtl>": "rtl/lyon"},
    "docs/render.md": {"<your-scene.toml>": "data/scenes/kbsphere512-diffuse.toml"},
}
# Documented failures: (document, a word of the command) -> exit status.
EXPECTED = {("docs/your-rtl.md", "my_lirp_wrong"): 1, ("docs/your-rtl.md", "MY_LIRP_TIES_UP=1"): 1,
            ("docs/your-rtl.md", "MY_LYON_BUG_G2"): 1}
LINKED = ("configs", "sweeps", "rtl", "data", "examples")


def run_document(build, src, name, commands):
    with tempfile.TemporaryDirectory(prefix="phongsim-docs.") as work:
        os.mkdir(os.path.join(work, "build"))
        os.symlink(os.path.join(build, "phongsim"), os.path.join(work, "build", "phongsim"))
        for d in LINKED:
            os.symlink(os.path.join(src, d), os.path.join(work, d))
        env = dict(os.environ, PHONGSIM_QUICK="1")
        placeholders = PLACEHOLDERS.get(name, {})
        for written in commands:
            shown = shlex.join(written)
            unknown = [w for w in written
                       if w.startswith("<") and w.endswith(">") and w not in placeholders]
            if unknown:
                print(f"FAIL {name}: placeholder {unknown[0]} is not in PLACEHOLDERS: {shown}")
                return False
            words = [placeholders.get(w, w) for w in written]
            want = next((status for (doc, word), status in EXPECTED.items()
                         if doc == name and word in words), 0)
            r = subprocess.run(words, cwd=work, env=env, stdin=subprocess.DEVNULL,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            if r.returncode != want:
                print(f"FAIL {name} (exit {r.returncode}, documented {want}): {shown}\n"
                      f"{r.stderr[-2000:]}")
                return False
            print(f"ok {name}: {shown}")
    return True


def main():
    build, src = (os.path.abspath(a) for a in sys.argv[1:3])
    documents = ["README.md"] + sorted(
        os.path.join("docs", f) for f in os.listdir(os.path.join(src, "docs")) if f.endswith(".md"))
    commands = {d: readme_commands(os.path.join(src, d)) for d in documents}
    total = sum(len(c) for c in commands.values())
    # A floor, so that documents reformatted past this parser fail instead of testing nothing.
    if len(commands["README.md"]) < 20 or total < 30:
        sys.exit(f"only {len(commands['README.md'])} README and {total} commands in all found")
    before = sorted(os.walk(os.path.join(src, "configs")))
    for d in documents:
        if commands[d] and not run_document(build, src, d, commands[d]):
            return 1
    # configs/ is the source tree's: a command writing into it (sweep search without --out)
    # would change the checkout.
    if sorted(os.walk(os.path.join(src, "configs"))) != before:
        print("FAIL: the commands changed the source tree's configs/")
        return 1
    print(f"PASS: {total} documented commands")
    return 0


if __name__ == "__main__":
    sys.exit(main())
