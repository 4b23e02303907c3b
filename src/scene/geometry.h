// Mesh building blocks shared by the glTF loader and the built-in scenes: the one tangent
// generator, flat normals, and parametric surfaces (quads, boxes, UV spheres, tori, cones, lathes) with
// analytic normals.
#pragma once

#include <functional>
#include <string>

#include "scene/scene.h"

namespace glint::scene {

// Per-vertex tangents from the uv derivatives of the triangles around each vertex (weighted by
// triangle area), made orthogonal to the vertex normal (Gram-Schmidt). w is the glTF handedness:
// cross(normal, tangent.xyz) * w points along -dP/dv, towards the top of a texture image. A vertex
// whose triangles have degenerate uvs gets some unit tangent perpendicular to its normal, w = +1.
// Normals must already be unit length.
void generateTangents(Mesh& mesh);

// Some unit vector perpendicular to the unit vector n (deterministic).
glm::vec3 anyPerpendicular(glm::vec3 n);

// glTF's rule for primitives without normals: flat shading. Every triangle gets three vertices of
// its own carrying the face normal (a degenerate triangle gets +y); uvs and tangents are copied.
void makeFlatShaded(Mesh& mesh);

// Area-weighted average of the face normals around each vertex, unit length; +y for a vertex
// that touches only degenerate triangles. Used to repair zero-length normals.
std::vector<glm::vec3> smoothNormals(const Mesh& mesh);

// Appends `from`'s vertices and triangles to `into` (material and name of `into` are kept).
void appendMesh(Mesh& into, const Mesh& from);

// A point of a parametric surface at parameters (s, t) in [0, 1]^2.
struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 normal;  // need not be unit length; must not be zero
  glm::vec2 uv;
};
using Surface = std::function<SurfacePoint(float s, float t)>;

// A (columns + 1) x (rows + 1) grid of surface points, two triangles per cell, each wound
// counter-clockwise as seen from the side its normals point to; triangles with two coincident
// corners (the poles of a sphere) are left out. Tangents are generated.
Mesh makeParametricSurface(std::string name, int material, int columns, int rows, const Surface& surface);

// A surface given by its positions alone, P(s, t) on [0, 1]^2, meshed as makeParametricSurface
// does: each vertex's normal is the cross product of central differences of P (steps of 1e-3, one
// side at the edges of [0, 1]; t wraps around when `periodicT`), turned to point away from
// `inside(s, t)`; where the differences vanish (a pole) the normal is `poleNormal(s, t)`.
Mesh makeSurfaceFromPositions(std::string name, int material, int columns, int rows, bool periodicT,
                              const std::function<glm::vec3(float s, float t)>& position,
                              const std::function<glm::vec3(float s, float t)>& inside,
                              const std::function<glm::vec3(float s, float t)>& poleNormal,
                              const std::function<glm::vec2(float s, float t)>& uv);

// The triangles of `mesh` for which `picked(triangle index)` holds, as a mesh of their own named
// `name` with `material`, and `mesh` without them; each keeps only the vertices it uses, in order.
Mesh splitOffTriangles(Mesh& mesh, std::string name, int material, const std::function<bool(std::size_t)>& picked);

// A parallelogram centred at `centre` spanning +-halfU and +-halfV; uv runs over [0, uvExtent] along
// halfU and halfV (v grows along +halfV); the normal is cross(halfV, halfU) normalised, so a floor
// with halfU = +x and halfV = +z faces +y.
Mesh makeQuad(std::string name, int material, glm::vec3 centre, glm::vec3 halfU, glm::vec3 halfV,
              glm::vec2 uvExtent = glm::vec2(1.0f));

// An axis-aligned box, six outward quads; uvs in metres times uvPerMetre on each face.
Mesh makeBox(std::string name, int material, glm::vec3 centre, glm::vec3 halfSize, float uvPerMetre);

// A UV sphere: uv = (phi / 2 pi, theta / pi) * uvExtent with theta from the +y pole, phi = 0 at +z
// and growing towards +x, so that the texture is not mirrored seen from outside. uvExtent
// (2 pi r, pi r) gives uvs in metres along the equator and the meridians.
Mesh makeUvSphere(std::string name, int material, glm::vec3 centre, float radius, int segments, int rings,
                  glm::vec2 uvExtent = glm::vec2(1.0f));

// A torus (a ring of tube): the circle of radius majorRadius around `centre` in the plane
// perpendicular to the unit vector `axis`, swept by a tube of radius minorRadius, `segments` quads
// around the ring and `sides` around the tube. uv in metres times uvPerMetre: u = arc length
// along the ring's centre line (the tangent runs along it), v = arc length around the tube, so
// that a texture or a glint pattern keeps its proportions on a thin tube. The ring starts
// (u = 0) at anyPerpendicular(axis) from the centre.
Mesh makeTorus(std::string name, int material, glm::vec3 centre, glm::vec3 axis, float majorRadius, float minorRadius,
               int segments, int sides, float uvPerMetre = 1.0f);

// A cone from the circle of radius baseRadius around `base` in the plane perpendicular to the unit
// vector `axis` to its tip at base + length * axis, open at the base: uv = (angle / 2 pi, t) with
// t from the base (0) to the tip (1); the tip's coincident vertices leave no slivers.
Mesh makeCone(std::string name, int material, glm::vec3 base, glm::vec3 axis, float baseRadius, float length, int segments);

// A point of a lathe profile at t in [0, 1]: its abscissa along the axis, its radius (>= 0) and
// the profile's outward normal in the (axis, radius) plane.
struct ProfilePoint {
  float x;
  float radius;
  glm::vec2 normal;
};
// A body of revolution around the x axis through `centre`: u = t along the profile, v = angle / 2 pi.
Mesh makeLathe(std::string name, int material, glm::vec3 centre, int segments, int rings,
               const std::function<ProfilePoint(float t)>& profile);

}  // namespace glint::scene
