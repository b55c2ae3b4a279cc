// The renderer: a pinhole camera, one Embree primary ray per pixel centre against every
// patch, and the radiosity of the leaf element hit (its polynomial evaluated at the hit
// point). Back sides of the one-sided patches show black. Tone mapping: a linear exposure
// that maps the 97th percentile of the pixels' largest channel to 1 (or a given exposure),
// clamping, then gamma 2.2; the PNG is encoded with stb_image_write.
#pragma once

#include <string>
#include <vector>

#include "radiosity/hierarchy.h"
#include "radiosity/scene.h"

namespace radquad {

struct RadianceImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, top row first, linear radiosity
};

RadianceImage renderRadiosity(const Hierarchy& hierarchy, const Camera& camera);

// The automatic exposure: 1 over the 97th percentile of the pixels' largest channel (1 for a
// black image).
double automaticExposure(const RadianceImage& image);

// exposure <= 0: automatic. Returns the PNG file's bytes.
std::string encodePng(const RadianceImage& image, double exposure = 0.0, double gamma = 2.2);

}  // namespace radquad
