/* The seam between `meld` and the module that compiles Meld source (libmeld_frontend.so: the
 * front end, the checks and the lowering of meldc, with the ANTLR runtime). meld loads it only
 * when it is given a .meld file, so that running bytecode or native code neither loads the ANTLR
 * runtime nor builds its parser tables (half the instructions of a tiny run). Both sides come
 * from one build: the program comes back as the C++ object it is, and the version guards against
 * a stale module. */
#pragma once

#include <stddef.h>

#define MELD_FRONTEND_MODULE_VERSION 1

#ifdef __cplusplus
extern "C" {
#endif

/* Receives the diagnostics' text (file:line:col: ...), once, after the compilation. */
typedef void (*meld_frontend_report)(const char* text, size_t size, void* context);

/* What meld_frontend_compile returns. */
enum {
  MELD_FRONTEND_COMPILED = 0,      /* *program is a meldvm::Program* the caller now owns */
  MELD_FRONTEND_ERRORS = 1,        /* the program has errors: see the report */
  MELD_FRONTEND_INTERNAL_ERROR = 2 /* the compiled program fails the verifier: see error */
};

typedef int (*meld_frontend_version_fn)(void);
/* Compiles the file at `path` (the -I folders, then the standard library; -D NAME=VALUE pairs)
 * into a verified program. Never throws. */
typedef int (*meld_frontend_compile_fn)(const char* path, const char* const* include_dirs,
                                        size_t include_count, const char* const* define_names,
                                        const char* const* define_values, size_t define_count,
                                        meld_frontend_report report, void* context, void** program,
                                        char* error, size_t error_size);

#ifdef __cplusplus
}
#endif
