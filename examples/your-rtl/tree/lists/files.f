// my_lirp_top's sources (read with -F: paths from this folder).
+incdir+../inc
../src/my_lirp_top.sv
../src/my_lirp_modes.sv  # a package (not *_pkg.sv), listed after its user
../../my_lirp.sv
