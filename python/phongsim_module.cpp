// The `phongsim` Python module (pybind11): the golden model of a configuration on NumPy arrays,
// the RTL where a plugin is built or can be, co-simulation and sweep points as dicts.
// docs/library.md; examples/python/.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <sstream>

#include "base/error.h"
#include "base/paths.h"
#include "sim/cosim/cosim.h"
#include "sim/cosim/harness.h"
#include "sim/explore/sweep.h"
#include "sim/pipelines/golden.h"

namespace py = pybind11;
using phongsim::GoldenModel;

namespace {

// A dict {"pipeline": ..., "format": {...}, "mode": {...}, "param": {...}, "setup": {...}} as
// the TOML of a configuration file (strings quoted, integers bare).
std::string toml_of(const py::dict& d) {
  std::ostringstream s;
  std::ostringstream tables;
  for (const auto& [key, value] : d) {
    const std::string k = py::str(key);
    if (py::isinstance<py::dict>(value)) {
      tables << "[" << k << "]\n";
      for (const auto& [sub, v] : value.cast<py::dict>()) {
        const std::string sk = py::str(sub);
        if (py::isinstance<py::bool_>(v) || !py::isinstance<py::int_>(v)) {
          tables << sk << " = \"" << std::string(py::str(v)) << "\"\n";
        } else {
          tables << sk << " = " << v.cast<long long>() << "\n";
        }
      }
    } else {
      s << k << " = \"" << std::string(py::str(value)) << "\"\n";
    }
  }
  return s.str() + tables.str();
}

GoldenModel load(const py::object& config) {
  if (py::isinstance<py::dict>(config)) {
    return GoldenModel::from_toml(toml_of(config.cast<py::dict>()), "dict.toml");
  }
  return GoldenModel(std::string(py::str(config)));
}

// Rows of raw input values: a 2-D array (n, inputs) or a sequence of sequences; one row alone
// (1-D) counts as one vector.
std::vector<std::int64_t> rows_of(const py::object& rows, std::size_t width) {
  const auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(rows);
  if (!a) throw phongsim::Error("rows must be integers (a NumPy array or nested sequences)");
  if (a.ndim() > 2 || (a.ndim() == 2 && static_cast<std::size_t>(a.shape(1)) != width) ||
      (a.ndim() == 1 && static_cast<std::size_t>(a.shape(0)) != width)) {
    throw phongsim::Error(fmt::format("rows must have {} values each", width));
  }
  return {a.data(), a.data() + a.size()};
}

py::array_t<std::int64_t> as_array(const std::vector<std::int64_t>& values, std::size_t width) {
  py::array_t<std::int64_t> out(
      {static_cast<py::ssize_t>(values.size() / width), static_cast<py::ssize_t>(width)});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::list fields_of(const std::vector<phongsim::Field>& fields) {
  py::list l;
  for (const auto& f : fields) l.append(py::make_tuple(f.name, f.fmt.str()));
  return l;
}

phongsim::RtlDesign design_of(const GoldenModel& g, const std::vector<std::string>& rtl,
                              const std::string& top) {
  return g.rtl_design({rtl.begin(), rtl.end()}, top);
}

}  // namespace

PYBIND11_MODULE(phongsim, m) {
  m.doc() =
      "phongsim: bit-accurate golden models of fixed-point pixel-shading pipelines, their "
      "Verilated RTL, co-simulation and width exploration (docs/library.md).";
  py::register_exception<phongsim::Error>(m, "Error", PyExc_ValueError);

  py::class_<GoldenModel>(m, "Model")
      .def(py::init(&load), py::arg("config"),
           "A configuration: a file (configs/<pipeline>/<name>.toml or yours) or a dict with "
           "the file's keys ({'pipeline': 'lirp', 'format': {'p': 'S1.10', ...}, ...}).")
      .def_property_readonly("pipeline",
                             [](const GoldenModel& g) { return std::string(g.pipeline().name); })
      .def_property_readonly("config", [](const GoldenModel& g) { return g.config().origin(); })
      .def_property_readonly(
          "inputs", [](const GoldenModel& g) { return fields_of(g.inputs()); },
          "(name, format) of every input field, in row order")
      .def_property_readonly("outputs", [](const GoldenModel& g) { return fields_of(g.outputs()); })
      .def(
          "eval",
          [](GoldenModel& g, const py::object& rows) {
            return as_array(g.eval_batch(rows_of(rows, g.inputs().size())), g.outputs().size());
          },
          py::arg("rows"),
          "Raw integer input rows (inputs order) -> raw output rows (outputs order), as "
          "`phongsim eval` does for CSV.")
      .def(
          "rtl_eval",
          [](GoldenModel& g, const py::object& rows, const std::vector<std::string>& rtl,
             const std::string& top) {
            const auto in = rows_of(rows, g.inputs().size());
            const auto make_dut =
                g.rtl(design_of(g, rtl, top), phongsim::RtlBuild::if_missing, stderr);
            auto dut = make_dut();
            std::vector<std::int64_t> out;
            const auto r = phongsim::stream_vectors(*dut, g.inputs().size(), g.outputs().size(), in,
                                                    [&](std::span<const std::int64_t> o) {
                                                      out.insert(out.end(), o.begin(), o.end());
                                                    });
            if (r.reason != phongsim::StopReason::finished) throw phongsim::Error(r.message);
            return as_array(out, g.outputs().size());
          },
          py::arg("rows"), py::arg("rtl") = std::vector<std::string>{}, py::arg("top") = "",
          "The same rows through the Verilated RTL (phongsim's, or yours: rtl=[paths], top=...), "
          "Verilated on first use into the content-keyed cache.")
      .def(
          "stages",
          [](GoldenModel& g, const py::object& row) {
            py::dict d;
            for (const auto& s : g.stages(rows_of(row, g.inputs().size()))) {
              d[py::str(s.name)] = py::make_tuple(s.value.raw, s.value.real(), s.value.fmt.str());
            }
            return d;
          },
          py::arg("row"), "Every stage value of one row: {name: (raw, real, format)}.")
      .def(
          "float_error",
          [](const GoldenModel& g, std::uint64_t samples, std::uint64_t seed) {
            const phongsim::ModelError e = g.pipeline().float_error(g.config(), samples, seed);
            py::dict d;
            d["max_lsb"] = e.max_lsb;
            d["mean_lsb"] = e.mean_lsb;
            d["max_abs"] = e.max_abs;
            d["samples"] = e.samples;
            return d;
          },
          py::arg("samples") = 100000, py::arg("seed") = 1,
          "The model against the pipeline's float reference on random in-range inputs (as "
          "sweeps measure it): max and mean error in output LSBs, max absolute error.")
      .def("reset", &GoldenModel::reset)
      .def(
          "vectors",
          [](const GoldenModel& g, std::uint64_t count, std::uint64_t seed, bool directed) {
            const auto stimulus = g.stimulus();
            const std::size_t n = g.inputs().size();
            const std::uint64_t first = directed ? 0 : stimulus.directed_count();
            const std::uint64_t last = stimulus.directed_count() + count;
            std::vector<std::int64_t> rows((last - first) * n);
            for (std::uint64_t i = first; i < last; ++i) {
              stimulus.vector(seed, i, std::span(rows).subspan((i - first) * n, n));
            }
            return as_array(rows, n);
          },
          py::arg("count") = 1000, py::arg("seed") = 1, py::arg("directed") = true,
          "The co-simulation stimulus as rows: the directed corners, then `count` random ones.");

  m.def(
      "cosim",
      [](const py::object& config, std::uint64_t vectors, std::uint64_t seed,
         const std::string& source_idle, const std::string& backpressure,
         const std::vector<std::string>& rtl, const std::string& top) {
        GoldenModel g = load(config);
        const auto stimulus = g.stimulus();
        std::string label;
        auto make_dut =
            g.rtl(design_of(g, rtl, top), phongsim::RtlBuild::if_missing, stderr, &label);
        phongsim::CosimOptions o;
        o.seed = seed;
        o.random_vectors = vectors == 0 ? g.pipeline().default_vectors : vectors;
        o.source = phongsim::StallPattern::parse(source_idle);
        o.sink = phongsim::StallPattern::parse(backpressure);
        const phongsim::CosimReport r =
            phongsim::cosim({std::string(g.pipeline().name), g.config(), g.model(), stimulus,
                             g.pipeline().independent_vectors, make_dut, label, "",
                             g.pipeline().contract(g.model(), g.config())},
                            o);
        py::dict d;
        d["passed"] = r.passed;
        d["summary"] = r.summary();
        d["pipeline"] = r.pipeline;
        d["config"] = r.config_path;
        d["rtl"] = r.rtl_label;
        d["vectors"] = r.vectors;
        d["outputs"] = r.outputs;
        d["in_contract"] = r.contract ? r.contract->in : r.vectors;
        d["out_of_contract"] = r.contract ? r.contract->out() : 0;
        d["mismatches"] = r.mismatches;
        d["cycles"] = r.cycles;
        d["throughput"] = r.throughput;
        d["latency"] = py::make_tuple(r.latency_min, r.latency_max);
        d["failure_kind"] = r.failure_kind;
        d["failure"] = r.failure;
        return d;
      },
      py::arg("config"), py::arg("vectors") = 0, py::arg("seed") = 1,
      py::arg("source_idle") = "none", py::arg("backpressure") = "none",
      py::arg("rtl") = std::vector<std::string>{}, py::arg("top") = "",
      "Co-simulate the configuration's RTL (or yours) against its model, as `phongsim cosim`; "
      "vectors 0: the pipeline's default. Returns the result as a dict.");

  m.def(
      "sweep_point",
      [](const std::string& sweep_file, const std::string& config) {
        const auto spec = phongsim::load_sweep(sweep_file);
        const auto r = phongsim::evaluate_point(spec, config, 0, nullptr);
        return py::module_::import("json").attr("loads")(phongsim::point_result_json(r));
      },
      py::arg("sweep"), py::arg("config"),
      "Evaluate one configuration with a sweep file's error, scene and synthesis settings "
      "(as `phongsim sweep point`); returns the point's metrics as a dict.");

  m.def(
      "format_value",
      [](std::int64_t raw, const std::string& format) {
        return phongsim::value_text(raw, phongsim::fx::Format::parse(format));
      },
      py::arg("raw"), py::arg("format"), "'0x802  -2046 -1.998046875' for raw -2046 in S1.10.");
  m.def(
      "quantize",
      [](double x, const std::string& format) {
        const auto f = phongsim::fx::Format::parse(format);
        return phongsim::fx::quantize(x, f, phongsim::fx::Round::half_even,
                                      phongsim::fx::Overflow::saturate);
      },
      py::arg("x"), py::arg("format"),
      "The raw value of real x in a format: nearest, ties to even, saturating.");
  m.def(
      "data_root", []() { return phongsim::data_root().string(); },
      "phongsim's share/phongsim directory (configs/, rtl/, data/, ...).");
  m.def(
      "to_real",
      [](std::int64_t raw, const std::string& format) {
        return phongsim::fx::to_real(raw, phongsim::fx::Format::parse(format));
      },
      py::arg("raw"), py::arg("format"));
}
