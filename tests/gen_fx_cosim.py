#!/usr/bin/env python3
"""Generate the exhaustive co-simulation top of the rtl/common fx_* helpers and its case table.

Writes <out>/fx_cosim_top.sv and <out>/fx_cosim_cases.h from the one CASES table below, so the
Verilated top and the C++ test (tests/fx_rtl_test.cpp) cannot disagree about what slot holds
what. Every case reads its operands from the low bits of a_i (and b_i) and drives one 32-bit slot
of out_o, zero-extended; the test sweeps a_i (and b_i) over every value. Result widths are left
to fx_pkg in the RTL, so the test also checks that the RTL's width growth matches the model's.
"""
import os
import re
import sys

# fx_pkg.sv's encodings (model/config.cpp's Config::rtl_parameters() uses the same ones).
MODES = {"truncate": 0, "half_up": 1, "half_even": 2, "wrap": 0, "saturate": 1}


def format_word(text):
    """fx_pkg format word of "S1.10" / "1.10": signed * 65536 + int_bits * 256 + frac_bits."""
    m = re.fullmatch(r"([Ss]?)(\d+)\.(\d+)", text)
    if not m:
        raise ValueError(f"'{text}' is not a fixed-point format")
    return (65536 if m.group(1) else 0) + int(m.group(2)) * 256 + int(m.group(3))


ROUNDS = ["truncate", "half_up", "half_even"]
OVERFLOWS = ["wrap", "saturate"]

# Requantization: (input, output). Inputs up to 16 bits (a_i sweeps 2^16 values): fewer fraction
# bits by 1, 2, 4, 5 and down to none, more fraction bits, fewer integer bits (overflow), both
# signedness changes, 1-bit formats.
RESIZE = [
    ("S3.4", "S3.2"), ("S3.4", "S1.3"), ("S3.4", "2.4"), ("S3.4", "S5.6"), ("S3.4", "S2.0"),
    ("S3.4", "0.1"), ("4.4", "4.2"), ("4.4", "S2.3"), ("4.4", "2.5"), ("4.4", "3.0"),
    ("S7.8", "S3.4"), ("S7.8", "S7.3"), ("8.8", "S4.4"), ("8.8", "5.2"), ("S0.7", "S0.2"),
    ("S0.7", "1.8"), ("S1.10", "S1.5"), ("S1.10", "0.8"), ("S1.10", "S0.10"), ("S7.0", "S3.0"),
    ("S0.0", "S0.0"), ("0.1", "S0.0"), ("S2.13", "S0.1"), ("16.0", "S2.3"),
]
# Exact operations: (a, b), operands up to 8 bits each (a_i[7:0] x a_i[15:8]): every signedness
# pairing, unequal fraction counts, zero-fraction and 1-bit operands.
BINARY = [
    ("S3.4", "S3.4"), ("S3.4", "4.4"), ("4.4", "S3.4"), ("4.4", "4.4"), ("S0.7", "2.6"),
    ("S7.0", "0.8"), ("S1.2", "S3.4"), ("0.3", "S0.0"), ("S0.0", "S0.0"), ("8.0", "S7.0"),
]
NEG = ["S3.4", "4.4", "S0.0", "0.8", "S7.0"]  # also the operands of abs
# Binary-point shifts: (operand, k) across both edges (the point passing the last fraction bit
# and the first integer bit).
SCALE = [("S3.4", 2), ("S3.4", 6), ("S3.4", -2), ("S3.4", -5), ("4.4", 5), ("4.4", -7),
         ("S0.7", -1), ("8.0", 3), ("S7.0", -8)]


# Clamping to [0, 1]: signed with and without room above 1.0, unsigned.
CLAMP = ["S3.4", "S2.5", "S0.7", "4.4", "0.8"]
# fx_rq (round and saturate) over a subset of the requantizations above, every rounding mode.
RQ = [("S3.4", "S3.2"), ("S3.4", "S1.3"), ("S3.4", "2.4"), ("4.4", "S2.3"), ("S7.8", "S3.4"),
      ("8.8", "5.2"), ("S1.10", "0.8"), ("S2.13", "S0.1")]
# fx_dot3: (a, b, out); a_i holds a's three components then b's (at most 16 bits in all), so
# every pair of vectors is swept. Exact, rounded and saturating outputs.
DOT3 = [("S0.1", "S0.1", "S1.2"), ("S0.1", "S0.1", "S0.1"), ("S0.1", "S0.1", "1.0"),
        ("S1.1", "1.1", "S1.1"), ("S1.1", "1.1", "S3.2"), ("1.2", "0.2", "0.3"),
        ("S0.2", "S0.2", "S0.1")]


def cases():
    for a, b in RESIZE:
        for r in ROUNDS:
            for o in OVERFLOWS:
                yield ("resize", a, b, r, o)
    for op in ("add", "sub", "mul"):
        for a, b in BINARY:
            yield (op, a, b, "", "")
    for a in NEG:
        yield ("neg", a, "", "", "")
        yield ("abs", a, "", "", "")
    for a, k in SCALE:
        yield ("scale", a, str(k), "", "")
    for a in CLAMP:
        yield ("clamp01", a, "", "", "")
    for a, b in RQ:
        for r in ROUNDS:
            yield ("rq", a, b, r, "saturate")
    for a, b, out in DOT3:
        for r in ROUNDS:
            yield ("dot3", a, f"{b}:{out}", r, "saturate")


def width_expr(op, a, b):
    fa = format_word(a)
    if op == "scale":
        return f"fx_pkg::fx_width(fx_pkg::fx_scale_fmt({fa}, {b}))"
    if op == "clamp01":
        return f"fx_pkg::fx_width({fa})"
    if op == "dot3":
        return f"fx_pkg::fx_width({format_word(b.split(':')[1])})"
    fb = format_word(b) if b else 0
    result = {
        "resize": f"{fb}",
        "rq": f"{fb}",
        "add": f"fx_pkg::fx_add_fmt({fa}, {fb})",
        "sub": f"fx_pkg::fx_sub_fmt({fa}, {fb})",
        "mul": f"fx_pkg::fx_mul_fmt({fa}, {fb})",
        "neg": f"fx_pkg::fx_neg_fmt({fa})",
        "abs": f"fx_pkg::fx_abs_fmt({fa})",
    }[op]
    return f"fx_pkg::fx_width({result})"


def instance(i, op, a, b, rnd, ovf):
    fa = format_word(a)
    wa = f"fx_pkg::fx_width({fa})"
    lines = [f"  // slot {i}: {op} {a} {b} {rnd} {ovf}".rstrip(),
             f"  logic [{width_expr(op, a, b)}-1:0] r{i};"]
    if op == "resize":
        lines.append(
            f"  fx_resize #(.InFmt({fa}), .OutFmt({format_word(b)}), .Round({MODES[rnd]}), "
            f".Overflow({MODES[ovf]})) u{i} (.in_i(a_i[{wa}-1:0]), .out_o(r{i}));")
    elif op == "rq":
        lines.append(
            f"  fx_rq #(.InFmt({fa}), .OutFmt({format_word(b)}), .Round({MODES[rnd]})) u{i} "
            f"(.in_i(a_i[{wa}-1:0]), .out_o(r{i}));")
    elif op == "dot3":
        fb, fo = (format_word(f) for f in b.split(":"))
        wb = f"fx_pkg::fx_width({fb})"
        lines.append(
            f"  fx_dot3 #(.AFmt({fa}), .BFmt({fb}), .OutFmt({fo}), .Round({MODES[rnd]})) u{i} "
            f"(.a_i(a_i[3*{wa}-1:0]), .b_i(a_i[3*{wa}+:3*{wb}]), .dot_o(r{i}));")
    elif op == "neg":
        lines.append(f"  fx_neg #(.AFmt({fa})) u{i} (.a_i(a_i[{wa}-1:0]), .neg_o(r{i}));")
    elif op == "abs":
        lines.append(f"  fx_abs #(.AFmt({fa})) u{i} (.a_i(a_i[{wa}-1:0]), .abs_o(r{i}));")
    elif op == "clamp01":
        lines.append(f"  fx_clamp01 #(.AFmt({fa})) u{i} (.a_i(a_i[{wa}-1:0]), .clamped_o(r{i}));")
    elif op == "scale":
        lines.append(f"  fx_scale #(.AFmt({fa}), .Shift({b})) u{i} (.a_i(a_i[{wa}-1:0]), "
                     f".scaled_o(r{i}));")
    else:
        fb = format_word(b)
        port = {"add": "sum_o", "sub": "delta_o", "mul": "prod_o"}[op]
        lines.append(
            f"  fx_{op} #(.AFmt({fa}), .BFmt({fb})) u{i} (.a_i(a_i[{wa}-1:0]), "
            f".b_i(a_i[8+:fx_pkg::fx_width({fb})]), .{port}(r{i}));")
    lines.append(f"  assign out_o[{i}*32+:32] = 32'(r{i});")
    return "\n".join(lines)


def write_if_changed(path, text):
    """Leave an unchanged file alone so re-running CMake does not force a rebuild."""
    try:
        with open(path) as f:
            if f.read() == text:
                return
    except FileNotFoundError:
        pass
    with open(path, "w") as f:
        f.write(text)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    all_cases = list(cases())
    n = len(all_cases)
    sv = [
        "// Generated by tests/gen_fx_cosim.py; do not edit.",
        "/* verilator lint_off UNUSEDSIGNAL */",
        f"module fx_cosim_top (input logic [15:0] a_i, output logic [{n}*32-1:0] out_o);",
    ]
    sv += [instance(i, *c) for i, c in enumerate(all_cases)]
    sv += ["endmodule", ""]
    write_if_changed(os.path.join(out, "fx_cosim_top.sv"), "\n".join(sv))
    hdr = [
        "// Generated by tests/gen_fx_cosim.py; do not edit.",
        "#pragma once",
        "struct FxCosimCase { const char* op; const char* a; const char* b; const char* round;"
        " const char* overflow; };",
        "inline constexpr FxCosimCase kFxCosimCases[] = {",
    ]
    hdr += [f'    {{"{op}", "{a}", "{b}", "{r}", "{o}"}},' for op, a, b, r, o in all_cases]
    hdr += ["};", ""]
    write_if_changed(os.path.join(out, "fx_cosim_cases.h"), "\n".join(hdr))


if __name__ == "__main__":
    main()
