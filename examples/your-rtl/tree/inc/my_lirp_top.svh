// Included by my_lirp_top.sv (found through the list's +incdir+): the default of the tie
// rounding, which the define MY_LIRP_TIES_UP overrides (the failing example sets it to 1).
`ifndef MY_LIRP_TIES_UP
`define MY_LIRP_TIES_UP 0
`endif
