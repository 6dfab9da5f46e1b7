#!/usr/bin/env python3
"""Print the Verilator -G parameters of a phongsim configuration file, one per line.

configs/<pipeline>/<name>.toml is the single source of a pipeline's widths (model/config.h).
This is the mechanical rule that turns it into RTL parameters, used by CMake for the built-in
configurations and by `phongsim` for configurations Verilated on demand:

  [format] p = "S1.10"           ->  -GPFmt=<fx_pkg format word>   (signed*65536 + int*256 + frac)
  [mode]   out_round = "half_up" ->  -GOutRound=<fx_pkg encoding>
  [param]  k = 2                 ->  -GK=2

Keys become UpperCamelCase (out_round -> OutRound). Validation (widths, required keys) is the
model's job; this script only refuses what it cannot translate.
"""
import re
import sys
import tomllib

# fx_pkg.sv / model/fixed.h encodings.
MODES = {"truncate": 0, "half_up": 1, "half_even": 2, "wrap": 0, "saturate": 1}
FORMAT = re.compile(r"^([SsUu]?)(\d+)\.(\d+)$")


def format_word(text):
    """fx_pkg format word of "S1.10" / "1.10": signed * 65536 + int_bits * 256 + frac_bits."""
    m = FORMAT.match(str(text))
    if not m:
        raise ValueError(f"'{text}' is not a fixed-point format")
    signed = m.group(1) in ("S", "s")
    return (65536 if signed else 0) + int(m.group(2)) * 256 + int(m.group(3))


def camel(key):
    return "".join(part[:1].upper() + part[1:] for part in key.split("_"))


def gflags(path):
    with open(path, "rb") as f:
        cfg = tomllib.load(f)
    flags = []
    for key, text in sorted(cfg.get("format", {}).items()):
        try:
            flags.append(f"-G{camel(key)}Fmt={format_word(text)}")
        except ValueError as e:
            raise ValueError(f"[format] {key}: {e}") from None
    for key, name in sorted(cfg.get("mode", {}).items()):
        if name not in MODES:
            raise ValueError(f"[mode] {key}: unknown mode '{name}'")
        flags.append(f"-G{camel(key)}={MODES[name]}")
    for key, value in sorted(cfg.get("param", {}).items()):
        if not isinstance(value, int):
            raise ValueError(f"[param] {key}: '{value}' is not an integer")
        flags.append(f"-G{camel(key)}={value}")
    return flags


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: config_gflags.py CONFIG.toml")
    try:
        print("\n".join(gflags(sys.argv[1])))
    except (OSError, ValueError, tomllib.TOMLDecodeError) as e:
        sys.exit(f"{sys.argv[1]}: {e}")


if __name__ == "__main__":
    main()
