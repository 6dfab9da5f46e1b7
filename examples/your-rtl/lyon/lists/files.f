// my_lyon's sources (read with -F: paths from this folder). The top and its submodule come
// first, the package (src/my_lyon_types.sv, not *_pkg.sv) after its users; the header
// my_lyon_defs.svh is found through +incdir+. MY_LYON_EXACT_W sizes the requantizer's exact word.
+incdir+../inc
+define+MY_LYON_EXACT_W=64
../src/my_lyon.sv
../src/my_lyon_dot3.sv
../src/my_lyon_types.sv   # package my_lyon_types: Round encodings and rq()
