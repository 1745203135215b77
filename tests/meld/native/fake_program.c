/* Shared objects that claim to be native Meld programs but are not loadable ones (meld.cli.native):
 * built with FAKE_ABI (another native ABI version), FAKE_BYTECODE (bytecode that is not bytecode)
 * or FAKE_MAGIC (a wrong magic word). */
#include "meldvm/native_abi.h"

static const uint8_t not_bytecode[8] = {'n', 'o', 't', ' ', 'm', 'b', 'c', '!'};

static const meld_native_program_desc description = {
#ifdef FAKE_MAGIC
    0x12345678u,
#else
    MELD_NATIVE_MAGIC,
#endif
#ifdef FAKE_ABI
    MELD_NATIVE_ABI_VERSION + 98u,
#else
    MELD_NATIVE_ABI_VERSION,
#endif
    FAKE_BYTECODE_VERSION,
    0,
    not_bytecode,
    sizeof not_bytecode,
    0};

const meld_native_program_desc* meld_native_program(void) { return &description; }
