// The directional-albedo tables of the multiple-scattering compensation (kernel/multiple_scattering.h,
// Kulla & Conty 2017), computed by glint: E(mu, alpha), the albedo of the single-scattering
// Cook-Torrance lobe of each smooth target and masking with F = 1, on the grid the kernel reads,
// and E_avg(alpha), its cosine-weighted mean. `glint albedo-tables` writes them as the kernel header
// kernel/albedo_tables.h (docs/method.md, "Multiple scattering").
#pragma once

#include <string>
#include <vector>

namespace glint {

// E(mu, alpha) = integral of f(wo, wi) wi.z dwi for wo at cos theta = mu, isotropic alpha, no
// correlation, F = 1, by quadrature over the half vector's slope plane (substituted r = alpha
// sinh t out to 1e4 alpha, so that GGX's tail is included). Deterministic.
double singleScatteringAlbedo(int ndf, int masking, double alpha, double mu);

struct AlbedoTables {
  // [table][alpha node][mu node], table = 2 ndf + masking; nodes as kernel/multiple_scattering.h.
  std::vector<float> albedo;
  // [table][alpha node]: 2 integral of E mu dmu of the kernel's own interpolation of `albedo`.
  std::vector<float> average;
};
AlbedoTables computeAlbedoTables();

// The text of kernel/albedo_tables.h for these tables.
std::string albedoTablesHeader(const AlbedoTables& tables);

}  // namespace glint
