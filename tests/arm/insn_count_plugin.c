/* qemu-user TCG plugin (host x86-64 shared object): counts the executed guest instructions of a
 * single-threaded arm64 program and tells the program its count on request, so the program can use the
 * count as its clock (tests/arm/insn_counter.hpp). Debian's qemu-user ships no qemu-plugin.h: the few
 * declarations of the plugin API version 1 used here are written out below (qemu 7.2 supports API 0..1).
 *
 * Protocol: the guest issues write(kMarkerFd, NULL, reply_fd) (aarch64 syscall 64; kMarkerFd is an invalid
 * descriptor, so the call itself only returns EBADF, also when not run under this plugin). The plugin's
 * syscall callback runs before the syscall and writes the 8-byte count of instructions executed so far into
 * the host descriptor reply_fd (qemu-user passes guest descriptors through unchanged: the guest's pipe).
 * At exit the plugin prints the total to stderr ("insn_count total N").
 *
 * Exact for one thread: each translated block adds its instruction count inline when it starts; a block ends
 * at every syscall, so the count at a marker is exact. Not atomic across threads (one global counter). */
#include <inttypes.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <unistd.h>

typedef uint64_t qemu_plugin_id_t;
typedef struct qemu_info_t qemu_info_t; /* only passed through */
struct qemu_plugin_tb;
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb* tb);
typedef void (*qemu_plugin_vcpu_syscall_cb_t)(qemu_plugin_id_t id, unsigned int vcpu_index, int64_t num,
                                              uint64_t a1, uint64_t a2, uint64_t a3, uint64_t a4, uint64_t a5,
                                              uint64_t a6, uint64_t a7, uint64_t a8);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void* userdata);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb* tb);
void qemu_plugin_register_vcpu_tb_exec_inline(struct qemu_plugin_tb* tb, enum qemu_plugin_op op, void* ptr,
                                              uint64_t imm);
void qemu_plugin_register_vcpu_syscall_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_syscall_cb_t cb);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void* userdata);

#define VISNAV_EXPORT __attribute__((visibility("default")))
VISNAV_EXPORT int qemu_plugin_version = 1;

enum { kAarch64SysWrite = 64, kMarkerFd = -0x7a6d }; /* must match tests/arm/insn_counter.cpp */

static uint64_t g_insns;   /* executed guest instructions */
static uint64_t g_markers; /* marker calls answered */

static void onTranslate(qemu_plugin_id_t id, struct qemu_plugin_tb* tb) {
  (void)id;
  qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &g_insns,
                                           qemu_plugin_tb_n_insns(tb));
}

static void onSyscall(qemu_plugin_id_t id, unsigned int vcpu, int64_t num, uint64_t a1, uint64_t a2,
                      uint64_t a3, uint64_t a4, uint64_t a5, uint64_t a6, uint64_t a7, uint64_t a8) {
  (void)id, (void)vcpu, (void)a2, (void)a4, (void)a5, (void)a6, (void)a7, (void)a8;
  if (num != kAarch64SysWrite || (int64_t)a1 != kMarkerFd) return;
  const uint64_t count = g_insns;
  if (write((int)a3, &count, sizeof count) == (ssize_t)sizeof count) ++g_markers;
}

static void onExit(qemu_plugin_id_t id, void* userdata) {
  (void)id, (void)userdata;
  /* stderr directly: qemu_plugin_outs would print only with `-d plugin`. */
  fprintf(stderr, "insn_count total %" PRIu64 " markers %" PRIu64 "\n", g_insns, g_markers);
}

VISNAV_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t* info, int argc, char** argv) {
  (void)info, (void)argc, (void)argv;
  qemu_plugin_register_vcpu_tb_trans_cb(id, onTranslate);
  qemu_plugin_register_vcpu_syscall_cb(id, onSyscall);
  qemu_plugin_register_atexit_cb(id, onExit, NULL);
  return 0;
}
