// The prepare pass (wavefront/prepare.comp): a single invocation between passes that turns a
// queue's counter into indirect dispatch arguments and resets the counters the next pass appends
// to. Declared once for the shader and the host (host/wavefront/passes/prepare_pass.cpp).
#ifndef MIXTRACE_WAVEFRONT_PREPARE_INTERFACE_H
#define MIXTRACE_WAVEFRONT_PREPARE_INTERFACE_H
#include "shared/path_state.h"

#define PREPARE_BUFFERS(X) BUFFER_QUEUE_STATE(X)

SHARED_BEGIN
// PrepareConstants.queue: which queue the next pass reads.
const uint kPrepareRays = 0u;     // the extension rays, before intersect + shade
const uint kPrepareShadows = 1u;  // the shadow rays, before shadow
const uint kPrepareShade = 2u;    // the rays intersect queued for shade, before shade (where it queues them)

struct PrepareConstants {
  uint queue;    // kPrepareRays, kPrepareShade or kPrepareShadows
  uint queueIn;  // kPrepareRays: which ray queue (0/1) the next intersect and shade read
};
SHARED_END
#endif
