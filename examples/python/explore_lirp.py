#!/usr/bin/env python3
"""Narrowest LIRP widths within an error budget, with phongsim's Python module (docs/library.md).

For every fraction width of p (the vectors) and a (the factor), the LIRP's error against its
float reference; the narrowest total width whose max error stays within BUDGET output LSBs wins.
Plots max error against width (one curve per a width) to OUT/lirp-widths.png and writes the
model's outputs on the co-simulation vectors of configs/lirp/default.toml to OUT/vectors.csv and
OUT/model.csv (the test suite compares them with `phongsim eval --backend model`).

    PYTHONPATH=<prefix>/lib/python3/dist-packages /usr/bin/python3 explore_lirp.py OUT [BUDGET]
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import phongsim  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "."
budget = float(sys.argv[2]) if len(sys.argv) > 2 else 4.0  # output LSBs (S1.10)
os.makedirs(out, exist_ok=True)


def lirp(p_frac, a_frac):
    return phongsim.Model({"pipeline": "lirp",
                           "format": {"p": f"S1.{p_frac}", "a": f"1.{a_frac}", "out": "S1.10"},
                           "mode": {"out_round": "half_even", "out_overflow": "saturate"}})


errors = {(p, a): lirp(p, a).float_error(samples=20000)["max_lsb"]
          for p in range(5, 13) for a in range(5, 13)}
fits = [(p + a, p, a) for (p, a), e in errors.items() if e <= budget]
width, p_frac, a_frac = min(fits)
print(f"narrowest within {budget} LSB: p S1.{p_frac}, a 1.{a_frac} "
      f"({errors[p_frac, a_frac]:.3f} LSB max)")

for a in range(5, 13, 2):
    ps = range(5, 13)
    plt.semilogy(list(ps), [errors[p, a] for p in ps], marker="o", label=f"a 1.{a}")
plt.axhline(budget, color="grey", linestyle="--", label="budget")
plt.xlabel("fraction bits of p")
plt.ylabel("max error (output LSBs, S1.10, log scale)")
plt.title("LIRP: error against width")
plt.legend()
plt.savefig(os.path.join(out, "lirp-widths.png"), dpi=100)

# The model on the co-simulation vectors, as `phongsim eval` writes it.
model = phongsim.Model(os.path.join(phongsim.data_root(), "configs", "lirp", "default.toml"))
rows = model.vectors(count=500, seed=4)
with open(os.path.join(out, "vectors.csv"), "w") as f:
    f.write(",".join(name for name, _ in model.inputs) + "\n")
    f.writelines(",".join(str(v) for v in row) + "\n" for row in rows)
with open(os.path.join(out, "model.csv"), "w") as f:
    f.write(",".join(name for name, _ in model.outputs) + "\n")
    f.writelines(",".join(str(v) for v in row) + "\n" for row in model.eval(rows))
