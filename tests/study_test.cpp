// phongsim study (sim/render/study.h): the Wilson interval against published values, scenes as a
// pure function of (seed, index) whatever the number of jobs, and the claims' bookkeeping.
#include "sim/render/study.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <regex>
#include <string>

#include "base/error.h"
#include "base/vec3.h"

namespace phongsim {
namespace {

// Wilson score intervals at 95 % (z = 1.96), as tabulated by Newcombe (1998), Table I
// method 3, and Brown, Cai and DasGupta (2001): 5/10 -> 0.2366..0.7634, 0/10 -> 0..0.2775,
// 81/263 -> 0.2553..0.3662.
TEST(Study, WilsonIntervalMatchesPublishedValues) {
  const auto [lo5, hi5] = wilson_interval(5, 10);
  EXPECT_NEAR(lo5, 0.2366, 5e-5);
  EXPECT_NEAR(hi5, 0.7634, 5e-5);
  const auto [lo0, hi0] = wilson_interval(0, 10);
  EXPECT_EQ(lo0, 0.0);
  EXPECT_NEAR(hi0, 0.2775, 5e-5);
  const auto [lo, hi] = wilson_interval(81, 263);
  EXPECT_NEAR(lo, 0.2553, 5e-5);
  EXPECT_NEAR(hi, 0.3662, 5e-5);
  EXPECT_EQ(wilson_interval(0, 0), std::make_pair(0.0, 1.0));  // no scenes: nothing known
}

TEST(Study, ScenesDependOnSeedAndIndexOnly) {
  StudyOptions one{.scenes = 3, .seed = 7, .size = 32, .jobs = 1};
  StudyOptions more = one;
  more.scenes = 5;
  more.jobs = 3;
  const auto none = [](std::uint64_t, std::uint64_t) {};
  const StudyResult a = run_study(one, none), b = run_study(more, none);
  ASSERT_EQ(a.scenes.size(), 3U);
  ASSERT_EQ(b.scenes.size(), 5U);
  for (std::size_t i = 0; i < a.scenes.size(); ++i) {
    EXPECT_EQ(a.scenes[i].file, b.scenes[i].file) << i;
    EXPECT_EQ(a.scenes[i].holds, b.scenes[i].holds) << i;
    EXPECT_EQ(a.scenes[i].difference, b.scenes[i].difference) << i;
  }
  more.seed = 8;
  EXPECT_NE(run_study(more, none).scenes[0].file, b.scenes[0].file);
}

TEST(Study, ClaimsCountWhereTheyApplyAndHold) {
  const StudyResult r =
      run_study({.scenes = 6, .seed = 1, .size = 32, .jobs = 2}, [](auto, auto) {});
  ASSERT_EQ(r.claims.size(), study_claims().size());
  for (std::size_t c = 0; c < r.claims.size(); ++c) {
    std::uint64_t applies = 0, holds = 0;
    for (const StudyScene& s : r.scenes) {
      applies += s.applies[c] ? 1 : 0;
      holds += s.holds[c] ? 1 : 0;
      EXPECT_EQ(s.holds[c], s.applies[c] && s.difference[c] > 0) << study_claims()[c].name;
    }
    EXPECT_EQ(r.claims[c].scenes, applies);
    EXPECT_EQ(r.claims[c].holds, holds);
  }
}

// The first "<key> = [x, y, z]" in a scene file.
Vec3 VectorIn(const std::string& text, const std::string& key) {
  std::smatch m;
  const std::regex re(key + R"( = \[([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\])");
  EXPECT_TRUE(std::regex_search(text, m, re)) << key << " in\n" << text;
  return {std::stod(m[1]), std::stod(m[2]), std::stod(m[3])};
}

// Lyon's glancing claim is judged on each closed mesh's glancing variant: the same scene lit by
// one light behind it, 130 to 160 degrees from the view, so that light and view graze the
// surface where the highlight is; the triangle, seen from the front, has none. The scene itself
// keeps its own lights.
TEST(Study, GlancingVariantsAreLitFromBehind) {
  const StudyResult r =
      run_study({.scenes = 8, .seed = 1, .size = 32, .jobs = 2}, [](auto, auto) {});
  const auto& claims = study_claims();
  const auto glancing = static_cast<std::size_t>(
      std::find_if(claims.begin(), claims.end(),
                   [](const StudyClaim& c) { return c.name == "lyon-row10-loses-glancing"; }) -
      claims.begin());
  ASSERT_LT(glancing, claims.size());
  int judged = 0;
  for (const StudyScene& s : r.scenes) {
    if (s.mesh == "triangle") {
      EXPECT_TRUE(s.glancing_file.empty()) << s.index;
      EXPECT_FALSE(s.applies[glancing]) << s.index;
      continue;
    }
    ASSERT_FALSE(s.glancing_file.empty()) << s.index;
    EXPECT_EQ(s.applies[glancing], s.shininess > 4) << s.index;
    judged += s.applies[glancing] ? 1 : 0;
    // Closed meshes are centred on the origin, the camera's target.
    const Vec3 eye = VectorIn(s.glancing_file, "eye");
    const Vec3 light = VectorIn(s.glancing_file, "position");
    const double degrees =
        std::acos(dot(normalized(eye), normalized(light))) * 180 / std::numbers::pi;
    EXPECT_GE(degrees, 130 - 0.01) << s.index;
    EXPECT_LE(degrees, 160 + 0.01) << s.index;
    EXPECT_EQ(s.glancing_file.find("[[light]]"), s.glancing_file.rfind("[[light]]")) << s.index;
    EXPECT_EQ(VectorIn(s.file, "eye").x, eye.x) << s.index;  // the same camera
    EXPECT_EQ(s.file.find("glancing"), std::string::npos) << s.index;
  }
  EXPECT_GT(judged, 0);
}

TEST(Study, RefusesOutOfRangeOptions) {
  const auto none = [](std::uint64_t, std::uint64_t) {};
  EXPECT_THROW((void)run_study({.scenes = 0}, none), Error);
  EXPECT_THROW((void)run_study({.scenes = 1, .size = 8}, none), Error);
}

}  // namespace
}  // namespace phongsim
