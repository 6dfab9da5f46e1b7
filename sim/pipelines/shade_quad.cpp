// shade_quad: the walker of quad (sim/pipelines/quad.cpp) with the triangle's number as its tag.
// Everything but the number is quad's: each part of this entry hands a program's walker fields
// (the first ShadeQuadModel::kProgramFields) to quad's entry.
#include "sim/pipelines/shade_quad.h"

#include <memory>

#include "model/shade_quad.h"
#include "sim/pipelines/native_walker.h"
#include "sim/pipelines/quad.h"

namespace phongsim {
namespace {

const QuadModel& walker(const PipelineModel& model) {
  return dynamic_cast<const ShadeQuadModel&>(model).walker();
}

std::span<const std::int64_t> program(std::span<const std::int64_t> in) {
  return in.first(ShadeQuadModel::kProgramFields);
}

std::vector<PortBinding> ports() {
  std::vector<PortBinding> p =
      walker_program_ports({"in_red_i", "in_green_i", "in_blue_i"}, {"r", "g", "b"});
  p.insert(p.end(), {{"in_tri_i", true, {"tri"}},
                     {"out_x_o", false, {"x"}},
                     {"out_y_o", false, {"y"}},
                     {"out_tri_o", false, {"tri"}},
                     {"out_rgb_o", false, {"r", "g", "b"}}});
  return p;
}

std::unique_ptr<PipelineModel> make_model(const Config& cfg) {
  const QuadFormats formats = QuadFormats::from_config(cfg);
  (void)quad_mode(cfg);  // the stimulus reads it; check it here
  cfg.check_all_used();
  return std::make_unique<ShadeQuadModel>(formats);
}

// quad's vectors, each program numbered: directed ones by their index, random ones by theirs
// (modulo 2^16), so consecutive programs differ.
Stimulus make_stimulus(const PipelineModel& model, const Config& cfg) {
  const Stimulus quad = quad_pipeline().make_stimulus(walker(model), cfg);
  const std::size_t fields = ShadeQuadModel::kProgramFields;
  std::vector<std::vector<std::int64_t>> directed;
  for (std::uint64_t i = 0; i < quad.directed_count(); ++i) {
    std::vector<std::int64_t> v(fields + 1);
    quad.vector(0, i, std::span<std::int64_t>(v).first(fields));
    v[fields] = static_cast<std::int64_t>(i);
    directed.push_back(std::move(v));
  }
  auto random = [quad, fields](std::uint64_t seed, std::uint64_t index,
                               std::span<std::int64_t> in) {
    quad.vector(seed, index, in.first(fields));  // index counts the directed vectors too
    in[fields] = static_cast<std::int64_t>(index & 0xffff);
  };
  return Stimulus(model, std::move(directed), random);
}

FrameCycles cycles(const Config&, std::span<const std::int64_t> in,
                   std::span<const std::int64_t> out, std::span<const std::uint32_t> counts,
                   std::vector<FrameCycles>* per_vector) {
  return walker_cycles(in, out, 6, counts, per_vector);
}

std::vector<StageValue> stages(PipelineModel& model, std::span<const std::int64_t> in) {
  QuadModel w = walker(model);
  return quad_pipeline().stages(w, program(in));
}

CoverpointSampler coverpoints(const PipelineModel& model, const Config& cfg) {
  CoverpointSampler c = quad_pipeline().coverpoints(walker(model), cfg);
  c.sample = [quad = c.sample](PipelineModel& model, std::span<const std::int64_t> in,
                               Coverpoints& cp) {
    QuadModel w = walker(model);
    quad(w, program(in), cp);
  };
  return c;
}

InputContract contract(const PipelineModel& model, const Config& cfg) {
  InputContract quad = quad_pipeline().contract(walker(model), cfg);
  return InputContract(quad.clauses(), [quad](std::span<const std::int64_t> in) mutable {
    return quad.check(program(in));
  });
}

ModelError float_error(const Config& cfg, std::uint64_t samples, std::uint64_t seed) {
  return quad_pipeline().float_error(cfg, samples, seed);
}

// configs/shade_quad/default.toml by hand: quad/default's walker (acc S2.32, out 0.8), the
// triangle's number after the program and on each pixel.
std::size_t native(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  std::size_t n = 0;
  fx::on_kernel_isa(
      [&] { n = native_walker<35, 32, 8, 8, ShadeQuadModel::kProgramFields + 1, true>(in, out); });
  return n;
}

void analyze(std::span<const Config> configs, std::uint64_t samples, std::uint64_t seed,
             AnalysisReport& out) {
  out.print(
      "shade_quad is quad's walker with the triangle's number carried along: quad's "
      "analysis\n\n");
  quad_pipeline().analyze(configs, samples, seed, out);
}

}  // namespace

const PipelineInfo& shade_quad_pipeline() {
  static const PipelineInfo info{
      .name = "shade_quad",
      .summary = "Triangle to pixels: the quadratic colour walker with the triangle's number",
      .top = "shade_quad",
      .rtl_files = {"rtl/common", "rtl/quad/quad_channel.sv", "rtl/quad/quad_walker_core.sv",
                    "rtl/shade_quad/shade_quad.sv"},
      .ports = ports(),
      .make_model = make_model,
      .make_stimulus = make_stimulus,
      .independent_vectors = true,
      .default_vectors = quad_pipeline().default_vectors,
      .latency = quad_pipeline().latency,
      .one_per_clock = false,
      .cycles = cycles,
      .stages = stages,
      .coverpoints = coverpoints,
      .native = native,
      .contract = contract,
      .float_error = float_error,
      .analyze = analyze,
      .mutants = {{"shade-quad-tag", "default", "rtl/quad/quad_walker_core.sv",
                   ".in_data_i  ({tag_q, rgb, y_q, x_q}),",
                   ".in_data_i  ({head[ProgW-1-:TagW], rgb, y_q, x_q}),",
                   "pixels take the number of the program waiting behind theirs"}},
  };
  return info;
}

}  // namespace phongsim
