/*
 * arbor/arbor.h - the whole Arbor plugin SDK, version 1.
 *
 * Include this one header to write a plugin.  See sdk/docs/plugin-guide.md for
 * a walk-through and sdk/examples/ for a complete plugin in plain C.
 */
#ifndef ARBOR_ARBOR_H
#define ARBOR_ARBOR_H

#include "abi.h"
#include "branch_tree.h"
#include "depictor.h"
#include "filter.h"
#include "host.h"
#include "image.h"
#include "importer.h"
#include "params.h"
#include "plugin.h"
#include "renderer.h"
#include "simplifier.h"
#include "transfer_function.h"
#include "volume.h"

#endif /* ARBOR_ARBOR_H */
