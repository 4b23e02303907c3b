// Ambient light from a scene's environment: diffuse irradiance as 9 spherical-harmonic
// coefficients, specular from a mip-mapped equirectangular texture (both without glints).
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::gl {

// Irradiance E(n) = sum_i c_i Y_i(n) (Ramamoorthi & Hanrahan 2001, "An Efficient Representation
// for Irradiance Environment Maps"): radiance projected on the 9 real SH basis functions of
// bands 0-2 and scaled by the clamped-cosine factors pi, 2pi/3, pi/4. Includes the intensity and
// the rotation.
std::array<glm::vec3, 9> irradianceSh(const scene::Environment& environment);

// Unit direction (+y up) for equirectangular coordinates in [0, 1]^2, rows from the top; the
// inverse of the shader's environmentRadiance() lookup.
glm::vec3 equirectDirection(float u, float v);

}  // namespace glint::gl
