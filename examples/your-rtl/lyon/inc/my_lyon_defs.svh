// my_lyon_defs.svh - macros shared by the my_lyon sources (found through +incdir+../inc).
//
// Format words, as phongsim passes them (docs/your-rtl.md): signed * 65536 + int_bits * 256 +
// frac_bits, e.g. S1.10 = 65802, 1.12 = 268. The fields are read arithmetically so lint sees
// every bit of the parameter used.
`ifndef MY_LYON_DEFS_SVH
`define MY_LYON_DEFS_SVH

// Width of the one exact word every requantization goes through (my_lyon_types::rq). 64 covers
// every phongsim lyon configuration (the widest exact value, n * D.D, is 35 bits in `default`);
// lists/files.f sets it explicitly, a build without the list gets this default.
`ifndef MY_LYON_EXACT_W
`define MY_LYON_EXACT_W 64
`endif

// Format word fields.
`define MY_LYON_FMT_S(f) (((f) / 65536) % 2)
`define MY_LYON_FMT_I(f) (((f) / 256) % 256)
`define MY_LYON_FMT_F(f) ((f) % 256)
`define MY_LYON_FMT_W(f) (`MY_LYON_FMT_S(f) + `MY_LYON_FMT_I(f) + `MY_LYON_FMT_F(f))

// Requantize (the spec's rq): exact signed value X with XFRAC fraction bits to format FMT,
// rounded with the enclosing module's Round parameter, saturated; the result's low W bits.
// X must be a signed expression (it is sign-extended to the exact word). The call is wrapped in
// a concatenation because Icarus 11 refuses a size cast of a function call ("Cast base
// expression must be a vector type").
`define MY_LYON_RQ(W, X, XFRAC, FMT) \
  W'({my_lyon_types::rq(`MY_LYON_EXACT_W'(X), (XFRAC), (FMT), Round)})

// One pipeline register loaded with its stage's enable.
`define MY_LYON_FF(EN, Q, D) \
  always_ff @(posedge clk_i) begin \
    if (EN) Q <= D; \
  end

`endif  // MY_LYON_DEFS_SVH
