/*
 * Switching between stacks, for the coroutines of polling.c. On x86-64 a few instructions save the
 * callee-saved registers and swap stack pointers (a switch costs what a function call does); other
 * machines, or a build with VS_POLLING_UCONTEXT defined, use POSIX ucontext (slower: it saves the
 * signal mask with a system call).
 */
#ifndef SIMCORE_CONTEXT_SWITCH_H
#define SIMCORE_CONTEXT_SWITCH_H

#include <stddef.h>

#if !defined(__x86_64__) && !defined(VS_POLLING_UCONTEXT)
#define VS_POLLING_UCONTEXT 1
#endif

#ifdef VS_POLLING_UCONTEXT
#include <ucontext.h>
typedef struct vs_co_context {
  ucontext_t uc;
} vs_co_context;
#else
typedef struct vs_co_context {
  void* sp; /* the saved stack pointer: the registers lie on the stack above it */
} vs_co_context;
#endif

/* Prepares `ctx` to run entry(arg) on the stack [stack, stack + size) at its first switch; entry
 * must never return (it switches away for good). */
void vs_co_make(vs_co_context* ctx, void* stack, size_t size, void (*entry)(void*), void* arg);
/* Saves the running context in `from` and continues `to`. */
void vs_co_switch(vs_co_context* from, vs_co_context* to);

#endif
