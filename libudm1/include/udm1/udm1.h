/*
 * udm1/udm1.h - public C interface of libudm1: includes every part.
 *
 *   udm1/core.h     version, export macro, status codes, the last error
 *   udm1/seq.h      sequences: presets, creation, random access, fills, cursor, generator check
 *   udm1/stream.h   one stream of a sequence, drawn per sample inline (a renderer's pixel)
 *   udm1/domain.h   domains: keyed sub-samplers of a stream's sample, up to four dimensions each
 *   udm1/metrics.h  discrepancies, distances, integrands, integration error, spectra, zone plate
 *   udm1/noise.h    lattice noise, POV-Ray patterns and colour maps
 *   udm1/cellular.h cellular (Worley) noise
 *
 * An embedder may include this header or only the parts it uses.
 *
 * libudm1 generates uniformly-distributed-modulo-1 (Weyl/Kronecker) sample
 * sequences for computer graphics, exactly, at any index, behind a stable C ABI.
 *
 * This header compiles as C99 and C++. Everything it declares is prefixed udm1_
 * or UDM1_. Nothing else is exported from the shared library.
 *
 * The sequence contract (the arithmetic every value follows, randomization, threads
 * and errors) is at the top of udm1/seq.h.
 */
#ifndef UDM1_UDM1_H
#define UDM1_UDM1_H

#include "udm1/core.h"
#include "udm1/seq.h"
#include "udm1/stream.h"
#include "udm1/domain.h"
#include "udm1/metrics.h"
#include "udm1/exact_sum.h"
#include "udm1/lattice_bound.h"
#include "udm1/noise.h"
#include "udm1/cellular.h"

#endif /* UDM1_UDM1_H */
