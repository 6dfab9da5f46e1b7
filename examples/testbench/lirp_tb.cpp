// A user's Verilator testbench (its own main and clocking) for phongsim's LIRP, checked against
// the golden model through the installed phongsim package, in two ways:
//  1. its own loop: random vectors from the model's stimulus, every output compared in order;
//  2. phongsim's co-simulation harness and scoreboard around the same Verilated top, under
//     random stalls (sim/cosim/verilated_dut.h binds ports to model fields).
// Exit 0 when both pass.
#include <verilated.h>

#include <cstdio>
#include <deque>
#include <vector>

#include "Vlirp_unit.h"
#include "sim/cosim/cosim.h"
#include "sim/cosim/verilated_dut.h"
#include "sim/pipelines/golden.h"

namespace {

int own_loop(phongsim::GoldenModel& golden, std::uint64_t vectors) {
  VerilatedContext context;
  Vlirp_unit top(&context);
  const auto stimulus = golden.stimulus();
  const std::size_t n_in = golden.inputs().size();
  std::deque<std::vector<std::int64_t>> expected;
  std::vector<std::int64_t> in(n_in);
  std::uint64_t sent = 0, checked = 0, mismatches = 0;
  const auto tick = [&] {
    top.clk_i = 1;
    top.eval();
    top.clk_i = 0;
    top.eval();
  };
  top.rst_ni = 0;
  top.clk_i = 0;
  top.eval();
  tick();
  top.rst_ni = 1;
  top.out_ready_i = 1;
  // Fields packed from bit 0 up, each as wide as its format (`phongsim contract lirp`).
  const auto pack = [](std::span<const std::int64_t> v, const phongsim::fx::Format& f) {
    std::uint64_t word = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      word |= phongsim::fx::to_bits(v[i], f) << (i * static_cast<std::size_t>(f.width()));
    }
    return word;
  };
  const auto& pf = golden.inputs()[0].fmt;
  const auto& af = golden.inputs()[6].fmt;
  const auto& of = golden.outputs()[0].fmt;
  for (std::uint64_t cycle = 0; checked < vectors && cycle < 10 * vectors; ++cycle) {
    top.in_valid_i = sent < vectors;
    if (sent < vectors) {
      stimulus.vector(7, sent, in);
      top.in_p0_i = pack(std::span(in).subspan(0, 3), pf);
      top.in_p1_i = pack(std::span(in).subspan(3, 3), pf);
      top.in_a_i = static_cast<std::uint16_t>(phongsim::fx::to_bits(in[6], af));
    }
    top.eval();
    const bool take_in = top.in_valid_i && top.in_ready_o;
    if (top.out_valid_o) {
      const auto want = expected.front();
      expected.pop_front();
      for (std::size_t c = 0; c < 3; ++c) {
        const auto bits = (top.out_p_o >> (c * static_cast<std::size_t>(of.width()))) &
                          ((1ULL << of.width()) - 1);
        if (phongsim::fx::from_bits(bits, of) != want[c]) ++mismatches;
      }
      ++checked;
    }
    if (take_in) {
      expected.push_back(golden.eval(in));
      ++sent;
    }
    tick();
  }
  std::printf("own loop: %llu outputs checked, %llu mismatches\n",
              static_cast<unsigned long long>(checked),
              static_cast<unsigned long long>(mismatches));
  return checked == vectors && mismatches == 0 ? 0 : 1;
}

int with_phongsim_harness(phongsim::GoldenModel& golden) {
  const auto stimulus = golden.stimulus();
  const auto bind = [](Vlirp_unit& top, phongsim::PortMap& map) {
    map.input(top.in_p0_i, {"p0_x", "p0_y", "p0_z"});
    map.input(top.in_p1_i, {"p1_x", "p1_y", "p1_z"});
    map.input(top.in_a_i, {"a"});
    map.output(top.out_p_o, {"p_x", "p_y", "p_z"});
  };
  const phongsim::DutFactory make_dut = [&] {
    return phongsim::DutPtr(
        new phongsim::VerilatedDut<Vlirp_unit>(golden.inputs(), golden.outputs(), bind),
        phongsim::DutDeleter{});
  };
  phongsim::CosimOptions o;
  o.random_vectors = 20000;
  o.source = phongsim::StallPattern::parse("random:0.3");
  o.sink = phongsim::StallPattern::parse("random:0.5");
  const phongsim::CosimReport r = phongsim::cosim(
      {"lirp", golden.config(), golden.model(), stimulus, true, make_dut, "my testbench's top", ""},
      o);
  if (!r.passed) std::printf("%s", r.failure.c_str());
  std::printf("phongsim harness: %s\n", r.summary().c_str());
  return r.passed ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    phongsim::GoldenModel golden(argc > 1 ? argv[1] : LIRP_CONFIG);
    const int a = own_loop(golden, 20000);
    golden.reset();
    const int b = with_phongsim_harness(golden);
    return a != 0 || b != 0 ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lirp_tb: %s\n", e.what());
    return 2;
  }
}
