/* modelc runtime: everything a front end needs. */
#ifndef MODELC_H
#define MODELC_H
#include "config.h"
#include "fixed.h"
#include "trig.h"
#include "scene.h"
#include "view.h"
#include "render.h"
#include "finish.h"
#endif
