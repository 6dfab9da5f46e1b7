// Registry entry of the LIRP unit (rtl/lirp/lirp_unit.sv, model/lirp.h, docs/lirp.md).
#include "sim/pipelines/lirp.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/rng.h"
#include "model/lirp.h"
#include "model/plan.h"
#include "ref/lirp_float.h"

namespace phongsim {
namespace {

std::unique_ptr<PipelineModel> make_model(const Config& cfg) {
  const LirpFormats formats = LirpFormats::from_config(cfg);
  try {
    return std::make_unique<LirpModel>(formats);
  } catch (const Error& e) {
    cfg.fail(e.what());
  }
}

// Corner values of a and of the vector components, crossed so that every component sees every
// corner against every other one, plus a values that make exact rounding ties (a = 1/4, 1/2,
// 3/4 times an odd difference leaves exactly half an output LSB when a has more fraction bits).
Stimulus make_stimulus(const PipelineModel& model, const Config& cfg) {
  const LirpFormats f = LirpFormats::from_config(cfg);
  const auto pc = corner_values(f.p);
  auto ac = corner_values(f.a);
  for (int quarter = 1; quarter <= 3; ++quarter) {
    if (f.a.frac_bits >= 2) ac.push_back(std::int64_t{quarter} << (f.a.frac_bits - 2));
  }
  std::vector<std::vector<std::int64_t>> directed;
  const std::size_t n = pc.size();
  for (const std::int64_t a : ac) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) {
        directed.push_back({pc[i], pc[j], pc[(i + j) % n], pc[j], pc[i], pc[(i * j + 1) % n], a});
      }
    }
  }
  return Stimulus(model, std::move(directed));
}

// The domain of the accuracy claim (docs/lirp.md, "Input contract").
InputContract contract(const PipelineModel&, const Config& cfg) {
  const LirpFormats f = LirpFormats::from_config(cfg);
  const std::int64_t one_p = std::int64_t{1} << f.p.frac_bits;
  const std::int64_t one_a = std::int64_t{1} << f.a.frac_bits;
  const std::int64_t p_lo = f.p.is_signed ? -one_p : 0;
  // The output range at the scale of p0 + a·(p1 - p0) (2^-(p + a fraction bits)), exactly.
  const double scale = std::ldexp(1.0, f.p.frac_bits + f.a.frac_bits);
  const double out_lo = fx::to_real(f.out.min_raw(), f.out) * scale;
  const double out_hi = fx::to_real(f.out.max_raw(), f.out) * scale;
  constexpr std::size_t n_in = 7;  // p0 x y z, p1 x y z, a (LirpModel::inputs)
  return InputContract(
      {"a in [0, 1]", f.p.is_signed ? "p0, p1 in [-1, 1]" : "p0, p1 in [0, 1]",
       "p in the output range"},
      InputContract::Check([=](std::span<const std::int64_t> vectors, std::size_t width,
                               std::span<std::int16_t> out) {
        if (width != n_in)
          throw Error(fmt::format("a LIRP vector has {} fields, not {}", n_in, width));
        // A block of vectors at a time, field by field (structure of arrays), so that the
        // clauses' loop vectorizes; every clause without a branch (random vectors break them at
        // random), the first one broken kept.
        fx::on_kernel_isa([&] {
          for_each_field_block<std::int64_t, n_in>(
              vectors, out, [&](const auto& v, std::size_t m, std::int16_t* o) {
                for (std::size_t k = 0; k < m; ++k) {
                  const std::int64_t a = v[6][k];
                  const std::int64_t a_out = (a < 0) | (a > one_a);
                  std::int64_t p_out = 0, range_out = 0;
                  for (std::size_t c = 0; c < 6; ++c) p_out |= (v[c][k] < p_lo) | (v[c][k] > one_p);
                  for (std::size_t c = 0; c < 3; ++c) {
                    const double p =
                        static_cast<double>(v[c][k]) * static_cast<double>(one_a) +
                        static_cast<double>(a) * static_cast<double>(v[3 + c][k] - v[c][k]);
                    range_out |= (p < out_lo) | (p > out_hi);
                  }
                  const std::int64_t from_range = range_out != 0 ? 2 : InputContract::kIn;
                  const std::int64_t from_p = p_out != 0 ? 1 : from_range;
                  o[k] = static_cast<std::int16_t>(a_out != 0 ? 0 : from_p);
                }
              });
        });
      }));
}

int latency(const Config&) { return 3; }  // delta, prod, out (docs/lirp.md)

std::vector<StageValue> stages(PipelineModel& model, std::span<const std::int64_t> in) {
  const auto& m = dynamic_cast<const LirpModel&>(model);
  std::vector<StageValue> s;
  for (int c = 0; c < 3; ++c) {
    const LirpStages st = m.component(in[c], in[3 + c], in[6]);
    const std::string axis(1, "xyz"[c]);
    s.push_back({"delta_" + axis, st.delta});
    s.push_back({"prod_" + axis, st.prod});
    s.push_back({"sum_" + axis, st.sum});
    s.push_back({"p_" + axis, st.p});
  }
  return s;
}

// The output's requantization p = rq(sum) (the three components one point) saturating (or, with
// out_overflow wrap, wrapping) low, high and not.
CoverpointSampler coverpoints(const PipelineModel& model, const Config& cfg) {
  const LirpFormats f = LirpFormats::from_config(cfg);
  const LirpModel& m = dynamic_cast<const LirpModel&>(model);
  CoverpointSampler c;
  const auto p = c.points.declare_sides("p", m.component(0, 0, 0).sum.fmt, f.out, f.out_round);
  c.sample = [f, p](PipelineModel& model, std::span<const std::int64_t> in, Coverpoints& points) {
    const auto& m = dynamic_cast<const LirpModel&>(model);
    for (int c = 0; c < 3; ++c) {
      const fx::Fixed sum = m.component(in[c], in[3 + c], in[6]).sum;
      points.hit_side(p, fx::resize_side(sum.raw, sum.fmt, f.out, f.out_round));
    }
  };
  return c;
}

// configs/lirp/default.toml by hand: p S1.10, a 1.10, out S1.10, half_even, saturate. delta S2.10,
// prod = a·delta S3.20, sum = (p0 << 10) + prod S4.20, p = rq(sum) dropping 10 bits.
// Laid out as the model's plan is (LirpPlan::run), so the two are compared on equal terms: a
// block at a time on structure-of-arrays temporaries, run on the same instruction set
// (fx::on_kernel_isa; the loops inside the call, so that they are compiled for that set).
std::size_t native(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  const std::size_t n = in.size() / 7;
  const std::size_t at = out.size();
  out.resize(at + 3 * n);
  fx::on_kernel_isa([&] {
    fx::for_each_block<7, 3>(
        in.data(), out.data() + at, n,
        [](const std::int64_t* const* f, std::int64_t* const* o, std::size_t m) {
          for (int c = 0; c < 3; ++c) {
            const std::int64_t* p0 = f[c];
            const std::int64_t* p1 = f[3 + c];
            const std::int64_t* a = f[6];
            alignas(64) std::int64_t p[fx::kBlock];  // a local: no aliasing
            for (std::size_t i = 0; i < m; ++i) {
              const std::int64_t sum = (p0[i] << 10) + a[i] * (p1[i] - p0[i]);
              p[i] = std::clamp<std::int64_t>((sum + 511 + ((sum >> 10) & 1)) >> 10, -2048, 2047);
            }
            std::copy_n(p, m, o[c]);
          }
        });
  });
  return n;
}

// One vector's outputs against p0 + a·(p1 - p0) on the exact reals (p, a) it was quantized from,
// clamped to the output range, added to `tally` in output LSBs.
class FloatCheck {
 public:
  explicit FloatCheck(const LirpFormats& f)
      : f_(f),
        model_(f),
        lsb_(std::ldexp(1.0, -f.out.frac_bits)),
        lo_(fx::to_real(f.out.min_raw(), f.out)),
        hi_(fx::to_real(f.out.max_raw(), f.out)) {}

  [[nodiscard]] LirpModel& model() { return model_; }

  void add(std::span<const std::int64_t> v, const double (&p)[6], double a, ErrorTally& tally) {
    result_.clear();
    (void)model_.eval(v, result_);
    for (int c = 0; c < 3; ++c) {
      const double exact = std::clamp(lirp::lirp(p[c], p[3 + c], a), lo_, hi_);
      tally.add(std::abs(fx::to_real(result_[static_cast<std::size_t>(c)], f_.out) - exact), lsb_);
    }
  }

 private:
  LirpFormats f_;
  LirpModel model_;
  double lsb_, lo_, hi_;
  std::vector<std::int64_t> result_;
};

// The model against p0 + a·(p1 - p0) on exact reals clamped to the output range (the model sees
// them quantized), in output LSBs, over vectors whose first broken clause is `clause`
// (InputContract::kIn: inside the contract). Inside: components uniform over the contract's
// interval, a in [0, 1]. Outside, each clause broken alone: a above 1; components over the whole
// input format; p leaving the output range (found among in-range inputs; none where it cannot).
ModelError lirp_contract_error(const Config& cfg, int clause, std::uint64_t samples,
                               std::uint64_t seed) {
  const LirpFormats f = LirpFormats::from_config(cfg);
  FloatCheck check(f);
  InputContract contract = lirp_pipeline().contract(check.model(), cfg);
  const double p_lo = f.p.is_signed ? -1.0 : 0.0;
  const double p_min = fx::to_real(f.p.min_raw(), f.p), p_max = fx::to_real(f.p.max_raw(), f.p);
  const double a_max = fx::to_real(f.a.max_raw(), f.a);
  const auto q = [](double x, fx::Format fmt) {
    return fx::quantize(x, fmt, fx::Round::half_even, fx::Overflow::saturate);
  };
  std::vector<std::int64_t> v(check.model().inputs().size());
  ErrorTally tally;
  std::uint64_t vectors = 0;
  for (std::uint64_t i = 0; vectors < samples && i < 50 * samples; ++i) {
    Rng rng(seed, kStimulusStream, i);
    double p[6];
    for (double& x : p) {
      x = clause == 1 ? p_min + rng.uniform() * (p_max - p_min) : p_lo + rng.uniform() * (1 - p_lo);
    }
    const double a = clause == 0 ? 1 + rng.uniform() * (a_max - 1) : rng.uniform();
    for (int c = 0; c < 6; ++c) v[static_cast<std::size_t>(c)] = q(p[c], f.p);
    v[6] = q(a, f.a);
    if (contract.check(v) != clause) continue;
    ++vectors;
    check.add(v, p, a, tally);
  }
  return tally.result();
}

void analyze(std::span<const Config> configs, std::uint64_t samples, std::uint64_t seed,
             AnalysisReport& out) {
  out.print(
      "LIRP output against p0 + a (p1 - p0) in float, inside the input contract (docs/lirp.md: "
      "components uniform in [-1, 1], [0, 1] unsigned, a in [0, 1], p in the output range; "
      "quantized to the input formats), in output LSBs; {} random vectors, seed {}\n",
      samples, seed);
  out.print("  {:<12} {:>8} {:>8} {:>8} {:>10} {:>10}\n", "config", "p", "a", "out", "max", "mean");
  out.table("LIRP output against p0 + a (p1 - p0) in float, in output LSBs",
            {"config", "p", "a", "out", "max_lsb", "mean_lsb"});
  for (const Config& cfg : configs) {
    const LirpFormats f = LirpFormats::from_config(cfg);
    const ModelError e = lirp_contract_error(cfg, InputContract::kIn, samples, seed);
    out.print("  {:<12} {:>8} {:>8} {:>8} {:>10.4f} {:>10.4f}\n", cfg.name(), f.p.str(), f.a.str(),
              f.out.str(), e.max_lsb, e.mean_lsb);
    out.row({cfg.name(), f.p.str(), f.a.str(), f.out.str(), e.max_lsb, e.mean_lsb});
  }
  out.print(
      "\nOutside the input contract, each clause broken alone, against the float value clamped "
      "to the output range, in output LSBs ('-': no such vector for the configuration)\n");
  out.print("  {:<12} {:<24} {:>8} {:>10} {:>10}\n", "config", "clause broken", "outputs", "max",
            "mean");
  out.table("LIRP outside the input contract, in output LSBs",
            {"config", "clause", "outputs", "max_lsb", "mean_lsb"});
  for (const Config& cfg : configs) {
    const LirpFormats f = LirpFormats::from_config(cfg);
    LirpModel model(f);
    const InputContract contract = lirp_pipeline().contract(model, cfg);
    for (std::size_t c = 0; c < contract.clauses().size(); ++c) {
      const ModelError e = lirp_contract_error(cfg, static_cast<int>(c), samples, seed);
      if (e.samples == 0) {
        out.print("  {:<12} {:<24} {:>8} {:>10} {:>10}\n", cfg.name(), contract.clauses()[c], 0,
                  "-", "-");
        continue;
      }
      out.print("  {:<12} {:<24} {:>8} {:>10.4f} {:>10.4f}\n", cfg.name(), contract.clauses()[c],
                e.samples, e.max_lsb, e.mean_lsb);
      out.row({cfg.name(), contract.clauses()[c], static_cast<double>(e.samples), e.max_lsb,
               e.mean_lsb});
    }
  }
}

}  // namespace

ModelError lirp_float_error(const Config& cfg, std::uint64_t samples, std::uint64_t seed) {
  const LirpFormats f = LirpFormats::from_config(cfg);
  FloatCheck check(f);
  ErrorTally tally;
  const auto q = [](double x, fx::Format fmt) {
    return fx::quantize(x, fmt, fx::Round::half_even, fx::Overflow::saturate);
  };
  std::vector<std::int64_t> v(check.model().inputs().size());
  for (std::uint64_t i = 0; i < samples; ++i) {
    Rng rng(seed, kStimulusStream, i);
    double p[6];
    for (int c = 0; c < 6; ++c) {
      p[c] = 2 * rng.uniform() - 1;
      v[static_cast<std::size_t>(c)] = q(p[c], f.p);
    }
    const double a = rng.uniform();
    v[6] = q(a, f.a);
    check.add(v, p, a, tally);
  }
  return tally.result();
}

const PipelineInfo& lirp_pipeline() {
  static const PipelineInfo info{
      .name = "lirp",
      .summary = "LIRP unit: p = (1 - a)·p0 + a·p1 on 3-vectors (Lyon Fig. 7a)",
      .top = "lirp_unit",
      .rtl_files = {"rtl/common", "rtl/lirp/lirp_core.sv", "rtl/lirp/lirp_unit.sv"},
      .ports = {{"in_p0_i", true, {"p0_x", "p0_y", "p0_z"}},
                {"in_p1_i", true, {"p1_x", "p1_y", "p1_z"}},
                {"in_a_i", true, {"a"}},
                {"out_p_o", false, {"p_x", "p_y", "p_z"}}},
      .make_model = make_model,
      .make_stimulus = make_stimulus,
      .independent_vectors = true,
      .default_vectors = 1000000,
      .latency = latency,
      .one_per_clock = true,
      .cycles = one_per_clock<latency>,
      .stages = stages,
      .coverpoints = coverpoints,
      .native = native,
      .contract = contract,
      .float_error = lirp_float_error,
      .analyze = analyze,
      .mutants = {{"round", "default", "rtl/common/fx_resize.sv",
                   "assign bias = Half - IntW'(1) + ", "assign bias = Half + ",
                   "convergent rounding constant off by one LSB"},
                  {"skid-valid", "default", "rtl/common/stream_skid.sv",
                   "if (spare_valid_q) begin\n        main_valid_d  = 1'b1;",
                   "if (spare_valid_q) begin\n        main_valid_d  = 1'b0;",
                   "skid buffer drops the transaction it caught during a stall"},
                  {"ready", "default", "rtl/common/pipe_ctrl.sv",
                   "assign ready[i] = out_ready_i | ~valid_q[i];",
                   "assign ready[i] = out_ready_i | valid_q[i];",
                   "last pipeline stage accepts while full: overwrites a stalled transaction"},
                  {"sub-order", "default", "rtl/lirp/lirp_core.sv", ".a_i    (p1_i[c*PW+:PW]),",
                   ".a_i    (p0_i[c*PW+:PW]),", "difference delta = p0 - p0 instead of p1 - p0"}},
  };
  return info;
}

}  // namespace phongsim
