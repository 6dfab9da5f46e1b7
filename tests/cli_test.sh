#!/usr/bin/env bash
# Command-line behaviour of phongsim, one named case per ctest test:
#   tests/cli_test.sh BUILD_DIR CASE
# Bad input must give one line on stderr naming the problem, exit status 2, and no output file.
source "$(dirname "$0")/cli_common.sh"

case "$case_name" in
  help)
    for sub in "" cosim eval build-rtl lint synth bench list render sweep vectors analyze; do
      $phongsim $sub --help >"$tmp/help" 2>&1 || fail "phongsim $sub --help failed"
      grep -q -i "usage" "$tmp/help" || fail "phongsim $sub --help prints no usage"
    done
    # Every command's (and sweep action's) help in plain words (issue 44): no CLI11 artefacts
    # such as "UINT:UINT in [1 - 256]=1" or a flag's "{false}", and --progress; the commands as
    # --help lists them.
    commands() { "$phongsim" "$@" --help | sed -n '/^Subcommands:/,$s/^  \([a-z-]*\) .*/\1/p'; }
    leaves=()
    for cmd in $(commands); do
      actions=$(commands "$cmd")
      [ -n "$actions" ] || leaves+=("$cmd")
      for action in $actions; do leaves+=("$cmd $action"); done
    done
    [ "${#leaves[@]}" -ge 17 ] || fail "commands not found in --help: ${leaves[*]}"
    for words in "${leaves[@]}"; do
      # shellcheck disable=SC2086  # "sweep run": two words
      $phongsim $words --help >"$tmp/help" 2>&1 || fail "phongsim $words --help failed"
      ! grep -nE '\{false\}|\{true\}|UINT|INT:|TEXT:' "$tmp/help" ||
        fail "phongsim $words --help shows CLI11's artefacts"
      grep -q -- '--progress auto|always|never' "$tmp/help" ||
        fail "phongsim $words --help has no --progress"
    done
    "$phongsim" synth --help >"$tmp/help"
    # synth reads sources: no plugin, nothing Verilated.
    ! grep -qE -- '^  (--rtl-plugin|--no-build)' "$tmp/help" ||
      fail "synth --help lists cosim's options"
    expect_error "requires|subcommand" "$phongsim"
    expect_error "unknown-option|The following argument was not expected|--bogus" \
      "$phongsim" cosim --config "$default" --bogus
    ;;

  bad-config)
    expect_error "cannot read configuration file" \
      "$phongsim" cosim --config "$tmp/missing.toml" --json "$tmp/result.json"
    printf 'pipeline = "lirp"\n[format\np = "S1.10"\n' >"$tmp/syntax.toml"
    expect_error "syntax.toml:2" "$phongsim" cosim --config "$tmp/syntax.toml" --json "$tmp/result.json"
    write_config "$tmp/wide.toml" S70.2 1.10 S1.10
    expect_error "wide.toml:4: \[format\] p: format S70.2: 73 bits exceeds" \
      "$phongsim" cosim --config "$tmp/wide.toml" --json "$tmp/result.json"
    write_config "$tmp/overflow.toml" S1.40 1.40 S1.10
    expect_error "overflow.toml: .*the exact result needs .* bits" \
      "$phongsim" cosim --config "$tmp/overflow.toml" --json "$tmp/result.json"
    write_config "$tmp/typo.toml" S1.1O 1.10 S1.10
    expect_error "typo.toml:4: \[format\] p: 'S1.1O' is not a fixed-point format" \
      "$phongsim" cosim --config "$tmp/typo.toml"
    printf 'pipeline = "lirp"\n[format]\np = "S1.10"\n' >"$tmp/missing_key.toml"
    expect_error "missing_key.toml: \[format\] is missing 'a'" \
      "$phongsim" cosim --config "$tmp/missing_key.toml"
    write_config "$tmp/extra.toml" S1.10 1.10 S1.10
    echo 'k = 3' >>"$tmp/extra.toml"
    expect_error "extra.toml:10: \[mode\] k: unknown key" "$phongsim" cosim --config "$tmp/extra.toml"
    expect_error "unknown pipeline 'nope'" "$phongsim" cosim --pipeline nope --config "$default"
    sed 's/pipeline = "lirp"/pipeline = "mystery"/' "$default" >"$tmp/other.toml"
    expect_error "unknown pipeline 'mystery'" "$phongsim" cosim --config "$tmp/other.toml"
    no_outputs
    ;;

  bad-options)
    expect_error "stall pattern 'random:2'" "$phongsim" cosim --config "$default" --backpressure random:2
    expect_error "stall pattern 'sometimes'" "$phongsim" cosim --config "$default" --source-idle sometimes
    expect_error "cannot write $tmp/no/such/dir/result.json" \
      "$phongsim" cosim --config "$default" --vectors 10 --json "$tmp/no/such/dir/result.json"
    mkdir "$tmp/dir.fst"
    expect_error "cannot write $tmp/dir.fst: it is a directory" \
      "$phongsim" cosim --config "$default" --vectors 10 --trace "$tmp/dir.fst"
    no_outputs
    ;;

  cosim-json)
    "$phongsim" cosim --config "$default" --vectors 5000 --seed 3 --backpressure random:0.5 \
      --json "$tmp/result.json" >"$tmp/out" || fail "cosim failed: $(cat "$tmp/out")"
    grep -q '^PASS lirp/default: ' "$tmp/out" || fail "no PASS summary: $(cat "$tmp/out")"
    python3 - "$tmp/result.json" <<'EOT' || fail "JSON summary is wrong: $(cat "$tmp/result.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["schema"] == "phongsim/1" and j["command"] == "cosim" and j["passed"] is True, j
assert len(j["runs"]) == 1, j
r = j["runs"][0]
assert r["pipeline"] == "lirp" and r["config"] == "default", r
assert r["mismatches"] == 0 and r["passed"] is True and r["failure"] is None, r
assert r["vectors"] == r["directed_vectors"] + 5000 == r["outputs"], r
assert r["seed"] == 3 and r["backpressure"] == "random:0.5", r
assert r["throughput"] == 1.0 and r["latency"] == {"min": 3, "max": 3}, r
assert r["cycles"] > r["vectors"], r
EOT
    # A matrix writes every run (it used to be refused).
    "$phongsim" cosim --config "$default" --config "$src/configs/lirp/narrow.toml" --vectors 200 \
      --source-idle none,random:0.3 --json "$tmp/matrix.json" >"$tmp/out" || fail "matrix: $(cat "$tmp/out")"
    python3 - "$tmp/matrix.json" <<'EOT' || fail "matrix JSON: $(cat "$tmp/matrix.json")"
import json, sys
j = json.load(open(sys.argv[1]))
runs = j["runs"]
assert j["passed"] is True and j["runs_passed"] == 4 and len(runs) == 4, j
assert [(r["config"], r["source_idle"]) for r in runs] == [
    ("default", "none"), ("default", "random:0.3"), ("narrow", "none"), ("narrow", "random:0.3")], runs
EOT
    ;;

  bench-json)
    # Every pipeline's bench: the native kernel is checked bit-identical to the model on the bench
    # vectors (an error otherwise), and the JSON has every part and ratio (Icarus's too). No
    # timing is asserted.
    for p in lirp lyon kb quad shade_lyon shade_quad shade_kb; do
      "$phongsim" bench "$p" --vectors 5000 --jobs 2 --json "$tmp/$p.json" >"$tmp/out" 2>&1 ||
        fail "bench $p: $(cat "$tmp/out")"
      grep -q "native kernel bit-identical to the model on all 5000 vectors" "$tmp/out" ||
        fail "bench $p: no native check: $(cat "$tmp/out")"
      python3 - "$tmp/$p.json" "$p" <<'EOT' || fail "bench $p JSON: $(cat "$tmp/$p.json")"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["pipeline"] == sys.argv[2] and r["config"] == "default" and r["vectors"] == 5000, r
assert r["isa"] in ("baseline", "avx2", "avx512"), r
for part in ("model", "native", "rtl", "bare_rtl", "bare_rtl_jobs", "cosim", "cosim_jobs", "icarus"):
    assert r[part]["vectors_per_s"] > 0 and r[part]["outputs_per_s"] > 0, (part, r)
assert r["bare_rtl_jobs"]["jobs"] == 2 and r["bare_rtl_jobs"]["cycles_per_s"] > 0, r
assert 1 <= r["icarus"]["vectors"] <= 5000 and r["icarus"]["cycles_per_s"] > 0, r
assert r["stimulus"]["vectors_per_s"] > 0, r
for ratio in ("model_native", "model_rtl", "rtl_bare_rtl", "cosim_rtl", "jobs_cosim",
              "jobs_bare_rtl", "verilator_icarus"):
    assert r["ratios"][ratio] > 0, (ratio, r)
assert 0 < r["ratios"]["cosim_ceiling_rtl"] < 1, r
EOT
    done
    # The vectorized kernels' baseline code, whatever this CPU runs by default: the native kernel
    # against the model, both on it.
    for p in lirp lyon; do
      PHONGSIM_ISA=baseline "$phongsim" bench "$p" --vectors 5000 --no-icarus --json "$tmp/$p.json" \
        >"$tmp/out" 2>&1 || fail "bench $p on baseline: $(cat "$tmp/out")"
      grep -q "native kernel bit-identical to the model on all 5000 vectors" "$tmp/out" ||
        fail "bench $p on baseline: no native check: $(cat "$tmp/out")"
      grep -q '"isa": "baseline"' "$tmp/$p.json" || fail "bench $p: not on baseline: $(cat "$tmp/$p.json")"
    done
    # RTL that fails its co-simulation is refused, not timed: one line, exit 2, no JSON.
    ex="$src/examples/your-rtl"
    "$phongsim" build-rtl lirp --rtl "$ex/my_lirp.sv" "$ex/my_lirp_wrong.sv" --top my_lirp_wrong \
      >/dev/null 2>&1 || fail "build-rtl of the wrong LIRP"  # so that the bench prints no build line
    status=0
    "$phongsim" bench lirp --rtl "$ex/my_lirp.sv" "$ex/my_lirp_wrong.sv" --top my_lirp_wrong \
      --vectors 2000 --no-icarus --json "$tmp/wrong.json" >"$tmp/out" 2>"$tmp/err" || status=$?
    [ "$status" = 2 ] && [ "$(wc -l <"$tmp/err")" = 1 ] && [ ! -e "$tmp/wrong.json" ] &&
      grep -q "bench: the RTL fails its co-simulation (mismatch)" "$tmp/err" ||
      fail "bench of a wrong LIRP: status $status: $(cat "$tmp/err")"
    # An instruction set that does not exist is refused up front, in one line.
    status=0
    PHONGSIM_ISA=avx3 "$phongsim" bench lirp --vectors 10 >"$tmp/out" 2>"$tmp/err" || status=$?
    [ "$status" = 2 ] && [ "$(wc -l <"$tmp/err")" = 1 ] &&
      grep -q "PHONGSIM_ISA=avx3: not an instruction set" "$tmp/err" ||
      fail "PHONGSIM_ISA=avx3: status $status: $(cat "$tmp/err")"
    ;;

  trace)
    "$phongsim" cosim --config "$default" --vectors 100 --trace "$tmp/wave.fst" --trace-window 50 \
      >"$tmp/out" || fail "cosim with --trace failed"
    [ -s "$tmp/wave.fst" ] || fail "no waveform written"
    head -c 1 "$tmp/wave.fst" | od -An -tx1 | grep -q '00' || fail "not an FST file"
    ;;

  eval)
    python3 - "$tmp/vectors.csv" <<'EOT'
import random, sys
random.seed(5)
with open(sys.argv[1], "w") as f:
    f.write("a, p0_x,p0_y,p0_z,p1_x,p1_y,p1_z\n# comment lines and blank lines are skipped\n\n")
    for _ in range(3000):
        f.write(",".join(str(v) for v in [random.randint(0, 2047)] +
                         [random.randint(-2048, 2047) for _ in range(6)]) + "\n")
EOT
    "$phongsim" eval --config "$default" --backend model --in "$tmp/vectors.csv" --out "$tmp/model.csv" \
      || fail "eval model failed"
    "$phongsim" eval --config "$default" --backend rtl --in "$tmp/vectors.csv" --out "$tmp/rtl.csv" \
      || fail "eval rtl failed"
    [ "$(head -1 "$tmp/model.csv")" = "p_x,p_y,p_z" ] || fail "bad header: $(head -1 "$tmp/model.csv")"
    [ "$(wc -l <"$tmp/model.csv")" -eq 3001 ] || fail "expected 3000 rows"
    cmp "$tmp/model.csv" "$tmp/rtl.csv" || fail "model and rtl outputs differ"
    # --stages: every vector's stage values; the last stage of each component is its output.
    "$phongsim" eval --config "$default" --backend rtl --in "$tmp/vectors.csv" --out "$tmp/rtl2.csv" \
      --stages "$tmp/stages.csv" || fail "eval --stages failed"
    cmp "$tmp/model.csv" "$tmp/rtl2.csv" || fail "--stages changed the outputs"
    python3 - "$tmp/stages.csv" "$tmp/model.csv" <<'EOT' || fail "stages CSV: $(head "$tmp/stages.csv")"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
out = list(csv.DictReader(open(sys.argv[2])))
assert len(rows) == 12 * len(out), (len(rows), len(out))
for r in rows:
    if r["stage"] in ("p_x", "p_y", "p_z"):
        assert r["raw"] == out[int(r["vector"])][r["stage"]], r
assert [r["stage"] for r in rows[:4]] == ["delta_x", "prod_x", "sum_x", "p_x"], rows[:4]
EOT
    expect_error "--out and --stages name the same file -" \
      "$phongsim" eval --config "$default" --in "$tmp/vectors.csv" --out - --stages -
    # Reals: exactly representable values give the same raw results.
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z,a\n0.5,-1,1,0.25,1.5,-2,0.5\n' >"$tmp/real.csv"
    "$phongsim" eval --config "$default" --in "$tmp/real.csv" --out "$tmp/real_out.csv" --real \
      || fail "eval --real failed"
    [ "$(tail -1 "$tmp/real_out.csv")" = "0.375,0.25,-0.5" ] || fail "real eval: $(cat "$tmp/real_out.csv")"
    # Lyon: the co-simulation stimulus as a golden vector file, through both backends.
    "$phongsim" vectors --config "$src/configs/lyon/fig8_k2.toml" --vectors 3000 --out "$tmp/lyon.csv" \
      || fail "vectors failed"
    for backend in model rtl; do
      "$phongsim" eval --config "$src/configs/lyon/fig8_k2.toml" --backend $backend \
        --in "$tmp/lyon.csv" --out "$tmp/lyon_$backend.csv" || fail "lyon eval $backend failed"
    done
    [ "$(wc -l <"$tmp/lyon_model.csv")" -eq "$(wc -l <"$tmp/lyon.csv")" ] || fail "lyon: row count"
    cmp "$tmp/lyon_model.csv" "$tmp/lyon_rtl.csv" || fail "lyon: model and rtl outputs differ"
    # Kuijk–Blake: span programs in, pixels out (many rows per program).
    "$phongsim" vectors --config "$src/configs/kb/d2_only.toml" --vectors 2000 --out "$tmp/kb.csv" \
      || fail "kb vectors failed"
    for backend in model rtl; do
      "$phongsim" eval --config "$src/configs/kb/d2_only.toml" --backend $backend \
        --in "$tmp/kb.csv" --out "$tmp/kb_$backend.csv" || fail "kb eval $backend failed"
    done
    [ "$(head -1 "$tmp/kb_model.csv")" = "value,last" ] || fail "kb: header"
    [ "$(wc -l <"$tmp/kb_model.csv")" -gt 10000 ] || fail "kb: too few pixels"
    cmp "$tmp/kb_model.csv" "$tmp/kb_rtl.csv" || fail "kb: model and rtl outputs differ"
    # Quadratic interpolator: triangle programs in, pixels out.
    "$phongsim" vectors --config "$src/configs/quad/linear.toml" --vectors 200 --out "$tmp/quad.csv" \
      || fail "quad vectors failed"
    for backend in model rtl; do
      "$phongsim" eval --config "$src/configs/quad/linear.toml" --backend $backend \
        --in "$tmp/quad.csv" --out "$tmp/quad_$backend.csv" || fail "quad eval $backend failed"
    done
    [ "$(head -1 "$tmp/quad_model.csv")" = "x,y,r,g,b" ] || fail "quad: header"
    cmp "$tmp/quad_model.csv" "$tmp/quad_rtl.csv" || fail "quad: model and rtl outputs differ"
    ;;

  eval-errors)
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z,a\n1,2,3,4,5,6,x7\n' >"$tmp/bad_int.csv"
    expect_error "bad_int.csv:2: column 'a': 'x7' is not an integer" \
      "$phongsim" eval --config "$default" --in "$tmp/bad_int.csv" --out "$tmp/result.csv"
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z\n1,2,3,4,5,6\n' >"$tmp/missing.csv"
    expect_error "missing.csv:1: missing column 'a'" \
      "$phongsim" eval --config "$default" --in "$tmp/missing.csv" --out "$tmp/result.csv"
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z,a,q\n1,2,3,4,5,6,7,8\n' >"$tmp/extra.csv"
    expect_error "extra.csv:1: unknown column 'q'" \
      "$phongsim" eval --config "$default" --in "$tmp/extra.csv" --out "$tmp/result.csv"
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z,a\n1,2,3,4,5,6,7\n1,2,3,4,5,6,4096\n' >"$tmp/range.csv"
    expect_error "range.csv:3: column 'a': 4096 is outside 1.10" \
      "$phongsim" eval --config "$default" --backend rtl --in "$tmp/range.csv" --out "$tmp/result.csv"
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z,a\n1,2,3\n' >"$tmp/short.csv"
    expect_error "short.csv:2: 3 values, but the header has 7 columns" \
      "$phongsim" eval --config "$default" --in "$tmp/short.csv" --out "$tmp/result.csv"
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z,a\n0,0,0,0,0,0,2.5\n' >"$tmp/real_range.csv"
    expect_error "real_range.csv:2: column 'a': 2.5 is outside the range of 1.10" \
      "$phongsim" eval --config "$default" --real --in "$tmp/real_range.csv" --out "$tmp/result.csv"
    expect_error "no_such.csv: cannot read input vectors" \
      "$phongsim" eval --config "$default" --in "$tmp/no_such.csv" --out "$tmp/result.csv"
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z,a\n1,2,3,4,5,6,7\n' >"$tmp/good.csv"
    expect_error "cannot write /proc/phongsim_result.csv" \
      "$phongsim" eval --config "$default" --in "$tmp/good.csv" --out /proc/phongsim_result.csv
    no_outputs
    ;;

  input-contract)
    # Issue 18: eval and cosim count the vectors inside and outside the pipeline's input
    # contract (its spec's "Input contract"), in the summary line and the JSON, and still check
    # every vector. LIRP: one vector inside, one with a = 1.5 (the first clause), one with a
    # component of -1.5; both backends count the same.
    printf 'p0_x,p0_y,p0_z,p1_x,p1_y,p1_z,a\n0.5,-1,1,0.25,1,0,0.5\n0,0,0,0,0,0,1.5\n-1.5,0,0,0,0,0,0\n' \
      >"$tmp/lirp.csv"
    for backend in model rtl; do
      "$phongsim" eval --config "$default" --backend $backend --real --in "$tmp/lirp.csv" \
        --out "$tmp/lirp_$backend.csv" --json "$tmp/lirp_$backend.json" >"$tmp/line" ||
        fail "eval $backend failed"
      grep -qF "3 vectors: 1 in contract, 2 out of contract (a in [0, 1]: 1; p0, p1 in [-1, 1]: 1)" \
        "$tmp/line" || fail "eval $backend summary: $(cat "$tmp/line")"
      python3 - "$tmp/lirp_$backend.json" <<'EOT' || fail "eval $backend JSON"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["command"] == "eval" and j["vectors"] == 3 and j["outputs"] == 3, j
assert j["in_contract"] == 1 and j["out_of_contract"] == 2, j
assert [(c["clause"], c["out_of_contract"]) for c in j["contract_clauses"]] == [
    ("a in [0, 1]", 1), ("p0, p1 in [-1, 1]", 1), ("p in the output range", 0)], j
EOT
    done
    cmp "$tmp/lirp_model.csv" "$tmp/lirp_rtl.csv" || fail "model and rtl outputs differ"
    # Lyon: N0 = N1 = (1.5, 0, 0) is too long to be normalized (|N'| > 1) -- counted, and still
    # co-simulated bit-exactly; the co-simulation's own random stimulus, half arbitrary bits,
    # lands on both sides.
    printf 'n0_x,n0_y,n0_z,n1_x,n1_y,n1_z,a,v_x,v_y,v_z,l_x,l_y,l_z,shin\n0,0,1,0,0,1,0,0,0,1,0,0.6,0.8,10\n1.5,0,0,1.5,0,0,0,1,0,0,1,0,0,10\n' \
      >"$tmp/lyon.csv"
    "$phongsim" eval --config "$src/configs/lyon/default.toml" --real --in "$tmp/lyon.csv" \
      --out "$tmp/lyon_out.csv" >"$tmp/line" || fail "lyon eval failed"
    grep -qF "2 vectors: 1 in contract, 1 out of contract (|N'| in [1/sqrt 2, 1]: 1)" "$tmp/line" ||
      fail "lyon eval summary: $(cat "$tmp/line")"
    "$phongsim" cosim --config "$src/configs/lyon/default.toml" --vectors 300 \
      --json "$tmp/cosim.json" >"$tmp/line" || fail "lyon cosim failed: $(cat "$tmp/line")"
    grep -qE "^PASS lyon/default: .* [1-9][0-9]* in contract, [1-9][0-9]* out of contract \(a in .* 0 mismatches" \
      "$tmp/line" || fail "cosim summary: $(cat "$tmp/line")"
    python3 - "$tmp/cosim.json" <<'EOT' || fail "cosim JSON: $(cat "$tmp/cosim.json")"
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]
assert r["in_contract"] > 0 and r["out_of_contract"] > 0, r
assert r["in_contract"] + r["out_of_contract"] == r["vectors"], r
assert sum(c["out_of_contract"] for c in r["contract_clauses"]) == r["out_of_contract"], r
assert r["contract_clauses"][1]["clause"] == "|N'| in [1/sqrt 2, 1]", r
EOT
    ;;

  on-demand)
    # A configuration nobody built yet: refused under --no-build, Verilated into the cache on
    # first use, then reused.
    export PHONGSIM_CACHE="$tmp/cache"
    write_config "$tmp/mine.toml" S1.9 1.9 S1.8
    expect_error "the RTL of lirp is not built for its current content and parameters \(first build of this top with these parameters\)" \
      "$phongsim" cosim --config "$tmp/mine.toml" --no-build --vectors 10
    # The first run on a terminal (a pseudo-terminal; the line after the usual 2 s): the
    # Verilation shows its progress.
    PHONGSIM_PROGRESS_AFTER=2 "$src/tests/on_terminal.py" "$tmp/first" "$phongsim" cosim \
      --config "$tmp/mine.toml" --vectors 20000 --backpressure random:0.3 ||
      fail "first run failed: $(cat "$tmp/first")"
    grep -qF $'\r\033[K  Verilating (' "$tmp/first" || fail "no Verilation progress on a terminal"
    grep -q "Verilating lirp" "$tmp/first" || fail "first run did not build: $(cat "$tmp/first")"
    "$phongsim" cosim --config "$tmp/mine.toml" --vectors 20000 --no-build >"$tmp/second" 2>&1 \
      || fail "second run failed: $(cat "$tmp/second")"
    ! grep -q "Verilating" "$tmp/second" || fail "second run rebuilt"
    grep -q "^PASS lirp/mine: .*; RTL: built-in lirp_unit" "$tmp/second" || fail "second run: $(cat "$tmp/second")"
    unset PHONGSIM_CACHE
    # A copy of a built-in configuration (other file, same parameters) is the same design: the
    # build's cache has it.
    cp "$default" "$tmp/copy.toml"
    "$phongsim" build-rtl --config "$tmp/copy.toml" >"$tmp/copy" 2>&1 || fail "$(cat "$tmp/copy")"
    grep -q "(cached)" "$tmp/copy" || fail "copy of default was not found cached: $(cat "$tmp/copy")"
    ;;

  stale)
    # Editing any RTL file never reports the old result: a copy of rtl/ passed with --rtl is
    # built once; after an edit, --no-build refuses (naming the file) and a normal run rebuilds.
    export PHONGSIM_CACHE="$tmp/cache"
    cp -r "$src/rtl" "$tmp/rtl"
    run() { "$phongsim" cosim lirp --rtl "$tmp/rtl/common" "$tmp/rtl/lirp" --vectors 2000 "$@"; }
    run >"$tmp/first" 2>&1 || fail "first run: $(cat "$tmp/first")"
    grep -qE "^PASS lirp/default: .*; RTL: lirp_unit from --rtl, [0-9]+ files" "$tmp/first" ||
      fail "first run: $(cat "$tmp/first")"
    run --no-build >"$tmp/again" 2>&1 || fail "unchanged RTL was not found built: $(cat "$tmp/again")"
    echo "// an edit" >>"$tmp/rtl/common/fx_resize.sv"
    expect_error "not built for its current content.*changed since the last build: fx_resize.sv" \
      run --no-build
    run >"$tmp/rebuilt" 2>&1 || fail "rebuild: $(cat "$tmp/rebuilt")"
    grep -q "Verilating lirp/default (changed since the last build: fx_resize.sv" "$tmp/rebuilt" ||
      fail "no rebuild notice: $(cat "$tmp/rebuilt")"
    # Extra Verilator flags are part of the key too, and the refusal says so.
    PHONGSIM_VERILATOR_FLAGS="--output-split 500" expect_error \
      'not built for its current content.*PHONGSIM_VERILATOR_FLAGS changed: now "--output-split 500"' \
      run --no-build
    # ... but never one that would change the design the verdict names (tests/adversarial_test.sh
    # tries every form), and a compiler flag only from the list of optimization flags.
    PHONGSIM_VERILATOR_FLAGS="-O3 -GOutRound=0" expect_error \
      'PHONGSIM_VERILATOR_FLAGS: -GOutRound=0 is refused: it would change the design' run --no-build
    PHONGSIM_VERILATOR_FLAGS="-CFLAGS -O2" run --no-build >"$tmp/cflags" 2>&1
    grep -q "PHONGSIM_VERILATOR_FLAGS changed" "$tmp/cflags" ||
      fail "a C++ -O2 after -CFLAGS was refused: $(cat "$tmp/cflags")"
    # A model Verilated for two simulation threads (-threads: Verilator's --threads) gets a
    # context with two: its DUTs ask for as many threads as the model was built for.
    PHONGSIM_VERILATOR_FLAGS="-threads 2" run >"$tmp/threads" 2>&1 ||
      fail "-threads 2: $(cat "$tmp/threads")"
    grep -q "^PASS lirp/default" "$tmp/threads" || fail "-threads 2: $(cat "$tmp/threads")"
    # A plugin file given by hand is refused once a file it was built from changed.
    plugin=$("$phongsim" build-rtl lirp --rtl "$tmp/rtl/common" "$tmp/rtl/lirp" | sed -n 's/.*: \(.*plugin.so\)$/\1/p')
    [ -s "$plugin" ] || fail "build-rtl printed no plugin path"
    "$phongsim" cosim lirp --rtl-plugin "$plugin" --vectors 100 >"$tmp/p" 2>&1 || fail "plugin: $(cat "$tmp/p")"
    echo "// another edit" >>"$tmp/rtl/lirp/lirp_core.sv"
    expect_error "was built from an older .*lirp_core.sv" \
      "$phongsim" cosim lirp --rtl-plugin "$plugin" --vectors 100
    ;;

  file-lists)
    # docs/your-rtl.md, "File lists, include folders and defines": examples/your-rtl/tree through
    # -F, -f, --rtl with +incdir+, nested lists with comments and $VAR; an edited include or a
    # define is a rebuild, never an old result; a missing include folder is one line naming the
    # include; the same sources go to lint, synth and Icarus; bad lists are one line each.
    export PHONGSIM_CACHE="$tmp/cache"  # its own: every edit below is a build of its own
    mkdir -p "$PHONGSIM_CACHE"
    cp -r "$build/rtl-cache"/runtime-* "$PHONGSIM_CACHE/"
    cp -r "$src/examples/your-rtl" "$tmp/ex"
    t="$tmp/ex/tree"
    run() { "$phongsim" cosim lirp --top my_lirp_top --vectors 2000 "$@"; }
    run -F "$t/lists/files.f" >"$tmp/a" 2>&1 || fail "-F: $(cat "$tmp/a")"
    grep -q "^PASS lirp/default: .*RTL: my_lirp_top from --rtl, 3 files" "$tmp/a" || fail "$(cat "$tmp/a")"
    # -f: paths from the current folder; a nested -F with comments and an environment variable.
    printf '%s\n' "// outer list" "-F \${TREE}/lists/files.f  # the tree's own" >"$tmp/outer.f"
    (cd "$tmp" && TREE="$t" "$phongsim" cosim lirp -f outer.f --top my_lirp_top --vectors 2000 --no-build) \
      >"$tmp/b" 2>&1 || fail "nested -f/-F with \$VAR: $(cat "$tmp/b")"
    (cd "$t" && run --rtl src/my_lirp_top.sv src/my_lirp_modes.sv ../my_lirp.sv +incdir+inc --no-build) \
      >"$tmp/c" 2>&1 || fail "--rtl with +incdir+: $(cat "$tmp/c")"
    # Only the included file changes: refused under --no-build, naming it; rebuilt otherwise.
    echo "// an edit" >>"$t/inc/my_lirp_top.svh"
    expect_error "a file it includes changed: my_lirp_top.svh" run -F "$t/lists/files.f" --no-build
    run -F "$t/lists/files.f" >"$tmp/d" 2>&1 || fail "rebuild after an include edit: $(cat "$tmp/d")"
    grep -q "Verilating lirp/default (a file it includes changed: my_lirp_top.svh" "$tmp/d" || fail "$(cat "$tmp/d")"
    # A define: its own build, and the bug it selects fails; the reproduce line, pasted as printed,
    # carries the list and the define.
    expect_error 'its defines changed: now "MY_LIRP_TIES_UP=1"' run -F "$t/lists/files.f" -D MY_LIRP_TIES_UP=1 --no-build
    run -F "$t/lists/files.f" -D MY_LIRP_TIES_UP=1 >"$tmp/e" 2>&1
    [ $? -eq 1 ] || fail "the define's bug did not fail: $(cat "$tmp/e")"
    repro=$(sed -n 's/^  reproduce: //p' "$tmp/e")
    grep -q -- "-F $t/lists/files.f -D MY_LIRP_TIES_UP=1 --top my_lirp_top" <<<"$repro" || fail "reproduce: $repro"
    eval "$repro" >"$tmp/f" 2>&1
    [ $? -eq 1 ] && [ "$(grep '^MISMATCH' "$tmp/f")" = "$(grep '^MISMATCH' "$tmp/e")" ] ||
      fail "the reproduce line: $(cat "$tmp/f")"
    # An edited list (the same define, now in the list): never the old result.
    cp "$t/lists/files.f" "$tmp/files.f.orig"
    echo "+define+MY_LIRP_TIES_UP=1" >>"$t/lists/files.f"
    run -F "$t/lists/files.f" >"$tmp/l" 2>&1
    [ $? -eq 1 ] && grep -q "^FAIL lirp/default: .*MY_LIRP_TIES_UP=1" "$tmp/l" ||
      fail "a define added to the list: $(cat "$tmp/l")"
    cp "$tmp/files.f.orig" "$t/lists/files.f"
    # Without the include folder: one line naming the include.
    grep -v incdir "$t/lists/files.f" >"$t/lists/noinc.f"
    expect_error "Cannot find include file: my_lirp_top.svh" run -F "$t/lists/noinc.f"
    # The same sources through lint, synth (against phongsim's) and Icarus.
    "$phongsim" lint --config "$default" -F "$t/lists/files.f" --top my_lirp_top >"$tmp/g" 2>&1 ||
      fail "lint: $(cat "$tmp/g")"
    "$phongsim" synth --config "$default" -F "$t/lists/files.f" --top my_lirp_top >"$tmp/h" 2>&1 ||
      fail "synth: $(cat "$tmp/h")"
    grep -q "^against phongsim's lirp_unit: [0-9]* vs [0-9]* cells" "$tmp/h" || fail "synth: $(cat "$tmp/h")"
    "$phongsim" cosim lirp -F "$t/lists/files.f" --top my_lirp_top --vectors 100 --simulator icarus \
      >"$tmp/i" 2>&1 || fail "icarus: $(cat "$tmp/i")"
    # Bad lists and words: one line each.
    echo "-v lib.sv" >"$tmp/lib.f"
    expect_error "lib.f:1: -v: library files and folders are not read" run -f "$tmp/lib.f"
    echo '$NOT_SET_ANYWHERE/a.sv' >"$tmp/var.f"
    expect_error 'var.f:1: \$NOT_SET_ANYWHERE is not set' run -f "$tmp/var.f"
    echo "-F self.f" >"$tmp/self.f"
    expect_error "self.f includes itself" run -F "$tmp/self.f"
    expect_error "nowhere.f: cannot read the file list" run -f "$tmp/nowhere.f"
    expect_error "no such include folder" run --rtl "$t/src" +incdir+"$tmp/nope"
    expect_error "'1X' is not a macro name" run -F "$t/lists/files.f" -D 1X
    expect_error "-I, -D, \+incdir\+ and \+define\+ go with your RTL" "$phongsim" cosim lirp -D X=1
    ;;

  reports)
    # Reports that say what is true (issue 46): the cosim JSON's rtl as data (every file and
    # include with its SHA-256, as built); a missing top named with the modules the files have;
    # rebuild reasons that name what changed; a --vector-index run counts its own output.
    export PHONGSIM_CACHE="$tmp/cache"
    mkdir -p "$PHONGSIM_CACHE"
    cp -r "$build/rtl-cache"/runtime-* "$PHONGSIM_CACHE/"
    cp -r "$src/examples/your-rtl" "$tmp/ex"
    t="$tmp/ex/tree"
    "$phongsim" cosim lirp -F "$t/lists/files.f" --top my_lirp_top --vectors 100 \
      --json "$tmp/tree.json" >"$tmp/a" 2>&1 || fail "tree: $(cat "$tmp/a")"
    grep -q "Verilating lirp/default (first build of this top with these parameters" "$tmp/a" || fail "$(cat "$tmp/a")"
    "$phongsim" cosim lirp --vectors 100 --json "$tmp/builtin.json" >"$tmp/b" 2>&1 || fail "$(cat "$tmp/b")"
    "$phongsim" cosim lirp -F "$t/lists/files.f" --top my_lirp_top --vectors 100 --simulator icarus \
      --json "$tmp/icarus.json" >"$tmp/c" 2>&1 || fail "icarus: $(cat "$tmp/c")"
    python3 - "$tmp" "$t" <<'PY' || fail "runs[].rtl"
import hashlib, json, os, sys
tmp, tree = sys.argv[1], sys.argv[2]
def sha(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest()
def check_files(entries, expected):
    got = [(os.path.realpath(f["path"]), f["sha256"]) for f in entries]
    want = [(os.path.realpath(p), sha(p)) for p in expected]
    assert got == want, (got, want)
rtl = json.load(open(f"{tmp}/tree.json"))["runs"][0]["rtl"]
assert rtl["top"] == "my_lirp_top" and rtl["source"] == "rtl" and rtl["simulator"] == "verilator", rtl
assert len(rtl["key"]) == 64 and rtl["key"][:16] in rtl["plugin"], rtl
# Packages first: my_lirp_modes.sv, then the list's order.
check_files(rtl["files"], [f"{tree}/src/my_lirp_modes.sv", f"{tree}/src/my_lirp_top.sv",
                           f"{tree}/../my_lirp.sv"])
check_files(rtl["includes"], [f"{tree}/inc/my_lirp_top.svh"])
assert [os.path.realpath(d) for d in rtl["include_dirs"]] == [os.path.realpath(f"{tree}/inc")], rtl
assert rtl["parameters"]["PFmt"] == 65802 and "--assert" in rtl["flags"], rtl
builtin = json.load(open(f"{tmp}/builtin.json"))["runs"][0]["rtl"]
assert builtin["source"] == "builtin" and builtin["top"] == "lirp_unit", builtin
assert any(f["path"].endswith("rtl/lirp/lirp_unit.sv") for f in builtin["files"]), builtin
check_files(builtin["files"], [f["path"] for f in builtin["files"]])
icarus = json.load(open(f"{tmp}/icarus.json"))["runs"][0]["rtl"]
assert icarus["simulator"] == "icarus" and icarus["key"] is None and icarus["flags"] is None, icarus
check_files(icarus["files"], [f"{tree}/src/my_lirp_modes.sv", f"{tree}/src/my_lirp_top.sv",
                              f"{tree}/../my_lirp.sv"])
PY
    # The same files, flattened into one folder with their header: a build of its own, said so.
    mkdir "$tmp/flat"
    cp "$t"/src/*.sv "$t"/inc/*.svh "$tmp/ex/my_lirp.sv" "$tmp/flat/"
    expect_error "the same files, but other include folders" \
      "$phongsim" cosim lirp --rtl "$tmp/flat" --top my_lirp_top --vectors 10 --no-build
    # A file that changed: named.
    echo "// an edit" >>"$tmp/flat/my_lirp_modes.sv"
    expect_error "changed since the last build: my_lirp_modes.sv" \
      "$phongsim" cosim lirp --rtl "$tmp/flat" --top my_lirp_top --vectors 10 --no-build
    # No --top, or a wrong one: the modules the files declare.
    expect_error "no module lirp_unit in the design's files \(--top defaults to lirp_unit, the built-in design's top\); modules in these files: my_lirp_top, my_lirp" \
      "$phongsim" cosim lirp -F "$t/lists/files.f" --vectors 10
    expect_error "no module my_lirp_tpo in the design's files \(--top names it\); modules in these files: my_lirp_top, my_lirp" \
      "$phongsim" cosim lirp -F "$t/lists/files.f" --top my_lirp_tpo --vectors 10
    expect_error "no module lirp_unit in the design's files .*modules in these files: my_lirp_top, my_lirp" \
      "$phongsim" synth lirp -F "$t/lists/files.f"
    expect_error "no module lirp_unit in the design's files .*modules in these files: my_lirp_top, my_lirp" \
      "$phongsim" lint lirp -F "$t/lists/files.f"
    # --vector-index: the vector alone, its output compared.
    wrong="$src/examples/your-rtl/my_lirp_wrong.sv"
    "$phongsim" cosim lirp --rtl "$wrong" --top my_lirp_wrong --vectors 2000 >"$tmp/d" 2>&1
    [ $? -eq 1 ] || fail "my_lirp_wrong: $(cat "$tmp/d")"
    alone=$(sed -n 's/^  this vector alone: //p' "$tmp/d")
    index=$(grep -o -- "--vector-index [0-9]*" <<<"$alone" | cut -d' ' -f2)
    [ -n "$index" ] || fail "no vector-alone line: $(cat "$tmp/d")"
    eval "$alone" >"$tmp/e" 2>&1
    [ $? -eq 1 ] || fail "the vector alone: $(cat "$tmp/e")"
    grep -qE "^FAIL lirp/default: vector $index alone \((directed|random), seed 1\), .*, 1 output compared, 1 mismatch, " \
      "$tmp/e" || fail "$(grep '^FAIL' "$tmp/e")"
    ;;

  your-lyon)
    # examples/your-rtl/lyon (docs/your-rtl.md): a Lyon unit as a real RTL tree (file list,
    # include folder, defines, a package not named *_pkg.sv) passes cosim under stalls, lint,
    # synth against phongsim's, Icarus and render; its define-selected bug (g2 without y^2)
    # fails with the first differing stage named, and renders nothing.
    list="$src/examples/your-rtl/lyon/lists/files.f"
    "$phongsim" cosim lyon -F "$list" --top my_lyon --vectors 20000 --backpressure random:0.5 \
      --source-idle random:0.3 >"$tmp/a" 2>&1 || fail "cosim: $(cat "$tmp/a")"
    grep -q "^PASS lyon/default: .*RTL: my_lyon from --rtl, 3 files, MY_LYON_EXACT_W=64" "$tmp/a" ||
      fail "cosim: $(cat "$tmp/a")"
    "$phongsim" cosim lyon -F "$list" --top my_lyon -D MY_LYON_BUG_G2 --json "$tmp/bug.json" \
      >"$tmp/b" 2>&1
    [ $? -eq 1 ] || fail "the g2 bug did not fail: $(cat "$tmp/b")"
    python3 - "$tmp/bug.json" <<'EOT' || fail "bug report: $(cat "$tmp/b")"
import json, sys
f = json.load(open(sys.argv[1]))["runs"][0]["failure"]
assert f["first_differing_stage"] == "n.g", f["first_differing_stage"]
assert f["message"].startswith("mismatch at cycle") and "first stage to differ: n.g" in f["message"], f["message"]
g = next(s for s in f["stages"] if s["field"] == "n.g")
assert g["signals"] and not any(x["held"] for x in g["signals"]), g
assert all(x["held"] for s in f["stages"] if s["field"] in ("n.z", "n.y") for x in s["signals"]), f["stages"]
EOT
    "$phongsim" lint lyon -F "$list" --top my_lyon >"$tmp/c" 2>&1 || fail "lint: $(cat "$tmp/c")"
    "$phongsim" synth lyon -F "$list" --top my_lyon >"$tmp/d" 2>&1 || fail "synth: $(cat "$tmp/d")"
    grep -q "^against phongsim's lyon_top: [0-9]* vs [0-9]* cells" "$tmp/d" || fail "synth: $(cat "$tmp/d")"
    "$phongsim" cosim lyon -F "$list" --top my_lyon --simulator icarus --vectors 300 \
      --backpressure random:0.5 >"$tmp/e" 2>&1 || fail "icarus: $(cat "$tmp/e")"
    # Rendering: the lyon-k2 unit through the user's RTL, output by output against the model.
    "$phongsim" render --method lyon-k2 --backend rtl -F "$list" --top my_lyon --pipeline lyon \
      --size 16 --out "$tmp/r" --quiet >"$tmp/f" 2>&1 || fail "render: $(cat "$tmp/f")"
    [ -s "$tmp/r/shinyballs_lyon-k2.png" ] || fail "render wrote no image: $(ls "$tmp/r")"
    "$phongsim" render --method lyon-k2 --backend rtl -F "$list" --top my_lyon --pipeline lyon \
      -D MY_LYON_BUG_G2 --size 24 --out "$tmp/r2" --quiet >"$tmp/g" 2>&1
    [ $? -eq 1 ] || fail "render of the bug: $(cat "$tmp/g")"
    grep -q "FAIL: lyon-k2 \[rtl\]: your RTL (my_lyon) with .* differs from its model at output" "$tmp/g" ||
      fail "render of the bug: $(cat "$tmp/g")"
    [ ! -e "$tmp/r2" ] || fail "a failing render left files: $(ls "$tmp/r2")"
    expect_error "--rtl: say which pipeline your RTL implements with --pipeline" \
      "$phongsim" render --method lyon-k2 --backend rtl -F "$list" --out "$tmp/r3"
    expect_error "--rtl: no method chosen here runs on a lyon unit through the RTL backend" \
      "$phongsim" render --method phong -F "$list" --pipeline lyon --out "$tmp/r3"
    ;;

  sweep-rtl)
    # docs/exploration.md, "Your RTL in a sweep": every point synthesizes and co-simulates the
    # user's design (examples/your-rtl/tree); a failing point fails the sweep (exit 1) and the
    # table says which; results of two designs do not merge; sweep search verifies the found
    # configuration on the user's design.
    list="$src/examples/your-rtl/tree/lists/files.f"
    printf '%s\n' 'name = "two"' "base = \"$default\"" '[axes]' '"format.p" = { frac = [9, 10] }' \
      '[error]' 'samples = 2000' >"$tmp/two.toml"
    "$phongsim" sweep run "$tmp/two.toml" --out "$tmp/a" -F "$list" --top my_lirp_top \
      --verify-vectors 3000 >"$tmp/out" 2>&1 || fail "sweep run: $(cat "$tmp/out")"
    grep -q "^RTL: my_lirp_top from --rtl ([0-9a-f]*); co-simulated at every point: all pass" "$tmp/a/summary.md" ||
      fail "summary: $(cat "$tmp/a/summary.md")"
    python3 - "$tmp/a/sweep.csv" <<'EOT' || fail "sweep.csv: $(cat "$tmp/a/sweep.csv")"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2 and all(r["rtl_passed"] == "1" for r in rows), rows
assert all(r["latency"] == "4" for r in rows), rows  # my_lirp's measured latency, not lirp_unit's 3
EOT
    grep -q -- "--rtl $src/examples/your-rtl/tree/lists/../src/my_lirp_top.sv .* +incdir+$src/examples/your-rtl/tree/lists/../inc --top my_lirp_top --verify-vectors 3000$" "$tmp/a/jobs.txt" ||
      fail "jobs.txt: $(cat "$tmp/a/jobs.txt")"
    # The bug at one point: that point fails (exit 1), and merging it with the others' is refused.
    "$phongsim" sweep point "$tmp/a/points/0001.toml" --sweep "$tmp/two.toml" --index 1 \
      --out "$tmp/a/results/0001.json" -F "$list" --top my_lirp_top -D MY_LIRP_TIES_UP=1 \
      --verify-vectors 3000 >"$tmp/p" 2>&1
    [ $? -eq 1 ] || fail "a failing point: $(cat "$tmp/p")"
    python3 -c 'import json,sys; assert json.load(open(sys.argv[1]))["verified"]["passed"] is False' "$tmp/a/results/0001.json" || fail "result: $(cat "$tmp/a/results/0001.json")"
    expect_error "point 0 was evaluated with my_lirp_top from --rtl \([0-9a-f]*\), point 1 with my_lirp_top from --rtl \([0-9a-f]*\): run the sweep again with one design" \
      "$phongsim" sweep merge "$tmp/two.toml" --out "$tmp/a"
    printf '%s\n' 'name = "found"' "base = \"$default\"" 'signals = ["p"]' 'min_frac = 8' \
      'max_lsb = 4.0' 'samples = 2000' 'verify_vectors = 3000' >"$tmp/search.toml"
    "$phongsim" sweep search "$tmp/search.toml" --out "$tmp/found.toml" -F "$list" --top my_lirp_top \
      -D MY_LIRP_TIES_UP=1 >"$tmp/s" 2>&1
    [ $? -eq 1 ] && grep -q "FAIL: the found configuration fails co-simulation; not written" "$tmp/s" &&
      grep -q -- "-D MY_LIRP_TIES_UP=1 --top my_lirp_top" "$tmp/s" || fail "search with the bug: $(cat "$tmp/s")"
    [ ! -e "$tmp/found.toml" ] || fail "a failing search wrote its configuration"
    expect_error "--rtl is what the verification runs: not with --no-verify" \
      "$phongsim" sweep search "$tmp/search.toml" --out "$tmp/found.toml" -F "$list" --no-verify
    ;;

  stage-report)
    # docs/your-rtl.md, "Stage reports and waveforms": phongsim's LIRP with one register broken
    # (delta_q's LSB flipped) fails with a one-line message naming the first stage to differ,
    # the stage table names the register that never held the model's value, and the waveform
    # (read back here) holds the vector indices, expected fields and mismatch flags.
    mkdir "$tmp/mut"
    cp "$src"/rtl/common/*.sv "$src"/rtl/lirp/*.sv "$tmp/mut/"
    sed -i 's/      delta_q <= delta_d;/      delta_q <= delta_d ^ 1;/' "$tmp/mut/lirp_core.sv"
    grep -q 'delta_q <= delta_d ^ 1;' "$tmp/mut/lirp_core.sv" || fail "the mutation did not apply"
    "$phongsim" cosim lirp --rtl "$tmp/mut" --top lirp_unit --json "$tmp/r.json" \
      --trace "$tmp/w.vcd" >"$tmp/out" 2>&1
    [ $? -eq 1 ] || fail "the broken register passed: $(cat "$tmp/out")"
    grep -q "delta_x .*NEVER on top.lirp_unit.u_core.delta_q   <-- first to differ" "$tmp/out" ||
      fail "stage table: $(cat "$tmp/out")"
    python3 - "$tmp/r.json" "$tmp/w.vcd" <<'EOT' || fail "JSON or waveform: $(cat "$tmp/out")"
import json, re, sys
f = json.load(open(sys.argv[1]))["runs"][0]["failure"]
assert f["first_differing_stage"] == "delta_x", f["first_differing_stage"]
assert "first stage to differ: delta_x" in f["message"], f["message"]
delta = f["stages"][0]
assert delta["field"] == "delta_x" and {"path": "top.lirp_unit.u_core.delta_q", "held": False} in delta["signals"], delta
# The waveform: the phongsim scope's variables, then their values at the failing output's time.
ids, values, time, at_failure = {}, {}, None, None
scope = []
for line in open(sys.argv[2]):
    w = line.split()
    if w[:1] == ["$scope"]: scope.append(w[2])
    elif w[:1] == ["$upscope"]: scope.pop()
    elif w[:1] == ["$var"] and scope == ["phongsim"]: ids[w[3]] = w[4]
    elif line.startswith("#"):
        if time == 2 * f["cycle"]: at_failure = dict(values)
        time = int(line[1:])
    elif w and w[0][0] == "b" and w[1] in ids: values[ids[w[1]]] = w[0][1:]
    elif w and w[0][0] in "01x" and w[0][1:] in ids: values[ids[w[0][1:]]] = w[0][0]
if time == 2 * f["cycle"]: at_failure = dict(values)
for name in ["in_accept", "in_vector", "out_take", "out_vector", "out_index", "mismatch",
             "expected_p_x", "mismatch_p_x", "expected_p_y", "mismatch_p_y"]:
    assert name in ids.values(), (name, ids)
assert at_failure, "no values at the failing output's time"
assert at_failure["out_take"] == "1" and at_failure["mismatch"] == "1", at_failure
assert int(at_failure["out_vector"], 2) == f["vector_index"], at_failure
x = next(o for o in f["outputs"] if o["field"] == "p_x")
assert at_failure["mismatch_p_x"] == ("1" if x["differs"] else "0"), at_failure
assert int(at_failure["expected_p_x"], 2) == x["expected"]["raw"] % (1 << 12), at_failure
EOT
    ;;

  your-rtl)
    # docs/your-rtl.md's commands: the independent LIRP passes every configuration under stalls
    # (through the CI script, JUnit out); the wrong one fails with a first-mismatch report whose
    # reproduce command fails the same way; a port that breaks the contract is one line, exit 2.
    ex="$src/examples/your-rtl"
    PIPELINE=lirp RTL="$ex/my_lirp.sv" TOP=my_lirp JUNIT="$tmp/cosim.xml" VECTORS=20000 \
      SOURCES=none,random:0.3 SINKS=random:0.5,long:100:300 PHONGSIM="$phongsim" \
      CONFIGS="$(ls "$src"/configs/lirp/*.toml | tr '\n' ' ')" "$ex/ci.sh" >"$tmp/ci" 2>&1 ||
      fail "ci.sh on my_lirp: $(cat "$tmp/ci")"
    grep -q "^16 of 16 runs passed" "$tmp/ci" || fail "ci.sh: $(cat "$tmp/ci")"
    [ "$(grep -c '^PASS lirp/.*latency 4 cycles; RTL: my_lirp from --rtl, 1 file' "$tmp/ci")" -eq 16 ] ||
      fail "ci.sh summaries: $(cat "$tmp/ci")"
    /usr/bin/python3 - "$tmp/cosim.xml" <<'PY' || fail "JUnit: $(cat "$tmp/cosim.xml")"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
cases = root.findall(".//testcase")
assert root.tag == "testsuites" and len(cases) == 16, (root.tag, len(cases))
assert not root.findall(".//failure") and root.get("failures") == "0"
PY
    "$phongsim" cosim lirp --rtl "$ex/my_lirp.sv" "$ex/my_lirp_wrong.sv" --top my_lirp_wrong \
      --vectors 1000 --junit "$tmp/wrong.xml" >"$tmp/wrong" 2>&1
    [ $? -eq 1 ] || fail "the wrong LIRP did not fail with exit 1: $(cat "$tmp/wrong")"
    grep -q "^MISMATCH at cycle" "$tmp/wrong" || fail "no mismatch report: $(cat "$tmp/wrong")"
    grep -q "<-- differs" "$tmp/wrong" || fail "no differing field marked: $(cat "$tmp/wrong")"
    /usr/bin/python3 - "$tmp/wrong.xml" <<'PY' || fail "JUnit of the failure: $(cat "$tmp/wrong.xml")"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
failures = root.findall(".//testcase/failure")
assert len(failures) == 1 and failures[0].get("type") == "mismatch", failures
assert "MISMATCH at cycle" in failures[0].text
PY
    repro=$(sed -n 's/^  reproduce: //p' "$tmp/wrong")  # pasted as printed
    (cd "$src" && eval "$repro") >"$tmp/again" 2>&1
    [ $? -eq 1 ] || fail "the reproduce command did not fail: $repro"
    [ "$(grep '^MISMATCH' "$tmp/again")" = "$(grep '^MISMATCH' "$tmp/wrong")" ] ||
      fail "the reproduce command failed differently: $(cat "$tmp/again")"
    sed 's/output logic \[3\*OW-1:0\] out_p_o/output logic [3*OW-4:0] out_p_o/' "$ex/my_lirp.sv" >"$tmp/narrow_lirp.sv"
    expect_error "port out_p_o of my_lirp is 33 bits wide, the contract says 36 with these parameters" \
      "$phongsim" cosim lirp --rtl "$tmp/narrow_lirp.sv" --top my_lirp
    expect_error "top no_such_top|no_such_top" "$phongsim" cosim lirp --rtl "$ex/my_lirp.sv" --top no_such_top
    sed 's/in_a_i/in_alpha_i/g' "$ex/my_lirp.sv" >"$tmp/alpha_lirp.sv"
    expect_error "top my_lirp has no port in_a_i" \
      "$phongsim" cosim lirp --rtl "$tmp/alpha_lirp.sv" --top my_lirp
    expect_error "--top needs --rtl or -f" "$phongsim" cosim lirp --top my_lirp
    ;;

  render)
    # The main job's command at a small size: every output file, a JSON summary, the RTL rows.
    "$phongsim" render --scene shinyballs --size 12 --no-build --out "$tmp/r" --json "$tmp/r.json" \
      >"$tmp/stdout" 2>"$tmp/err" || fail "render failed: $(cat "$tmp/err")"
    for f in grid.png scanline.png scanline.csv metrics.csv metrics.md phong.png lyon-k2.png lyon-k2_diff.png; do
      [ -s "$tmp/r/shinyballs_$f" ] || fail "missing shinyballs_$f"
    done
    grep -q '| lyon-k2 | rtl |' "$tmp/stdout" || fail "lyon-k2 not through the RTL: $(cat "$tmp/stdout")"
    grep -q '"backend": "rtl"' "$tmp/r.json" || fail "JSON summary: $(cat "$tmp/r.json")"
    [ "$(head -c 8 "$tmp/r/shinyballs_grid.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
      fail "grid is not a PNG"
    # A scene file with a mesh file next to it.
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/tri.obj"
    printf 'mesh = "tri.obj"\n[[light]]\ndirection = [0, 0, 1]\n' >"$tmp/scene.toml"
    "$phongsim" render --scene "$tmp/scene.toml" --method gouraud,phong --backend float --size 32 \
      --out "$tmp/s" >"$tmp/stdout" 2>&1 || fail "scene file: $(cat "$tmp/stdout")"
    [ -s "$tmp/s/scene_gouraud.png" ] || fail "scene file: no image ($(ls "$tmp/s"))"
    # Every method on a mesh scene, with the texture and terms options; the CPU-time table.
    "$phongsim" render --list-methods >"$tmp/stdout" || fail "--list-methods failed"
    for m in env-map blinn-map quad-blinn-map fast-phong fence highlight-track; do
      grep -q "^  $m " "$tmp/stdout" || fail "--list-methods lacks $m: $(cat "$tmp/stdout")"
    done
    "$phongsim" render --scene triangle --method all --backend float --size 48 --terms specular \
      --texture-size 64 --texture-filter nearest --out "$tmp/all" --quiet >"$tmp/stdout" 2>&1 ||
      fail "render --method all: $(cat "$tmp/stdout")"
    [ "$(grep -c '| float |' "$tmp/stdout")" -eq "$(grep -c '^  ' <("$phongsim" render --list-methods))" ] ||
      fail "--method all did not render every method: $(cat "$tmp/stdout")"
    for m in env-map blinn-map quad-blinn-map fast-phong fence highlight-track; do
      [ -s "$tmp/all/triangle_$m.png" ] || fail "missing triangle_$m.png"
    done
    "$phongsim" bench methods --scene triangle --rounds 1 --size 64 >"$tmp/stdout" 2>&1 ||
      fail "bench methods: $(cat "$tmp/stdout")"
    grep -qE '^\| gouraud \| [0-9.]+ \| 1\.0000 \| [0-9.]+ \|$' "$tmp/stdout" &&
      grep -qE '^\| phong \| [0-9.]+ \| [0-9.]+ \| 1\.0000 \|$' "$tmp/stdout" &&
      grep -q '^| highlight-track |' "$tmp/stdout" || fail "bench methods table: $(cat "$tmp/stdout")"
    ;;

  render-errors)
    expect_error "unknown scene 'nonesuch'" "$phongsim" render --scene nonesuch --out "$tmp/o"
    expect_error "unknown method 'bogus'" "$phongsim" render --method phong,bogus --out "$tmp/o"
    expect_error "unknown backend 'fpga'" "$phongsim" render --backend fpga --out "$tmp/o"
    expect_error "method 'quadratic' interpolates over triangles" \
      "$phongsim" render --method quadratic --out "$tmp/o"
    expect_error "method 'blinn' has no hardware unit" \
      "$phongsim" render --method blinn --backend model --out "$tmp/o"
    expect_error "--size: -3 is out of range" "$phongsim" render --size -3 --out "$tmp/o"
    # No silent fallbacks: --size 0 and --scanline -5 used to render at the default size and
    # the middle row.
    expect_error "--size: 0 is out of range \(1..2048\)" "$phongsim" render --size 0 --out "$tmp/o"
    expect_error "--scanline: -5 is out of range" \
      "$phongsim" render --size 8 --method lyon-k2 --backend float --scanline -5 --out "$tmp/o"
    # A --unit-config no chosen method uses was ignored.
    expect_error "--unit-config .* is a lirp configuration, but no method chosen here" \
      "$phongsim" render --size 8 --method lyon-k2 --backend model --unit-config "$default" --out "$tmp/o"
    expect_error "--scanline 999 is outside the image" \
      "$phongsim" render --size 8 --method lyon-k2 --backend float --scanline 999 --out "$tmp/o"
    expect_error "--texture-size: 5000 is out of range" \
      "$phongsim" render --scene triangle --method blinn-map --texture-size 5000 --out "$tmp/o"
    expect_error "unknown texture filter 'cubic'" \
      "$phongsim" render --scene triangle --method blinn-map --texture-filter cubic --out "$tmp/o"
    expect_error "unknown terms 'ambient'" "$phongsim" render --terms ambient --out "$tmp/o"
    expect_error "method 'fence' interpolates over triangles" \
      "$phongsim" render --method fence --out "$tmp/o"
    # Normals that cancel at the centroid: Fast Phong has nothing to expand about.
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1 0 0\nvn -0.5 0.8660254037844386 0\nvn -0.5 -0.8660254037844386 0\nf 1//1 2//2 3//3\n' \
      >"$tmp/cancel.obj"
    printf 'mesh = "cancel.obj"\n[[light]]\ndirection = [0, 0, 1]\n' >"$tmp/cancel.toml"
    expect_error "scene 'cancel', triangle 0: fast Phong: the interpolated normal vanishes" \
      "$phongsim" render --scene "$tmp/cancel.toml" --method fast-phong --out "$tmp/o"
    expect_error "--method all stands for every method" \
      "$phongsim" render --scene triangle --method all,phong --out "$tmp/o"
    expect_error "--rounds: 0 is out of range" "$phongsim" bench methods --rounds 0
    expect_error "unknown method 'nonesuch'" "$phongsim" bench methods --method nonesuch
    printf 'mesh = "tri.obj"\nwidht = 3\n[[light]]\ndirection = [0, 0, 1]\n' >"$tmp/bad.toml"
    expect_error "bad.toml:2: " "$phongsim" render --scene "$tmp/bad.toml" --out "$tmp/o"
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n' >"$tmp/bad.obj"
    printf 'mesh = "bad.obj"\n[[light]]\ndirection = [0, 0, 1]\n' >"$tmp/badmesh.toml"
    expect_error "bad.obj:4: " "$phongsim" render --scene "$tmp/badmesh.toml" --out "$tmp/o"
    [ ! -e "$tmp/o" ] || fail "an output directory was created for bad input"
    # Unwritable output: one line, nothing written.
    mkdir "$tmp/ro" && chmod 500 "$tmp/ro"
    if [ "$(id -u)" != 0 ]; then
      expect_error "cannot (write|create)" "$phongsim" render --size 8 --method lyon-k2 \
        --backend float --out "$tmp/ro/sub"
    fi
    expect_error "cannot (write|create)" "$phongsim" render --size 8 --method lyon-k2 \
      --backend float --out /proc/phongsim-out
    expect_error "cannot write" "$phongsim" render --size 8 --method lyon-k2 --backend float \
      --out "$tmp/o2" --json /proc/x.json
    [ ! -e "$tmp/o2" ] || fail "outputs written although the JSON path is unwritable"
    ;;

  sweep)
    # A small sweep end to end (model errors, generic and iCE40 synthesis, Pareto plot), then the
    # same as planned jobs run by make and merged: identical tables.
    "$phongsim" sweep run "$src/sweeps/lirp-small.toml" --out "$tmp/run" >"$tmp/stdout" 2>&1 ||
      fail "sweep run: $(cat "$tmp/stdout")"
    [ "$(wc -l <"$tmp/run/sweep.csv")" -eq 5 ] || fail "sweep.csv: $(cat "$tmp/run/sweep.csv")"
    [ -s "$tmp/run/pareto.png" ] || fail "no pareto.png"
    [ "$(wc -l <"$tmp/run/pareto.csv")" -eq 5 ] || fail "pareto.csv: $(cat "$tmp/run/pareto.csv")"
    grep -q "| yes |" "$tmp/run/summary.md" || fail "no Pareto point marked: $(cat "$tmp/run/summary.md")"
    python3 - "$tmp/run/sweep.csv" <<'EOT' || fail "sweep.csv: $(cat "$tmp/run/sweep.csv")"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for r in rows:
    assert r["pipeline"] == "lirp" and r["base"] == "lirp/default", r
    for k in ("cells", "transistors", "depth", "lut4", "carry", "mac16", "ff", "fmax_mhz"):
        assert float(r[k]) > 0, (k, r)
    assert r["ice40_fits"] == "1" and r["pareto"] in ("0", "1"), r
assert sum(r["pareto"] == "1" for r in rows) == 3, rows
EOT
    "$phongsim" sweep plan "$src/sweeps/lirp-small.toml" --out "$tmp/plan" >"$tmp/stdout" 2>&1 ||
      fail "sweep plan: $(cat "$tmp/stdout")"
    [ "$(wc -l <"$tmp/plan/jobs.txt")" -eq 4 ] || fail "jobs.txt: $(cat "$tmp/plan/jobs.txt")"
    make -s -j2 -C "$tmp/plan" >"$tmp/make" 2>&1 || fail "make: $(cat "$tmp/make")"
    cmp "$tmp/run/sweep.csv" "$tmp/plan/sweep.csv" || fail "planned sweep differs from run"
    ;;

  sweep-errors)
    base="$src/configs/lirp/default.toml"
    printf 'base = "%s"\n[axes]\n"format.bogus" = ["S1.8"]\n' "$base" >"$tmp/s1.toml"
    expect_error "point 0 .*has no \[format\] bogus" "$phongsim" sweep run "$tmp/s1.toml" --out "$tmp/o"
    printf 'base = "%s"\n[axes]\n"format.p" = { frac = [9, 3] }\n' "$base" >"$tmp/s2.toml"
    expect_error "s2.toml:3: axis 'format.p' is empty" "$phongsim" sweep run "$tmp/s2.toml" --out "$tmp/o"
    printf 'base = "%s"\n[axes]\n"format.p" = ["S30.40"]\n' "$base" >"$tmp/s3.toml"
    expect_error "point 0 .*(63|bits|overflow|wide)" "$phongsim" sweep run "$tmp/s3.toml" --out "$tmp/o"
    printf 'base = "%s"\nsamples = 3\n' "$base" >"$tmp/s4.toml"
    expect_error "s4.toml:2: unknown key 'samples'" "$phongsim" sweep run "$tmp/s4.toml" --out "$tmp/o"
    printf 'base = "nonesuch.toml"\n' >"$tmp/s5.toml"
    expect_error "nonesuch.toml does not exist" "$phongsim" sweep plan "$tmp/s5.toml" --out "$tmp/o"
    [ ! -e "$tmp/o" ] || fail "output written for a bad sweep file"
    printf 'base = "%s"\nsignals = ["p"]\n' "$base" >"$tmp/search.toml"
    expect_error "no budget" "$phongsim" sweep search "$tmp/search.toml" --write "$tmp/found.toml"
    printf 'base = "%s"\nsignals = ["p"]\nmin_colour_correctness = 0.9\nscene = "shinyballs"\nmethod = "lyon-k2"\n' \
      "$base" >"$tmp/search.toml"
    expect_error "method 'lyon-k2' does not run on a lirp unit" \
      "$phongsim" sweep search "$tmp/search.toml" --write "$tmp/found.toml"
    printf 'base = "%s"\nsignals = ["q"]\nmax_lsb = 1\n' "$base" >"$tmp/search.toml"
    expect_error "signal 'q' is not a \[format\] key" "$phongsim" sweep search "$tmp/search.toml" \
      --write "$tmp/found.toml"
    [ ! -e "$tmp/found.toml" ] || fail "a configuration was written for a bad search file"
    ;;

  sweep-search)
    # The search finds a configuration, Verilates and co-simulates it (10^6 vectors), writes it.
    "$phongsim" sweep search "$src/sweeps/lirp-search.toml" --write "$tmp/found.toml" \
      --junit "$tmp/search.xml" >"$tmp/stdout" 2>&1 || fail "search: $(cat "$tmp/stdout")"
    grep -q "^verified: PASS lirp/found: 1001859 vectors" "$tmp/stdout" ||
      fail "not verified: $(cat "$tmp/stdout")"
    # Issue 14: --junit on every command that co-simulates: the verification as one testcase.
    python3 - "$tmp/search.xml" <<'EOT' || fail "search --junit: $(cat "$tmp/search.xml")"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
cases = root.findall("./testsuite/testcase")
assert root.get("tests") == "1" and root.get("failures") == "0" and len(cases) == 1, root.attrib
assert cases[0].get("classname") == "lirp.found", cases[0].attrib
EOT
    "$phongsim" sweep search "$src/sweeps/lirp-search.toml" --write "$tmp/x.toml" --no-verify \
      --junit "$tmp/x.xml" >"$tmp/stdout" 2>&1 && fail "--junit with --no-verify accepted"
    [ ! -e "$tmp/x.xml" ] && [ ! -e "$tmp/x.toml" ] || fail "a refused search left files"
    grep -q 'p = .S1.8.' "$tmp/found.toml" || fail "found: $(cat "$tmp/found.toml")"
    "$phongsim" cosim --config "$tmp/found.toml" --vectors 1000 >/dev/null 2>&1 ||
      fail "the written configuration does not load"
    # A colour-correctness budget on a scene (model only: Lyon's Verilation is left to users).
    "$phongsim" sweep search "$src/sweeps/lyon-cc-search.toml" --write "$tmp/cc.toml" --no-verify \
      >"$tmp/stdout" 2>&1 || fail "cc search: $(cat "$tmp/stdout")"
    grep -qE "^found after [0-9]+ evaluations: [1-9][0-9]* fraction bits fewer, .*colour correctness 0\.96[5-9]" \
      "$tmp/stdout" || fail "cc search: $(cat "$tmp/stdout")"
    grep -q "colour correctness" "$tmp/cc.toml" || fail "cc search result: $(cat "$tmp/cc.toml")"
    # Without --out: <name>.toml in the current folder, never into configs/ (issue 44).
    mkdir "$tmp/here" && ls -lR "$src/configs" >"$tmp/configs_before"
    (cd "$tmp/here" && "$phongsim" sweep search "$src/sweeps/lirp-search.toml" --no-verify) \
      >"$tmp/stdout" 2>&1 || fail "search without --out: $(cat "$tmp/stdout")"
    [ -s "$tmp/here/min_4lsb.toml" ] && grep -q "^wrote min_4lsb.toml$" "$tmp/stdout" ||
      fail "search without --out: $(ls "$tmp/here"; cat "$tmp/stdout")"
    ls -lR "$src/configs" | cmp -s - "$tmp/configs_before" || fail "search wrote into configs/"
    ;;

  lint-json)
    # Issue 46: lint findings as data. A copy of the independent LIRP with one signal nothing
    # uses: its finding in the JSON (file relative to the current folder, the added line, the
    # rule), as a GitHub annotation and as a GCC-style line; --fail-on error passes on that
    # warning and fails on an error; the built-in design is clean, with no findings.
    sed '/^  logic       move;$/a\  logic       stray_q;' "$src/examples/your-rtl/my_lirp.sv" >"$tmp/my_lirp.sv"
    line=$(grep -n '^  logic       stray_q;$' "$tmp/my_lirp.sv" | cut -d: -f1)
    [ -n "$line" ] || fail "the unused signal was not added to my_lirp.sv"
    message="Signal is not driven, nor used: 'stray_q'"
    cd "$tmp" || fail "cd $tmp"
    lint=("$phongsim" lint lirp --rtl my_lirp.sv --top my_lirp)
    "${lint[@]}" --json "$tmp/lint.json" >"$tmp/text" 2>&1
    [ $? -eq 1 ] || fail "a warning did not fail the lint with exit 1: $(cat "$tmp/text")"
    grep -q "^%Warning-UNUSEDSIGNAL: .*my_lirp.sv:$line:" "$tmp/text" ||
      fail "--format text is not Verilator's own text: $(cat "$tmp/text")"
    python3 - "$tmp/lint.json" "$line" "$message" <<'EOT' || fail "lint JSON: $(cat "$tmp/lint.json")"
import json, sys
j = json.load(open(sys.argv[1]))
line, message = int(sys.argv[2]), sys.argv[3]
assert j["clean"] is False and j["verilator_exit"] == 1, j
assert j["warnings"] == 1 and j["errors"] == 0, j
assert j["findings"] == [{"file": "my_lirp.sv", "line": line, "column": 15, "rule": "UNUSEDSIGNAL",
                          "severity": "warning", "message": message}], j["findings"]
EOT
    "${lint[@]}" --format github >"$tmp/github" 2>&1
    [ $? -eq 1 ] || fail "--format github: exit $?: $(cat "$tmp/github")"
    grep -qxF "::warning file=my_lirp.sv,line=$line,col=15,title=UNUSEDSIGNAL::$message" "$tmp/github" ||
      fail "no GitHub annotation of my_lirp.sv line $line: $(cat "$tmp/github")"
    [ "$(grep -c '^::' "$tmp/github")" -eq 1 ] && ! grep -q '^%' "$tmp/github" ||
      fail "--format github: $(cat "$tmp/github")"
    "${lint[@]}" --format gcc >"$tmp/gcc" 2>&1
    [ $? -eq 1 ] || fail "--format gcc: exit $?: $(cat "$tmp/gcc")"
    grep -qxF "my_lirp.sv:$line:15: warning: $message [UNUSEDSIGNAL]" "$tmp/gcc" ||
      fail "no GCC-style line: $(cat "$tmp/gcc")"
    # --fail-on error: the warning printed and listed, exit 0.
    "${lint[@]}" --format gcc --fail-on error --json "$tmp/warned.json" >"$tmp/warned" 2>&1 ||
      fail "--fail-on error failed on a warning: $(cat "$tmp/warned")"
    grep -qxF "my_lirp.sv:$line:15: warning: $message [UNUSEDSIGNAL]" "$tmp/warned" ||
      fail "--fail-on error hid the warning: $(cat "$tmp/warned")"
    python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); assert j["warnings"] == 1 and len(j["findings"]) == 1, j' \
      "$tmp/warned.json" || fail "--fail-on error JSON: $(cat "$tmp/warned.json")"
    # An error fails with --fail-on error too (a syntax error: an annotation on its line).
    sed 's/^endmodule/  assign = 1;\nendmodule/' my_lirp.sv >broken_lirp.sv
    bad_line=$(grep -n "^  assign = 1;" broken_lirp.sv | cut -d: -f1)
    "$phongsim" lint lirp --rtl broken_lirp.sv --top my_lirp --fail-on error --format github \
      >"$tmp/broken" 2>&1
    [ $? -eq 1 ] || fail "an error passed --fail-on error: $(cat "$tmp/broken")"
    grep -q "^::error file=broken_lirp.sv,line=$bad_line," "$tmp/broken" ||
      fail "the error's annotation: $(cat "$tmp/broken")"
    # No such top is no finding of the design: one line naming the modules there are, exit 2.
    expect_error "no module no_such_top in the design's files \(--top names it\); modules in these files: my_lirp" \
      "$phongsim" lint lirp --rtl my_lirp.sv --top no_such_top --format github
    # A file outside the current folder keeps its absolute path.
    mkdir "$tmp/sub" && cd "$tmp/sub" || fail "cd $tmp/sub"
    "$phongsim" lint lirp --rtl ../my_lirp.sv --top my_lirp --json "$tmp/outside.json" >/dev/null 2>&1
    python3 -c 'import json, sys; f = json.load(open(sys.argv[1]))["findings"][0]; assert f["file"] == sys.argv[2], f' \
      "$tmp/outside.json" "$(cd "$tmp" && pwd -P)/my_lirp.sv" ||
      fail "a file outside the current folder is not shown absolute: $(cat "$tmp/outside.json")"
    # The built-in design: clean, exit 0, no findings.
    "$phongsim" lint lirp --json "$tmp/clean.json" --format github >"$tmp/clean" 2>&1 ||
      fail "the built-in LIRP does not lint clean: $(cat "$tmp/clean")"
    python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); assert j["clean"] is True and j["findings"] == [] and j["warnings"] == j["errors"] == 0, j' \
      "$tmp/clean.json" || fail "clean lint JSON: $(cat "$tmp/clean.json")"
    expect_error "--format: xml not in \{text,gcc,github\}" "$phongsim" lint lirp --format xml
    expect_error "--fail-on: info not in \{warning,error\}" "$phongsim" lint lirp --fail-on info
    ;;

  contract-json)
    # Issue 46: `contract --json` is all a wrapper generator needs. tests/gen_contract_pack.py
    # generates pack/unpack functions from it alone; per pipeline (one data port per field, a
    # stateful one with 1-bit ports, a composed one with multi-field ports up to 228 bits) they
    # must agree with the text header, round-trip every vector of `phongsim vectors` and every
    # output row of `phongsim eval`, and give the very words the built-in RTL's ports carry in a
    # co-simulation trace of the same vectors (seed 3).
    for p in lirp kb shade_lyon; do
      "$phongsim" contract "$p" --json "$tmp/$p.json" >"$tmp/$p.sv" || fail "contract $p --json"
      python3 "$src/tests/gen_contract_pack.py" "$tmp/$p.json" >"$tmp/${p}_pack.py" ||
        fail "gen_contract_pack.py $p"
      "$phongsim" vectors "$p" --vectors 50 --seed 3 --out "$tmp/$p.in.csv" >/dev/null ||
        fail "vectors $p"
      "$phongsim" eval "$p" --in "$tmp/$p.in.csv" --out "$tmp/$p.out.csv" >/dev/null ||
        fail "eval $p"
      "$phongsim" cosim "$p" --vectors 50 --seed 3 --trace "$tmp/$p.vcd" --trace-window 1000 \
        >"$tmp/cosim" 2>&1 || fail "cosim $p: $(cat "$tmp/cosim")"
    done
    # --json -: the document alone on stdout, the header on stderr, both as with a file.
    "$phongsim" contract lirp --json - >"$tmp/stdout" 2>"$tmp/stderr" || fail "contract --json -"
    cmp -s "$tmp/stdout" "$tmp/lirp.json" && cmp -s "$tmp/stderr" "$tmp/lirp.sv" ||
      fail "contract --json -: $(head -c 300 "$tmp/stdout") / $(head -c 300 "$tmp/stderr")"
    python3 - "$tmp" lirp kb shade_lyon <<'EOT' || fail "contract --json"
import csv, importlib.util, json, os, re, sys
tmp, pipelines = sys.argv[1], sys.argv[2:]

def read_vcd(path):
    """The top scope's signals just before each rising edge of clk_i (None: x or z)."""
    ids, scope, samples, now = {}, [], [], {}
    with open(path) as f:
        for line in f:
            w = line.split()
            if w[:1] == ["$scope"]:
                scope.append(w[2])
            elif w[:1] == ["$upscope"]:
                scope.pop()
            elif w[:1] == ["$var"] and len(scope) == 1:
                ids.setdefault(w[3], []).append(w[4])
            elif w[:1] == ["$enddefinitions"]:
                break
        for line in f:
            if line[0] == "b":
                bits, code = line[1:].split()
            elif line[0] in "01xz":
                bits, code = line[0], line[1:].strip()
            else:
                continue
            value = None if "x" in bits or "z" in bits else int(bits, 2)
            for name in ids.get(code, []):
                if name == "clk_i" and value == 1 and now.get("clk_i") == 0:
                    samples.append(dict(now))
                now[name] = value
    return samples

def rows(path):
    with open(path, newline="") as f:
        return [{k: int(v) for k, v in r.items()} for r in csv.DictReader(f)]

def width(f):
    return f["msb"] - f["lsb"] + 1

for p in pipelines:
    j = json.load(open(os.path.join(tmp, f"{p}.json")))
    header = open(os.path.join(tmp, f"{p}.sv")).read()
    spec = importlib.util.spec_from_file_location(f"{p}_pack", os.path.join(tmp, f"{p}_pack.py"))
    pack = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(pack)
    assert j["command"] == "contract" and j["pipeline"] == p and j["config"] == "default", j
    assert j["independent_vectors"] == (p != "kb"), (p, j["independent_vectors"])  # kb: state
    # Parameters: the header's, in order; each value is what its meaning says.
    params = re.findall(r"^  parameter int (\w+) = (-?\d+),?$", header, re.M)
    assert [(n, int(v)) for n, v in params] == [(x["name"], x["value"]) for x in j["parameters"]], \
        (p, params, j["parameters"])
    for x in j["parameters"]:
        if m := re.fullmatch(r"\[format\] \w+ = (S?)(\d+)\.(\d+) \(format word: .*\)", x["meaning"]):
            assert x["value"] == (65536 if m[1] else 0) + int(m[2]) * 256 + int(m[3]), (p, x)
        else:
            assert re.fullmatch(rf"\[mode\] \w+ = \w+ \(encoding {x['value']}\)|\[param\] \w+ = "
                                rf"{x['value']}", x["meaning"]), (p, x)
    # Ports: the header's names, directions and widths, in order; a data port is as wide as its
    # fields, packed from bit 0 up without gaps, each as the header's comment says.
    declared = re.findall(r"^  (input|output) +logic (?:\[(\d+):0\] )?(\w+)[, ] *(?://\s*(.*))?$",
                          header, re.M)
    assert [(d, int(w) + 1 if w else 1, n) for d, w, n, _ in declared] == \
        [(x["direction"], x["width"], x["name"]) for x in j["ports"]], (p, declared, j["ports"])
    assert {x["name"]: x["role"] for x in j["ports"] if x["role"] != "data"} == {
        "clk_i": "clock", "rst_ni": "reset", "in_valid_i": "valid", "in_ready_o": "ready",
        "out_valid_o": "valid", "out_ready_i": "ready"}, (p, j["ports"])
    data = [x for x in j["ports"] if x["role"] == "data"]
    comments = [c for _, w, _, c in declared if w]
    assert len(comments) == len(data) and all(x["fields"] is None for x in j["ports"] if x not in data)
    for x, comment in zip(data, comments):
        fields = x["fields"]
        assert sum(width(f) for f in fields) == x["width"] and fields[0]["lsb"] == 0, (p, x)
        assert all(b["lsb"] == a["msb"] + 1 for a, b in zip(fields, fields[1:])), (p, x)
        for f in fields:
            assert width(f) == f["signed"] + f["int_bits"] + f["frac_bits"], (p, f)
            assert f["format"] == f["signed"] * 65536 + f["int_bits"] * 256 + f["frac_bits"], (p, f)
            assert f["format_text"] == f"{'S' if f['signed'] else ''}{f['int_bits']}.{f['frac_bits']}", f
        assert comment == ", ".join(f"{f['name']} {f['format_text']} [{f['msb']}:{f['lsb']}]"
                                    for f in fields), (p, x["name"], comment)
    # The handshake rules are the header's words.
    prose = " ".join(l[3:] for l in header.splitlines() if l.startswith("// ")).lower()
    assert all(rule.lower() in prose for rule in j["handshake"]), (p, j["handshake"], prose)
    # Round trip: each vector through every input port, each output row through every output
    # port; every field in exactly one port.
    inputs = rows(os.path.join(tmp, f"{p}.in.csv"))
    outputs = rows(os.path.join(tmp, f"{p}.out.csv"))
    for direction, table in (("input", inputs), ("output", outputs)):
        ports = [x for x in data if x["direction"] == direction]
        carried = sorted(f["name"] for x in ports for f in x["fields"])
        assert carried == sorted(table[0]), (p, direction, carried, list(table[0]))
        for i, r in enumerate(table):
            for x in ports:
                word = pack.pack(x["name"], r)
                assert 0 <= word < 1 << x["width"], (p, f"{direction} row {i}", x["name"], word)
                want = {f["name"]: r[f["name"]] for f in x["fields"]}
                got = pack.unpack(x["name"], word)
                assert got == want, (p, f"{direction} row {i}", x["name"], want, got)
    # The RTL: at each accepted input every input port carries the packed vector (the harness's
    # in_vector indexes `phongsim vectors`' rows: same seed); the k-th output taken unpacks to
    # eval's row k.
    samples = read_vcd(os.path.join(tmp, f"{p}.vcd"))
    accepted = [s for s in samples if s.get("in_accept") == 1]
    taken = [s for s in samples if s.get("out_take") == 1]
    assert accepted and taken, (p, len(samples), len(accepted), len(taken))
    for s in accepted:
        v = s["in_vector"]
        for x in data:
            if x["direction"] == "input":
                assert s[x["name"]] == pack.pack(x["name"], inputs[v]), \
                    (p, "seed 3 vector", v, x["name"], s[x["name"]], inputs[v])
    for k, s in enumerate(taken):
        for x in data:
            if x["direction"] == "output":
                want = {f["name"]: outputs[k][f["name"]] for f in x["fields"]}
                got = pack.unpack(x["name"], s[x["name"]])
                assert got == want, (p, "seed 3 output", k, x["name"], want, got)
    print(f"ok: {p}: {len(j['parameters'])} parameters, {len(data)} data ports; {len(inputs)} "
          f"vectors and {len(outputs)} outputs round-tripped; {len(accepted)} inputs and "
          f"{len(taken)} outputs as the RTL's ports carry them")
EOT
    ;;

  *)
    fail "unknown case $case_name"
    ;;
esac
