// Plugin adapter for rtl/quad/quad_walker.sv: which port carries which model field.
#include "Vquad_walker.h"
#include "sim/cosim/verilated_dut.h"

PHONGSIM_RTL_PLUGIN(Vquad_walker, [](Vquad_walker& top, phongsim::PortMap& map) {
  map.input(top.in_bbox_i, {"x0", "y0", "x1", "y1"});
  map.input(top.in_edge0_i, {"e0_kind", "e0_q", "e0_r", "e0_d", "e0_dq", "e0_dr"});
  map.input(top.in_edge1_i, {"e1_kind", "e1_q", "e1_r", "e1_d", "e1_dq", "e1_dr"});
  map.input(top.in_edge2_i, {"e2_kind", "e2_q", "e2_r", "e2_d", "e2_dq", "e2_dr"});
  map.input(top.in_red_i, {"r_f", "r_gy", "r_gx", "r_a", "r_b", "r_c"});
  map.input(top.in_green_i, {"g_f", "g_gy", "g_gx", "g_a", "g_b", "g_c"});
  map.input(top.in_blue_i, {"b_f", "b_gy", "b_gx", "b_a", "b_b", "b_c"});
  map.output(top.out_x_o, {"x"});
  map.output(top.out_y_o, {"y"});
  map.output(top.out_rgb_o, {"r", "g", "b"});
})
