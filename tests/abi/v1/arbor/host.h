/*
 * arbor/host.h - services the host offers to plugins.
 *
 * Two records: arbor_host, handed to a library at init and to every plugin
 * instance at creation (logging, identity of the host), and arbor_task, handed
 * to every long-running call (progress, cancellation, memory for outputs whose
 * size only the plugin knows).
 */
#ifndef ARBOR_HOST_H
#define ARBOR_HOST_H

#include "abi.h"

typedef uint32_t arbor_log_level;
#define ARBOR_LOG_DEBUG 0
#define ARBOR_LOG_INFO 1
#define ARBOR_LOG_WARNING 2
#define ARBOR_LOG_ERROR 3

typedef struct arbor_host arbor_host;

struct arbor_host {
    uint32_t struct_size;
    arbor_version abi_version; /* ABI the host was built against */
    const char *name;          /* "Arbor" */
    const char *version;       /* host application version, e.g. "0.1.0" */
    void *host_data;           /* private to the host; do not touch */

    /* Write a message to the host log.  Thread-safe; may be called from any
     * thread between the library's init and deinit.  The host attributes the
     * message to the library or instance it gave this arbor_host to, so always
     * log through the pointer you were given.  While a pipeline job uses the
     * instance, its messages go to that job's log (the workstation's jobs
     * panel); otherwise to stderr at or above the host's log level.  Not for
     * per-voxel or per-branch messages.  [thread-safe]
     * [borrowed: message until return] */
    void (*log)(const arbor_host *host, arbor_log_level level, const char *message);

    /* Optional host extension by id ("arbor.host.something/1"), or NULL when
     * the host does not offer it.  Version 1 hosts offer none; the function
     * exists so later minors can add services without a new record. */
    const void *(*get_extension)(const arbor_host *host, const char *extension_id);
};
#define ARBOR_MIN_SIZE_arbor_host ARBOR_SIZE_THROUGH(arbor_host, get_extension) /* through ABI 1.0 */

typedef struct arbor_task arbor_task;

/* One task per long-running call.  Valid only during that call: never keep
 * the pointer.  The host always passes one, never NULL, with all three
 * functions set (a test of the host checks every call); plugins that are also
 * called by other programs may still check.  All three functions are
 * thread-safe: a plugin may call them from its worker threads during the
 * call.  [borrowed: until return] */
struct arbor_task {
    uint32_t struct_size;
    uint32_t reserved0; /* 0; the padding before the pointers, named (ABI 1.3) */
    void *host_data; /* private to the host */

    /* Report progress of the current call: fraction in [0, 1], stage a short
     * label ("sorting", "join tree") or NULL to keep the previous one.  Cheap
     * (the host rate-limits its display).  Returns non-zero when cancellation
     * was requested, like cancelled().  [thread-safe] [cheap] */
    arbor_bool32 (*progress)(arbor_task *task, double fraction, const char *stage);

    /* Non-zero once the user asked to cancel.  Poll it at least every tenth
     * of a second of work; when set, stop and return ARBOR_ERROR_CANCELLED.
     * [thread-safe] [cheap] */
    arbor_bool32 (*cancelled)(arbor_task *task);

    /* Memory for outputs whose size only the plugin knows (e.g. transfer
     * function control points).  Owned by the host, 64-byte aligned,
     * zero-filled, valid until the call returns: the host copies what the
     * outputs point into before it releases the task, so never keep a pointer
     * to it for a later call.  Never free it.  Returns NULL for size 0 and
     * when the host refuses (Arbor's limit: 16 GiB per call): then return
     * ARBOR_ERROR_OUT_OF_MEMORY or ARBOR_ERROR_TOO_LARGE.  Not for scratch
     * memory: use your own.  [thread-safe] */
    void *(*allocate)(arbor_task *task, uint64_t size);
};
#define ARBOR_MIN_SIZE_arbor_task ARBOR_SIZE_THROUGH(arbor_task, allocate) /* through ABI 1.0 */

#endif /* ARBOR_HOST_H */
