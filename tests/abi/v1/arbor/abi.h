/*
 * arbor/abi.h - the foundations of the Arbor plugin ABI, version 1.
 *
 * Everything a plugin and the host exchange is built from the types in this
 * file: the ABI version, the export macro for the single entry symbol, and the
 * stable status codes.  The rules every SDK header follows are:
 *
 *  - C99, fixed-width integer types only; "enums" are uint32_t typedefs with
 *    #define'd values that never change meaning.
 *  - Every data record starts with `uint32_t struct_size` (the size the writer
 *    of the record was compiled with) and only ever grows at its end; a
 *    reader demands only ARBOR_MIN_SIZE(type), never sizeof.  Every byte of a
 *    record is a named field on every architecture (padding is "reserved").  The
 *    caller allocates records and sets struct_size; a callee must not touch
 *    fields beyond struct_size.
 *  - Inputs are borrowed: valid during the call, read-only.  Outputs go into
 *    memory the host owns.  Nothing is ever freed across the boundary.
 *  - Strings are UTF-8 and NUL-terminated.
 *  - Interfaces (tables of functions) are fetched by a string id that carries
 *    a revision ("arbor.importer/1").  A changed interface gets a new id; the
 *    old one keeps working.  Ids never change once released.
 *
 * The contract.  Every function and pointer of the SDK carries tags saying who
 * calls it, from which thread, and how long what it hands over lives
 * (share/arbor/sdk/docs/contract.md, installed with these headers, has the
 * whole contract and the reasons):
 *
 *   [main-thread]  called only on the thread that loaded the library (in
 *                  `arbor` and the workstation the process's main thread).
 *   [instance]     called from any thread, but never while another call into
 *                  the same instance runs: the host orders the calls into one
 *                  instance, and what one call wrote is visible to the next,
 *                  whichever thread makes it.  Calls into *different*
 *                  instances, also of the same plugin, may overlap unless the
 *                  descriptor sets ARBOR_PLUGIN_FLAG_SERIALIZE.
 *   [thread-safe]  may be called from any thread, at the same time as any
 *                  other call (the plugin's own or the host's).
 *   [cheap]        called often or while the user waits: no file reading
 *                  beyond what is named, no large allocation, no GPU context.
 *   [borrowed: X]  the callee may read it until X, never later; copy what
 *                  you keep ("until return": until the call returns).
 *   [host-owned]   memory the host allocated and frees; the plugin writes
 *                  into it during the call only.
 *   [nullable]     may be NULL (the text says when); everything else is
 *                  never NULL when the host calls.
 *   [since 1.N]    added in ABI minor N: read it only under ARBOR_HAS_FIELD.
 */
#ifndef ARBOR_ABI_H
#define ARBOR_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
#define ARBOR_EXTERN_C extern "C"
#else
#define ARBOR_EXTERN_C
#endif

#if defined(_WIN32)
#define ARBOR_EXPORT __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#define ARBOR_EXPORT __attribute__((visibility("default")))
#else
#define ARBOR_EXPORT
#endif

/* ABI version.  A plugin is loaded only if its major version equals the
 * host's.  Minor versions add records, fields at the end of records, and new
 * interface ids; a plugin built against a newer minor than the host must check
 * struct sizes and interface availability before using additions. */
#define ARBOR_ABI_VERSION_MAJOR 1
#define ARBOR_ABI_VERSION_MINOR 6
#define ARBOR_ABI_VERSION_PATCH 0

typedef struct arbor_version {
    uint32_t major;
    uint32_t minor;
    uint32_t patch;
} arbor_version;

#define ARBOR_ABI_VERSION_INIT \
    { ARBOR_ABI_VERSION_MAJOR, ARBOR_ABI_VERSION_MINOR, ARBOR_ABI_VERSION_PATCH }

/* A 32-bit truth value: 0 is false, anything else is true. */
typedef uint32_t arbor_bool32;

/* Status codes.  Values are stable forever; new codes may be added.  A caller
 * that meets a code it does not know treats it like ARBOR_ERROR_INTERNAL.
 * The human-readable reason of the last failure of a plugin instance comes
 * from arbor_plugin::last_error (see plugin.h). */
typedef int32_t arbor_status;

#define ARBOR_OK 0
/* A NULL pointer, a record whose struct_size is too small, an index out of
 * range, or an argument that makes no sense for the call. */
#define ARBOR_ERROR_INVALID_ARGUMENT (-1)
/* A valid request this plugin cannot serve (voxel type, feature, encoding). */
#define ARBOR_ERROR_UNSUPPORTED (-2)
/* A file could not be opened, read or written. */
#define ARBOR_ERROR_IO (-3)
/* The input data is malformed (bad header, truncated data). */
#define ARBOR_ERROR_FORMAT (-4)
/* Memory could not be obtained (including host allocation refusals). */
#define ARBOR_ERROR_OUT_OF_MEMORY (-5)
/* The host asked to cancel through the task (see host.h). */
#define ARBOR_ERROR_CANCELLED (-6)
/* A parameter value lies outside its description (type, range, choices). */
#define ARBOR_ERROR_OUT_OF_RANGE (-7)
/* An unknown id: parameter, plugin, interface or measure. */
#define ARBOR_ERROR_NOT_FOUND (-8)
/* The input exceeds a size limit of the format, the plugin or the host. */
#define ARBOR_ERROR_TOO_LARGE (-9)
/* A bug or an unexpected condition inside the plugin. */
#define ARBOR_ERROR_INTERNAL (-10)

/* Stable short name of a status code, for logs and messages. */
static inline const char *arbor_status_name(arbor_status status)
{
    switch (status) {
    case ARBOR_OK: return "ok";
    case ARBOR_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case ARBOR_ERROR_UNSUPPORTED: return "unsupported";
    case ARBOR_ERROR_IO: return "input/output error";
    case ARBOR_ERROR_FORMAT: return "malformed input";
    case ARBOR_ERROR_OUT_OF_MEMORY: return "out of memory";
    case ARBOR_ERROR_CANCELLED: return "cancelled";
    case ARBOR_ERROR_OUT_OF_RANGE: return "out of range";
    case ARBOR_ERROR_NOT_FOUND: return "not found";
    case ARBOR_ERROR_TOO_LARGE: return "too large";
    case ARBOR_ERROR_INTERNAL: return "internal error";
    default: return "unknown status";
    }
}

/* True when a record written with `size` bytes contains the field `field` of
 * record type `type`.  Use it before reading fields added in later minors:
 *     if (ARBOR_HAS_FIELD(arbor_volume, volume->struct_size, value_unit)) ... */
#define ARBOR_HAS_FIELD(type, size, field) \
    ((size) >= (uint32_t)(offsetof(type, field) + sizeof(((type *)0)->field)))

/* The bytes of a record up to the end of `field`. */
#define ARBOR_SIZE_THROUGH(type, field) ((uint32_t)(offsetof(type, field) + sizeof(((type *)0)->field)))

/* The least struct_size a reader may demand of a record: the end of its last
 * field in the minor that introduced the record (1.0 for most; each header
 * defines ARBOR_MIN_SIZE_<type> after the record).  Check records against
 * this, never against sizeof, which grows with every minor: a record written
 * by a 1.0 plugin or host stays valid in every 1.x, and fields added later
 * are read only under ARBOR_HAS_FIELD.
 *     if (!rows || rows->struct_size < ARBOR_MIN_SIZE(arbor_measure_rows)) ... */
#define ARBOR_MIN_SIZE(type) ARBOR_MIN_SIZE_##type

#endif /* ARBOR_ABI_H */
