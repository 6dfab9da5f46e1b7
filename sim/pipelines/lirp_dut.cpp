// Plugin adapter for rtl/lirp/lirp_unit.sv: which port carries which model field.
#include "Vlirp_unit.h"
#include "sim/cosim/verilated_dut.h"

PHONGSIM_RTL_PLUGIN(Vlirp_unit, [](Vlirp_unit& top, phongsim::PortMap& map) {
  map.input(top.in_p0_i, {"p0_x", "p0_y", "p0_z"});
  map.input(top.in_p1_i, {"p1_x", "p1_y", "p1_z"});
  map.input(top.in_a_i, {"a"});
  map.output(top.out_p_o, {"p_x", "p_y", "p_z"});
})
