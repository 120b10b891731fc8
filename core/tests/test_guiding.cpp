// Path guiding's SD-tree (guiding.h): the quadtree's sample() and pdf() agree, its pdf is a
// density, and recording concentrates it where radiance was recorded.
#include "torrance/integrator/guiding.h"
#include "torrance/util/sampling.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace torrance {
namespace {

// Radiance from a cone of directions around `peak` (cos > 0.9) over a dim uniform background,
// recorded as a training pass would: directions drawn uniformly, radiance over their pdf.
void record_peak(GuidingField& field, const Vec3& p, const Vec3& peak, int n, Rng& rng) {
  for (int i = 0; i < n; ++i) {
    const Vec3 dir = test::uniform_sphere(rng);
    const float radiance = glm::dot(dir, peak) > 0.9f ? 10.0f : 0.1f;
    field.record(p, dir, radiance * 4.0f * kPi, 0.0f, 0.0f, 0.0f);
  }
}

// A field trained on a peaked distribution at the origin, refined three times.
GuidingField trained_field(const Vec3& peak) {
  GuidingField field(Vec3(-1.0f), Vec3(1.0f));
  Rng rng(1, 2, 3);
  for (int pass = 0; pass < 3; ++pass) {
    record_peak(field, Vec3(0.0f), peak, 20000 << pass, rng);
    field.refine();
  }
  return field;
}

TEST(Guiding, CylindricalMapRoundTrips) {
  Rng rng(7, 0, 0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 d = test::uniform_sphere(rng);
    const Vec3 back = square_to_direction(direction_to_square(d));
    EXPECT_NEAR(glm::dot(d, back), 1.0f, 1e-5f);
  }
}

TEST(Guiding, QuadtreePdfIntegratesToOne) {
  const Vec3 peak = glm::normalize(Vec3(0.3f, -0.5f, 0.8f));
  const GuidingField field = trained_field(peak);
  const GuideDistribution guide = field.at(Vec3(0.0f));
  ASSERT_TRUE(guide);
  // Midpoint rule over the sphere through the square (area 4pi x cell area).
  constexpr int kN = 512;
  double integral = 0.0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      integral += guide.pdf(square_to_direction(Vec2((i + 0.5f) / kN, (j + 0.5f) / kN)));
  integral *= 4.0 * kPi / (double(kN) * kN);
  EXPECT_NEAR(integral, 1.0, 0.01);
}

TEST(Guiding, SamplesFollowThePdf) {
  const Vec3 peak = glm::normalize(Vec3(-0.6f, 0.2f, -0.3f));
  const GuidingField field = trained_field(peak);
  const GuideDistribution guide = field.at(Vec3(0.0f));
  ASSERT_TRUE(guide);
  // Histogram of samples on a 32 x 32 grid of the square vs the pdf integrated over each cell
  // (8 x 8 midpoints); Pearson's chi-square over cells expecting >= 5 (the rest pooled).
  constexpr int kGrid = 32, kSub = 8, kSamples = 400000;
  std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
  Rng rng(11, 0, 0);
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 p = direction_to_square(guide.sample(rng.next_2d()));
    observed[std::min(int(p.y * kGrid), kGrid - 1) * kGrid + std::min(int(p.x * kGrid), kGrid - 1)] += 1.0;
  }
  for (int cy = 0; cy < kGrid; ++cy)
    for (int cx = 0; cx < kGrid; ++cx) {
      double sum = 0.0;
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx)
          sum += guide.pdf(square_to_direction(
              Vec2((cx + (sx + 0.5f) / kSub) / kGrid, (cy + (sy + 0.5f) / kSub) / kGrid)));
      expected[cy * kGrid + cx] = sum * 4.0 * kPi / (double(kGrid) * kGrid * kSub * kSub) * kSamples;
    }
  double chi2 = 0.0, pooled_observed = 0.0, pooled_expected = 0.0;
  int dof = -1;
  for (int i = 0; i < kGrid * kGrid; ++i) {
    if (expected[i] < 5.0) {
      pooled_observed += observed[i];
      pooled_expected += expected[i];
      continue;
    }
    chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++dof;
  }
  if (pooled_expected >= 5.0) {
    chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
    ++dof;
  }
  // Wilson-Hilferty: the chi-square quantile of p = 1e-4 (z = 3.72) for `dof` degrees of freedom.
  const double k = 2.0 / (9.0 * dof), limit = dof * std::pow(1.0 - k + 3.72 * std::sqrt(k), 3.0);
  std::printf("chi-square %.1f, %d dof, limit %.1f\n", chi2, dof, limit);
  EXPECT_LT(chi2, limit);
}

// sample() finds its point's density on the way down, pdf() by a descent of its own: the two agree
// (to rounding: they sum a node's energies in different orders) on trees of many levels, so the
// quadrant each level of sample() chooses is the one holding the point it returns -- except for
// the rare point that origin + u x size rounds onto the edge of the next cell.
TEST(Guiding, SampleReturnsThePdfOfItsPoint) {
  Rng rng(13, 0, 0);
  int samples = 0, disagreeing = 0;
  for (int tree_index = 0; tree_index < 8; ++tree_index) {
    const Vec2 centre = rng.next_2d();
    DirectionalQuadtree tree;
    for (int pass = 0; pass < 4; ++pass) {
      for (int i = 0; i < 20000; ++i) {
        const Vec2 jitter = (rng.next_2d() - Vec2(0.5f)) * 0.05f;
        const Vec2 p = i % 4 ? glm::clamp(centre + jitter, Vec2(0.0f), Vec2(0.999f)) : rng.next_2d();
        tree.record(p, 1.0f);
      }
      tree.build_sums();
      if (pass < 3) tree = tree.refined(0.01f, 20, 1024);
    }
    ASSERT_GT(tree.num_nodes(), 20u);
    for (int i = 0; i < 20000; ++i, ++samples) {
      float pdf = 0.0f;
      const Vec2 p = tree.sample(rng.next_2d(), &pdf);
      ASSERT_GT(pdf, 0.0f);
      if (std::abs(tree.pdf(p) / pdf - 1.0f) > 1e-5f) ++disagreeing;
    }
  }
  std::printf("%d of %d samples on a cell edge\n", disagreeing, samples);
  EXPECT_LT(disagreeing, samples / 1000);
}

TEST(Guiding, RecordingConcentratesTheDensityWhereRadianceCameFrom) {
  const Vec3 peak = glm::normalize(Vec3(0.2f, 0.9f, 0.1f));
  const GuidingField field = trained_field(peak);
  const GuideDistribution guide = field.at(Vec3(0.0f));
  ASSERT_TRUE(guide);
  // The cone holds 10 x 0.05 of the sphere against 0.1 x 0.95: 84% of the energy.
  Rng rng(5, 0, 0);
  int inside = 0;
  constexpr int kSamples = 20000;
  for (int i = 0; i < kSamples; ++i) inside += glm::dot(guide.sample(rng.next_2d()), peak) > 0.9f;
  std::printf("share of samples in the cone: %.3f\n", double(inside) / kSamples);
  EXPECT_GT(double(inside) / kSamples, 0.75);
  EXPECT_GT(guide.pdf(peak), 10.0f * guide.pdf(-peak));
  // The dim background keeps a density.
  EXPECT_GT(guide.pdf(-peak), 0.0f);
}

// Threads record in any order; the learned guide must not depend on it (else the same seed gives
// another image). The same records, of magnitudes over six decades, forwards and backwards: the
// same densities bit for bit, and the same BSDF fraction.
TEST(Guiding, TheOrderOfRecordsDoesNotChangeTheGuide) {
  struct Record {
    Vec3 dir;
    float radiance_over_pdf, estimate, bsdf_pdf, guide_pdf;
  };
  std::vector<Record> records;
  Rng rng(7, 1, 2);
  for (int i = 0; i < 50000; ++i) {
    const Vec3 dir = test::uniform_sphere(rng);
    const float magnitude = std::pow(10.0f, 6.0f * rng.next_1d() - 3.0f);
    records.push_back({dir, magnitude, magnitude * rng.next_1d(), 0.1f + rng.next_1d(), 0.1f + rng.next_1d()});
  }
  std::vector<GuidingField> fields;
  for (bool backwards : {false, true}) {
    GuidingField field(Vec3(-1.0f), Vec3(1.0f));
    for (int pass = 0; pass < 3; ++pass) {
      for (size_t k = 0; k < records.size(); ++k) {
        const Record& r = records[backwards ? records.size() - 1 - k : k];
        field.record(Vec3(0.0f), r.dir, r.radiance_over_pdf, r.estimate, r.bsdf_pdf, pass > 0 ? r.guide_pdf : 0.0f);
      }
      field.refine();
    }
    fields.push_back(std::move(field));
  }
  const GuideDistribution forwards = fields[0].at(Vec3(0.0f), true), backwards = fields[1].at(Vec3(0.0f), true);
  ASSERT_TRUE(forwards && backwards);
  EXPECT_EQ(forwards.bsdf_fraction(), backwards.bsdf_fraction());
  int differ = 0;
  for (int i = 0; i < 10000; ++i) {
    const Vec3 dir = test::uniform_sphere(rng);
    differ += forwards.pdf(dir) != backwards.pdf(dir);
  }
  EXPECT_EQ(differ, 0) << "of 10000 directions";
}

TEST(Guiding, EachLeafChoosesTheBsdfFractionOfLeastSecondMoment) {
  const Vec3 peak(0, 0, 1);
  for (bool guide_helps : {true, false}) {
    GuidingField field = trained_field(peak);
    ASSERT_EQ(field.at(Vec3(0.0f)).bsdf_fraction(), kInitialBsdfFraction);
    // Light arrives where the guide's density is high and the BSDF's low, or the other way round.
    const float bsdf_pdf = guide_helps ? 0.05f : 2.0f, guide_pdf = guide_helps ? 2.0f : 0.05f;
    for (int i = 0; i < 1000; ++i) field.record(Vec3(0.0f), peak, 0.0f, 1.0f, bsdf_pdf, guide_pdf);
    field.refine();
    const GuideDistribution guide = field.at(Vec3(0.0f));
    if (guide_helps) {
      ASSERT_TRUE(guide);
      EXPECT_EQ(guide.bsdf_fraction(), kBsdfFractions.front());
    } else {
      EXPECT_FALSE(guide) << "a useless guide is switched off (fraction 1)";
    }
  }
}

TEST(Guiding, AfterTheDecisionPassGuidingGoesOnOnlyIfItPromisesASaving) {
  for (bool guide_helps : {true, false}) {
    GuidingOptions options;
    options.decision_pass = 2;
    GuidingField field(Vec3(-1.0f), Vec3(1.0f), options);
    const float bsdf_pdf = guide_helps ? 0.05f : 2.0f, guide_pdf = guide_helps ? 2.0f : 0.05f;
    for (int pass = 1; pass <= 2; ++pass) {
      for (int i = 0; i < 1000; ++i) field.record(Vec3(0.0f), Vec3(0, 0, 1), 1.0f, 1.0f, bsdf_pdf, guide_pdf);
      const bool go_on = field.refine();
      if (pass < options.decision_pass) EXPECT_TRUE(go_on) << "only the decision pass decides";
      else EXPECT_EQ(go_on, guide_helps) << "guide helps: " << guide_helps;
    }
  }
}

TEST(Guiding, RecordsAreWeightedByTheirPixelsRelativeError) {
  EXPECT_FLOAT_EQ(pixel_weight(Vec3(0.0f)), 10.0f);  // 1 / sqrt(0 + 0.01)
  EXPECT_NEAR(pixel_weight(Vec3(10.0f)), 1.0f / std::sqrt(100.01f), 1e-6f);
  // Paths of a bright pixel (estimate 10) find radiance 10 from above, paths of a dark one
  // (estimate 0.1) find 0.1 from below: by absolute radiance below would get 1 % of the density,
  // by relative error (each divided by sqrt(estimate^2 + 0.01)) 10 / sqrt(100.01) against
  // 0.1 / sqrt(0.02): 0.71 of above's.
  const Vec3 up(0.0f, 0.0f, 1.0f), down(0.0f, 0.0f, -1.0f);
  GuidingField field(Vec3(-1.0f), Vec3(1.0f));
  for (int i = 0; i < 100; ++i) {
    for (const float value : {10.0f, 0.1f}) {
      GuidePathRecorder path(&field, pixel_weight(Vec3(value)));
      path.add_vertex(field.at(Vec3(0.0f)).leaf(), direction_to_square(value > 1.0f ? up : down), Vec3(1.0f),
                      Vec3(1.0f), 1.0f, 1.0f, 0.0f);
      path.add_contribution(Vec3(value));
    }  // recorded here
  }
  field.refine();
  const GuideDistribution guide = field.at(Vec3(0.0f));
  ASSERT_TRUE(guide);
  const float ratio = guide.pdf(down) / guide.pdf(up);
  std::printf("guide density below / above: %.3f\n", ratio);
  EXPECT_NEAR(ratio, 0.1f / std::sqrt(0.02f) / (10.0f / std::sqrt(100.01f)), 0.02f);
}

TEST(Guiding, NothingRecordedMeansNoGuide) {
  GuidingField field(Vec3(-1.0f), Vec3(1.0f));
  EXPECT_FALSE(field.at(Vec3(0.0f)));
  field.refine();
  EXPECT_FALSE(field.at(Vec3(0.0f)));
}

TEST(Guiding, ManyRecordsSplitSpaceAndEachHalfLearnsItsOwnDirection) {
  GuidingOptions options;
  options.spatial_threshold = 1000.0f;
  GuidingField field(Vec3(-1.0f), Vec3(1.0f), options);
  Rng rng(3, 0, 0);
  const Vec3 up(0, 0, 1), down(0, 0, -1);
  for (int pass = 0; pass < 3; ++pass) {
    record_peak(field, Vec3(-0.5f, 0.0f, 0.0f), up, 5000, rng);
    record_peak(field, Vec3(0.5f, 0.0f, 0.0f), down, 5000, rng);
    field.refine();
  }
  EXPECT_GT(field.num_leaves(), 1u);
  const GuideDistribution left = field.at(Vec3(-0.5f, 0.0f, 0.0f)), right = field.at(Vec3(0.5f, 0.0f, 0.0f));
  ASSERT_TRUE(left);
  ASSERT_TRUE(right);
  EXPECT_GT(left.pdf(up), 5.0f * left.pdf(down));
  EXPECT_GT(right.pdf(down), 5.0f * right.pdf(up));
}

}  // namespace
}  // namespace torrance
