#!/usr/bin/env bash
# Never a false PASS (issue 39), tried as an adversary would: each case is a way a wrong design
# once got exit 0 and PASS, or a user got stuck; each now ends in exit 1 (the design is wrong, and
# that is the verdict) or exit 2 (refused with one line), never 0. The designs are
# examples/your-rtl/my_lirp.sv (a LIRP written apart from rtl/) and mutants of it made here.
#   tests/adversarial_test.sh BUILD_DIR CASE
# CASE: edit-during-build, long-sequence, long-runs, include, flags, moddup, late-output,
# outputs-are-inputs, nothing-to-check, damaged-cache, shared-cache, small.
source "$(dirname "$0")/cli_common.sh"

good="$src/examples/your-rtl/my_lirp.sv"
# A mutant of my_lirp.sv: `mutant FILE PYTHON-EXPRESSION-OF-s` writes FILE from my_lirp.sv.
mutant() {
  python3 - "$good" "$1" "$2" <<'EOT' || fail "mutant $1"
import sys
s = open(sys.argv[1]).read()
t = eval(sys.argv[3])
assert t != s, "the mutation changed nothing"
open(sys.argv[2], "w").write(t)
EOT
}
# The component output assignment, where the mutants put their bugs.
out_assign='    assign out_p_o[c*OW+:OW] = p_q;'
# A cache of this test's own (so that nothing an earlier run built is found), with the build's
# Verilator runtime library copied in.
private_cache() {
  export PHONGSIM_CACHE="$tmp/cache"
  mkdir -p "$PHONGSIM_CACHE"
  cp -r "$build/rtl-cache"/runtime-* "$PHONGSIM_CACHE/"
}
# expect_status STATUS CMD...: the exit status is STATUS; the output goes to $tmp/run.
expect_status() {
  local want=$1
  shift
  "$@" >"$tmp/run" 2>&1
  local rc=$?
  [ $rc -eq "$want" ] || fail "expected exit $want, got $rc from: $* ($(tail -5 "$tmp/run"))"
}

case "$case_name" in
  edit-during-build)
    # 1. A file saved while Verilator reads it. The run hashes W (wrong: ties round up), then,
    #    while Verilator runs on it, the file becomes C (correct). Never stored under W's key:
    #    the build is refused (exit 2) or, had Verilator read W before the save, W fails (1).
    #    Afterwards W never passes, with or without --no-build, and C passes. Then the same with
    #    the file saved and reverted (W, C, W) during the build.
    private_cache
    mkdir "$tmp/d"
    mutant "$tmp/wrong.sv" 's.replace("parameter bit TiesUp      = 1\x27b0", "parameter bit TiesUp      = 1\x27b1")'
    for round in save save-and-revert; do
      cp "$tmp/wrong.sv" "$tmp/d/my_lirp.sv"
      echo "// $round" >>"$tmp/d/my_lirp.sv"  # new content: not cached by an earlier round
      python3 - "$phongsim" "$tmp/d/my_lirp.sv" "$good" "$round" <<'EOT' || fail "$round"
import os, subprocess, sys, time
phongsim, target, good, round_ = sys.argv[1:5]
wrong = open(target).read()
p = subprocess.Popen([phongsim, "cosim", "lirp", "--rtl", target, "--top", "my_lirp",
                      "--vectors", "2000"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
edited = False
while p.poll() is None and not edited:
    for pid in os.listdir("/proc"):
        try:
            cmd = open(f"/proc/{pid}/cmdline", "rb").read()
        except OSError:
            continue
        # The build's Verilator run (phongsim's check before it has no --make).
        if b"verilator_bin" in cmd and b"--make" in cmd and target.encode() in cmd:
            open(target, "w").write(open(good).read())
            if round_ == "save-and-revert":
                time.sleep(0.01)
                open(target, "w").write(wrong)
            edited = True
            break
    time.sleep(0.002)
out = p.communicate()[0].decode()
print(out)
assert edited, "the build's Verilator run was never seen"
assert p.returncode in (1, 2), p.returncode
if p.returncode == 2:
    assert "changed while lirp was being built" in out, out
else:
    assert out.count("\nFAIL lirp/default") + out.startswith("FAIL") == 1, out
EOT
      [ $round = save ] || { echo "ok: $round"; continue; }  # the follow-up once is enough
      # The file as the run hashed it (W) never passes; the correct one does.
      cp "$tmp/wrong.sv" "$tmp/d/my_lirp.sv"
      echo "// $round" >>"$tmp/d/my_lirp.sv"
      "$phongsim" cosim lirp --rtl "$tmp/d/my_lirp.sv" --top my_lirp --vectors 2000 --no-build \
        >"$tmp/run" 2>&1
      rc=$?
      [ $rc -eq 1 ] || [ $rc -eq 2 ] || fail "$round: W with --no-build: exit $rc: $(cat "$tmp/run")"
      expect_status 1 "$phongsim" cosim lirp --rtl "$tmp/d/my_lirp.sv" --top my_lirp --vectors 2000
      cp "$good" "$tmp/d/my_lirp.sv"
      expect_status 0 "$phongsim" cosim lirp --rtl "$tmp/d/my_lirp.sv" --top my_lirp --vectors 2000
      echo "ok: $round"
    done
    ;;

  long-sequence)
    # 2. A design that goes wrong at its 70,000th output since reset (a 17-bit counter): the
    #    default run gives the whole stream to one DUT and fails there; with --jobs 16 each DUT
    #    sees 1/16 of the stream, and the PASS says so (the longest sequence since reset).
    mutant "$tmp/wrap.sv" "s.replace('''$out_assign''', '''    assign out_p_o[c*OW+:OW] = p_q ^ OW'(taken_q == 17'd69999);''').replace('''  logic [3*PW-1:0] p0_q, p1_q;''', '''  logic [16:0] taken_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) taken_q <= '0;
    else if (out_valid_o && out_ready_i) taken_q <= taken_q + 17'd1;
  end
  logic [3*PW-1:0] p0_q, p1_q;''')"
    expect_status 1 "$phongsim" cosim lirp --rtl "$tmp/wrap.sv" --top my_lirp --json "$tmp/r.json"
    grep -q "MISMATCH at cycle .*, vector 69999 " "$tmp/run" || fail "not at vector 69999: $(cat "$tmp/run")"
    python3 -c 'import json,sys; r=json.load(open(sys.argv[1]))["runs"][0]; assert r["duts"] == 1 and r["longest_since_reset"]["vectors"] >= 70000, r' "$tmp/r.json" ||
      fail "JSON: $(cat "$tmp/r.json")"
    expect_status 0 "$phongsim" cosim lirp --rtl "$tmp/wrap.sv" --top my_lirp --jobs 16
    grep -qE "^PASS .*; longest since reset 6[0-9]{4} vectors, 6[0-9]{4} outputs \(16 DUTs\)" "$tmp/run" ||
      fail "the split run does not state its longest sequence: $(cat "$tmp/run")"
    echo "ok: $(grep -o 'longest since reset [^;]*' "$tmp/run")"
    ;;

  long-runs)
    # 2. One DUT sees a long stream in every pipeline: at least 2^20 vectors since reset for the
    #    pipelines of one output per vector (LIRP, Lyon), 2^17 for the others (span programs,
    #    triangles), and the verdict says so.
    for p in $("$phongsim" list --json - | python3 -c 'import json,sys; print(" ".join(p["name"] for p in json.load(sys.stdin)["pipelines"]))'); do
      case $p in lirp | lyon) n=1048576 ;; *) n=131072 ;; esac
      expect_status 0 "$phongsim" cosim "$p" --no-build --vectors "$n" --json "$tmp/$p.json"
      python3 -c 'import json,sys; r=json.load(open(sys.argv[1]))["runs"][0]; assert r["passed"] and r["duts"] == 1 and r["longest_since_reset"]["vectors"] >= int(sys.argv[2]), r' \
        "$tmp/$p.json" "$n" || fail "$p: $(cat "$tmp/$p.json")"
      echo "ok: $p: $(grep -o 'longest since reset [^;]*' "$tmp/run")"
    done
    ;;

  include)
    # 3. An `include'd file is part of the key: editing it is never an old result (--no-build
    #    refuses, a run rebuilds and fails), and a relative include is found the same way by the
    #    check and by the build, from any working folder.
    private_cache
    mkdir -p "$tmp/d/sub" "$tmp/elsewhere"
    mutant "$tmp/d/sub/my_lirp.sv" "s.replace('''$out_assign''', '''    assign out_p_o[c*OW+:OW] = p_q ^ OW'(Flip);''').replace('''  // Wide enough''', '''  \`include \"flip.svh\"
  // Wide enough''')"
    echo "localparam int Flip = 0;" >"$tmp/d/sub/flip.svh"
    cd "$tmp/elsewhere" || fail "cd"
    rtl=(--rtl ../d/sub/my_lirp.sv --top my_lirp --vectors 2000)
    expect_status 0 "$phongsim" cosim lirp "${rtl[@]}"
    expect_status 0 "$phongsim" cosim lirp "${rtl[@]}" --no-build
    echo "localparam int Flip = 1;" >"$tmp/d/sub/flip.svh"
    expect_error "not built for its current content" "$phongsim" cosim lirp "${rtl[@]}" --no-build
    expect_status 1 "$phongsim" cosim lirp "${rtl[@]}"
    # A plugin given by hand is refused once a file it includes changed.
    echo "localparam int Flip = 0;" >"$tmp/d/sub/flip.svh"
    plugin=$("$phongsim" build-rtl lirp --rtl ../d/sub/my_lirp.sv --top my_lirp | sed -n 's/.*: \(.*plugin.so\)$/\1/p')
    [ -s "$plugin" ] || fail "build-rtl printed no plugin path"
    expect_status 0 "$phongsim" cosim lirp --rtl-plugin "$plugin" --top my_lirp --vectors 100
    echo "localparam int Flip = 0; // edited" >"$tmp/d/sub/flip.svh"
    expect_error "was built from an older .*flip.svh" \
      "$phongsim" cosim lirp --rtl-plugin "$plugin" --top my_lirp --vectors 100
    ;;

  flags)
    # 4. $PHONGSIM_VERILATOR_FLAGS by allowlist: every form that would change the design, the
    #    simulation's semantics or what is compiled is refused with one line, before any build;
    #    flags that only change speed are taken.
    touch "$tmp/extra.cpp" "$tmp/extra.sv" "$tmp/args.f"
    while IFS= read -r flags; do
      [ -z "$flags" ] && continue
      PHONGSIM_VERILATOR_FLAGS="$flags" expect_error "^phongsim: error: PHONGSIM_VERILATOR_FLAGS: .* is refused" \
        "$phongsim" cosim lirp --rtl "$good" --top my_lirp --vectors 100
    done <<EOT
-top-module other
--top-module other
-top other
--GOutRound=0
-GOutRound=0
-pvalue+OutRound=0
$tmp/extra.cpp
$tmp/extra.sv
-x-initial 0
-x-assign 0
--x-initial unique
--DFOO
-DFOO
+define+FOO
--I$tmp
+incdir+$tmp
--f $tmp/args.f
-F $tmp/args.f
--exe
-y $tmp
-v $tmp/extra.sv
--no-assert
-CFLAGS -DFOO
-CFLAGS -include$tmp/extra.cpp
-CFLAGS -ffast-math
-LDFLAGS $tmp/extra.cpp
-LDFLAGS -lfoo
-CFLAGS -fplugin=evil.so
--prefix Vother
--threads=2
EOT
    for flags in "-O2" "--threads 1" "-CFLAGS -O2" "-Wno-WIDTH -fno-gate"; do
      PHONGSIM_VERILATOR_FLAGS="$flags" "$phongsim" cosim lirp --config "$default" --no-build \
        --vectors 10 >"$tmp/run" 2>&1
      grep -q "not built for its current content" "$tmp/run" || fail "$flags was refused: $(cat "$tmp/run")"
    done
    ;;

  moddup)
    # 5. Two definitions of the top (or of any module) in the set: refused, naming both files.
    mutant "$tmp/other.sv" 's.replace("p_q   <= requantize(sum_q);", "p_q   <= ~requantize(sum_q);")'
    expect_error "module my_lirp is defined twice, in .*my_lirp.sv:[0-9]+ and .*other.sv:[0-9]+" \
      "$phongsim" cosim lirp --rtl "$good" "$tmp/other.sv" --top my_lirp --vectors 100
    expect_error "module my_lirp is defined twice" \
      "$phongsim" cosim lirp --rtl "$tmp/other.sv" "$good" --top my_lirp --simulator icarus --vectors 100
    ;;

  late-output)
    # 6. One extra output 300 idle cycles after the last expected one: in the drain window, under
    #    every pattern of the 4 x 4 stall matrix.
    mutant "$tmp/late.sv" "s.replace('''  assign out_valid_o = valid_q[3];''', '''  logic [9:0] idle_q;
  logic extra_q, spent_q;
  assign out_valid_o = valid_q[3] || extra_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      idle_q <= '0; extra_q <= 1'b0; spent_q <= 1'b0;
    end else begin
      idle_q <= (valid_q != '0 || in_valid_i) ? '0 : (idle_q == 10'h3ff ? idle_q : idle_q + 10'd1);
      if (idle_q == 10'd300 && !spent_q) begin extra_q <= 1'b1; spent_q <= 1'b1; end
      else if (out_ready_i) extra_q <= 1'b0;
    end
  end''')"
    expect_status 1 "$phongsim" cosim lirp --rtl "$tmp/late.sv" --top my_lirp --vectors 2000 \
      --source-idle none,periodic:1110,random:0.3,long:64:200 \
      --backpressure none,random:0.5,periodic:0001,long:100:300 --junit "$tmp/j.xml"
    grep -q "^0 of 16 runs passed" "$tmp/run" || fail "$(grep -E '^(PASS|FAIL)' "$tmp/run")"
    [ "$(grep -c "first failure: unexpected output" "$tmp/run")" -eq 16 ] || fail "$(cat "$tmp/run")"
    grep -q 'failures="16"' "$tmp/j.xml" || fail "JUnit: $(head -3 "$tmp/j.xml")"
    ;;

  outputs-are-inputs)
    # 7. An output never replaces an input: --junit, --json, --trace, eval --out naming an --rtl
    #    file (directly, through a symbolic link or "..", or inside an --rtl folder), or an
    #    output inside --coverage: refused before any work, the file unchanged.
    mkdir "$tmp/r"
    cp "$good" "$tmp/r/my_lirp.sv"
    echo "localparam int X = 0;" >"$tmp/r/inc.svh"
    ln -s r/my_lirp.sv "$tmp/link.sv"
    "$phongsim" vectors --config "$default" --vectors 10 --out "$tmp/v.csv" || fail "vectors"
    cp -r "$tmp/r" "$tmp/r.before"
    for out in "--junit $tmp/r/my_lirp.sv" "--json $tmp/r/my_lirp.sv" "--json $tmp/link.sv" \
               "--json $tmp/r/../r/my_lirp.sv" "--json $tmp/r/inc.svh" "--coverage $tmp/r" \
               "--coverage $tmp/c --json $tmp/c" "--coverage $tmp/c --junit $tmp/c/coverage.info"; do
      # shellcheck disable=SC2086
      expect_error "is also an input|lies in the --coverage folder" \
        "$phongsim" cosim lirp --rtl "$tmp/r/my_lirp.sv" --top my_lirp --vectors 10 $out
    done
    expect_error "is also an input" "$phongsim" cosim lirp --rtl "$tmp/r" --top my_lirp --vectors 10 \
      --json "$tmp/r/inc.svh"
    expect_error "is also an input" "$phongsim" eval --config "$default" --backend rtl \
      --rtl "$tmp/r/my_lirp.sv" --top my_lirp --in "$tmp/v.csv" --out "$tmp/link.sv"
    expect_error "is also an input" "$phongsim" lint --config "$default" --rtl "$tmp/r/my_lirp.sv" \
      --top my_lirp --json "$tmp/r/my_lirp.sv"
    diff -r "$tmp/r.before" "$tmp/r" || fail "an input was changed"
    [ ! -e "$tmp/c" ] || fail "the refused --coverage made $tmp/c"
    ;;

  nothing-to-check)
    # 8. Zero vectors is refused, under the stall pattern that would have failed a wrong design.
    expect_error "nothing to check" "$phongsim" cosim lirp --rtl "$src/examples/your-rtl/my_lirp_wrong.sv" \
      --top my_lirp_wrong --vectors 0 --no-directed --backpressure random:0.5
    expect_error "empty value" "$phongsim" cosim lirp --json "" --vectors 10
    ;;

  damaged-cache)
    # 9. A damaged cached plugin is one line and a rebuild (--no-build: refused), never a crash;
    #    a truncated plugin given by hand is a clean exit naming it.
    export PHONGSIM_CACHE="$tmp/cache"
    cp -r "$build/rtl-cache" "$PHONGSIM_CACHE"  # lirp/default built already
    plugin=$("$phongsim" build-rtl --config "$default" --no-build | sed -n 's/.*: \(.*plugin.so\)$/\1/p')
    [ -s "$plugin" ] || fail "no cached plugin of lirp/default"
    cp "$plugin" "$tmp/whole.so"
    truncate -s $(($(stat -c %s "$plugin") / 2)) "$plugin"
    expect_error "the cached plugin of lirp is damaged .*plugin.so is [0-9]+ bytes, not the [0-9]+" \
      "$phongsim" cosim --config "$default" --vectors 100 --no-build
    expect_status 0 "$phongsim" cosim --config "$default" --vectors 100
    grep -q "phongsim: cached plugin of lirp damaged (.*), rebuilding" "$tmp/run" || fail "$(cat "$tmp/run")"
    head -c $(($(stat -c %s "$tmp/whole.so") / 2)) "$tmp/whole.so" >"$tmp/half.so"
    "$phongsim" cosim lirp --rtl-plugin "$tmp/half.so" --vectors 100 >"$tmp/run" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "a truncated --rtl-plugin: exit $rc: $(cat "$tmp/run")"
    grep -q "half.so" "$tmp/run" || fail "the plugin is not named: $(cat "$tmp/run")"
    [ -z "$(ls "$PHONGSIM_CACHE" | grep phongsim-tmp)" ] || fail "temporaries left: $(ls "$PHONGSIM_CACHE")"
    ;;

  shared-cache)
    # 9. Two containers on one cache volume: a live build temporary of a process this one cannot
    #    see (its pid means nothing here) is locked, and stays; a user's file named like an old
    #    temporary beside an output stays too.
    export PHONGSIM_CACHE="$tmp/cache"
    cp -r "$build/rtl-cache" "$PHONGSIM_CACHE"  # lirp/default built already
    mkdir -p "$PHONGSIM_CACHE/build.phongsim-tmp-Other1" "$tmp/out"
    echo keep >"$tmp/out/r.json.tmp.4242"
    python3 - "$phongsim" "$PHONGSIM_CACHE/build.phongsim-tmp-Other1" "$default" "$tmp/out/r.json" <<'EOT' || fail "shared-cache"
import fcntl, os, subprocess, sys, time
phongsim, live, default, out = sys.argv[1:5]
fd = os.open(live, os.O_RDONLY)
fcntl.flock(fd, fcntl.LOCK_EX)
time.sleep(2.5)  # old enough to be swept, were it not locked
subprocess.run([phongsim, "cosim", "--config", default, "--vectors", "10", "--json", out],
               check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
assert os.path.isdir(live), "a live temporary of another process was removed"
os.close(fd)
subprocess.run([phongsim, "cosim", "--config", default, "--vectors", "10", "--json", out],
               check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
assert not os.path.exists(live), "a stale temporary (its lock free) was kept"
EOT
    [ "$(cat "$tmp/out/r.json.tmp.4242")" = keep ] || fail "a user's file was removed"
    ;;

  small)
    # The smaller findings: reproduce lines that paste; a search name that is a file name; OBJ
    # indices beyond an int; standard output streamed; build-rtl --no-build builds nothing.
    mkdir "$tmp/we ird"
    cp "$src/examples/your-rtl/my_lirp_wrong.sv" "$tmp/we ird/it's.sv"
    cp "$default" "$tmp/we ird/c\$onfig.toml"
    expect_status 1 "$phongsim" cosim --config "$tmp/we ird/c\$onfig.toml" --rtl "$good" \
      "$tmp/we ird/it's.sv" --top my_lirp_wrong --vectors 2000
    line=$(sed -n 's/^  reproduce: //p' "$tmp/run")
    [ -n "$line" ] || fail "no reproduce line: $(cat "$tmp/run")"
    eval "set -- $line"  # as printed, the program first
    [ "$1" = "$phongsim" ] || fail "the reproduce line does not begin with the program run: $line"
    expect_status 1 "$@"
    grep -q "^FAIL lirp/c\$onfig: " "$tmp/run" || fail "the pasted reproduce line: $(cat "$tmp/run")"
    printf 'name = "../../escaped"\nbase = "%s"\nsignals = ["p"]\n' "$default" >"$tmp/s.toml"
    expect_error "name '../../escaped': a file name" "$phongsim" sweep search "$tmp/s.toml" --out "$tmp/found.toml"
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 4294967297 2 3\n' >"$tmp/w.obj"
    printf 'mesh = "w.obj"\nwidth = 16\nheight = 16\n[[light]]\ndirection = [0, 0, -1]\n' >"$tmp/w.toml"
    expect_error "w.obj:4: index 4294967297 is out of range" \
      "$phongsim" render --scene "$tmp/w.toml" --method gouraud --out "$tmp/render"
    # Output to standard output is streamed: the first rows arrive while no copy of them exists
    # anywhere (there was a full copy in $TMPDIR).
    mkdir "$tmp/t"
    TMPDIR="$tmp/t" python3 - "$phongsim" "$default" "$tmp/t" <<'EOT' || fail "streamed output"
import os, subprocess, sys
phongsim, default, tmpdir = sys.argv[1:4]
p = subprocess.Popen([phongsim, "vectors", "--config", default, "--vectors", "3000000", "--out", "-"],
                     stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
first = p.stdout.readline()
assert first.startswith(b"p0_x"), first
assert os.listdir(tmpdir) == [], os.listdir(tmpdir)
rows = 1 + sum(1 for _ in p.stdout)
assert p.wait() == 0 and rows == 1 + 1859 + 3000000, (p.returncode, rows)
assert os.listdir(tmpdir) == [], os.listdir(tmpdir)
EOT
    export PHONGSIM_CACHE="$tmp/cache"
    expect_error "not built for its current content" "$phongsim" build-rtl lirp --no-build
    [ ! -e "$PHONGSIM_CACHE" ] || [ -z "$(ls "$PHONGSIM_CACHE")" ] || fail "build-rtl --no-build built: $(ls "$PHONGSIM_CACHE")"
    ;;

  *)
    fail "unknown case $case_name"
    ;;
esac
echo "PASS: $case_name"
