/* modelc runtime: everything a front end needs. */
#ifndef MODELC_H
#define MODELC_H
#include "config.h"
#include "fixed.h"
#include "trig.h"
#include "bits.h"
#include "chunk.h"
#include "xform.h"
#include "target.h"
#include "octree.h"
#include "pmesh.h"
#include "model.h"
#include "octree_render.h"
#include "finish.h"
#include "raster.h"
#include "line.h"
#include "mesh_render.h"
#include "mesh_lines.h"
#endif
