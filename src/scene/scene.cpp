#include "scene/scene.h"

#include <limits>

namespace glint::scene {

glm::vec3 Scene::boundsMin() const {
  glm::vec3 low(std::numeric_limits<float>::max());
  for (const Mesh& mesh : meshes) {
    for (const Vertex& v : mesh.vertices) low = glm::min(low, v.position);
  }
  return low;
}

glm::vec3 Scene::boundsMax() const {
  glm::vec3 high(std::numeric_limits<float>::lowest());
  for (const Mesh& mesh : meshes) {
    for (const Vertex& v : mesh.vertices) high = glm::max(high, v.position);
  }
  return high;
}

}  // namespace glint::scene
