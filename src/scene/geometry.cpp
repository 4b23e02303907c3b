#include "scene/geometry.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <utility>

namespace glint::scene {

namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

// Squared lengths below this count as zero: far below any real mesh's features (1e-10 m^2), far
// above float round-off of unit vectors' differences.
constexpr float kDegenerate = 1e-20f;

// The unit vector a fraction `turn` of a full turn from the unit vector `first` towards the unit
// vector `second` (perpendicular to it). A whole turn gives `first` exactly (float's 2 pi would not
// give cos 1, sin 0), so rings of vertices close without cracks.
glm::vec3 turned(glm::vec3 first, glm::vec3 second, float turn) {
  const float angle = turn >= 1.0f ? 0.0f : kTwoPi * turn;
  return std::cos(angle) * first + std::sin(angle) * second;
}

}  // namespace

glm::vec3 anyPerpendicular(glm::vec3 n) {
  // Cross with the axis least aligned with n, so the result is never near zero.
  const glm::vec3 a = glm::abs(n);
  const glm::vec3 axis = (a.x <= a.y && a.x <= a.z) ? glm::vec3(1, 0, 0)
                         : (a.y <= a.z)             ? glm::vec3(0, 1, 0)
                                                    : glm::vec3(0, 0, 1);
  return glm::normalize(glm::cross(n, axis));
}

void generateTangents(Mesh& mesh) {
  std::vector<glm::vec3> dpdu(mesh.vertices.size(), glm::vec3(0.0f));
  std::vector<glm::vec3> dpdv(mesh.vertices.size(), glm::vec3(0.0f));
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const std::uint32_t index[3] = {mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]};
    const Vertex& v0 = mesh.vertices[index[0]];
    const Vertex& v1 = mesh.vertices[index[1]];
    const Vertex& v2 = mesh.vertices[index[2]];
    const glm::vec3 e1 = v1.position - v0.position;
    const glm::vec3 e2 = v2.position - v0.position;
    const glm::vec2 d1 = v1.uv - v0.uv;
    const glm::vec2 d2 = v2.uv - v0.uv;
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 0.0f) || !std::isfinite(det)) continue;  // degenerate uvs: no information
    // Solve [e1 e2] = [dP/du dP/dv] [d1 d2] for the two derivatives.
    const glm::vec3 du = (e1 * d2.y - e2 * d1.y) / det;
    const glm::vec3 dv = (e2 * d1.x - e1 * d2.x) / det;
    if (!std::isfinite(glm::dot(du, du)) || !std::isfinite(glm::dot(dv, dv))) continue;
    // Weight by area so that slivers do not dominate; derivatives themselves are size-independent.
    const float area = 0.5f * glm::length(glm::cross(e1, e2));
    for (std::uint32_t k : index) {
      dpdu[k] += du * area;
      dpdv[k] += dv * area;
    }
  }
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    Vertex& v = mesh.vertices[k];
    glm::vec3 t = dpdu[k] - v.normal * glm::dot(v.normal, dpdu[k]);
    const float length2 = glm::dot(t, t);
    if (!(length2 > kDegenerate) || !std::isfinite(length2)) {
      v.tangent = glm::vec4(anyPerpendicular(v.normal), 1.0f);
      continue;
    }
    t /= std::sqrt(length2);
    // glTF: the bitangent cross(n, t) * w points towards decreasing v (up in the image).
    const float w = glm::dot(glm::cross(v.normal, t), -dpdv[k]) < 0.0f ? -1.0f : 1.0f;
    v.tangent = glm::vec4(t, w);
  }
}

void makeFlatShaded(Mesh& mesh) {
  std::vector<Vertex> vertices;
  vertices.reserve(mesh.indices.size());
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    Vertex corner[3] = {mesh.vertices[mesh.indices[i]], mesh.vertices[mesh.indices[i + 1]],
                        mesh.vertices[mesh.indices[i + 2]]};
    const glm::vec3 n = glm::cross(corner[1].position - corner[0].position, corner[2].position - corner[0].position);
    const float length2 = glm::dot(n, n);
    const glm::vec3 normal = (length2 > kDegenerate && std::isfinite(length2)) ? n / std::sqrt(length2)
                                                                                 : glm::vec3(0, 1, 0);
    for (Vertex& v : corner) {
      v.normal = normal;
      vertices.push_back(v);
    }
  }
  mesh.vertices = std::move(vertices);
  mesh.indices.resize(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
}

std::vector<glm::vec3> smoothNormals(const Mesh& mesh) {
  std::vector<glm::vec3> sums(mesh.vertices.size(), glm::vec3(0.0f));
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const glm::vec3& p0 = mesh.vertices[mesh.indices[i]].position;
    const glm::vec3& p1 = mesh.vertices[mesh.indices[i + 1]].position;
    const glm::vec3& p2 = mesh.vertices[mesh.indices[i + 2]].position;
    const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);  // length = twice the area: area weighting
    for (std::size_t k = 0; k < 3; ++k) sums[mesh.indices[i + k]] += n;
  }
  for (glm::vec3& n : sums) {
    const float length2 = glm::dot(n, n);
    n = (length2 > kDegenerate && std::isfinite(length2)) ? n / std::sqrt(length2) : glm::vec3(0, 1, 0);
  }
  return sums;
}

void appendMesh(Mesh& into, const Mesh& from) {
  const auto offset = static_cast<std::uint32_t>(into.vertices.size());
  into.vertices.insert(into.vertices.end(), from.vertices.begin(), from.vertices.end());
  for (std::uint32_t index : from.indices) into.indices.push_back(offset + index);
}

Mesh makeParametricSurface(std::string name, int material, int columns, int rows, const Surface& surface) {
  assert(columns >= 1 && rows >= 1);
  Mesh mesh;
  mesh.name = std::move(name);
  mesh.material = material;
  mesh.vertices.reserve(static_cast<std::size_t>(columns + 1) * static_cast<std::size_t>(rows + 1));
  for (int j = 0; j <= rows; ++j) {
    // j / rows is exactly 0 and 1 at the ends, so surfaces can snap their poles.
    const float t = static_cast<float>(j) / static_cast<float>(rows);
    for (int i = 0; i <= columns; ++i) {
      const float s = static_cast<float>(i) / static_cast<float>(columns);
      const SurfacePoint point = surface(s, t);
      Vertex v;
      v.position = point.position;
      v.normal = glm::normalize(point.normal);
      v.uv = point.uv;
      v.tangent = glm::vec4(0.0f);
      mesh.vertices.push_back(v);
    }
  }
  auto at = [columns](int i, int j) { return static_cast<std::uint32_t>(j * (columns + 1) + i); };
  auto addTriangle = [&mesh](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Vertex& va = mesh.vertices[a];
    const Vertex& vb = mesh.vertices[b];
    const Vertex& vc = mesh.vertices[c];
    if (va.position == vb.position || vb.position == vc.position || vc.position == va.position) return;
    // Wind so that the geometric normal agrees with the surface's normals: callers then need not
    // care which way their parameters turn.
    const glm::vec3 geometric = glm::cross(vb.position - va.position, vc.position - va.position);
    if (glm::dot(geometric, va.normal + vb.normal + vc.normal) < 0.0f) std::swap(b, c);
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
  };
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      addTriangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      addTriangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  generateTangents(mesh);
  return mesh;
}

Mesh makeSurfaceFromPositions(std::string name, int material, int columns, int rows, bool periodicT,
                              const std::function<glm::vec3(float s, float t)>& position,
                              const std::function<glm::vec3(float s, float t)>& inside,
                              const std::function<glm::vec3(float s, float t)>& poleNormal,
                              const std::function<glm::vec2(float s, float t)>& uv) {
  constexpr float kStep = 1e-3f;
  return makeParametricSurface(std::move(name), material, columns, rows, [&](float s, float t) {
    const glm::vec3 p = position(s, t);
    const glm::vec3 alongS = position(std::min(s + kStep, 1.0f), t) - position(std::max(s - kStep, 0.0f), t);
    const glm::vec3 alongT = periodicT ? position(s, t + kStep) - position(s, t - kStep)
                                       : position(s, std::min(t + kStep, 1.0f)) - position(s, std::max(t - kStep, 0.0f));
    glm::vec3 normal = glm::cross(alongS, alongT);
    const float length2 = glm::dot(normal, normal);
    // Differences that vanish against the size of the steps: a pole, or a fold.
    const float scale = glm::dot(alongS, alongS) * glm::dot(alongT, alongT);
    if (!(length2 > 1e-6f * scale) || !(length2 > kDegenerate)) {
      normal = poleNormal(s, t);
    } else if (glm::dot(normal, p - inside(s, t)) < 0.0f) {
      normal = -normal;
    }
    return SurfacePoint{p, normal, uv(s, t)};
  });
}

Mesh splitOffTriangles(Mesh& mesh, std::string name, int material, const std::function<bool(std::size_t)>& picked) {
  Mesh pickedMesh;
  pickedMesh.name = std::move(name);
  pickedMesh.material = material;
  Mesh kept;
  kept.name = mesh.name;
  kept.material = mesh.material;
  // New index of each old vertex in either mesh, or none yet.
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> inPicked(mesh.vertices.size(), kNone), inKept(mesh.vertices.size(), kNone);
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const bool goes = picked(i / 3);
    Mesh& into = goes ? pickedMesh : kept;
    std::vector<std::uint32_t>& map = goes ? inPicked : inKept;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t old = mesh.indices[i + k];
      if (map[old] == kNone) {
        map[old] = static_cast<std::uint32_t>(into.vertices.size());
        into.vertices.push_back(mesh.vertices[old]);
      }
      into.indices.push_back(map[old]);
    }
  }
  mesh = std::move(kept);
  return pickedMesh;
}

Mesh makeQuad(std::string name, int material, glm::vec3 centre, glm::vec3 halfU, glm::vec3 halfV, glm::vec2 uvExtent) {
  const glm::vec3 normal = glm::normalize(glm::cross(halfV, halfU));
  return makeParametricSurface(std::move(name), material, 1, 1, [=](float s, float t) {
    return SurfacePoint{centre + (2.0f * s - 1.0f) * halfU + (2.0f * t - 1.0f) * halfV, normal, glm::vec2(s, t) * uvExtent};
  });
}

Mesh makeBox(std::string name, int material, glm::vec3 centre, glm::vec3 halfSize, float uvPerMetre) {
  Mesh box;
  box.name = name;
  box.material = material;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 n(0.0f);
      n[axis] = sign;
      // Side faces keep +y up in their texture; the top and bottom take -z and +z as up. Then
      // halfV = -up and halfU = up x n give cross(halfV, halfU) = n, the outward normal.
      const glm::vec3 up = axis == 1 ? glm::vec3(0, 0, -sign) : glm::vec3(0, 1, 0);
      const glm::vec3 uAxis = glm::cross(up, n);
      const glm::vec3 halfU = uAxis * glm::dot(glm::abs(uAxis), halfSize);
      const glm::vec3 halfV = -up * glm::dot(glm::abs(up), halfSize);
      const glm::vec2 uvExtent = 2.0f * uvPerMetre * glm::vec2(glm::length(halfU), glm::length(halfV));
      appendMesh(box, makeQuad(name, material, centre + n * halfSize[axis], halfU, halfV, uvExtent));
    }
  }
  return box;
}

Mesh makeUvSphere(std::string name, int material, glm::vec3 centre, float radius, int segments, int rings,
                  glm::vec2 uvExtent) {
  return makeParametricSurface(std::move(name), material, segments, rings, [=](float s, float t) {
    const float phi = kTwoPi * s;
    const float theta = std::numbers::pi_v<float> * t;
    // Exact zeros at the poles, so that their vertices coincide and their slivers are dropped.
    const float sinTheta = (t <= 0.0f || t >= 1.0f) ? 0.0f : std::sin(theta);
    const glm::vec3 direction(sinTheta * std::sin(phi), std::cos(theta), sinTheta * std::cos(phi));
    return SurfacePoint{centre + radius * direction, direction, glm::vec2(s, t) * uvExtent};
  });
}

Mesh makeTorus(std::string name, int material, glm::vec3 centre, glm::vec3 axis, float majorRadius, float minorRadius,
               int segments, int sides, float uvPerMetre) {
  const glm::vec3 first = anyPerpendicular(axis);
  const glm::vec3 second = glm::cross(axis, first);
  const glm::vec2 uvExtent = uvPerMetre * kTwoPi * glm::vec2(majorRadius, minorRadius);
  Mesh torus = makeParametricSurface(std::move(name), material, segments, sides, [=](float s, float t) {
    // The last row and column repeat the first ones' positions exactly; only their uvs run on.
    const glm::vec3 radial = turned(first, second, s);
    const glm::vec3 normal = turned(radial, axis, t);
    return SurfacePoint{centre + majorRadius * radial + minorRadius * normal, normal, glm::vec2(s, t) * uvExtent};
  });
  // The generated tangents follow the chords of the grid, which at the seam come from one side
  // only (a segment's half angle off); the ring's own direction there is known exactly. The
  // generated handedness stays.
  for (Vertex& v : torus.vertices) {
    const glm::vec3 offset = v.position - centre;
    const glm::vec3 along = glm::normalize(glm::cross(axis, offset - axis * glm::dot(axis, offset)));
    v.tangent = glm::vec4(along, v.tangent.w);
  }
  return torus;
}

Mesh makeLathe(std::string name, int material, glm::vec3 centre, int segments, int rings,
               const std::function<ProfilePoint(float t)>& profile) {
  return makeParametricSurface(std::move(name), material, rings, segments, [&](float t, float s) {
    const ProfilePoint p = profile(t);
    const float angle = kTwoPi * s;
    const glm::vec3 radial(0.0f, std::cos(angle), std::sin(angle));
    return SurfacePoint{centre + glm::vec3(p.x, 0.0f, 0.0f) + p.radius * radial,
                        glm::vec3(p.normal.x, 0.0f, 0.0f) + p.normal.y * radial, glm::vec2(t, s)};
  });
}

Mesh makeCone(std::string name, int material, glm::vec3 base, glm::vec3 axis, float baseRadius, float length, int segments) {
  const glm::vec3 first = anyPerpendicular(axis);
  const glm::vec3 second = glm::cross(axis, first);
  return makeParametricSurface(std::move(name), material, segments, 1, [=](float s, float t) {
    const glm::vec3 radial = turned(first, second, s);
    const float radius = t >= 1.0f ? 0.0f : baseRadius * (1.0f - t);  // an exact zero closes the tip
    // Perpendicular to the slant line, which runs -baseRadius along radial per length along axis.
    const glm::vec3 normal = length * radial + baseRadius * axis;
    return SurfacePoint{base + t * length * axis + radius * radial, normal, glm::vec2(s, t)};
  });
}

}  // namespace glint::scene
