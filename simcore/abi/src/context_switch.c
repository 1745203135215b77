#include "context_switch.h"

#include <stdint.h>
#include <stdlib.h>

#ifdef VS_POLLING_UCONTEXT

/* makecontext passes int arguments only: the pointers travel in two halves. */
static void ucontext_entry(unsigned lo, unsigned hi, unsigned flo, unsigned fhi) {
  void* arg = (void*)(((uintptr_t)hi << 32) | lo);
  void (*entry)(void*) = (void (*)(void*))(((uintptr_t)fhi << 32) | flo);
  entry(arg);
  abort();
}

void vs_co_make(vs_co_context* ctx, void* stack, size_t size, void (*entry)(void*), void* arg) {
  getcontext(&ctx->uc);
  ctx->uc.uc_stack.ss_sp = stack;
  ctx->uc.uc_stack.ss_size = size;
  ctx->uc.uc_link = NULL;
  const uintptr_t a = (uintptr_t)arg, f = (uintptr_t)entry;
  makecontext(&ctx->uc, (void (*)(void))ucontext_entry, 4, (unsigned)a, (unsigned)(a >> 32), (unsigned)f,
              (unsigned)(f >> 32));
}

void vs_co_switch(vs_co_context* from, vs_co_context* to) { swapcontext(&from->uc, &to->uc); }

#else

/* vs_co_switch_sp(&from->sp, to->sp): pushes the callee-saved registers of the System V ABI, saves
 * the stack pointer, loads the other one and pops that context's registers; `ret` then continues
 * it. A new context's stack holds zeroed registers except rbx = arg and r12 = entry, under the
 * address of vs_co_trampoline, which calls entry(arg) with the stack aligned as a call wants. */
void vs_co_switch_sp(void** save, void* load);
void vs_co_trampoline(void);
__asm__(
    ".text\n"
    ".p2align 4\n"
    ".hidden vs_co_switch_sp\n"
    ".globl vs_co_switch_sp\n"
    ".type vs_co_switch_sp,@function\n"
    "vs_co_switch_sp:\n"
    "  pushq %rbp\n"
    "  pushq %rbx\n"
    "  pushq %r12\n"
    "  pushq %r13\n"
    "  pushq %r14\n"
    "  pushq %r15\n"
    "  movq %rsp, (%rdi)\n"
    "  movq %rsi, %rsp\n"
    "  popq %r15\n"
    "  popq %r14\n"
    "  popq %r13\n"
    "  popq %r12\n"
    "  popq %rbx\n"
    "  popq %rbp\n"
    "  ret\n"
    ".size vs_co_switch_sp, .-vs_co_switch_sp\n"
    ".p2align 4\n"
    ".hidden vs_co_trampoline\n"
    ".globl vs_co_trampoline\n"
    ".type vs_co_trampoline,@function\n"
    "vs_co_trampoline:\n"
    "  movq %rbx, %rdi\n"
    "  callq *%r12\n"
    "  ud2\n"
    ".size vs_co_trampoline, .-vs_co_trampoline\n");

void vs_co_make(vs_co_context* ctx, void* stack, size_t size, void (*entry)(void*), void* arg) {
  /* After the six pops and the ret the stack pointer is `top`, 16-byte aligned, as a call needs. */
  uintptr_t top = ((uintptr_t)stack + size) & ~(uintptr_t)15;
  void** sp = (void**)(top - 7 * sizeof(void*));
  sp[0] = NULL;                     /* r15 */
  sp[1] = NULL;                     /* r14 */
  sp[2] = NULL;                     /* r13 */
  sp[3] = (void*)entry;             /* r12 */
  sp[4] = arg;                      /* rbx */
  sp[5] = NULL;                     /* rbp */
  sp[6] = (void*)vs_co_trampoline;  /* ret, at top - 8 */
  ctx->sp = sp;
}

void vs_co_switch(vs_co_context* from, vs_co_context* to) { vs_co_switch_sp(&from->sp, to->sp); }

#endif
