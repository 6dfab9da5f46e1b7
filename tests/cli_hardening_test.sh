#!/usr/bin/env bash
# The hardened command line (issue 15), one named case per ctest test: outputs that never
# replace what they point at, signals, bounded work, the interface, the JSON schema.
#   tests/cli_hardening_test.sh BUILD_DIR CASE
source "$(dirname "$0")/cli_common.sh"

case "$case_name" in
  outputs)
    # Issue 15, finding 1: outputs never replace what is not a regular file. A FIFO and a symlink
    # in the temp folder first, then a device node of the test's own (never a real one: CI runs
    # as root).
    mkfifo "$tmp/fifo"
    cat "$tmp/fifo" >"$tmp/from_fifo" &
    reader=$!
    "$phongsim" cosim --config "$default" --vectors 10 --json "$tmp/fifo" >/dev/null ||
      fail "cosim --json FIFO"
    wait $reader
    [ -p "$tmp/fifo" ] || fail "the FIFO was replaced by a regular file"
    python3 -c 'import json,sys; assert json.load(open(sys.argv[1]))["command"] == "cosim"' \
      "$tmp/from_fifo" || fail "nothing came through the FIFO: $(cat "$tmp/from_fifo")"
    echo old >"$tmp/target.json"
    ln -s target.json "$tmp/link.json"
    "$phongsim" cosim --config "$default" --vectors 10 --json "$tmp/link.json" >/dev/null ||
      fail "cosim --json symlink"
    [ -L "$tmp/link.json" ] || fail "the symlink was replaced"
    grep -q '"schema": "phongsim/1"' "$tmp/target.json" || fail "the symlink's target was not written"
    # A character device: a private node like /dev/null (mknod needs root, as CI has; skipped
    # otherwise), so that a regression replaces the test's own node, never the machine's.
    if mknod "$tmp/null" c 1 3 2>/dev/null; then
      "$phongsim" cosim --config "$default" --vectors 10 --json "$tmp/null" >/dev/null ||
        fail "cosim --json to a character device"
      [ -c "$tmp/null" ] || fail "the character device was replaced by a regular file"
      ! ls "$tmp" | grep -q 'null.tmp' || fail "a temporary was left beside the device"
    fi
    # "-" is standard output: the JSON alone on stdout, the report on stderr.
    "$phongsim" cosim --config "$default" --vectors 10 --json - >"$tmp/stdout" 2>"$tmp/stderr" ||
      fail "cosim --json -"
    python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$tmp/stdout" ||
      fail "--json -: stdout is not JSON: $(cat "$tmp/stdout")"
    grep -q '^PASS' "$tmp/stderr" || fail "--json -: the report is not on stderr"
    [ ! -e ./- ] && [ ! -e "$tmp/-" ] || fail "a file named - was created"
    # /dev/stdout is a symlink to /proc/self/fd/1: the same through a link of the test's own.
    ln -s /proc/self/fd/1 "$tmp/to_stdout"
    # Captured in files, not piped to `head`: an early-closing pipe would SIGPIPE phongsim.
    "$phongsim" vectors --config "$default" --vectors 5 --out "$tmp/to_stdout" 2>/dev/null \
      >"$tmp/linked.csv" && head -1 "$tmp/linked.csv" | grep -q '^p0_x,' ||
      fail "vectors --out a link to /proc/self/fd/1 (as /dev/stdout)"
    [ -L "$tmp/to_stdout" ] || fail "the link to standard output was replaced"
    "$phongsim" vectors --config "$default" --vectors 5 --out "$tmp/v.csv" >/dev/null
    "$phongsim" eval --config "$default" --in "$tmp/v.csv" --out - 2>/dev/null >"$tmp/dash.csv" &&
      head -1 "$tmp/dash.csv" | grep -q '^p_x,p_y,p_z$' || fail "eval --out -"
    # Waveforms: .vcd is a VCD, .fst an FST, anything else refused.
    "$phongsim" cosim --config "$default" --vectors 10 --trace "$tmp/w.vcd" --trace-window 20 \
      >/dev/null || fail "--trace .vcd"
    head -1 "$tmp/w.vcd" | grep -q '^\$date' && grep -q '^\$enddefinitions' "$tmp/w.vcd" ||
      fail "not a VCD: $(head -3 "$tmp/w.vcd")"
    grep -q 'in_valid_i' "$tmp/w.vcd" || fail "the VCD has no ports"
    expect_error "--trace .*w.txt: a waveform is .fst .* or .vcd" \
      "$phongsim" cosim --config "$default" --vectors 10 --trace "$tmp/w.txt"
    # Finding 4: a render is complete or absent as a set. Re-rendering the scene replaces its
    # files (no stale images beside metrics that do not list them); a render that fails midway
    # (a file-size limit standing in for a full disk) leaves the earlier set untouched.
    "$phongsim" render --size 8 --method lyon-k2,blinn --backend float --out "$tmp/r" --quiet \
      >/dev/null || fail "render"
    "$phongsim" render --size 8 --method lyon-k2 --backend float --out "$tmp/r" --quiet \
      >/dev/null || fail "render again"
    [ ! -e "$tmp/r/shinyballs_blinn.png" ] || fail "a stale image of the previous render stayed"
    [ -s "$tmp/r/shinyballs_lyon-k2.png" ] || fail "render again: no image"
    python3 - "$tmp/r" <<'EOT' || fail "manifest: $(cat "$tmp/r/manifest.json")"
import json, os, sys
m = json.load(open(os.path.join(sys.argv[1], "manifest.json")))
files = m["sets"]["render shinyballs"]
assert sorted(files + ["manifest.json"]) == sorted(os.listdir(sys.argv[1])), (files, os.listdir(sys.argv[1]))
EOT
    cp -r "$tmp/r" "$tmp/r_before"
    (ulimit -f 12; "$phongsim" render --size 40 --method lyon-k2,blinn --backend float \
      --out "$tmp/r" --quiet) >/dev/null 2>"$tmp/err"
    rc=$?
    [ $rc -eq 2 ] || fail "a render on a full disk: exit $rc ($(cat "$tmp/err"))"
    grep -q "File too large" "$tmp/err" || fail "full disk: $(cat "$tmp/err")"
    diff -r "$tmp/r_before" "$tmp/r" || fail "a failed render changed the earlier set"
    (ulimit -f 12; "$phongsim" render --size 40 --backend float --method lyon-k2 \
      --out "$tmp/fresh" --quiet) >/dev/null 2>&1
    [ ! -e "$tmp/fresh" ] || fail "a failed render left $(ls "$tmp/fresh")"
    # A sweep plan is complete or absent: jobs.txt failing after the point files leaves nothing.
    (ulimit -f 1; "$phongsim" sweep plan "$src/sweeps/lirp-small.toml" --out "$tmp/plan") \
      >/dev/null 2>"$tmp/err"
    [ $? -eq 2 ] || fail "sweep plan on a full disk: $(cat "$tmp/err")"
    [ ! -e "$tmp/plan" ] || fail "a half-planned directory: $(find "$tmp/plan")"
    ! ls "$tmp" | grep -q 'phongsim-tmp-' || fail "temporaries left: $(ls "$tmp")"
    ;;

  signals)
    # Finding 3: SIGINT and SIGTERM remove the temporaries and exit 130/143; temporaries of dead
    # processes are swept on start.
    mkdir "$tmp/t" "$tmp/cache"
    TMPDIR="$tmp/t" python3 - "$phongsim" "$tmp" "$default" <<'EOT' || fail "signals"
import os, signal, subprocess, sys, time
phongsim, tmp, default = sys.argv[1:4]
out = os.path.join(tmp, "out")
os.mkdir(out)
for sig, status in ((signal.SIGTERM, 143), (signal.SIGINT, 130)):
    p = subprocess.Popen([phongsim, "cosim", "lyon", "--vectors", "100000000", "--json",
                          os.path.join(out, "r.json"), "--trace", os.path.join(out, "w.vcd")],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.time() + 30
    while time.time() < deadline and not any(".phongsim-tmp-" in f for f in os.listdir(out)):
        time.sleep(0.1)
    assert os.listdir(out), "no temporary appeared"
    assert os.listdir(os.environ["TMPDIR"]), "no temporary in TMPDIR"
    p.send_signal(sig)
    assert p.wait(timeout=30) == status, (sig, p.returncode, p.stderr.read())
    assert os.listdir(out) == [], os.listdir(out)
    assert os.listdir(os.environ["TMPDIR"]) == [], os.listdir(os.environ["TMPDIR"])

# Synthesis (Yosys in a process group of its own): its temporary folder goes, Yosys stops.
cfg = os.path.join(tmp, "odd.toml")
open(cfg, "w").write(open(default).read().replace('p = "S1.10"', 'p = "S1.7"'))
env = dict(os.environ, PHONGSIM_CACHE=os.path.join(tmp, "cache"))
p = subprocess.Popen([phongsim, "synth", "--config", cfg], env=env, stdout=subprocess.DEVNULL,
                     stderr=subprocess.DEVNULL)
deadline = time.time() + 30
def synth_dirs():
    return [f for f in os.listdir(os.environ["TMPDIR"]) if f.startswith("phongsim-synth-")]
while time.time() < deadline and not synth_dirs():
    time.sleep(0.05)
assert synth_dirs(), "synthesis made no temporary folder"
time.sleep(0.5)
p.send_signal(signal.SIGTERM)
assert p.wait(timeout=30) == 143, p.returncode
assert synth_dirs() == [], synth_dirs()
time.sleep(0.2)
for pid in os.listdir("/proc"):
    try:
        cmd = open(f"/proc/{pid}/cmdline", "rb").read()
    except OSError:
        continue
    assert os.environ["TMPDIR"].encode() not in cmd or pid == str(os.getpid()), cmd

# Stale temporaries (their owner gone: their lock free) go at the next start; a live one stays
# (locked, as a phongsim process in another PID namespace would hold it), and so does anything
# not named as phongsim names its temporaries.
import fcntl
stale = [os.path.join(os.environ["TMPDIR"], "phongsim-synth-abcdef"),
         os.path.join(os.environ["TMPDIR"], "phongsim-out-abcdef"),
         os.path.join(tmp, "cache", "build.phongsim-tmp-abcdef"),
         os.path.join(tmp, "cache", "synth", "0123.json.phongsim-tmp-abcdef"),
         os.path.join(out, "r.json.phongsim-tmp-abcdef")]
live = [os.path.join(os.environ["TMPDIR"], "phongsim-synth-live01"),
        os.path.join(tmp, "cache", "build.phongsim-tmp-live01")]
kept = live + [os.path.join(os.environ["TMPDIR"], "phongsim-cli.not-ours"),
               os.path.join(out, "r.json.tmp.12345"),
               os.path.join(out, "r.json.phongsim-tmp-abc")]
os.makedirs(os.path.join(tmp, "cache", "synth"), exist_ok=True)
for p_ in stale + kept:
    if "json" in os.path.basename(p_):
        open(p_, "w").write("{")
    else:
        os.makedirs(p_)
locks = []
for p_ in live:
    fd = os.open(p_, os.O_RDONLY)
    fcntl.flock(fd, fcntl.LOCK_EX)
    locks.append(fd)
time.sleep(2.5)  # older than the moment between a temporary's creation and its lock
subprocess.run([phongsim, "cosim", "--config", default, "--vectors", "10", "--json",
                os.path.join(out, "r.json")], env=env, check=True, stdout=subprocess.DEVNULL)
assert [p_ for p_ in stale if os.path.exists(p_)] == [], [p_ for p_ in stale if os.path.exists(p_)]
assert all(os.path.exists(p_) for p_ in kept), [p_ for p_ in kept if not os.path.exists(p_)]
EOT
    ;;

  bounded)
    # Finding 5: eval and vectors stream (memory does not grow with the number of vectors); a
    # sweep grid is checked before any work; running out of memory is reported as such.
    python3 - "$phongsim" "$tmp" "$src" <<'EOT' || fail "bounded"
import os, resource, subprocess, sys, time
phongsim, tmp, src = sys.argv[1:4]
quad = os.path.join(src, "configs/quad/default.toml")
lyon = os.path.join(src, "configs/lyon/default.toml")
def peak_kb(argv):
    # A fresh Python child per run, so RUSAGE_CHILDREN is this run's peak alone.
    code = ("import resource,subprocess,sys; subprocess.run(sys.argv[1:], check=True, "
            "stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL); "
            "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    return int(subprocess.run([sys.executable, "-c", code] + argv, check=True,
                              capture_output=True, text=True).stdout)
# The quadratic unit's directed triangle 4 covers 523776 pixels: 1 and 8 copies of it.
subprocess.run([phongsim, "vectors", "--config", quad, "--vectors", "0", "--out",
                os.path.join(tmp, "d.csv")], check=True, stdout=subprocess.DEVNULL)
lines = open(os.path.join(tmp, "d.csv")).read().splitlines()
big = lines[5]  # line 6 of the file: directed triangle 4
for n in (1, 8):
    open(os.path.join(tmp, f"big{n}.csv"), "w").write(lines[0] + "\n" + (big + "\n") * n)
one = peak_kb([phongsim, "eval", "--config", quad, "--in", os.path.join(tmp, "big1.csv"),
               "--out", os.path.join(tmp, "o1.csv")])
eight = peak_kb([phongsim, "eval", "--config", quad, "--in", os.path.join(tmp, "big8.csv"),
                 "--out", os.path.join(tmp, "o8.csv")])
assert sum(1 for _ in open(os.path.join(tmp, "o8.csv"))) == 8 * 523776 + 1
print("eval peak RSS: 1 triangle", one, "kB, 8 triangles", eight, "kB")
assert eight - one < 16 * 1024, (one, eight)  # the outputs alone are 160 MB as int64
os.remove(os.path.join(tmp, "o8.csv"))
small = peak_kb([phongsim, "vectors", "--config", lyon, "--vectors", "10000", "--out",
                 os.path.join(tmp, "v1.csv")])
large = peak_kb([phongsim, "vectors", "--config", lyon, "--vectors", "1000000", "--out",
                 os.path.join(tmp, "v2.csv")])
print("vectors peak RSS: 10^4", small, "kB, 10^6", large, "kB")
assert large - small < 16 * 1024, (small, large)  # the CSV is 60 MB
os.remove(os.path.join(tmp, "v2.csv"))
# A grid of 10^9 values is refused at once (it used to run out of memory after 55 s).
sweep = os.path.join(tmp, "huge.toml")
open(sweep, "w").write('base = "configs/lirp/default.toml"\n[axes]\n'
                       '"format.p" = { frac = [0, 1000000000] }\n')
start = time.time()
r = subprocess.run([phongsim, "sweep", "run", sweep, "--out", os.path.join(tmp, "o")],
                   capture_output=True, text=True)
assert r.returncode == 2 and "outside 0..62" in r.stderr and time.time() - start < 5, r
# Out of memory: the benchmark's vectors under a 1 GB address-space limit.
r = subprocess.run(["bash", "-c", 'ulimit -v 1000000; exec "$0" bench lyon --vectors 10000000',
                    phongsim], capture_output=True, text=True)
assert r.returncode == 2 and r.stderr.count("\n") == 1 and "out of memory" in r.stderr, r
EOT
    ;;

  interface)
    # Finding 8: --version, unknown commands named, a help screen per sweep action, one flag per
    # concept, progress as --progress says (a line on a terminal, heartbeats in a log).
    "$phongsim" --version >"$tmp/v" || fail "--version"
    grep -qE '^phongsim [0-9]+\.[0-9]+ \(.+\)$' "$tmp/v" && grep -q 'Verilator' "$tmp/v" &&
      grep -q 'Yosys' "$tmp/v" || fail "--version: $(cat "$tmp/v")"
    expect_error "unknown command 'rendre' \(commands: .*render" "$phongsim" rendre
    expect_error "unknown sweep action 'rnu' \(actions: run, plan, merge, point, search" \
      "$phongsim" sweep rnu x.toml
    for action in run plan merge point search; do
      "$phongsim" sweep $action --help >"$tmp/help_$action" 2>&1 ||
        fail "sweep $action --help"
      grep -q "Usage: .*sweep $action" "$tmp/help_$action" || fail "$(cat "$tmp/help_$action")"
    done
    grep -q -- '--index' "$tmp/help_point" && ! grep -q -- '--index' "$tmp/help_run" &&
      grep -q -- '--no-verify' "$tmp/help_search" || fail "the actions share one help screen"
    # bench: --size is the render size everywhere; --radius stays as its older name.
    "$phongsim" bench render --size 6 --json "$tmp/size.json" >/dev/null || fail "bench --size"
    "$phongsim" bench render --radius 6 --json "$tmp/radius.json" >/dev/null || fail "bench --radius"
    python3 - "$tmp/size.json" "$tmp/radius.json" <<'EOT' || fail "--size and --radius differ"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert a["size"] == b["size"] == 6 and a["width"] == b["width"] == 37, (a, b)
EOT
    # Today's sweep command lines still work, --write included.
    "$phongsim" sweep search "$src/sweeps/lirp-search.toml" --write "$tmp/found.toml" --no-verify \
      >/dev/null || fail "sweep search --write"
    [ -s "$tmp/found.toml" ] || fail "--write wrote nothing"
    # Progress (--progress auto, the default): on a terminal (a pseudo-terminal here), a line
    # updating in place once a run takes over PHONGSIM_PROGRESS_AFTER seconds (0 here, so the
    # check does not depend on the machine's speed).
    progress=("$phongsim" cosim lyon --vectors 300000 --no-directed)
    PHONGSIM_PROGRESS_AFTER=0 "$src/tests/on_terminal.py" "$tmp/pty" "${progress[@]}" ||
      fail "progress: $(cat "$tmp/pty")"
    grep -qF $'\r\033[K  cosim lyon/default' "$tmp/pty" && grep -qF ' s)' "$tmp/pty" ||
      fail "no progress line on a terminal: $(tail -c 300 "$tmp/pty")"
    # When stderr is not a terminal (a CI log), plain heartbeat lines instead, at most one every
    # PHONGSIM_PROGRESS_EVERY seconds (0 here: one an update): no \r, no escape codes; stdout
    # stays the report alone.
    PHONGSIM_PROGRESS_AFTER=0 PHONGSIM_PROGRESS_EVERY=0 "${progress[@]}" >"$tmp/report" \
      2>"$tmp/not_tty" || fail "progress: $(cat "$tmp/not_tty")"
    grep -qE '^phongsim: cosim lyon/default .*: [0-9]+ of 300000, [0-9]+s$' "$tmp/not_tty" ||
      fail "no heartbeat when stderr is not a terminal: $(head -c 300 "$tmp/not_tty")"
    ! grep -q $'[\r\033]' "$tmp/not_tty" || fail "a heartbeat line with \\r or an escape code"
    # (Helper programs it runs, such as verilator, may add lines of their own:
    # "phongsim: verilator: 0s".)
    [ "$(grep -cv '^phongsim: ' "$tmp/not_tty")" -eq 0 ] &&
      [ "$(wc -l <"$tmp/report")" -eq 1 ] && grep -q '^PASS lyon/default' "$tmp/report" ||
      fail "heartbeat: stderr $(head -c 300 "$tmp/not_tty"), stdout $(cat "$tmp/report")"
    # The default interval: one line at most in a run this short (the first, at once here).
    PHONGSIM_PROGRESS_AFTER=0 "${progress[@]}" >/dev/null 2>"$tmp/not_tty" ||
      fail "progress: $(cat "$tmp/not_tty")"
    [ "$(grep -c '^phongsim: cosim' "$tmp/not_tty")" -le 1 ] ||
      fail "heartbeat flood: $(cat "$tmp/not_tty")"
    # Helper programs (Yosys here) the same way.
    PHONGSIM_PROGRESS_AFTER=0 PHONGSIM_PROGRESS_EVERY=0 "$phongsim" synth --check \
      --config "$default" >/dev/null 2>"$tmp/tool" || fail "progress: $(cat "$tmp/tool")"
    grep -qE '^phongsim: yosys: [0-9]+s$' "$tmp/tool" ||
      fail "no tool heartbeat: $(cat "$tmp/tool")"
    # --progress never: nothing, terminal or not; always: the terminal line, even into a file.
    PHONGSIM_PROGRESS_AFTER=0 PHONGSIM_PROGRESS_EVERY=0 "${progress[@]}" --progress never \
      >/dev/null 2>"$tmp/never" || fail "progress: $(cat "$tmp/never")"
    [ ! -s "$tmp/never" ] || fail "--progress never printed: $(head -c 300 "$tmp/never")"
    PHONGSIM_PROGRESS_AFTER=0 "$src/tests/on_terminal.py" "$tmp/pty" "${progress[@]}" \
      --progress never || fail "progress: $(cat "$tmp/pty")"
    ! grep -q $'\r\033' "$tmp/pty" ||
      fail "--progress never on a terminal: $(tail -c 300 "$tmp/pty")"
    PHONGSIM_PROGRESS_AFTER=0 "${progress[@]}" --progress=always >/dev/null 2>"$tmp/always" ||
      fail "progress: $(cat "$tmp/always")"
    grep -qF $'\r\033[K  cosim lyon/default' "$tmp/always" ||
      fail "--progress=always: $(head -c 300 "$tmp/always")"
    expect_error "--progress: sometimes not in" "$phongsim" list --progress sometimes
    PHONGSIM_PROGRESS_EVERY=soon "$phongsim" list >/dev/null 2>"$tmp/err" && fail "EVERY=soon"
    grep -q "PHONGSIM_PROGRESS_EVERY='soon' is not a number of seconds" "$tmp/err" ||
      fail "PHONGSIM_PROGRESS_EVERY=soon: $(cat "$tmp/err")"
    ;;

  json)
    # Finding 9: every command that prints results writes the one versioned schema.
    python3 - "$phongsim" "$tmp" "$src" <<'EOT' || fail "json"
import csv, json, os, re, subprocess, sys
phongsim, tmp, src = sys.argv[1:4]
default = os.path.join(src, "configs/lirp/default.toml")
# docs/json.md, read as data: {(command, kind): {path: keys}}. Every document below is compared
# with it (the keys documented, no others), and every documented table must have been compared.
schema, where, path = {}, None, ""
for line in open(os.path.join(src, "docs/json.md"), encoding="utf-8"):
    if m := re.match(r"## `([^`]+)`(?: — kind `([^`]+)`)?", line):
        where, path = (m[1], m[2]), ""
    elif m := re.match(r"### `([^`]+)`", line):
        path = m[1]
    elif (m := re.match(r"\| `([^`]+)` \|", line)) and where:
        schema.setdefault(where, {}).setdefault(path, []).append(m[1])
assert len(schema) >= 10, schema
compared = set()
def objects(j, path):
    found = [j]
    for part in path.split(".") if path else []:
        name, each = part.removesuffix("[]"), part.endswith("[]")
        found = [o[name] for o in found if o.get(name) is not None]
        if each:
            found = [x for o in found for x in o]
    return found
def against_docs(j):
    where = (j["command"], j.get("kind"))
    assert where in schema, f"docs/json.md has no section for {where}"
    for path, keys in schema[where].items():
        for o in objects(j, path):
            assert list(o) == keys, (where, path, "documented:", keys, "written:", list(o))
            compared.add((where, path))
def doc(*args):
    r = subprocess.run([phongsim, *args, "--json", "-"], capture_output=True, text=True)
    assert r.returncode == 0, (args, r.stderr)
    j = json.loads(r.stdout)
    assert j["schema"] == "phongsim/1" and list(j)[:2] == ["schema", "command"], j
    against_docs(j)
    return j
j = doc("lint", "--config", default)
assert j["clean"] is True and j["files"] > 0, j
j = doc("contract", "lirp")
assert [p["name"] for p in j["ports"]][:2] == ["clk_i", "rst_ni"] and j["top"] == "lirp_unit", j
j = doc("build-rtl", "--config", default)
assert j["plugins"][0]["pipeline"] == "lirp", j
j = doc("list")
assert [p["name"] for p in j["pipelines"]] == ["lirp", "lyon", "kb", "quad", "shade_lyon", "shade_quad", "shade_kb"], j
assert any(c["path"] == "configs/lirp/default.toml" for c in j["pipelines"][0]["configs"]), j
j = doc("analyze", "lirp", "--samples", "1000")
t = j["tables"][0]
assert t["columns"] == ["config", "p", "a", "out", "max_lsb", "mean_lsb"], t
assert any(r["config"] == "default" and 1 < r["max_lsb"] < 2 for r in t["rows"]), t
j = doc("analyze", "quad", "--samples", "5000")
assert {t["title"][:5] for t in j["tables"]} == {"Drift", "Guard", "Outpu", "Outsi"}, j
t = j["tables"][-1]
assert any(r["config"] == "narrow_quad" and r["clause"] == "box within the guard bits"
           and r["channels_off"] > 0 for r in t["rows"]), t
j = doc("bench", "lirp", "--vectors", "1000")
assert j["kind"] == "pipeline" and j["vectors"] == 1000 and j["rtl"]["cycles_per_s"] > 0, j
j = doc("bench", "render", "--size", "6")
assert j["kind"] == "render" and set(j["object_pixels_per_s"]) == {"float", "model", "rtl"}, j
j = doc("bench", "methods", "--scene", "triangle", "--rounds", "1", "--size", "32")
assert j["kind"] == "methods" and j["methods"][0]["method"] == "gouraud", j
j = doc("render", "--size", "8", "--method", "lyon-k2", "--backend", "float", "--out",
        os.path.join(tmp, "r"), "--quiet")
m = j["methods"][0]
assert [r["region"] for r in m["regions"]] == j["regions"] == ["n=1", "n=4", "n=16", "n=64", "n=256"], j
assert all(0 < r["colour_correctness"] <= 1 for r in m["regions"]), m
assert len(j["files"]) == 7 and all(os.path.exists(f) for f in j["files"]), j
j = doc("study", "--scenes", "3", "--size", "32", "--jobs", "2", "--out", os.path.join(tmp, "st"))
# study.csv, study.md, study.png, three scene files and the glancing variant of scene 2, the one
# closed mesh among them (scenes 0 and 1 are triangles).
glancing = [f for f in j["files"] if f.endswith("-glancing.toml")]
assert [os.path.basename(f) for f in glancing] == ["scene2-glancing.toml"], j
assert j["scenes"] == 3 and len(j["files"]) == 7 and all(os.path.exists(f) for f in j["files"]), j
for c in j["claims"]:
    assert 0 <= c["holds"] <= c["scenes"] <= 3 and c["ci_low"] <= c["holds_fraction"] <= c["ci_high"], c
j = doc("synth", "--config", default)
assert j["generic"]["cells"] > 0 and j["ice40"] is None, j
# Logic depth: the deepest register or output leads the table, and is the design's depth.
assert j["generic"]["depth"] > 0 and j["stages"][0]["levels"] == j["generic"]["depth"], j
assert all(a["levels"] >= b["levels"] for a, b in zip(j["stages"], j["stages"][1:])), j
assert {s["to"] for s in j["stages"] if s["output"]} >= {"out_p_o", "out_valid_o"}, j
j1 = j
j = doc("synth", "lirp", "--all")
assert j["kind"] == "all" and [c["config"] for c in j["configs"]][:2] == ["colour8", "default"], j
assert all(c["generic"]["depth"] > 0 for c in j["configs"]), j
assert j["configs"][1]["stages"] == j1["stages"], (j["configs"][1], j1)
j = doc("sweep", "search", os.path.join(src, "sweeps/lirp-search.toml"), "--no-verify",
        "--out", os.path.join(tmp, "found.toml"))
assert j["formats"] == {"p": "S1.8", "a": "1.9"} and j["bits_saved"] == 3, j
j = doc("cosim", "--config", default, "--vectors", "100", "--backpressure", "none,random:0.5")
assert len(j["runs"]) == 2 and j["runs"][1]["throughput"] == 1.0, j
for run in j["runs"]:  # every accepted vector counted once against the input contract
    assert run["rtl"]["source"] == "builtin" and len(run["rtl"]["key"]) == 64, run["rtl"]
    assert run["in_contract"] + run["out_of_contract"] == run["vectors"], run
    assert sum(c["out_of_contract"] for c in run["contract_clauses"]) == run["out_of_contract"], run
vectors = os.path.join(tmp, "vectors.csv")
subprocess.run([phongsim, "vectors", "--config", default, "--vectors", "50", "--out", vectors],
               check=True, capture_output=True)
j = doc("eval", "--config", default, "--in", vectors, "--out", os.path.join(tmp, "eval.csv"))
assert j["vectors"] == j["outputs"] == j["in_contract"] + j["out_of_contract"] > 50, j
assert [c["clause"] for c in j["contract_clauses"]][0] == "a in [0, 1]", j
# A failing run (a deadlock: the sink stalls longer than the timeout) carries its failure as
# fields; throughput and latency were never measured, so they are null, not 0.
r = subprocess.run([phongsim, "cosim", "--config", default, "--vectors", "100", "--backpressure",
                    "long:500:1", "--timeout", "50", "--json", "-"], capture_output=True, text=True)
assert r.returncode == 1, r
against_docs(json.loads(r.stdout))
run = json.loads(r.stdout)["runs"][0]
assert run["passed"] is False and run["throughput"] is None and run["latency"] is None, run
f = run["failure"]
assert f["kind"] == "deadlock" and f["cycle"] > 0 and f["vector_index"] is not None, f
assert "DEADLOCK" in f["report"] and "reproduce:" in f["report"], f
# sweep.csv: pipeline and Pareto columns; empty cells for what was not computed (generic
# synthesis only: no iCE40 numbers, no ice40_fits = 1).
sweep = os.path.join(tmp, "generic.toml")
open(sweep, "w").write('base = "configs/lirp/default.toml"\n[synth]\ngeneric = true\n')
subprocess.run([phongsim, "sweep", "run", sweep, "--out", os.path.join(tmp, "s")], check=True,
               capture_output=True)
rows = list(csv.DictReader(open(os.path.join(tmp, "s", "sweep.csv"))))
assert len(rows) == 1, rows
row = rows[0]
assert row["pipeline"] == "lirp" and row["base"] == "lirp/default" and row["pareto"] == "1", row
assert int(row["cells"]) > 0 and int(row["transistors"]) > 0, row
assert int(row["depth"]) == j1["generic"]["depth"], (row, j1["generic"])
assert all(row[k] == "" for k in ("lut4", "carry", "mac16", "ff", "ice40_fits", "fmax_mhz")), row
assert "-1" not in open(os.path.join(tmp, "s", "sweep.csv")).read()
missing = {(w, p) for w, paths in schema.items() for p in paths} - compared
assert not missing, f"documented in docs/json.md but never compared: {sorted(missing)}"
EOT
    ;;

  cosim-failure-json)
    # A failing co-simulation's JSON carries the first mismatch as fields (config, seed, vector
    # index, cycle, per-field expected and got), and the text report is still printed. The RTL:
    # a copy of rtl/ with the rounding mutant of sim/pipelines/lirp.cpp (Verilated once; the
    # build's cache keeps it).
    cp -r "$src/rtl" "$tmp/rtl"
    sed -i 's/assign bias = Half - IntW.(1) + /assign bias = Half + /' "$tmp/rtl/common/fx_resize.sv"
    ! cmp -s "$src/rtl/common/fx_resize.sv" "$tmp/rtl/common/fx_resize.sv" || fail "no mutant"
    "$phongsim" cosim lirp --rtl "$tmp/rtl/common" "$tmp/rtl/lirp" --vectors 20000 --seed 7 \
      --backpressure random:0.5 --json "$tmp/fail.json" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    [ $rc -eq 1 ] || fail "expected exit 1, got $rc: $(cat "$tmp/err")"
    grep -q '^MISMATCH at cycle' "$tmp/out" && grep -q '^FAIL lirp/default' "$tmp/out" ||
      fail "no text report: $(cat "$tmp/out")"
    python3 - "$tmp/fail.json" "$tmp/out" <<'EOT' || fail "failure JSON: $(cat "$tmp/fail.json")"
import json, re, sys
j = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
assert j["passed"] is False
r = j["runs"][0]
assert r["config"] == "default" and r["seed"] == 7 and r["passed"] is False, r
f = r["failure"]
m = re.search(r"MISMATCH at cycle (\d+), vector (\d+) \(output (\d+) of (\d+)", text)
assert f["kind"] == "mismatch" and f["cycle"] == int(m[1]) and f["vector_index"] == int(m[2]), f
assert f["output_index"] == int(m[3]) - 1 and f["outputs_of_vector"] == int(m[4]), f
assert [x["field"] for x in f["inputs"]] == ["p0_x", "p0_y", "p0_z", "p1_x", "p1_y", "p1_z", "a"], f
outs = f["outputs"]
assert [o["field"] for o in outs] == ["p_x", "p_y", "p_z"], outs
assert any(o["differs"] for o in outs), outs
for o in outs:
    assert o["differs"] == (o["expected"]["raw"] != o["got"]["raw"]), o
    assert o["expected"]["format"] == "S1.10", o
assert f["report"].startswith("MISMATCH") and r["throughput"] is None, r
EOT
    ;;

  *)
    fail "unknown case $case_name"
    ;;
esac
