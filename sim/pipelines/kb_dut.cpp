// Plugin adapter for rtl/kb/kb_engine.sv: which port carries which model field.
#include "Vkb_engine.h"
#include "sim/cosim/verilated_dut.h"

PHONGSIM_RTL_PLUGIN(Vkb_engine, [](Vkb_engine& top, phongsim::PortMap& map) {
  map.input(top.in_n_i, {"n"});
  map.input(top.in_count_i, {"count"});
  map.input(top.in_f_i, {"f"});
  map.input(top.in_d1_i, {"d1"});
  map.input(top.in_d2_i, {"d2"});
  map.input(top.in_reload_i, {"reload"});
  map.output(top.out_value_o, {"value"});
  map.output(top.out_last_o, {"last"});
})
