// Every feature node, by axis. Each axis header documents its nodes with the seed they come
// from; ../shared/docs/water-models.md has the formulas and golden values.
#pragma once

#include "watergen/water/nodes/caustics.h"
#include "watergen/water/nodes/extinction.h"
#include "watergen/water/nodes/foam.h"
#include "watergen/water/nodes/fresnel.h"
#include "watergen/water/nodes/normals.h"
#include "watergen/water/nodes/reflection.h"
#include "watergen/water/nodes/refraction.h"
#include "watergen/water/nodes/shore.h"
#include "watergen/water/nodes/specular.h"
#include "watergen/water/nodes/waves.h"
