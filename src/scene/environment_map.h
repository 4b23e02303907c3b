// Environment maps (HDRIs): the equirectangular mapping both renderers use, reading .hdr and .exr
// maps, a procedural sky with a sun, and the rasteriser's split of a map into directional lights
// for its brightest small regions plus the rest (docs/renderer.md, "HDRI environments").
#pragma once

#include <array>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::scene {

// The equirectangular mapping, +y up, rows from the top: u = atan(d.x, -d.z) / 2pi + 1/2,
// v = acos(d.y) / pi (shaders/environment.glsl reads the map the same way), and its inverse.
glm::vec2 equirectFromDirection(glm::vec3 d);
glm::vec3 directionFromEquirect(glm::vec2 uv);
// The solid angle of a texel of row y in a width x height map: (2pi / width) (pi / height) sin(theta)
// at the row's centre.
double equirectTexelSolidAngle(int y, int width, int height);

// A .hdr or .exr file as an environment (intensity 1, no rotation). Throws Error with one line
// naming the file and the problem (glint::readRadianceImage).
Environment loadEnvironmentMap(const std::filesystem::path& path);

// The built-in scenes' sky radiance at an elevation (radians): a blue zenith fading to a pale
// horizon, grey ground below.
glm::vec3 skyRadiance(float elevation);

// A sky (skyRadiance) with a sun: a disc of `sunDiameterDegrees` at `sunAzimuthDegrees` to the left
// of -z and `sunElevationDegrees` above the horizon, of uniform radiance such that it gives
// `sunIrradiance` (W/m^2) on a plane facing it; its edge texels are covered in part (16 samples).
struct SunSky {
  int width = 512;
  int height = 256;
  float sunElevationDegrees = 35.0f;
  float sunAzimuthDegrees = 30.0f;
  float sunDiameterDegrees = 2.0f;
  float sunIrradiance = 8.0f;
};
Environment sunSkyEnvironment(const SunSky& sky);
// A photo studio: a dim grey backdrop (0.05 above the horizon, 0.02 below) and kStudioSoftboxes
// uniformly emitting rectangles in azimuth and elevation, 12 to 60 degrees wide, the softboxes of
// a product shot (docs/cli.md, `glint hdri --preset studio`).
struct Softbox {
  float azimuthDegrees;    // the centre, to the left of -z as SunSky's
  float elevationDegrees;
  float widthDegrees;      // in azimuth
  float heightDegrees;     // in elevation
  float radiance;          // white
};
inline constexpr Softbox kStudioSoftboxes[] = {
    {160.0f, 30.0f, 60.0f, 35.0f, 4.0f},   // key, behind the camera to its left
    {-145.0f, 15.0f, 40.0f, 30.0f, 2.5f},  // fill, behind the camera to its right
    {25.0f, 40.0f, 25.0f, 16.0f, 6.0f},    // rim, behind the subject
    {-70.0f, 62.0f, 12.0f, 12.0f, 10.0f},  // a small top light
};
Environment studioEnvironment(int width, int height);
// An overcast sky: the CIE standard overcast sky's radiance, (1 + 2 sin(elevation)) / 3 of the
// zenith's (zenith 1), over a dark grey ground (0.1).
Environment overcastEnvironment(int width, int height);
glm::vec3 sunSkyDirection(const SunSky& sky);  // unit, towards the sun

// A map split into directional lights for its brightest small regions and the rest.
//
// Bright texels are those whose luminance exceeds kEnvironmentLightContrast times the map's mean
// (weighted by solid angle); they group into regions of edge-connected texels (u wraps around). A
// region becomes a light when it covers at most kEnvironmentLightMaxSolidAngle and holds at least
// kEnvironmentLightMinPower of the map's power; the `maxLights` most powerful are taken.
//
// Each region's background L_bg is the mean radiance of the texels bordering it that are not
// bright. The light carries the region's radiance above it: over a small region of solid angle
// Omega, the reflected radiance integral f(wi) L(wi) cos(theta_i) d(omega) has f and cos nearly
// constant, so it is f(wc) cos(theta_c) E with E = sum over texels of (L_i - L_bg) omega_i: a
// directional light of irradiance E (W/m^2 on a plane facing it, scene::Light's unit) from the
// region's centroid wc (the texels' directions weighted by their luminance above L_bg times omega_i).
// The residual map holds L_bg in the region's texels, so map + lights = the original map's power
// (no light is counted twice); its intensity and rotation are the environment's, the lights'
// intensities include them and their directions are in the world.
inline constexpr float kEnvironmentLightContrast = 20.0f;
inline constexpr double kEnvironmentLightMaxSolidAngle = 0.05;  // sr: a cone of 7.2 degrees half-angle
inline constexpr double kEnvironmentLightMinPower = 0.02;       // of the map's luminance power
struct EnvironmentLights {
  std::vector<Light> lights;          // directional
  std::vector<double> solidAngles;    // each light's region, sr
  std::vector<double> powerFractions; // each light's share of the map's luminance power
  Environment residual;
};
EnvironmentLights extractEnvironmentLights(const Environment& environment, int maxLights);

// The rectangles of a map (its residual after extractEnvironmentLights) whose glints the rasteriser
// draws (docs/method.md, "Extended lights"). The map (averaged on a grid of at most
// kEnvironmentRegionGridWidth x half as many cells: the map itself up to 512 x 256), from eight
// tiles of 90 x 90 degrees, is split k-d into kEnvironmentRegionLeaves
// rectangles, each cut where its two halves' luminance spread (solid-angle weighted squared
// deviation from their mean) sums least, so that each is of nearly constant radiance; then the
// brightest of them, up to maxRegions and only those brighter than the map's mean, are taken, a
// rectangle wider than kEnvironmentRegionMaxExtent halved first. Each carries its mean radiance
// (times the environment's intensity). The rasteriser lights both lobes of every material with the
// regions analytically and prefilters `residual` (and takes its irradiance), the map less each
// region's mean radiance over its texels, so that a region's power is counted once. A uniform
// environment has none.
inline constexpr int kEnvironmentRegionGridWidth = 512;
inline constexpr int kEnvironmentRegionLeaves = 32;
inline constexpr double kEnvironmentRegionMaxExtent = 1.05;  // radians, 60 degrees
struct EnvironmentRegion {
  std::array<glm::vec3, 4> corners;  // unit world directions, in order around the rectangle
  glm::vec3 radiance{0.0f};          // mean, W/(m^2 sr), the environment's intensity included
  double solidAngle = 0.0;           // sr
};
struct EnvironmentRegions {
  std::vector<EnvironmentRegion> regions;
  Environment residual;
};
EnvironmentRegions environmentGlintRegions(const Environment& environment, int maxRegions);

}  // namespace glint::scene
