// Plugin adapter for rtl/lyon/lyon_top.sv: which port carries which model field.
#include "Vlyon_top.h"
#include "sim/cosim/verilated_dut.h"

PHONGSIM_RTL_PLUGIN(Vlyon_top, [](Vlyon_top& top, phongsim::PortMap& map) {
  map.input(top.in_n0_i, {"n0_x", "n0_y", "n0_z"});
  map.input(top.in_n1_i, {"n1_x", "n1_y", "n1_z"});
  map.input(top.in_a_i, {"a"});
  map.input(top.in_v_i, {"v_x", "v_y", "v_z"});
  map.input(top.in_l_i, {"l_x", "l_y", "l_z"});
  map.input(top.in_shin_i, {"shin"});
  map.output(top.out_spec_o, {"spec"});
  map.output(top.out_diff_o, {"diff"});
})
