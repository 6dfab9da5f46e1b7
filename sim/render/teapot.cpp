#include "sim/render/teapot.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "base/error.h"
#include "base/file_util.h"
#include "base/paths.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void fail_at(const fs::path& file, int line, const std::string& what) {
  throw Error(fmt::format("{}:{}: {}", file.string(), line, what));
}

// Line-oriented text: lines without their "\n" or "\r\n", numbered from 1.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  [[nodiscard]] int number() const { return number_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int number_ = 0;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    const std::size_t start = i;
    while (i < s.size() && !is_space(s[i])) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

// from_chars refuses a leading '+', which some writers emit.
std::string_view strip_plus(std::string_view tok) {
  return tok.size() > 1 && tok[0] == '+' && tok[1] != '-' ? tok.substr(1) : tok;
}

std::optional<double> parse_double(std::string_view tok) {
  tok = strip_plus(tok);
  double v = 0;
  const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (ec != std::errc() || end != tok.data() + tok.size() || !std::isfinite(v)) {
    return std::nullopt;
  }
  return v;
}

std::optional<long long> parse_integer(std::string_view tok) {
  tok = strip_plus(tok);
  long long v = 0;
  const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (ec != std::errc() || end != tok.data() + tok.size()) return std::nullopt;
  return v;
}

// ---- Bézier evaluation ----

// Cubic Bernstein basis and its derivative at t, with s = 1 - t passed in (so that grid points
// t = k/n, s = (n-k)/n are both correctly rounded and basis(t, s) mirrors basis(s, t) exactly).
struct Basis {
  std::array<double, 4> b;
  std::array<double, 4> d;
};

Basis basis(double t, double s) {
  Basis r;
  r.b = {s * (s * s), 3 * t * (s * s), 3 * s * (t * t), t * (t * t)};
  r.d = {-3 * (s * s), 3 * (s * s) - 6 * (s * t), 6 * (s * t) - 3 * (t * t), 3 * (t * t)};
  return r;
}

// Σ w[k]·q[k], summed in mirror-symmetric pairs so that a curve shared by two patches that run
// it in opposite directions evaluates to the same bits.
Vec3 combine4(const std::array<double, 4>& w, const Vec3 q[4]) {
  return (w[0] * q[0] + w[3] * q[3]) + (w[1] * q[1] + w[2] * q[2]);
}

struct SurfacePoint {
  Vec3 p, su, sv;
};

SurfacePoint evaluate(const BezierPatch& patch, const Basis& bu, const Basis& bv) {
  Vec3 row_p[4], row_d[4];
  for (int i = 0; i < 4; ++i) {
    const Vec3* row = &patch.p[static_cast<std::size_t>(4 * i)];
    row_p[i] = combine4(bu.b, row);
    row_d[i] = combine4(bu.d, row);
  }
  return {combine4(bv.b, row_p), combine4(bv.b, row_d), combine4(bv.d, row_p)};
}

// The unnormalized normal cross(Su, Sv) at grid point (u, v); at a degenerate point (a collapsed
// control row makes Su or Sv vanish) the normal a small step into the patch. Zero if every step
// fails (the caller then falls back to face normals).
Vec3 patch_normal(const BezierPatch& patch, const SurfacePoint& sp, double u, double v,
                  double tiny) {
  Vec3 n = cross(sp.su, sp.sv);
  if (length(n) > tiny) return n;
  for (const double step : {1e-5, 1e-3, 1e-2}) {
    const double u2 = u < 0.5 ? u + step : u - step;
    const double v2 = v < 0.5 ? v + step : v - step;
    const SurfacePoint q = evaluate(patch, basis(u2, 1 - u2), basis(v2, 1 - v2));
    n = cross(q.su, q.sv);
    if (length(n) > tiny) return n;
  }
  return {};
}

}  // namespace

std::vector<BezierPatch> read_bpt_patches(const fs::path& path) {
  const std::string text = read_file(path, "file");
  Lines lines(text);
  std::string_view line;
  // The next line that is not blank, split into tokens; fails at the end of the file.
  const auto next_tokens = [&](const std::string& expected) {
    while (lines.next(line)) {
      auto tokens = split_ws(line);
      if (!tokens.empty()) return tokens;
    }
    fail_at(path, lines.number(), fmt::format("file ends where {} was expected", expected));
  };
  auto tokens = next_tokens("the patch count");
  const auto count = parse_integer(tokens[0]);
  if (tokens.size() != 1 || !count || *count < 1 || *count > 100000) {
    fail_at(path, lines.number(), "expected the patch count (an integer in [1, 100000])");
  }
  std::vector<BezierPatch> patches(static_cast<std::size_t>(*count));
  for (std::size_t k = 0; k < patches.size(); ++k) {
    tokens = next_tokens(fmt::format("patch {}'s degrees", k + 1));
    if (tokens.size() != 2 || tokens[0] != "3" || tokens[1] != "3") {
      fail_at(path, lines.number(),
              fmt::format("patch {}: expected the degrees '3 3' (only bicubic patches)", k + 1));
    }
    for (Vec3& p : patches[k].p) {
      tokens = next_tokens(fmt::format("a control point of patch {}", k + 1));
      if (tokens.size() != 3) {
        fail_at(path, lines.number(),
                fmt::format("patch {}: a control point needs 3 coordinates, got {}", k + 1,
                            tokens.size()));
      }
      double c[3];
      for (int i = 0; i < 3; ++i) {
        const auto v = parse_double(tokens[i]);
        if (!v) fail_at(path, lines.number(), fmt::format("malformed number '{}'", tokens[i]));
        c[i] = *v;
      }
      p = {c[0], c[1], c[2]};
    }
  }
  while (lines.next(line)) {
    if (!split_ws(line).empty()) {
      fail_at(path, lines.number(), fmt::format("unexpected data after {} patches", *count));
    }
  }
  return patches;
}

Mesh tessellate(const std::vector<BezierPatch>& patches, int resolution) {
  if (resolution < 1 || resolution > 256) {
    throw Error(fmt::format("Bézier tessellation: resolution {} outside [1, 256]", resolution));
  }
  const int n = resolution;
  std::vector<Basis> grid(static_cast<std::size_t>(n + 1));
  for (int k = 0; k <= n; ++k) {
    grid[k] = basis(static_cast<double>(k) / n, static_cast<double>(n - k) / n);
  }
  Mesh raw;
  Vec3 lo{1e300, 1e300, 1e300}, hi = -lo;
  for (const BezierPatch& patch : patches) {
    Vec3 plo = patch.p[0], phi = patch.p[0];
    for (const Vec3& q : patch.p) {
      plo = {std::min(plo.x, q.x), std::min(plo.y, q.y), std::min(plo.z, q.z)};
      phi = {std::max(phi.x, q.x), std::max(phi.y, q.y), std::max(phi.z, q.z)};
    }
    lo = {std::min(lo.x, plo.x), std::min(lo.y, plo.y), std::min(lo.z, plo.z)};
    hi = {std::max(hi.x, phi.x), std::max(hi.y, phi.y), std::max(hi.z, phi.z)};
    const double size = length(phi - plo);
    const double tiny = 1e-12 * size * size;
    const int base = static_cast<int>(raw.positions.size());
    for (int iv = 0; iv <= n; ++iv) {
      for (int iu = 0; iu <= n; ++iu) {
        const SurfacePoint sp = evaluate(patch, grid[iu], grid[iv]);
        raw.positions.push_back(sp.p);
        raw.normals.push_back(patch_normal(patch, sp, static_cast<double>(iu) / n,
                                           static_cast<double>(iv) / n, tiny));
      }
    }
    // Cell corners a = (u, v), b = (u + du, v), c = (u + du, v + dv), d = (u, v + dv): (a, b, c)
    // and (a, c, d) turn from u towards v, so their normals follow cross(Su, Sv).
    for (int iv = 0; iv < n; ++iv) {
      for (int iu = 0; iu < n; ++iu) {
        const int a = base + iv * (n + 1) + iu, b = a + 1, d = a + n + 1, c = d + 1;
        raw.triangles.push_back({a, b, c});
        raw.triangles.push_back({a, c, d});
      }
    }
  }
  if (patches.empty()) return raw;
  const double eps = 1e-9 * std::max(length(hi - lo), 1e-300);
  Mesh m = weld(raw, eps, 0.5);  // crease: normals more than 60° apart stay separate
  check(m);
  return m;
}

Mesh read_teapot_bpt(const fs::path& path, int resolution) {
  Mesh m = tessellate(read_bpt_patches(path), resolution);
  if (m.triangles.empty()) throw Error(fmt::format("{}: no triangles", path.string()));
  const auto rotate = [](Vec3 v) { return Vec3{v.x, v.z, -v.y}; };
  for (Vec3& p : m.positions) p = rotate(p);
  for (Vec3& nrm : m.normals) nrm = rotate(nrm);
  return m;
}

Mesh teapot(int resolution) {
  return read_teapot_bpt(data_root() / "data" / "teapot.bpt",
                         resolution == 0 ? kTeapotDefaultResolution : resolution);
}

}  // namespace phongsim
