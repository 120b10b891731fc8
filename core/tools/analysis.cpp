// torrance_analysis OUTDIR: tables comparing the PAPER and PRINCIPLED models, as CSV files that
// scripts/analysis plots (docs/analysis/). Every value comes from the models' own code.
#include "torrance/bsdfs/albedo.h"

#include <cstdio>
#include <string>

using namespace torrance;

namespace {

Vec3 in_plane(float theta_deg) {  // a direction in the x-z plane at theta from the normal
  const float t = theta_deg * kPi / 180.0f;
  return Vec3(std::sin(t), 0.0f, std::cos(t));
}

Material material(Vec3 color, float metallic, float roughness) {
  Material m;
  m.base_color = color;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

FILE* open_csv(const std::string& dir, const char* name, const char* header) {
  const std::string path = dir + "/" + name;
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) {
    std::perror(path.c_str());
    std::exit(1);
  }
  std::fprintf(f, "%s\n", header);
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: torrance_analysis OUTDIR\n");
    return 2;
  }
  const std::string dir = argv[1];

  // D, G and F terms against angle.
  FILE* terms = open_csv(dir, "terms.csv", "roughness,theta_deg,D,G1_paper,G1_principled,F_paper,F_principled");
  for (float r : {0.2f, 0.5f, 0.8f})
    for (int i = 0; i <= 180; ++i) {
      const float theta = i * 0.5f;
      const float c = std::cos(theta * kPi / 180.0f);
      const CookTorranceBsdf paper(material(Vec3(0.8f), 0.0f, r));
      const PrincipledBsdf principled(material(Vec3(0.8f), 0.0f, r));
      std::fprintf(terms, "%g,%g,%g,%g,%g,%g,%g\n", r, theta, ggx::D(in_plane(theta), r * r), paper.geometry_G1(c),
                   ggx::smith_G1(c, r * r), paper.fresnel(c).x, principled.fresnel(c).x);
    }
  std::fclose(terms);

  // The full BRDF (f * cos_i) in the plane of incidence, wo at 45 degrees.
  FILE* slices = open_csv(dir, "brdf_slices.csv", "material,roughness,theta_i_deg,paper,principled");
  const Vec3 wo = in_plane(-45.0f);
  for (int kind = 0; kind < 2; ++kind)
    for (float r : {0.2f, 0.5f, 0.8f}) {
      const Material m = material(kind ? Vec3(0.9f, 0.6f, 0.3f) : Vec3(0.8f), float(kind), r);
      const MaterialBsdf paper(m, BrdfModel::Paper), principled(m, BrdfModel::Principled);
      for (int i = 0; i <= 178; ++i) {
        const float theta = i * 0.5f;
        const Vec3 wi = in_plane(theta);
        std::fprintf(slices, "%s,%g,%g,%g,%g\n", kind ? "metal" : "dielectric", r, theta, paper.eval(wo, wi).x,
                     principled.eval(wo, wi).x);
      }
    }
  std::fclose(slices);

  // Directional albedo (white furnace), by quadrature.
  FILE* albedo = open_csv(dir, "albedo.csv", "model,material,roughness,cos_o,albedo");
  for (BrdfModel model : {BrdfModel::Paper, BrdfModel::Principled})
    for (int kind = 0; kind < 2; ++kind)
      for (int ri = 1; ri <= 20; ++ri) {
        const float r = ri * 0.05f;
        const MaterialBsdf bsdf(material(Vec3(1.0f), float(kind), r), model);
        for (float c : {1.0f, 0.5f, 0.1f}) {
          const float s = std::sqrt(1.0f - c * c);
          std::fprintf(albedo, "%s,%s,%g,%g,%.5f\n", model == BrdfModel::Paper ? "PAPER" : "PRINCIPLED",
                       kind ? "metal" : "dielectric", r, c,
                       directional_albedo_quadrature(bsdf, Vec3(s, 0.0f, c), r * r, 256, 128));
        }
      }
  std::fclose(albedo);
  std::printf("torrance_analysis: wrote terms.csv, brdf_slices.csv, albedo.csv to %s\n", dir.c_str());
  return 0;
}
