// Glints under an environment map: the map as glint's rasteriser splits it (docs/renderer.md,
// "HDRI environments"), written by `glint env-regions MAP -o NAME.json` (NAME.json and the residual
// map NAME.exr): its brightest small regions as DirectionalLights, its brightest larger regions
// (softboxes, windows) as regions whose glints MeshGlintMaterial draws (the kernel's
// glint_extended_lights.h, as under a RectAreaLight), and the rest as the scene's environment, which
// three prefilters: smooth, as in glint. A region's light is counted once: the residual lacks it.
import { DirectionalLight, EquirectangularReflectionMapping, FloatType, Vector3 } from 'three';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';

// The most regions a program draws, as glint's rasteriser (gl::kMaxEnvironmentRegions).
const MAX_REGIONS = 16;

// glint env-regions's coordinates, (u, v) from the map's left and top edges, as the direction three
// looks the map up in (its equirectangular mapping, the texture's rows bottom up).
export function mapDirection([u, v]) {
  const phi = 2 * Math.PI * (u - 0.5);
  const radius = Math.sin(Math.PI * v);
  return new Vector3(radius * Math.cos(phi), Math.cos(Math.PI * v), radius * Math.sin(phi));
}

// The environment `glint env-regions` wrote at `url` (its JSON; the residual map beside it): a
// promise of { residual (an equirectangular float texture), lights: [{ direction (towards the light),
// irradiance: [r, g, b] }], regions: [{ corners: 4 unit directions, radiance: [r, g, b] }] }.
export async function loadGlintEnvironment(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: cannot fetch the glint environment (HTTP ${response.status})`);
  let description;
  try {
    description = await response.json();
  } catch (error) {
    throw new Error(`${url}: not a glint environment (${error.message})`);
  }
  if (!Array.isArray(description.regions) || !Array.isArray(description.lights) || typeof description.residual !== 'string') {
    throw new Error(`${url}: not a glint environment (no regions, lights and residual; write it with glint env-regions)`);
  }
  const numbers = (value, count) => Array.isArray(value) && value.length === count && value.every(Number.isFinite);
  description.lights.forEach((light, i) => {
    if (!numbers(light.uv, 2) || !numbers(light.irradiance, 3)) {
      throw new Error(`${url}: light ${i} needs uv (2 numbers) and irradiance (3 numbers)`);
    }
  });
  description.regions.forEach((region, i) => {
    if (!Array.isArray(region.corners) || region.corners.length !== 4 || !region.corners.every((c) => numbers(c, 2)) ||
        !numbers(region.radiance, 3)) {
      throw new Error(`${url}: region ${i} needs 4 corners (2 numbers each) and radiance (3 numbers)`);
    }
  });
  if (description.regions.length > MAX_REGIONS) {
    throw new Error(`${url}: ${description.regions.length} regions, more than the ${MAX_REGIONS} a program draws (glint env-regions --regions)`);
  }
  const page = typeof document !== 'undefined' ? document.baseURI : undefined;  // none in node
  const residualUrl = new URL(description.residual, new URL(url, page)).href;
  const loader = new EXRLoader();
  loader.setDataType(FloatType);
  const residual = await loader.loadAsync(residualUrl).catch((error) => {
    throw new Error(`${residualUrl}: cannot load the residual map (${error.message})`);
  });
  residual.mapping = EquirectangularReflectionMapping;
  return {
    residual,
    lights: description.lights.map((light) => ({ direction: mapDirection(light.uv), irradiance: light.irradiance })),
    regions: description.regions.map((region) => ({ corners: region.corners.map(mapDirection), radiance: region.radiance })),
  };
}

// Lights `scene` with the environment: a DirectionalLight for each of its lights, and for the glint
// materials its regions and the residual (scene.userData.glintEnvironment, which MeshGlintMaterial
// reads when it draws: the residual becomes its envMap, unless it has one of its own). The scene's
// environment, which every other material reflects, is `map` (the whole map, as three loads it),
// else the residual: then other materials lack the regions' light. `intensity` scales all of it, as
// scene.environmentIntensity would the map alone. Returns the lights it added.
export function applyGlintEnvironment(scene, environment, { intensity = 1, map = null } = {}) {
  scene.environment = map || environment.residual;
  scene.environmentIntensity = intensity;
  const added = environment.lights.map(({ direction, irradiance }) => {
    const strongest = Math.max(...irradiance, 1e-30);
    const light = new DirectionalLight(0xffffff, strongest * intensity);
    light.color.setRGB(irradiance[0] / strongest, irradiance[1] / strongest, irradiance[2] / strongest);
    light.position.copy(direction).multiplyScalar(100);  // from far along its direction, at the origin
    scene.add(light);
    return light;
  });
  // As the glint programs' uniforms take them (src/material.js): every region's corners in turn,
  // and each one's radiance.
  scene.userData.glintEnvironment = {
    residual: environment.residual,
    intensity,
    corners: environment.regions.flatMap(({ corners }) => corners),
    radiances: environment.regions.map(({ radiance }) => new Vector3(...radiance).multiplyScalar(intensity)),
  };
  return added;
}
