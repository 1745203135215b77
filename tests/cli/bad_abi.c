/* A block program built for a block ABI that does not exist (tests/cli): vsim must refuse it. */
#include "simcore/blockcode.h"

static const vs_blockcode bad_abi_code = {999, "bad-abi", 0, NULL, NULL, NULL, NULL};

const vs_blockcode* vs_blockcode_entry(void) { return &bad_abi_code; }
