// Every feature node, by axis. Each axis header documents its nodes with the seed they come
// from; ../shared/docs/water-models.md has the formulas and golden values.
#pragma once

#include "watergen/nodes/extinction.h"
#include "watergen/nodes/foam.h"
#include "watergen/nodes/fresnel.h"
#include "watergen/nodes/normals.h"
#include "watergen/nodes/reflection.h"
#include "watergen/nodes/refraction.h"
#include "watergen/nodes/shore.h"
#include "watergen/nodes/specular.h"
#include "watergen/nodes/waves.h"
