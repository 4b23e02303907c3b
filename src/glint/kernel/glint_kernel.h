// The whole kernel in one include, for a host's shaders or C++ and for `glint shader-bundle`
// (docs/integration.md): the 2020 model (glint_brdf.h) with the 2021 anti-aliasing
// (glint_antialiasing.h), material parameters (glint_material.h), glTF surfaces (surface.h), targets
// and masking (microfacet.h, microfacet_targets.h), multiple scattering (multiple_scattering.h,
// albedo_tables.h), normal-map filtering, lights, display encoding and the procedural dictionary. A
// shading-language host defines the dictionary hook (prelude.h). The Zirr & Kaplanyan 2016 baseline
// (zirr_kaplanyan.h) is not included: a host that wants it includes it too.
#ifndef GLINT_KERNEL_GLINT_KERNEL_H
#define GLINT_KERNEL_GLINT_KERNEL_H

#include "prelude.h"
#include "random.h"
#include "microfacet.h"
#include "microfacet_targets.h"
#include "multiple_scattering.h"
#include "dictionary_lookup.h"
#include "glint_antialiasing.h"
#include "glint_brdf.h"
#include "glint_material.h"
#include "surface.h"
#include "normal_map_filtering.h"
#include "lights.h"
#include "tonemap.h"
#include "procedural_dictionary.h"

#endif
